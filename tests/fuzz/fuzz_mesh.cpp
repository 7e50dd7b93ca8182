// libFuzzer target: PLY, STL and glTF / GLB loading (core/mesh_loader.cpp over Assimp). The
// first byte picks the extension, so one corpus reaches every importer; the rest is the file.
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static accel::fuzz::InputFile files[] = {accel::fuzz::InputFile(".ply"), accel::fuzz::InputFile(".stl"),
                                           accel::fuzz::InputFile(".gltf"), accel::fuzz::InputFile(".glb")};
  accel::fuzz::InputFile& file = files[data[0] % 4];
  auto scene = accel::load_scene(file.write(data + 1, size - 1));
  if (!scene) {
    if (scene.error().message.find('\n') != std::string::npos) std::abort();
    return 0;
  }
  accel::fuzz::build_and_trace_everything(scene.value());
  return 0;
}
