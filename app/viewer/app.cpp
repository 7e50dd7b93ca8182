// App, part 1: lifecycle and the rows, the per-frame update (session events, input, the
// keys) and drawing. The tools do the work; App passes each what it needs from the others.
#include "app.h"

#include <algorithm>
#include <cmath>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "bench_chart_panel.h"
#include "check.h"
#include "registry.h"
#include "scene2d.h"
#include "script_verbs.h"

namespace viz {
namespace {

// Weight of the newest frame in the smoothed frame time: about the last 20 frames count,
// so the number is readable yet follows a change within a fraction of a second.
constexpr double kTimingSmoothing = 0.05;

float aspect_of(glm::ivec2 size) { return static_cast<float>(size.x) / static_cast<float>(std::max(size.y, 1)); }

}  // namespace

// ---------------------------------------------------------------------------------------
// Lifecycle

App::App() {
  ToolHost& host = *this;
  // The order a key press is offered in: the playlist's PgDn / PgUp before the
  // construction's, which have them without a playlist or with shift.
  key_groups_ = {
      global_keys(),        ray_.key_bindings(),      compare_.key_bindings(host),  heatmap_.key_bindings(),
      vars_.key_bindings(), tree_.key_bindings(host), playlist_.key_bindings(host), build_.key_bindings(host)};
  // The verbs in the catalogue's order (script_verbs.h), each bound to whoever runs it.
  ToolVerbs<App> own_verbs(verbs_, *this, host);
  global_verbs(own_verbs);
  session_.add_verbs(verbs_, host);
  ray_.add_verbs(verbs_, host);
  blackboard_verbs(own_verbs);
  nodes_.add_verbs(verbs_, host);
  heatmap_.add_verbs(verbs_, host);
  compare_.add_verbs(verbs_, host);
  sweep_.add_verbs(verbs_, host);
  build_.add_verbs(verbs_, host);
  tree_.add_verbs(verbs_, host);
  trap_.add_verbs(verbs_, host);
  playlist_.add_verbs(verbs_, host);
  recorder_.add_verbs(verbs_, host);
  add_bench_chart_verbs(verbs_, chart_, host);
  // Exactly the verbs the parser knows, in its order: none parses without a run.
  const VerbTable& catalogue = script_verbs();
  ACCEL_CHECK(verbs_.size() == catalogue.size());
  for (size_t i = 0; i < catalogue.size(); ++i) ACCEL_CHECK(std::string_view(verbs_[i].name) == catalogue[i].name);
}

App::~App() { shutdown(); }

void App::set_synchronous(bool synchronous) {
  synchronous_ = synchronous;
  session_.set_synchronous(synchronous);
}

accel::Status App::load_scene(const std::string& spec) {
  accel::Status st = session_.load_scene(spec);
  sync_session();
  return st;
}

accel::Status App::init(GLFWwindow* window, const std::string& shader_dir, const Fonts& fonts) {
  window_ = window;
  fonts_ = fonts;
  auto renderer = Renderer::create(shader_dir);
  if (!renderer) return renderer.error();
  renderer_.emplace(std::move(renderer.value()));
  session_.init_gl();
  board_lines_.emplace(GL_LINES);
  nodes_.init_gl();
  ray_.init_gl();
  build_.init_gl();
  heatmap_.init_gl();
  tree_.init_gl();

  // GLFW callbacks are plain functions: the window's user pointer leads back to us.
  // ImGui's GLFW backend does not use the user pointer, and installs no drop callback.
  glfwSetWindowUserPointer(window, this);
  glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
    // Several files dropped at once: one scene is shown at a time, take the first.
    if (count > 0) static_cast<App*>(glfwGetWindowUserPointer(w))->request_load(paths[0]);
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
  update_window_title();
  return {};
}

void App::shutdown() {
  // Background jobs first: they may still read the scene and structure.
  session_.wait();
  build_.wait();
  heatmap_.wait();
  compare_.wait();
  sweep_.wait();
  // GL objects next: their destructors call into the context main() destroys next.
  heatmap_.release_gl();
  tree_.release_gl();
  ray_.release_gl();
  build_.release_gl();
  nodes_.release_gl();
  session_.release_gl();
  board_lines_.reset();
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

void App::update_window_title() {
  if (window_ == nullptr) return;
  // With a playlist the title names the state too (what the window manager's task bar and
  // the keyboard test read).
  std::string title = session_.window_title();
  if (recorder_.recording()) title += " - recording (R stops)";
  if (playlist_.loaded()) {
    title += " - " + playlist_.state_line();
    if (playlist_.has_pending()) title += " (loading)";
    else if (!playlist_.error().empty()) title += " (error)";
  }
  if (title != window_title_) {
    window_title_ = title;
    glfwSetWindowTitle(window_, title.c_str());
  }
}

// ---------------------------------------------------------------------------------------
// What the tools tell each other

void App::sync_session() {
  const SessionEvents e = session_.take_events();
  if (e.scene_loaded) {
    // A new scene: the old ray, its comparison and the heat map no longer mean anything.
    ray_.reset();
    build_.reset();
    trap_.on_scene_loaded(session_.scene_info().spec);
    compare_.clear();
    heatmap_.invalidate();
    board_.clear();
    camera_.set_top_down(session_.scene().planar());  // a 2D scene: the blackboard's view
    const std::string& spec = session_.scene_info().spec;
    if (!session_.scene().planar()) last_3d_scene_ = spec;
    else if (spec.ends_with(accel::kScene2dExtension)) board_path_ = spec;  // saved back where it came from
    frame_scene();
  }
  if (e.scene_edited) {  // the blackboard changed: the ray stays and replays on the new structure
    build_.reset();
    compare_.clear();
    heatmap_.invalidate();
  }
  if (e.structure_installed) {
    static const BuiltStructure kNothing;  // a failed build's replay: no structure to draw
    nodes_.install(session_.shown() ? *session_.shown() : kNothing);
    ray_.replay(session_.current());
    build_.reset();  // recorded on another structure
  }
  if (e.scene_loaded || e.scene_edited || e.structure_installed) update_window_title();
}

accel::Status App::apply_preset(const Preset& preset) {
  accel::Status st = session_.load_preset_scene(preset);
  sync_session();
  if (!st) return st;  // the error is shown in the panel
  const accel::Aabb bounds = session_.scene().bounds();
  if (preset.has_camera) {
    camera_.look_at(preset.eye, preset.target, preset.fovy_deg, bounds);
    frame_requested_ = false;
  }
  ray_.save_view(camera_.pinhole());
  if (preset.has_ray) {
    accel::Ray ray;
    ray.org = preset.ray_origin;
    ray.dir = glm::normalize(preset.ray_target - preset.ray_origin);
    set_ray(ray, "preset " + preset.name);
  } else {
    camera_.frame(frame_box(), aspect_of(view_size()));
    frame_requested_ = false;
    shoot_at_pixel(static_cast<float>(view_.x) + 0.5f * static_cast<float>(view_.z),
                   static_cast<float>(view_.y) + 0.5f * static_cast<float>(view_.w), false);
  }
  return {};
}

void App::shoot_at_pixel(float px, float py, bool from_saved_view) {
  ray_.shoot(camera_.pinhole(), view_, px, py, from_saved_view, session_.current());
  if (compare_.open()) start_compare();
}

void App::set_ray(const accel::Ray& ray, const std::string& origin) {
  ray_.set_ray(ray, origin, session_.current());
  if (compare_.open()) start_compare();
}

void App::start_compare() {
  if (!ray_.ray().active) return;
  compare_.start(session_.scene_ptr(), ray_.ray().ray, session_.current_request(), session_.current_ptr(),
                 synchronous_);
}

accel::Status App::start_sweep() {
  return sweep_.start(session_.editor_info(), session_.scene_ptr(), session_.editor_request(), camera_.pinhole(),
                      synchronous_);
}

accel::Status App::load_trap(const std::string& name) {
  auto found = accel::trap_demo(name);
  if (!found) return found.error();
  const accel::TrapDemo& demo = found.value();
  if (auto st = load_scene(demo.scene); !st) return st;
  session_.switch_structure(demo.structure, demo.params);
  sync_session();
  if (auto st = loaded(); !st) return st;
  trap_.set_demo(demo);
  set_ray(demo.ray, "trap " + demo.name);
  return {};
}

// ---------------------------------------------------------------------------------------
// The lecture playlist and the recording

namespace {

/// ScriptHost for a playlist state run in the window: the frames come from the main loop
/// (one command per frame), so rendering commands have nothing to wait for.
class InteractiveHost final : public ScriptHost {
 public:
  InteractiveHost(GLFWwindow* window, glm::ivec2 framebuffer, Recorder& recorder)
      : window_(window), framebuffer_(framebuffer), recorder_(recorder) {}
  accel::Status resize(int width, int height) override {
    if (window_ != nullptr) glfwSetWindowSize(window_, width, height);
    return {};
  }
  void render(int) override {}
  accel::Status screenshot(const std::string&) override {
    recorder_.request_screenshot();  // written at the end of this frame, numbered
    return {};
  }
  double measure_frames(int) override { return 0.0; }
  glm::ivec2 framebuffer_size() const override { return framebuffer_; }
  std::string gl_renderer() const override { return ""; }

 private:
  GLFWwindow* window_;
  glm::ivec2 framebuffer_;
  Recorder& recorder_;
};

}  // namespace

accel::Status App::set_structure(const std::string& name, const std::vector<std::string>& params) {
  if (auto choice = accel::parse_structure(name, params); !choice) return choice.error();
  switch_structure({name, params});
  sync_session();
  return {};
}

accel::Status App::go_to_state_number(size_t number) {
  const size_t count = playlist_.playlist().states.size();
  if (count == 0) return accel::make_error("--state: no playlist loaded (use --playlist FILE)");
  if (number < 1 || number > count)
    return accel::make_error("--state: expected a state 1.." + std::to_string(count) + ", got " + std::to_string(number));
  go_to_state(number - 1);
  return {};
}

accel::Status App::load_playlist(const std::string& path) {
  if (auto st = playlist_.load(path); !st) return st;
  go_to_state(0);
  return {};
}

void App::go_to_state(size_t index) {
  if (playlist_.go(index)) reset_for_playlist();
  update_window_title();
}

void App::reset_for_playlist() {
  // Going back replays from the first state: what a state may have changed returns to the
  // viewer's defaults first (the scene, structure and ray come from the states themselves).
  panels_ = Panels{};
  vars_.set_shown(true);
  vars_.set_strip_shown(true);
  ui_visible_ = true;
  tree_.set_on(false);
  heatmap_.set_on(false);
  compare_.set_open(false);
  sweep_.set_open(false);
  build_.set_active(false);
  trap_.set_open(true);
  nodes_.show_all();
  nodes_.set_visible(true);
  nodes_.set_opacity(0.55f);
  nodes_.set_mesh_mode(MeshStyle::Mode::Solid);
  layout_frames_ = 2;
}

void App::run_playlist(ScriptHost* host) {
  while (playlist_.has_pending()) {
    // In the window: one command per frame, and none while a build runs (the next one
    // needs its structure); the window stays live meanwhile.
    if (!host && (session_.building() || build_.recording())) return;
    const PlaylistTool::Pending next = playlist_.front();
    playlist_.pop();
    InteractiveHost interactive(window_, framebuffer_, recorder_);
    ScriptHost& h = host ? *host : interactive;
    if (auto st = execute(*next.command, h); !st) {
      playlist_.fail(script_error(playlist_.playlist().name, next.command->line, st.error().message));
      return;
    }
    sync_session();
    if (!host) return;
  }
}

void App::walk_recorded(accel::PlaybackClock& clock, size_t from, ScriptHost& host) {
  if (!recorder_.recording()) return;
  // A recording holds one frame per step: walk there one step and one frame at a time.
  const size_t to = clock.step();
  while (from != to) {
    from = from < to ? from + 1 : from - 1;
    clock.seek(from);
    host.render(1);
  }
}

void App::settle_camera(ScriptHost& host) {
  // The camera as it will be drawn: framing waits for the first draw (it needs the aspect
  // ratio), but a ray shot before that must use the framed camera too. The frames lay the
  // panels out (the 3D view's rectangle) and frame a new scene.
  host.render(layout_frames_ + 1);
}

accel::Status App::toggle_recording() {
  if (recorder_.recording()) return recorder_.stop();
  return recorder_.start(recorder_.path_field(), recorder_.options());
}

HeatmapView App::heatmap_view() const { return {camera_.pinhole(), session_.current_ptr(), view_size()}; }

// ---------------------------------------------------------------------------------------
// Per frame

void App::update(float dt) {
  session_.poll();
  sync_session();
  compare_.poll();
  build_.poll();
  update_camera_input();
  update_shortcuts();
  if (!synchronous_ && playlist_.loaded()) run_playlist(nullptr);
  if (!synchronous_) update_window_title();  // the playlist's state, a recording (cheap: set on change)
  // A new step of the animation (traversal or construction) is a new frame of a recording.
  const StepSeen seen{ray_.player().step(), build_.player().step(), build_.active()};
  if (!(seen == step_seen_)) {
    step_seen_ = seen;
    recorder_.step_changed();
  }

  const double frame_ms = 1000.0 * static_cast<double>(dt);
  timing_.frame_ms = timing_.frame_ms == 0.0
                         ? frame_ms
                         : (1.0 - kTimingSmoothing) * timing_.frame_ms + kTimingSmoothing * frame_ms;
  timing_.fps = timing_.frame_ms > 0.0 ? 1000.0 / timing_.frame_ms : 0.0;

  if (!synchronous_) {
    ray_.advance(static_cast<double>(dt));
    build_.advance(static_cast<double>(dt));
  }
  heatmap_.update(dt, heatmap_view());

  tree_.update(session_.current_ptr(), ray_.ray(), build_.active() ? build_.replay() : nullptr);
  apply_lecture_mode();
  const ImGuiIO& io = ImGui::GetIO();
  dock_ = {0.0f, io.DisplaySize.x};
  // The highlights (and the numbers the panels show) of the step this frame starts at.
  ray_.update(session_.scene(), session_.current());
  trap_.update(ray_.ray(), session_.scene(), session_.current());
  ray_.set_marked_step(trap_.marked_step(), "a naive traversal stops here");
  // The Variables panel shares the left column with the controls in the traversal mode
  // only; when it comes or goes the controls change height: lay out again.
  const bool vars_column = vars_.shown() && !build_.active() && !build_.recording();
  if (vars_column != vars_column_) {
    vars_column_ = vars_column;
    layout_frames_ = 2;
  }
  if (ui_visible_) {
    layout_windows();
    if (panels_.main) main_panel();
    const BuiltStructure* shown = session_.shown();
    ImFont* mono = lecture_mode_ ? fonts_.mono_large : fonts_.mono;
    if (build_.active() || build_.recording()) {  // the construction mode takes the traversal panels' places
      // The construction panel also holds the SAH cost plot: it takes a third of the code
      // panel's height (in lecture mode's large fonts the plot was cut off).
      WindowRect control = layout_.ray, code = layout_.code;
      const float moved = std::round(code.size.y / 3.0f);
      control.size.y += moved;
      code.pos.y += moved;
      code.size.y -= moved;
      if (panels_.ray) build_.control_panel(place(control), session_.scene_ptr(), session_.current_request());
      if (panels_.steps) build_.steps_panel(place(layout_.steps));
      if (panels_.code) build_.code_panel(place(code), mono);
    } else {
      if (panels_.ray && ray_.ray_panel(place(layout_.ray), shown, mode_2d())) {
        compare_.set_open(true);
        start_compare();
      }
      if (panels_.steps) ray_.steps_panel(place(layout_.steps), mode_2d());
      if (panels_.code) ray_.code_panel(place(layout_.code), shown, mono);
      WindowRect vars_rect = layout_.vars;
      if (lecture_mode_ && tree_.on())
        vars_rect.size.y = std::max(layout_.tree.pos.y - vars_rect.pos.y - layout_.main.pos.y, 6.0f * ImGui::GetFontSize());
      if (vars_.shown())
        vars_.panel(place(vars_rect), ray_.ray(), ray_.step_highlight(),
                    shown ? shown->kind : TraversalKind::Unknown, mode_2d(), mono,
                    [&] { trap_.block(ray_.ray(), ray_.player()); });
    }
    if (compare_.open()) {
      if (auto choice = compare_.panel(place(layout_.bottom, false), shown, ray_.ray().ray)) switch_structure(*choice);
      if (auto step = compare_.take_seek(); step && ray_.ray().active) ray_.player().seek(*step);
    }
    if (sweep_.open()) {
      WindowRect rect = layout_.bottom;
      if (compare_.open()) rect.pos.y -= rect.size.y + 0.4f * ImGui::GetFontSize();  // stacked above the compare table
      sweep_.panel(place(rect, false));
    }
    if (panels_.legend && heatmap_.on()) {
      const std::string noun = shown ? shown->info->node_noun : "nodes";
      heatmap_.legend(place({layout_.legend.pos, {0.0f, 0.0f}}, false), noun, heatmap_view());
    }
    if (tree_.on()) {  // docks along the bottom; the whole width when the left column is empty
      WindowRect rect = layout_.tree;
      // In lecture mode the controls are collapsed: the tree takes the whole width and the
      // Variables panel the column above it (its larger font needs the room more).
      if ((!panels_.main && !vars_.shown()) || lecture_mode_) {
        rect.size.x += rect.pos.x - layout_.main.pos.x;
        rect.pos.x = layout_.main.pos.x;
      }
      tree_.panel(place(rect));
    }
    bench_chart_window(chart_, layout_.chart.pos, layout_.chart.size, layout_apply_);
    if (vars_.strip_shown() && !build_.active()) traversal_numbers();
  }
  status_overlay();
  sync_session();  // the panels may have loaded a scene or switched the structure
  view_ = view_rect(dock_, {io.DisplaySize.x, io.DisplaySize.y}, {io.DisplayFramebufferScale.x, io.DisplayFramebufferScale.y},
                    ui_visible_);
  const float sx = io.DisplayFramebufferScale.x > 0.0f ? io.DisplayFramebufferScale.x : 1.0f;
  const float sy = io.DisplayFramebufferScale.y > 0.0f ? io.DisplayFramebufferScale.y : 1.0f;
  const glm::ivec2 fb(static_cast<int>(std::lround(io.DisplaySize.x * sx)), static_cast<int>(std::lround(io.DisplaySize.y * sy)));
  if (fb.x > 0 && fb.y > 0) framebuffer_ = fb;
  ray_.update(session_.scene(), session_.current());
  build_.update();
}

void App::update_camera_input() {
  const ImGuiIO& io = ImGui::GetIO();
  // The mouse belongs to ImGui while it hovers a window or drags a widget; a drag that
  // started over the scene keeps going even when it crosses a panel. Click or drag is
  // judged from the press and release positions (ClickTracker), never from the deltas.
  const ClickResult r = click_.update(io.MouseDown[ImGuiMouseButton_Left], {io.MousePos.x, io.MousePos.y},
                                      static_cast<double>(ImGui::GetTime()), !io.WantCaptureMouse);
  const ClickResult right = right_click_.update(io.MouseDown[ImGuiMouseButton_Right], {io.MousePos.x, io.MousePos.y},
                                                static_cast<double>(ImGui::GetTime()), !io.WantCaptureMouse);
  if (camera_.top_down()) update_board_input(r, right);  // 2D: corners, moves, rays, deletes
  else if (r.orbit != glm::vec2(0.0f)) camera_.orbit(r.orbit.x, r.orbit.y);
  if (!io.WantCaptureMouse && !click_.held()) {
    if (io.MouseDown[ImGuiMouseButton_Right] || io.MouseDown[ImGuiMouseButton_Middle]) {
      // Deltas are in window coordinates, so pan with the window's height, not the
      // framebuffer's (they differ on HiDPI screens).
      camera_.pan(io.MouseDelta.x, io.MouseDelta.y, io.DisplaySize.y);
    }
  }
  if (!io.WantCaptureMouse && io.MouseWheel != 0.0f) camera_.zoom(io.MouseWheel);
  if (r.click && !camera_.top_down()) {
    // A click: shoot through that pixel. Window coordinates -> framebuffer pixels.
    const float sx = io.DisplayFramebufferScale.x > 0.0f ? io.DisplayFramebufferScale.x : 1.0f;
    const float sy = io.DisplayFramebufferScale.y > 0.0f ? io.DisplayFramebufferScale.y : 1.0f;
    shoot_at_pixel(r.press_pos.x * sx, r.press_pos.y * sy, ray_.shoot_from_saved() || io.KeyShift);
  }
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
              {GLFW_KEY_F, "F", "frame the scene", act([this] { frame_scene(); })},
              // A failed load shows in the panel.
              {GLFW_KEY_D, "D", "the blackboard (2D mode) on and off", act([this] { (void)set_mode_2d(!mode_2d()); })},
              {GLFW_KEY_ESCAPE, "Esc", "blackboard: forget the corners placed so far", act([this] { board_.clear(); })},
              {GLFW_KEY_H, "H", "hide / show the panels", act([this] { ui_visible_ = !ui_visible_; })},
              {GLFW_KEY_L, "L", "lecture mode: large fonts, high contrast, controls collapsed",
               act([this] { lecture_mode_ = !lecture_mode_; })},
              // The notice says what happened.
              {GLFW_KEY_R, "R", "start / stop recording a GIF or MP4", act([this] { (void)toggle_recording(); })},
              {GLFW_KEY_F12, "F12",
               "screenshot: writes a numbered accelviz_NNNN.png into the pictures folder and says where",
               act([this] { recorder_.request_screenshot(); })},
          }};
}

// ---------------------------------------------------------------------------------------
// Drawing

void App::draw(int framebuffer_width, int framebuffer_height) {
  if (!renderer_ || framebuffer_width <= 0 || framebuffer_height <= 0) return;
  framebuffer_ = {framebuffer_width, framebuffer_height};
  // Uploads before the frame begins, in the order the tools draw.
  session_.upload(*renderer_);
  nodes_.sync_gl();
  ray_.sync_gl();
  build_.sync_gl();
  heatmap_.sync_gl();
  tree_.sync_gl();
  // The view keeps its rectangle from update(); clamp it to this framebuffer.
  view_.x = std::clamp(view_.x, 0, framebuffer_.x - 1);
  view_.z = std::clamp(view_.z, 1, framebuffer_.x - view_.x);
  view_.y = 0;
  view_.w = std::clamp(view_.w, 1, framebuffer_.y);  // shorter above a bottom panel (the tree)
  const float aspect = aspect_of(view_size());
  // Frame once the panels are placed: the view's rectangle (and aspect) is known then, so
  // the scene is framed into the part of the window the panels leave free.
  if (frame_requested_ && (!ui_visible_ || layout_frames_ == 0)) {
    camera_.frame(frame_box(), aspect);
    frame_requested_ = false;
  }
  FrameView view;
  view.view = camera_.view();
  view.projection = camera_.projection(aspect);
  view.eye = camera_.eye();
  view.viewport = view_size();
  view.origin = {view_.x, framebuffer_.y - view_.y - view_.w};
  renderer_->begin_frame(view, background_);
  // The mesh first (translucent too: it writes depth), so nodes and highlights behind it
  // are drawn faintly by the x-ray passes and those in front stay crisp.
  draw_board(true);  // 2D: the grid of world units, under everything
  renderer_->draw_mesh(nodes_.mesh_style());
  if (build_.active()) {
    build_.draw(*renderer_);  // the partly built structure instead of the finished one
  } else {
    const bool tracing = ray_.ray().active && !ray_.ray().player.empty();
    // While the tree isolates a subtree it draws that subtree instead of all the nodes.
    if (!tree_.isolating()) nodes_.draw(*renderer_, session_.current(), tracing);
    ray_.draw(*renderer_);
    tree_.draw(*renderer_);
  }
  session_.draw_bounds(*renderer_);
  draw_board(false);  // the corners placed and the ray being dragged
  heatmap_.draw(*renderer_, heatmap_view());
  renderer_->end_frame();
}

}  // namespace viz
