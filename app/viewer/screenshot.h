#pragma once
// Screenshots: the framebuffer read back and written as PNG (stb_image_write).
#include <string>

#include "result.h"

namespace viz {

/// Reads the current back buffer (call after drawing, before glfwSwapBuffers) of size
/// width x height and writes it to `path` as an 8-bit RGB PNG, top row first.
/// Returns an Error naming the path if the size is invalid or the file cannot be written.
accel::Status save_framebuffer_png(const std::string& path, int width, int height);

}  // namespace viz
