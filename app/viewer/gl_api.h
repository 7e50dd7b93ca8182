#pragma once
// The viewer's one OpenGL header. Natively: OpenGL 3.3 core through glad. In the browser:
// OpenGL ES 3.0, which is WebGL2 (emscripten). The renderer keeps to what both have; the
// few differences are answered here, in one place:
//  * shaders are written once for GLSL 3.30 and get the ES version line and precision at
//    load (glsl_for_this_gl);
//  * ES has no polygon mode: the wireframe mesh is drawn as lines (kHasPolygonMode);
//  * ES clears depth with the float variant;
//  * WebGL's finish() does not wait: wait_for_gpu() reads a pixel back instead.
#include <string>

#ifdef __EMSCRIPTEN__
#include <GLES3/gl3.h>
#else
#include <glad/gl.h>
#endif

namespace viz::gl {

/// glfwGetProcAddress's type: what loads GL's functions by name.
using ProcAddressFn = void (*(*)(const char* name))();

#ifdef __EMSCRIPTEN__
inline constexpr bool kHasPolygonMode = false;
/// The version line ImGui's OpenGL3 backend compiles its shaders with.
inline constexpr const char* kImGuiGlslVersion = "#version 300 es";
inline void clear_depth(float depth) { glClearDepthf(depth); }
inline void polygon_mode_lines(bool) {}
/// WebGL's finish() returns at once; reading a pixel back waits for the frame.
inline void wait_for_gpu() {
  unsigned char pixel[4];
  glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel);
}
/// WebGL's functions are there from the start.
inline bool load_functions(ProcAddressFn) { return true; }
#else
inline constexpr bool kHasPolygonMode = true;
inline constexpr const char* kImGuiGlslVersion = "#version 330 core";
inline void clear_depth(float depth) { glClearDepth(depth); }
/// Waits until the GPU has finished every command (frame-time measurements).
inline void wait_for_gpu() { glFinish(); }
/// Rasterises triangles as their edges (true) or filled (false); only where kHasPolygonMode.
inline void polygon_mode_lines(bool lines) { glPolygonMode(GL_FRONT_AND_BACK, lines ? GL_LINE : GL_FILL); }
/// Loads the GL 3.3 core functions (glad) for the current context; false when it cannot.
inline bool load_functions(ProcAddressFn get_proc_address) { return gladLoadGL(get_proc_address) != 0; }
#endif

/// `source` (a shader of shaders/, first line "#version 330 core") for this GL: unchanged
/// natively; with "#version 300 es" and high precision in the browser.
inline std::string glsl_for_this_gl(const std::string& source) {
#ifdef __EMSCRIPTEN__
  const std::string native = "#version 330 core";
  if (source.compare(0, native.size(), native) != 0) return source;
  return "#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp sampler2D;" +
         source.substr(native.size());
#else
  return source;
#endif
}

}  // namespace viz::gl
