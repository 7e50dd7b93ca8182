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

std::vector<uint8_t> read_back_buffer(glm::ivec4 rect, int framebuffer_height, int channels) {
  const size_t row_bytes = static_cast<size_t>(rect.z) * static_cast<size_t>(channels);
  std::vector<uint8_t> pixels(row_bytes * static_cast<size_t>(rect.w));
  // Rows are tightly packed (RGB rows of odd widths are not 4-byte aligned).
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glReadPixels(rect.x, framebuffer_height - rect.y - rect.w, rect.z, rect.w, channels == 4 ? GL_RGBA : GL_RGB,
               GL_UNSIGNED_BYTE, pixels.data());
  // GL's first row is the bottom one; ours is the top one.
  std::vector<uint8_t> row(row_bytes);
  for (int y = 0; y < rect.w / 2; ++y) {
    uint8_t* top = pixels.data() + static_cast<size_t>(y) * row_bytes;
    uint8_t* bottom = pixels.data() + static_cast<size_t>(rect.w - 1 - y) * row_bytes;
    std::memcpy(row.data(), top, row_bytes);
    std::memcpy(top, bottom, row_bytes);
    std::memcpy(bottom, row.data(), row_bytes);
  }
  return pixels;
}

accel::Status save_framebuffer_png(const std::string& path, int width, int height) {
  if (width <= 0 || height <= 0) {
    return accel::make_error("save_framebuffer_png: invalid size " + std::to_string(width) + "x" +
                             std::to_string(height));
  }
  const std::vector<uint8_t> pixels = read_back_buffer({0, 0, width, height}, height, 3);
  if (stbi_write_png(path.c_str(), width, height, 3, pixels.data(), width * 3) == 0) {
    return accel::make_error("cannot write screenshot " + path);
  }
  return {};
}

}  // namespace viz
