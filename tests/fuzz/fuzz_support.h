#pragma once
// What the libFuzzer targets share: the input bytes as a file on disk for the loaders that
// take a path (they read the file themselves: open, size, read, as the CLI does), and the
// structures' build-and-trace run that checks a loaded scene does not break a builder.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

#include "batch.h"
#include "build_control.h"
#include "ray_gen.h"
#include "registry.h"
#include "scene.h"

namespace accel::fuzz {

/// A file, one per process and extension, that every input overwrites. Under /dev/shm
/// when there is one, so the fuzzer does not wear out a disk.
class InputFile {
 public:
  explicit InputFile(std::string_view extension) {
    const char* dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : (std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp");
    path_ = std::string(dir) + "/accel_fuzz_" + std::to_string(getpid()) + std::string(extension);
  }
  ~InputFile() { std::remove(path_.c_str()); }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  /// Writes the input; the path, for the loader.
  const std::string& write(const uint8_t* data, size_t size) {
    FILE* f = std::fopen(path_.c_str(), "wb");
    if (!f) std::abort();  // the fuzzer's own environment is broken: stop loudly
    if (size && std::fwrite(data, 1, size, f) != size) std::abort();
    std::fclose(f);
    return path_;
  }

 private:
  std::string path_;
};

/// Builds every structure with its default parameters on a loaded scene and traces a few
/// rays: a scene the loader accepted (huge or tiny coordinates, slivers, duplicates) must
/// build within the budget or fail with an error, never crash. Skipped above `max_triangles`,
/// where one input would take longer than the fuzzer's per-input time.
inline void build_and_trace_everything(const Scene& scene, size_t max_triangles = 512) {
  if (scene.triangle_count() > max_triangles) return;
  const std::vector<Ray> rays = random_rays(scene.bounds(), 32, 7);
  for (const StructureInfo& info : structure_registry()) {
    auto params = ParamSet::parse(info.params, {}, info.name);
    if (!params) std::abort();  // the defaults are always valid
    BuildControl control;
    control.set_memory_limit(size_t(256) << 20);
    control.set_time_limit(2.0);
    auto built = build_structure(info, scene, params.value(), Kernel::Watertight, &control);
    if (!built) continue;  // a one-line error is an answer
    (void)trace_all(*built.value(), rays, 1);
  }
}

}  // namespace accel::fuzz
