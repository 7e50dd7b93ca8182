// libFuzzer target: the rays file (core/rays_io.cpp), parsed as `trace --rays FILE` reads it,
// and the generated ray sets' spec ("random:N:SEED", "primary:W:H") when the input starts
// with one of their names. Accepted rays must have a finite origin and direction.
#include <algorithm>
#include <cctype>
#include <cmath>

#include "fuzz_support.h"
#include "rays_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto rays = accel::parse_rays(text, "fuzz.rays");
  if (rays) {
    for (const accel::Ray& r : rays.value())
      for (int k = 0; k < 3; ++k)
        if (!std::isfinite(r.org[k]) || !std::isfinite(r.dir[k])) std::abort();
  } else if (rays.error().message.rfind("fuzz.rays:", 0) != 0) {
    std::abort();  // every error names the file (and its line)
  }
  // Large counts are valid requests (up to 1e8 rays), so only specs whose numbers have at
  // most three digits are generated: the parser's edge cases, not a gigabyte of rays.
  if (text.rfind("random:", 0) == 0 || text.rfind("primary:", 0) == 0) {
    size_t digits = 0, longest = 0;
    for (char c : text) longest = std::max(longest, digits = std::isdigit(static_cast<unsigned char>(c)) ? digits + 1 : 0);
    static const accel::Scene scene = accel::make_procedural_scene("cornell").value();
    if (longest <= 3) (void)accel::make_rays(text, scene);
  }
  return 0;
}
