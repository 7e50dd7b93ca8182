// App, part 1: lifecycle, the per-frame loop over the tools, the keys and drawing. The
// tools do the work, in the list's order (tools/tool_list.cpp); App passes them the frame.
#include "app.h"

#include <algorithm>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "check.h"
#include "global_verbs.h"
#include "registry.h"
#include "script_verbs.h"
#include "tools/bench_chart_tool.h"
#include "tools/node_display.h"
#include "tools/playlist_tool.h"
#include "tools/recorder.h"
#include "tools/structure_session.h"
#include "tools/tool_list.h"

namespace viz {
namespace {

// Weight of the newest frame in the smoothed frame time: about the last 20 frames count,
// so the number is readable yet follows a change within a fraction of a second.
constexpr double kTimingSmoothing = 0.05;

}  // namespace

// ---------------------------------------------------------------------------------------
// Lifecycle

App::App() : tools_(make_tools()) {
  for (const auto& tool : tools_) tool_list_.push_back(tool.get());
  ToolHost& host = *this;
  // The order a key press is offered in: App's own keys, then the tools' in the list's
  // order (the playlist's PgDn / PgUp before the construction's).
  key_groups_.push_back(global_keys());
  for (Tool* tool : tool_list_)
    if (std::vector<KeyBinding> rows = tool->keys(host); !rows.empty()) key_groups_.push_back({tool->name(), rows});
  // Every verb bound to whoever runs it: App's own, then the tools'.
  ToolVerbs<App> own_verbs(verbs_, *this, host);
  global_verbs(own_verbs);
  for (Tool* tool : tool_list_) tool->add_verbs(verbs_, host);
  // Exactly the verbs the parser knows (script_verbs.h): none parses without a run, and the
  // catalogue's order (the docs') need not be the tools'.
  const VerbTable& catalogue = script_verbs();
  ACCEL_CHECK(verbs_.size() == catalogue.size());
  for (size_t i = 0; i < catalogue.size(); ++i) ACCEL_CHECK(verbs_.find(catalogue[i].name) != nullptr);
}

App::~App() { shutdown(); }

void App::set_synchronous(bool synchronous) {
  synchronous_ = synchronous;
  session().set_synchronous(synchronous);
}

void App::set_memory_limit(size_t bytes) { session().set_memory_limit(bytes); }

accel::Status App::load_scene(const std::string& spec) {
  accel::Status st = session().load_scene(spec);
  sync_session();
  return st;
}

accel::Status App::load_bench(const std::string& path) { return tool<BenchChartTool>().load(path); }

accel::Status App::init(GLFWwindow* window, const std::string& shader_dir, const Fonts& fonts) {
  window_ = window;
  layout_.set_fonts(fonts);
  auto renderer = Renderer::create(shader_dir);
  if (!renderer) return renderer.error();
  renderer_.emplace(std::move(renderer.value()));
  for (Tool* tool : tool_list_) tool->init_gl();

  // GLFW callbacks are plain functions: the window's user pointer leads back to us.
  // ImGui's GLFW backend does not use the user pointer, and installs no drop callback.
  glfwSetWindowUserPointer(window, this);
  glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
    // Several files dropped at once: one scene is shown at a time, take the first.
    if (count > 0) static_cast<App*>(glfwGetWindowUserPointer(w))->session().request_load(paths[0]);
  });
  // Shortcuts are taken from key events rather than ImGui::IsKeyPressed(): ImGui 1.86 only
  // samples key state once per frame, so a quick tap between two slow frames (a big scene
  // on a lecture laptop) would be lost. ImGui's own callback still runs first. Repeats
  // count too: holding the right arrow steps through the trace.
  previous_key_callback_ = glfwSetKeyCallback(
      window, [](GLFWwindow* w, int key, int scancode, int action, int mods) {
        App* app = static_cast<App*>(glfwGetWindowUserPointer(w));
        if (app->previous_key_callback_ != nullptr) app->previous_key_callback_(w, key, scancode, action, mods);
        if (action == GLFW_PRESS || action == GLFW_REPEAT) app->pressed_keys_.push_back({key, mods});
      });
  refresh_title();
  return {};
}

void App::shutdown() {
  // Background jobs first: they may still read the scene and structure. GL objects next:
  // their destructors call into the context main() destroys next.
  for (Tool* tool : tool_list_) tool->wait();
  for (auto it = tool_list_.rbegin(); it != tool_list_.rend(); ++it) (*it)->release_gl();
  renderer_.reset();
  if (window_ != nullptr) {
    // Reverse order of init(): ImGui's shutdown then restores the callbacks it replaced.
    glfwSetKeyCallback(window_, previous_key_callback_);
    previous_key_callback_ = nullptr;
    glfwSetDropCallback(window_, nullptr);
    glfwSetWindowUserPointer(window_, nullptr);
    window_ = nullptr;
  }
}

void App::refresh_title() {
  if (window_ == nullptr) return;
  // With a playlist the title names the state too (what the window manager's task bar and
  // the keyboard test read).
  std::string title;
  for (Tool* tool : tool_list_) tool->window_title(title, *this);
  if (title != window_title_) {
    window_title_ = title;
    glfwSetWindowTitle(window_, title.c_str());
  }
}

void App::resize_window(int width, int height) {
  if (window_ != nullptr) glfwSetWindowSize(window_, width, height);
}

void App::notify(ToolEvent event) {
  if (event == ToolEvent::SceneLoaded) {
    camera_.camera().set_top_down(session().scene().planar());  // a 2D scene: the blackboard's view
    camera_.request_frame();
  }
  for (Tool* tool : tool_list_) tool->on_event(event, *this);
  if (event != ToolEvent::RayChanged) refresh_title();
}

accel::Status App::set_structure(const std::string& name, const std::vector<std::string>& params) {
  if (auto choice = accel::parse_structure(name, params); !choice) return choice.error();
  session().switch_structure(name, params);
  sync_session();
  return {};
}

accel::Status App::go_to_state_number(size_t number) {
  const size_t count = tool<PlaylistTool>().playlist().states.size();
  if (count == 0) return accel::make_error("--state: no playlist loaded (use --playlist FILE)");
  if (number < 1 || number > count)
    return accel::make_error("--state: expected a state 1.." + std::to_string(count) + ", got " + std::to_string(number));
  go_to_state(number - 1);
  return {};
}

void App::capture(bool with_ui) { tool<Recorder>().capture(with_ui, layout_.view(), layout_.framebuffer()); }
bool App::wants_capture(bool with_ui) const { return tool<Recorder>().wants_capture(with_ui); }

// ---------------------------------------------------------------------------------------
// Per frame

void App::update(float dt) {
  ToolHost& host = *this;
  update_shortcuts();
  const MouseFrame mouse = camera_.update();
  for (Tool* tool : tool_list_) tool->mouse(mouse, host);
  update_timing(dt);
  layout_.begin_frame();
  // Nothing advances on its own in script mode: the commands move the animation.
  for (Tool* tool : tool_list_) tool->update(host, synchronous_ ? 0.0f : dt);
  if (!synchronous_) refresh_title();  // the playlist's state, a recording (cheap: set on change)
  if (layout_.ui_visible()) {
    layout_.layout_windows();
    if (layout_.panels().main) main_panel();
    for (Tool* tool : tool_list_) tool->panels(host);
  }
  for (Tool* tool : tool_list_) tool->overlay(host);
  sync_session();  // the panels may have loaded a scene or switched the structure
  layout_.end_frame();
  for (Tool* tool : tool_list_) tool->late_update(host);
}

void App::update_timing(float dt) {
  const double frame_ms = 1000.0 * static_cast<double>(dt);
  timing_.frame_ms = timing_.frame_ms == 0.0
                         ? frame_ms
                         : (1.0 - kTimingSmoothing) * timing_.frame_ms + kTimingSmoothing * frame_ms;
  timing_.fps = timing_.frame_ms > 0.0 ? 1000.0 / timing_.frame_ms : 0.0;
}

void App::update_shortcuts() {
  std::vector<KeyPress> keys;
  keys.swap(pressed_keys_);
  // Typing "f" into the OBJ path field must not reframe the scene.
  if (ImGui::GetIO().WantCaptureKeyboard) return;
  for (const KeyPress& k : keys) dispatch_key(key_groups_, k);
}

KeyGroup App::global_keys() {
  auto act = [](std::function<void()> fn) {
    return [fn](const KeyPress&) {
      fn();
      return true;
    };
  };
  return {"viewer",
          {
              {GLFW_KEY_F, "F", "frame the scene", act([this] { camera_.request_frame(); })},
              {GLFW_KEY_H, "H", "hide / show the panels", act([this] { layout_.set_ui_visible(!layout_.ui_visible()); })},
              {GLFW_KEY_L, "L", "lecture mode: large fonts, high contrast, controls collapsed",
               act([this] { layout_.set_lecture(!layout_.lecture()); })},
          }};
}

// ---------------------------------------------------------------------------------------
// Drawing

void App::draw(int framebuffer_width, int framebuffer_height) {
  if (!renderer_ || framebuffer_width <= 0 || framebuffer_height <= 0) return;
  ToolHost& host = *this;
  // Uploads before the frame begins, in the order the tools draw.
  for (Tool* tool : tool_list_) tool->sync_gl(*renderer_, host);
  // The view keeps its rectangle from update(); clamp it to this framebuffer.
  layout_.clamp_to({framebuffer_width, framebuffer_height});
  const float aspect = layout_.view_aspect();
  // Frame once the panels are placed: the view's rectangle (and aspect) is known then, so
  // the scene is framed into the part of the window the panels leave free.
  camera_.frame_if_requested(session().scene(), aspect, !layout_.ui_visible() || layout_.settled());
  const Camera& camera = camera_.camera();
  const glm::ivec4 view_rect = layout_.view();
  FrameView view;
  view.view = camera.view();
  view.projection = camera.projection(aspect);
  view.eye = camera.eye();
  view.viewport = layout_.view_size();
  view.origin = {view_rect.x, framebuffer_height - view_rect.y - view_rect.w};
  renderer_->begin_frame(view, layout_.background());
  // Under: the blackboard's grid and the mesh (translucent too: it writes depth, so nodes
  // and highlights behind it are drawn faintly by the x-ray passes and those in front stay
  // crisp); then the structure and the highlights; over them the bounds, the corners and
  // the heat map.
  for (DrawLayer layer : {DrawLayer::Under, DrawLayer::Scene, DrawLayer::Over})
    for (Tool* tool : tool_list_) tool->draw(*renderer_, host, layer);
  renderer_->end_frame();
}

}  // namespace viz
