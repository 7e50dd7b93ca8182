// accelviz: the interactive viewer. Parses the command line, loads the scene, then follows
// the order of Dear ImGui's example_glfw_opengl3: error callback, GLFW and GL context, ImGui
// context and backends, a main loop that sleeps while iconified, cleanup in reverse.
//
// Exit codes: 0 success, 1 no display / no OpenGL 3.3 / missing shaders / screenshot not
// written, 2 bad command line (unknown option, invalid --size, scene that fails to load).
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glad/gl.h>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include "app.h"
#include "paths.h"
#include "scene.h"
#include "screenshot.h"

namespace {

/// What the command line asks for.
struct Options {
  std::string scene;            ///< OBJ path or procedural:NAME
  std::string screenshot;       ///< PNG path; empty = interactive
  int frames = 3;               ///< frames rendered before the screenshot
  int width = 1280, height = 720;
  bool no_ui = false;           ///< start with the panels hidden
};

constexpr int kMinSize = 64;
constexpr int kMaxSize = 8192;

// GLFW reports errors through a C callback with no user data. Before glfwInit() succeeds
// its messages are folded into our single "no display" line instead of being printed.
bool report_glfw_errors = false;

void glfw_error_callback(int error, const char* description) {
  if (report_glfw_errors) std::fprintf(stderr, "accelviz: GLFW error %d: %s\n", error, description);
}

// The default scene needs no file: the Cornell-like room shows boxes, walls and a ball,
// which makes every structure's cells and nodes easy to read on a projector.
std::string default_scene() { return "procedural:cornell"; }

// "1280x720" -> {1280, 720}; nullopt unless both are integers in [kMinSize, kMaxSize].
std::optional<std::pair<int, int>> parse_size(const std::string& text) {
  int w = 0, h = 0;
  char x = 0;
  int consumed = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%n", &w, &x, &h, &consumed) != 3) return std::nullopt;
  if ((x != 'x' && x != 'X') || static_cast<size_t>(consumed) != text.size()) return std::nullopt;
  if (w < kMinSize || w > kMaxSize || h < kMinSize || h > kMaxSize) return std::nullopt;
  return std::make_pair(w, h);
}

// The command as typed, for the "run it under xvfb-run" hint.
std::string command_line(int argc, char** argv) {
  std::string line = "accelviz";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool quote = arg.empty() || arg.find_first_of(" \t'\"$\\") != std::string::npos;
    line += quote ? " '" + arg + "'" : " " + arg;
  }
  return line;
}

bool env_set(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && value[0] != '\0';
}

// Parses argv into `options`. Returns an exit code when main() should stop (--help: 0,
// an error: 2), nullopt to go on.
std::optional<int> parse_command_line(int argc, char** argv, Options& options) {
  std::string names;
  for (const std::string& name : accel::procedural_scene_names()) names += (names.empty() ? "" : ", ") + name;

  CLI::App cli{"accelviz: interactive viewer for ray-tracing acceleration structures"};
  options.scene = default_scene();
  std::string size_text = "1280x720";
  cli.add_option("scene", options.scene, "OBJ file or procedural:NAME (NAME: " + names + ")")
      ->capture_default_str();
  cli.add_option("--screenshot", options.screenshot,
                 "render, write the framebuffer to this PNG file, and exit");
  cli.add_option("--frames", options.frames, "frames rendered before the screenshot, 1..1000")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cli.add_flag("--no-ui", options.no_ui, "hide the panels (H shows them): clean screenshots for slides");
  cli.add_option("--size", size_text, "window size WxH, W and H in 64..8192")->capture_default_str();
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);  // prints help, or the error naming the option
    return code == 0 ? 0 : 2;
  }
  const auto size = parse_size(size_text);
  if (!size) {
    std::fprintf(stderr, "accelviz: --size: expected WxH with W and H in %d..%d, got '%s'\n", kMinSize,
                 kMaxSize, size_text.c_str());
    return 2;
  }
  options.width = size->first;
  options.height = size->second;
  if (options.scene.empty()) {
    std::fprintf(stderr, "accelviz: no scene given and the core has no procedural scenes\n");
    return 2;
  }
  return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (const auto code = parse_command_line(argc, argv, options)) return *code;
  const bool screenshot_mode = !options.screenshot.empty();

  // The scene first: a bad path is the user's mistake (exit 2) whether or not there is a
  // display, and scripts get the same answer everywhere.
  viz::App app;
  if (const auto error = app.load_scene(options.scene)) {
    std::fprintf(stderr, "accelviz: %s\n", error->message.c_str());
    return 2;
  }
  const auto shader_dir =
      viz::find_shader_dir({"mesh.vert", "mesh.frag", "lines.vert", "lines.frag"});
  if (!shader_dir) {
    std::fprintf(stderr, "accelviz: %s\n", shader_dir.error().message.c_str());
    return 1;
  }

  // Without a display GLFW would fail with an X11 message; say what to do instead.
  const std::string hint = "run it under a virtual display: xvfb-run -a " + command_line(argc, argv);
  if (!env_set("DISPLAY") && !env_set("WAYLAND_DISPLAY")) {
    std::fprintf(stderr, "accelviz: no display found (DISPLAY is not set); %s\n", hint.c_str());
    return 1;
  }

  glfwSetErrorCallback(glfw_error_callback);
  if (!glfwInit()) {
    const char* description = nullptr;
    glfwGetError(&description);
    std::fprintf(stderr, "accelviz: no display found (GLFW: %s); %s\n",
                 description != nullptr ? description : "glfwInit failed", hint.c_str());
    return 1;
  }
  report_glfw_errors = true;

  // OpenGL 3.3 core: what glad was generated for and what the shaders' #version says.
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, 4);  // smooth edges on a projector; ignored if unsupported
  // A screenshot must have exactly the requested size: keep window managers from resizing.
  if (screenshot_mode) glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  report_glfw_errors = false;  // a failure here gets its own single line below
  GLFWwindow* window = glfwCreateWindow(options.width, options.height, "accelviz", nullptr, nullptr);
  report_glfw_errors = true;
  if (window == nullptr) {
    const char* description = nullptr;
    glfwGetError(&description);
    std::fprintf(stderr, "accelviz: cannot create an OpenGL 3.3 core window (GLFW: %s)\n",
                 description != nullptr ? description : "unknown error");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(screenshot_mode ? 0 : 1);  // vsync when interactive; no waiting otherwise

  // glad serves our renderer only; ImGui's OpenGL3 backend loads its own functions.
  if (gladLoadGL(glfwGetProcAddress) == 0) {
    std::fprintf(stderr, "accelviz: cannot load OpenGL 3.3 functions\n");
    glfwDestroyWindow(window);
    glfwTerminate();
    return 1;
  }

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini in whatever directory we were started from
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 4.0f;
  style.FrameRounding = 3.0f;
  style.ScaleAllSizes(1.25f);
  // A larger, smooth font reads at the back of a lecture hall. DejaVu Sans comes with most
  // Linux desktops; otherwise ImGui's built-in font, scaled.
  const char* font_path = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  if (std::FILE* font = std::fopen(font_path, "rb")) {
    std::fclose(font);
    io.Fonts->AddFontFromFileTTF(font_path, 18.0f);
  } else {
    io.FontGlobalScale = 1.25f;
  }

  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");

  app.set_ui_visible(!options.no_ui);
  int exit_code = 0;
  if (const auto error = app.init(window, shader_dir.value())) {
    std::fprintf(stderr, "accelviz: %s\n", error->message.c_str());
    exit_code = 1;
    glfwSetWindowShouldClose(window, GLFW_TRUE);
  }

  int frame = 0;
  double last_time = glfwGetTime();
  while (!glfwWindowShouldClose(window)) {
    glfwPollEvents();
    // Minimised: nothing to draw, so sleep until something happens.
    if (!screenshot_mode && glfwGetWindowAttrib(window, GLFW_ICONIFIED) != 0) {
      glfwWaitEvents();
      last_time = glfwGetTime();  // the sleep is not a frame
      continue;
    }
    const double now = glfwGetTime();
    const float dt = static_cast<float>(now - last_time);
    last_time = now;

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    app.update(dt);
    ImGui::Render();

    int fb_width = 0, fb_height = 0;
    glfwGetFramebufferSize(window, &fb_width, &fb_height);
    app.draw(fb_width, fb_height);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    // The back buffer holds the finished frame until the swap: read it now. ImGui needs a
    // frame or two to size its windows, hence --frames.
    if (screenshot_mode && ++frame >= options.frames) {
      if (fb_width != options.width || fb_height != options.height) {
        std::fprintf(stderr, "accelviz: warning: framebuffer is %dx%d, not the requested %dx%d\n",
                     fb_width, fb_height, options.width, options.height);
      }
      if (const auto error = viz::save_framebuffer_png(options.screenshot, fb_width, fb_height)) {
        std::fprintf(stderr, "accelviz: %s\n", error->message.c_str());
        exit_code = 1;
      }
      break;
    }
    glfwSwapBuffers(window);
  }

  app.shutdown();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return exit_code;
}
