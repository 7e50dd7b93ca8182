// png_check: asserts that a screenshot of the viewer is a real picture.
//
//   png_check FILE WIDTH HEIGHT [MIN_FRACTION]   exit 0 if FILE is a WIDTHxHEIGHT PNG in
//                                                 which at least MIN_FRACTION (default
//                                                 0.05) of the pixels differ from the
//                                                 background, in several shades
//   png_check --differ A B [MIN_PIXELS]          exit 0 if A and B have the same size and at
//                                                 least MIN_PIXELS (default 50) pixels differ
//   png_check --gif FILE FRAMES WIDTH HEIGHT     exit 0 if FILE decodes (stb_image's GIF
//                                                 decoder) to FRAMES images of WIDTHxHEIGHT,
//                                                 not all the same
//   png_check --skip REASON                      prints REASON, exits 77 (ctest SKIP)
//
// The background is the bottom-right corner pixel: ImGui's panel sits top-left, and the
// framed scene leaves the corners free.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#include <stb/stb_image.h>

namespace {

constexpr int kSkipCode = 77;
// Per-channel sum of absolute differences above which a pixel is "not background";
// large enough to ignore dithering or compression noise, small enough for dark shades.
constexpr int kDiffThreshold = 24;
// Flat shading gives many faces many brightnesses; a blank or single-colour frame fails.
constexpr size_t kMinShades = 8;

int fail(const std::string& message) {
  std::fprintf(stderr, "png_check: FAIL: %s\n", message.c_str());
  return 1;
}

/// --differ: two screenshots of different states (structures, trace steps) must not be the
/// same picture.
int differ(const std::string& a_path, const std::string& b_path, size_t min_pixels) {
  int aw = 0, ah = 0, bw = 0, bh = 0, channels = 0;
  unsigned char* a = stbi_load(a_path.c_str(), &aw, &ah, &channels, 3);
  if (a == nullptr) return fail("cannot read " + a_path);
  unsigned char* b = stbi_load(b_path.c_str(), &bw, &bh, &channels, 3);
  if (b == nullptr) {
    stbi_image_free(a);
    return fail("cannot read " + b_path);
  }
  if (aw != bw || ah != bh) {
    stbi_image_free(a);
    stbi_image_free(b);
    return fail("sizes differ: " + a_path + " vs " + b_path);
  }
  size_t differing = 0;
  for (size_t i = 0; i < static_cast<size_t>(aw) * static_cast<size_t>(ah); ++i) {
    const int diff = std::abs(a[3 * i] - b[3 * i]) + std::abs(a[3 * i + 1] - b[3 * i + 1]) +
                     std::abs(a[3 * i + 2] - b[3 * i + 2]);
    if (diff > kDiffThreshold) ++differing;
  }
  stbi_image_free(a);
  stbi_image_free(b);
  std::printf("png_check: %s vs %s: %zu pixels differ\n", a_path.c_str(), b_path.c_str(), differing);
  if (differing < min_pixels)
    return fail("only " + std::to_string(differing) + " pixels differ, need " + std::to_string(min_pixels));
  return 0;
}

/// --gif: a recording (the web page's downloaded GIF) decodes, with the expected frames.
int gif(const std::string& path, int want_frames, int want_w, int want_h) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (data.empty()) return fail("cannot read " + path);
  int* delays = nullptr;
  int w = 0, h = 0, frames = 0, channels = 0;
  unsigned char* pixels =
      stbi_load_gif_from_memory(data.data(), int(data.size()), &delays, &w, &h, &frames, &channels, 4);
  if (pixels == nullptr) return fail("cannot decode " + path + ": " + stbi_failure_reason());
  const size_t frame_bytes = 4 * static_cast<size_t>(w) * static_cast<size_t>(h);
  size_t distinct = 1;
  for (int k = 1; k < frames; ++k)
    if (std::memcmp(pixels + frame_bytes * size_t(k), pixels + frame_bytes * size_t(k - 1), frame_bytes) != 0)
      ++distinct;
  stbi_image_free(pixels);
  stbi_image_free(delays);
  std::printf("png_check: %s: %d frames of %dx%d, %zu changes\n", path.c_str(), frames, w, h, distinct);
  if (frames != want_frames) return fail(std::to_string(frames) + " frames, expected " + std::to_string(want_frames));
  if (w != want_w || h != want_h)
    return fail(std::to_string(w) + "x" + std::to_string(h) + ", expected " + std::to_string(want_w) + "x" +
                std::to_string(want_h));
  if (frames > 1 && distinct < 2) return fail("every frame is the same picture");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::string(argv[1]) == "--skip") {
    std::printf("png_check: skipped: %s\n", argv[2]);
    return kSkipCode;
  }
  if (argc == 6 && std::string(argv[1]) == "--gif")
    return gif(argv[2], std::atoi(argv[3]), std::atoi(argv[4]), std::atoi(argv[5]));
  if ((argc == 4 || argc == 5) && std::string(argv[1]) == "--differ")
    return differ(argv[2], argv[3], argc == 5 ? static_cast<size_t>(std::atol(argv[4])) : 50);
  if (argc < 4 || argc > 5) {
    std::fprintf(stderr,
                 "usage: png_check FILE WIDTH HEIGHT [MIN_FRACTION] | png_check --differ A B [MIN_PIXELS] | "
                 "png_check --gif FILE FRAMES WIDTH HEIGHT | png_check --skip REASON\n");
    return 2;
  }
  const std::string path = argv[1];
  const int want_w = std::atoi(argv[2]);
  const int want_h = std::atoi(argv[3]);
  const double min_fraction = argc == 5 ? std::atof(argv[4]) : 0.05;

  int w = 0, h = 0, channels = 0;
  unsigned char* pixels = stbi_load(path.c_str(), &w, &h, &channels, 3);
  if (pixels == nullptr) return fail("cannot read " + path + ": " + stbi_failure_reason());
  if (w != want_w || h != want_h) {
    stbi_image_free(pixels);
    return fail(path + " is " + std::to_string(w) + "x" + std::to_string(h) + ", expected " +
                std::to_string(want_w) + "x" + std::to_string(want_h));
  }

  const auto at = [&](int x, int y) { return pixels + 3 * (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)); };
  const unsigned char* bg = at(w - 1, h - 1);
  const int bg_r = bg[0], bg_g = bg[1], bg_b = bg[2];
  size_t differing = 0;
  std::set<int> shades;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const unsigned char* p = at(x, y);
      const int diff = std::abs(p[0] - bg_r) + std::abs(p[1] - bg_g) + std::abs(p[2] - bg_b);
      if (diff > kDiffThreshold) {
        ++differing;
        shades.insert((p[0] << 16) | (p[1] << 8) | p[2]);
      }
    }
  }
  stbi_image_free(pixels);

  const double fraction = static_cast<double>(differing) / (static_cast<double>(w) * static_cast<double>(h));
  std::printf("png_check: %s: %dx%d, background (%d,%d,%d), %.1f%% of pixels differ, %zu colours\n",
              path.c_str(), w, h, bg_r, bg_g, bg_b, 100.0 * fraction, shades.size());
  if (fraction < min_fraction) {
    return fail("only " + std::to_string(100.0 * fraction) + "% of pixels differ from the background, need " +
                std::to_string(100.0 * min_fraction) + "%: blank frame?");
  }
  if (shades.size() < kMinShades) {
    return fail("only " + std::to_string(shades.size()) + " colours besides the background: unshaded?");
  }
  std::printf("png_check: OK\n");
  return 0;
}
