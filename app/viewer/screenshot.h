#pragma once
// Screenshots: the framebuffer read back and written as PNG (stb_image_write).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "result.h"

namespace viz {

/// The back buffer's rectangle `rect` (x, y from the top-left, w, h; framebuffer pixels) of
/// a framebuffer `framebuffer_height` tall, read back as `channels` (3: RGB, 4: RGBA) bytes
/// per pixel, rows tightly packed, the top row first (GL's first row is the bottom one).
std::vector<uint8_t> read_back_buffer(glm::ivec4 rect, int framebuffer_height, int channels);

/// Reads the current back buffer (call after drawing, before glfwSwapBuffers) of size
/// width x height and writes it to `path` as an 8-bit RGB PNG, top row first.
/// Returns an Error naming the path if the size is invalid or the file cannot be written.
accel::Status save_framebuffer_png(const std::string& path, int width, int height);

}  // namespace viz
