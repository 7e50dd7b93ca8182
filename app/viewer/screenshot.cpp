#include "screenshot.h"

#include <cstdint>
#include <cstring>
#include <vector>

// The only translation unit with stb_image_write's implementation. STATIC keeps its
// symbols private, so they never clash with Debian's libstb, which also has them.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

#include "gl_api.h"

namespace viz {

std::vector<uint8_t> read_back_buffer(glm::ivec4 rect, int framebuffer_height, int channels) {
  const size_t width = static_cast<size_t>(rect.z), height = static_cast<size_t>(rect.w);
  // Read as RGBA, the one format WebGL2 always reads back (RGB may fail there), and drop
  // the alpha after when RGB is asked for.
  std::vector<uint8_t> rgba(width * height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glReadPixels(rect.x, framebuffer_height - rect.y - rect.w, rect.z, rect.w, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  // GL's first row is the bottom one; ours is the top one.
  const size_t row_bytes = width * static_cast<size_t>(channels);
  std::vector<uint8_t> pixels(row_bytes * height);
  for (size_t y = 0; y < height; ++y) {
    const uint8_t* from = rgba.data() + (height - 1 - y) * width * 4;
    uint8_t* to = pixels.data() + y * row_bytes;
    if (channels == 4) {
      std::memcpy(to, from, row_bytes);
    } else {
      for (size_t x = 0; x < width; ++x, from += 4, to += 3) std::memcpy(to, from, 3);
    }
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
