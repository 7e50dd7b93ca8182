// accelviz: the interactive viewer. Parses the command line, loads the scene, then follows
// the order of Dear ImGui's example_glfw_opengl3: error callback, GLFW and GL context, ImGui
// context and backends, a main loop that sleeps while iconified, cleanup in reverse. The web
// page runs this same main(): page.js turns its URL into these arguments, and after each frame
// the loop lends the background tasks time and waits for the browser's next frame (browser.h).
//
// Exit codes: 0 success, 1 no display / no OpenGL 3.3 / missing shaders / screenshot not
// written, 2 bad command line (unknown option, invalid --size, scene or --bench-json file
// that fails to load) or a failing --script command ("accelviz: SCRIPT:LINE: message").
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include "app.h"
#include "browser.h"
#include "gl_api.h"
#include "memory_budget.h"
#include "paths.h"
#include "renderer.h"
#include "scene.h"
#include "screenshot.h"
#include "script.h"
#include "script_verbs.h"
#include "warm_start.h"

namespace {

/// What the command line asks for.
struct Options {
  std::string scene;            ///< OBJ path or procedural:NAME
  std::string screenshot;       ///< PNG path; empty = interactive
  std::string script;           ///< command script; empty = none
  std::string bench_json;       ///< bench JSON for the "Speed vs error" chart; empty = none
  std::string playlist;         ///< lecture playlist; empty = none
  size_t state = 0;             ///< the playlist's state to open, from 1; 0 = the first
  std::string structure;        ///< structure to start with; empty = the default
  std::vector<std::string> params;  ///< its key=value parameters
  int frames = 3;               ///< frames rendered before the screenshot
  int width = 1280, height = 720;
  bool no_ui = false;           ///< start with the panels hidden
  int msaa = 4;                 ///< multisample anti-aliasing samples (0 = off)
  size_t memory_limit = 0;      ///< the builds' memory budget in bytes (0 = the default)
  std::string restore;          ///< a state file to reopen (--restore); empty = none
  std::string list;             ///< --list: keys, keys-summary, commands or mouse; empty = none
};

constexpr int kMinSize = 64;
constexpr int kMaxSize = 8192;
// The page's background work per frame: at least most of a 60 Hz frame, and as long as the
// last frame took to draw (up to 100 ms), so a slow renderer does not starve a build.
constexpr double kBackgroundMsMin = 10.0, kBackgroundMsMax = 100.0;

// GLFW reports errors through a C callback with no user data. Before glfwInit() succeeds
// its messages are folded into our single "no display" line instead of being printed.
bool report_glfw_errors = false;

void glfw_error_callback(int error, const char* description) {
  if (report_glfw_errors) std::fprintf(stderr, "accelviz: GLFW error %d: %s\n", error, description);
}

// GLFW's last error message, or nullptr (GLFW 3.2, the web page's, cannot tell).
const char* last_glfw_error() {
  const char* description = nullptr;
#if GLFW_VERSION_MAJOR > 3 || (GLFW_VERSION_MAJOR == 3 && GLFW_VERSION_MINOR >= 3)
  glfwGetError(&description);
#endif
  return description;
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
  cli.add_option("scene", options.scene, "mesh file (OBJ, PLY, STL, glTF, GLB) or procedural:NAME (NAME: " + names + ")")
      ->capture_default_str();
  cli.add_option("--screenshot", options.screenshot,
                 "render, write the framebuffer to this PNG file, and exit");
  cli.add_option("--frames", options.frames, "frames rendered before the screenshot, 1..1000")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cli.add_option("--script", options.script,
                 "run the viewer commands of this file (size, scene, structure, camera, ray-at-pixel, step, "
                 "screenshot, print-hit, ...; --list commands prints them all), then exit");
  cli.add_option("--list", options.list,
                 "print a Markdown table made from the tools' rows and exit: keys (every key), keys-summary (each "
                 "tool's keys), commands (the script commands) or mouse (the mouse in 3D and in 2D); "
                 "docs/viewer.md and README.md hold them")
      ->check(CLI::IsMember({"keys", "keys-summary", "commands", "mouse"}));
  cli.add_option("--bench-json", options.bench_json,
                 "open the speed-against-error chart of this accelviz-cli bench --out-json file");
  cli.add_option("--playlist", options.playlist,
                 "open a lecture playlist (state TITLE blocks of script commands; PgDn / PgUp move "
                 "between its states; see app/viewer/playlist.h)");
  cli.add_option("--state", options.state, "open the --playlist at this state (1 = the first)");
  cli.add_option("--structure", options.structure,
                 "start with this structure (grid, octree, kdtree, bvh, spheretree, brute) instead of the BVH");
  cli.add_option("--param", options.params,
                 "a parameter of --structure, key=value as accelviz-cli --param takes it (repeatable)");
  cli.add_flag("--no-ui", options.no_ui, "hide the panels (H shows them): clean screenshots for slides");
  cli.add_option("--msaa", options.msaa, "anti-aliasing samples per pixel, 0 (off) .. 16; 0 is much faster on "
                                         "software renderers (Mesa llvmpipe)")
      ->check(CLI::Range(0, 16))
      ->capture_default_str();
  cli.add_option("--size", size_text, "window size WxH, W and H in 64..8192")->capture_default_str();
  std::string restore_file;
  CLI::Option* restore = cli.add_option(
      "--restore", restore_file,
      "reopen a saved state: FILE (accelviz-cli check writes one per wrong ray), or without FILE the state the "
      "viewer had when its window last closed (" + viz::last_state_path() + ")");
  restore->expected(0, 1);
  std::string memory_limit_text;
  cli.add_option("--memory-limit", memory_limit_text,
                 "memory a structure build may use, e.g. 4G, 512M or 25% (default: 50% of physical memory); "
                 "as accelviz-cli's, also set in the Structure panel");
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);  // prints help, or the error naming the option
    return code == 0 ? 0 : 2;
  }
  if (restore->count() > 0) {
    options.restore = restore_file.empty() ? viz::last_state_path() : restore_file;
    if (restore_file.empty() && !std::filesystem::exists(options.restore)) {
      std::fprintf(stderr, "accelviz: --restore: no saved state at %s (the viewer saves one when its window closes)\n",
                   options.restore.c_str());
      return 2;
    }
  }
  const auto size = parse_size(size_text);
  if (!size) {
    std::fprintf(stderr, "accelviz: --size: expected WxH with W and H in %d..%d, got '%s'\n", kMinSize,
                 kMaxSize, size_text.c_str());
    return 2;
  }
  options.width = size->first;
  options.height = size->second;
  if (!memory_limit_text.empty()) {
    auto bytes = accel::parse_memory_size(memory_limit_text, "--memory-limit");
    if (!bytes) {
      std::fprintf(stderr, "accelviz: %s\n", bytes.error().message.c_str());
      return 2;
    }
    options.memory_limit = bytes.value();
  }
  if (!options.params.empty() && options.structure.empty()) {
    std::fprintf(stderr, "accelviz: --param: needs --structure NAME\n");
    return 2;
  }
  if (options.state != 0 && options.playlist.empty()) {
    std::fprintf(stderr, "accelviz: --state: needs --playlist FILE\n");
    return 2;
  }
  if (options.scene.empty()) {
    std::fprintf(stderr, "accelviz: no scene given and the core has no procedural scenes\n");
    return 2;
  }
  return std::nullopt;
}

// Fonts: DejaVu (most Linux desktops) at the normal and the lecture size, proportional and
// mono; ImGui's built-in font, scaled, where a file is missing.
viz::Fonts load_fonts(ImGuiIO& io) {
  auto load = [&io](const char* path, float size) -> ImFont* {
    if (std::FILE* f = std::fopen(path, "rb")) {
      std::fclose(f);
      return io.Fonts->AddFontFromFileTTF(path, size);
    }
    ImFontConfig config;
    config.SizePixels = size;
    return io.Fonts->AddFontDefault(&config);
  };
  const char* sans = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  const char* mono = "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf";
  viz::Fonts fonts;
  fonts.ui = load(sans, 18.0f);  // the first font added is ImGui's default
  fonts.ui_large = load(sans, 27.0f);
  fonts.mono = load(mono, 16.0f);
  fonts.mono_large = load(mono, 22.0f);
  return fonts;
}

/// One frame: events, ImGui, the app's update and draw. Returns the framebuffer size.
glm::ivec2 render_frame(GLFWwindow* window, viz::App& app, float dt) {
  glfwPollEvents();
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  app.update(dt);
  ImGui::Render();
  int fb_width = 0, fb_height = 0;
  glfwGetFramebufferSize(window, &fb_width, &fb_height);
  app.draw(fb_width, fb_height);
  if (app.wants_capture(false)) app.capture(false);  // a recording of the 3D view alone
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (app.wants_capture(true)) app.capture(true);    // with the panels; F12
  return {fb_width, fb_height};
}

/// Rendering for --script.
class WindowScriptHost final : public viz::ScriptHost {
 public:
  WindowScriptHost(GLFWwindow* window, viz::App& app) : window_(window), app_(app) {}

  accel::Status resize(int width, int height) override {
    glfwSetWindowSize(window_, width, height);
    // The X server answers asynchronously: wait (up to 2 s) until the framebuffer follows.
    for (int i = 0; i < 200; ++i) {
      glfwWaitEventsTimeout(0.01);
      const glm::ivec2 fb = framebuffer_size();
      if (fb.x == width && fb.y == height) return {};
    }
    const glm::ivec2 fb = framebuffer_size();
    return accel::make_error("size: the window stayed " + std::to_string(fb.x) + "x" + std::to_string(fb.y) +
                             " instead of " + std::to_string(width) + "x" + std::to_string(height));
  }

  void render(int frames) override {
    for (int i = 0; i < frames; ++i) {
      render_frame(window_, app_, dt());
      glfwSwapBuffers(window_);
    }
  }

  accel::Status screenshot(const std::string& path) override {
    // ImGui sizes auto-resized windows and scrolls lists one frame late: settle first.
    render(2);
    const glm::ivec2 fb = render_frame(window_, app_, dt());
    accel::Status st = viz::save_framebuffer_png(path, fb.x, fb.y);
    glfwSwapBuffers(window_);
    if (st) viz::browser::log_screenshot(path);  // the page: a test driving it keeps the PNG
    return st;
  }

  double measure_frames(int frames) override {
    render(3);  // warm up: uploads, shader compilation on first use
    viz::gl::wait_for_gpu();
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < frames; ++i) {
      render_frame(window_, app_, dt());
      viz::gl::wait_for_gpu();
      glfwSwapBuffers(window_);
    }
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / frames;
  }

  std::string gl_renderer() const override {
    const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return name != nullptr ? name : "unknown";
  }

  glm::ivec2 framebuffer_size() const override {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return {w, h};
  }

 private:
  // Real seconds since the previous frame, so the panel's frame time is true (the animation
  // does not advance on its own in script mode).
  float dt() {
    const double now = glfwGetTime();
    const float seconds = last_ < 0.0 ? 1.0f / 60.0f : static_cast<float>(now - last_);
    last_ = now;
    return seconds;
  }
  double last_ = -1.0;
  GLFWwindow* window_;
  viz::App& app_;
};

// Runs every command; the first error is printed as "accelviz: SCRIPT:LINE: message".
int run_script(const std::string& script_name, const std::vector<viz::ScriptCommand>& commands,
               GLFWwindow* window, viz::App& app) {
  WindowScriptHost host(window, app);
  host.render(1);
  for (const viz::ScriptCommand& command : commands) {
    if (const accel::Status st = app.execute(command, host); !st) {
      const std::string error = viz::script_error(script_name, command.line, st.error().message);
      std::fprintf(stderr, "accelviz: %s\n", error.c_str());
      viz::browser::log_line("script failed: " + error);
      return 2;
    }
  }
  viz::browser::log_line("script done");
  return 0;
}

/// --list: a Markdown table of the tools' rows. They need no window: an App without GL has them.
int print_list(const std::string& list) {
  const viz::App app;
  const std::string table = list == "commands"       ? viz::verbs_markdown(viz::script_verbs())
                            : list == "keys-summary" ? viz::keys_summary_markdown(app.key_groups())
                            : list == "mouse"        ? viz::mouse_markdown()
                                                     : viz::keys_markdown(app.key_groups());
  std::fputs(table.c_str(), stdout);
  return 0;
}

/// The commands to run once the window is up.
struct StartupCommands {
  std::vector<viz::ScriptCommand> script;   ///< --script's
  std::vector<viz::ScriptCommand> restore;  ///< --restore's: the state to reopen
};

// Parses --script and --restore before any window opens, so a typo or a stale or broken
// file is reported (with its line) first. A leading `size` sets the window's size from the
// start (no resize round trip). Returns an exit code when main() should stop.
std::optional<int> load_startup_commands(Options& options, StartupCommands& commands) {
  if (!options.script.empty()) {
    auto parsed = viz::load_script(options.script);
    if (!parsed) {
      std::fprintf(stderr, "accelviz: %s\n", parsed.error().message.c_str());
      viz::browser::log_line("script failed: " + parsed.error().message);
      return 2;
    }
    commands.script = std::move(parsed.value());
    // A leading `size` sets the window's size from the start (no resize round trip).
    for (const viz::ScriptCommand& c : commands.script) {
      if (c.verb == "size") {
        options.width = c.get<viz::SizeArgs>().width;
        options.height = c.get<viz::SizeArgs>().height;
      }
      if (c.verb != "size" && c.verb != "scene" && c.verb != "structure" && c.verb != "kernel") break;
    }
  }
  if (!options.restore.empty()) {
    auto parsed = viz::load_script(options.restore);
    if (!parsed) {
      std::fprintf(stderr, "accelviz: --restore: %s\n", parsed.error().message.c_str());
      return 2;
    }
    commands.restore = std::move(parsed.value());
  }
  return std::nullopt;
}

// Loads what the command line names into `app`: the structure, the scene, the bench file,
// the playlist. A bad one is the user's mistake (exit 2, "accelviz: FILE[:LINE]: ...")
// whether or not there is a display, and scripts get the same answer everywhere. The
// structure starts building in the background while the window opens (synchronously for a
// script); the playlist's first state runs once the window is up.
std::optional<int> load_command_line_inputs(const Options& options, viz::App& app) {
  app.set_synchronous(!options.script.empty());
  if (options.memory_limit) app.set_memory_limit(options.memory_limit);
  if (!options.structure.empty()) {
    if (const accel::Status st = app.set_structure(options.structure, options.params); !st) {
      std::fprintf(stderr, "accelviz: --structure: %s\n", st.error().message.c_str());
      return 2;
    }
  }
  accel::Status st = app.load_scene(options.scene);
  if (st && !options.bench_json.empty()) st = app.load_bench(options.bench_json);
  if (st && !options.playlist.empty()) {
    st = app.load_playlist(options.playlist);
    if (st && options.state != 0) st = app.go_to_state_number(options.state);
  }
  if (!st) {
    std::fprintf(stderr, "accelviz: %s\n", st.error().message.c_str());
    return 2;
  }
  return std::nullopt;
}

// A display and GLFW on it; false (after saying what to do instead) without one. Without a
// display GLFW would fail with an X11 message.
bool init_glfw(int argc, char** argv) {
  const std::string hint = "run it under a virtual display: xvfb-run -a " + command_line(argc, argv);
  if (!viz::browser::kInBrowser && !env_set("DISPLAY") && !env_set("WAYLAND_DISPLAY")) {
    std::fprintf(stderr, "accelviz: no display found (DISPLAY is not set); %s\n", hint.c_str());
    return false;
  }
  glfwSetErrorCallback(glfw_error_callback);
  if (!glfwInit()) {
    const char* description = last_glfw_error();
    std::fprintf(stderr, "accelviz: no display found (GLFW: %s); %s\n",
                 description != nullptr ? description : "glfwInit failed", hint.c_str());
    return false;
  }
  report_glfw_errors = true;
  return true;
}

// The window with an OpenGL 3.3 core context, current, its functions loaded; nullptr (after
// one line saying why, GLFW terminated) when that fails.
GLFWwindow* create_window(const Options& options, bool headless) {
  // OpenGL 3.3 core: what glad was generated for and what the shaders' #version says.
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, options.msaa);  // smooth edges on a projector; ignored if unsupported
  // A screenshot must have exactly the requested size: keep window managers from resizing
  // (a script's `size` command still resizes it).
  if (headless) glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  report_glfw_errors = false;  // a failure here gets its own single line below
  GLFWwindow* window = glfwCreateWindow(options.width, options.height, "accelviz", nullptr, nullptr);
  report_glfw_errors = true;
  if (window == nullptr) {
    const char* description = last_glfw_error();
    std::fprintf(stderr, "accelviz: cannot create an OpenGL 3.3 core window (GLFW: %s)\n",
                 description != nullptr ? description : "unknown error");
    glfwTerminate();
    return nullptr;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(headless ? 0 : 1);  // vsync when interactive; no waiting otherwise

  // glad serves our renderer only; ImGui's OpenGL3 backend loads its own functions.
  if (!viz::gl::load_functions(glfwGetProcAddress)) {
    std::fprintf(stderr, "accelviz: cannot load OpenGL 3.3 functions\n");
    glfwDestroyWindow(window);
    glfwTerminate();
    return nullptr;
  }
  return window;
}

// ImGui's context, style and backends on `window`. Larger, smooth fonts read at the back of
// a lecture hall; the lecture mode (L) switches to the larger size.
viz::Fonts init_imgui(GLFWwindow* window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini in whatever directory we were started from
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 4.0f;
  style.FrameRounding = 3.0f;
  style.ScaleAllSizes(1.25f);
  const viz::Fonts fonts = load_fonts(io);

  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init(viz::gl::kImGuiGlslVersion);
  return fonts;
}

// --screenshot: ImGui needs a frame or two to size its windows, hence --frames. The back
// buffer holds the finished frame until the swap: read it then. Returns the exit code.
int take_screenshot(GLFWwindow* window, viz::App& app, const Options& options) {
  glm::ivec2 fb{0, 0};
  for (int frame = 0; frame < options.frames; ++frame) {
    fb = render_frame(window, app, 1.0f / 60.0f);
    if (frame + 1 < options.frames) glfwSwapBuffers(window);
  }
  if (fb.x != options.width || fb.y != options.height) {
    std::fprintf(stderr, "accelviz: warning: framebuffer is %dx%d, not the requested %dx%d\n", fb.x, fb.y,
                 options.width, options.height);
  }
  if (const accel::Status st = viz::save_framebuffer_png(options.screenshot, fb.x, fb.y); !st) {
    std::fprintf(stderr, "accelviz: %s\n", st.error().message.c_str());
    return 1;
  }
  return 0;
}

// Once the window is up: the app's GL, then the state to reopen, the script, the
// screenshot. Returns the exit code; the window is told to close when nothing is left to do.
int run_startup(GLFWwindow* window, viz::App& app, const Options& options, const StartupCommands& commands,
                const std::string& shader_dir, const viz::Fonts& fonts) {
  const bool script_mode = !options.script.empty();
  if (const accel::Status st = app.init(window, shader_dir, fonts); !st) {
    std::fprintf(stderr, "accelviz: %s\n", st.error().message.c_str());
    glfwSetWindowShouldClose(window, GLFW_TRUE);
    return 1;
  }
  viz::browser::log_line("ready");  // the page is up (a test waits for this)
  if (!commands.restore.empty()) {
    app.set_synchronous(true);  // the ray is traced on the structure the file names
    const int exit_code = run_script(options.restore, commands.restore, window, app);
    app.set_synchronous(script_mode);
    if (exit_code != 0) {
      glfwSetWindowShouldClose(window, GLFW_TRUE);
      return exit_code;
    }
  }
  int exit_code = 0;
  if (script_mode) {
    exit_code = run_script(options.script, commands.script, window, app);
    // The page stays open on the script's last state (the window has nowhere to go).
    if (viz::browser::kInBrowser) app.set_synchronous(false);  // from here on, used by hand
    else glfwSetWindowShouldClose(window, GLFW_TRUE);
  }
  if (exit_code == 0 && !options.screenshot.empty()) {
    exit_code = take_screenshot(window, app, options);
    glfwSetWindowShouldClose(window, GLFW_TRUE);
  }
  return exit_code;
}

// Frames until the window closes. The page: after each frame the background tasks (builds
// and the like) get part of the frame's time, and the loop waits for the browser's next frame.
void run_loop(GLFWwindow* window, viz::App& app) {
  double last_time = glfwGetTime();
  double background_ms = kBackgroundMsMin;
  while (!glfwWindowShouldClose(window)) {
    // Minimised: nothing to draw, so sleep until something happens.
    if (glfwGetWindowAttrib(window, GLFW_ICONIFIED) != 0) {
      glfwWaitEvents();
      last_time = glfwGetTime();  // the sleep is not a frame
      continue;
    }
    const double now = glfwGetTime();
    const float dt = static_cast<float>(now - last_time);
    last_time = now;
    viz::browser::run_background_tasks(background_ms);
    const double render_start = glfwGetTime();
    render_frame(window, app, dt);
    glfwSwapBuffers(window);
    background_ms = std::clamp(1000.0 * (glfwGetTime() - render_start), kBackgroundMsMin, kBackgroundMsMax);
    viz::browser::wait_for_next_frame();
  }
}

// Cleanup in reverse. A session used by hand (`used_by_hand`: not a script, a screenshot or
// the page, and nothing failed) first leaves its state for --restore.
void shut_down(GLFWwindow* window, viz::App& app, bool used_by_hand) {
  if (used_by_hand && !viz::last_state_path().empty())
    if (const accel::Status st = app.save_state(viz::last_state_path()); !st)
      std::fprintf(stderr, "accelviz: %s\n", st.error().message.c_str());
  app.shutdown();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (const auto code = parse_command_line(argc, argv, options)) return *code;
  if (!options.list.empty()) return print_list(options.list);
  accel::prepare_for_builds();  // before the scene load: its freed memory serves the builds
  viz::browser::install_input_fetcher();  // the page: files next to it are fetched when opened
  const bool headless = !options.screenshot.empty() || !options.script.empty();

  // The script and the state to reopen first, then the scene and the other files: every
  // mistake of the command line is reported before any window opens.
  StartupCommands commands;
  if (const auto code = load_startup_commands(options, commands)) return *code;
  viz::App app;
  if (const auto code = load_command_line_inputs(options, app)) return *code;
  const auto shader_dir = viz::find_shader_dir(viz::Renderer::shader_files());
  if (!shader_dir) {
    std::fprintf(stderr, "accelviz: %s\n", shader_dir.error().message.c_str());
    return 1;
  }

  if (!init_glfw(argc, argv)) return 1;
  GLFWwindow* window = create_window(options, headless);
  if (window == nullptr) return 1;
  const viz::Fonts fonts = init_imgui(window);
  app.set_ui_visible(!options.no_ui);
  const int exit_code = run_startup(window, app, options, commands, shader_dir.value(), fonts);
  run_loop(window, app);
  shut_down(window, app, exit_code == 0 && !headless && !viz::browser::kInBrowser);
  return exit_code;
}
