#include "screenshot.h"

#include <cstdint>
#include <cstring>
#include <vector>

#include <glad/gl.h>

// The only translation unit with stb_image_write's implementation. STATIC keeps its
// symbols private, so they never clash with Debian's libstb, which also has them.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

namespace viz {

accel::Status save_framebuffer_png(const std::string& path, int width, int height) {
  if (width <= 0 || height <= 0) {
    return accel::make_error("save_framebuffer_png: invalid size " + std::to_string(width) + "x" +
                             std::to_string(height));
  }
  const size_t row_bytes = static_cast<size_t>(width) * 3;
  std::vector<uint8_t> pixels(row_bytes * static_cast<size_t>(height));
  // Rows are tightly packed (RGB rows of odd widths are not 4-byte aligned).
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());

  // GL's first row is the bottom one; PNG's is the top one.
  std::vector<uint8_t> row(row_bytes);
  for (int y = 0; y < height / 2; ++y) {
    uint8_t* top = pixels.data() + static_cast<size_t>(y) * row_bytes;
    uint8_t* bottom = pixels.data() + static_cast<size_t>(height - 1 - y) * row_bytes;
    std::memcpy(row.data(), top, row_bytes);
    std::memcpy(top, bottom, row_bytes);
    std::memcpy(bottom, row.data(), row_bytes);
  }
  if (stbi_write_png(path.c_str(), width, height, 3, pixels.data(), static_cast<int>(row_bytes)) == 0) {
    return accel::make_error("cannot write screenshot " + path);
  }
  return {};
}

}  // namespace viz
