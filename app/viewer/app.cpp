// App, part 1: lifecycle, scene and structure (background builds), input, drawing.
// Index:
//   [SECTION] Construction, scene loading, init/shutdown
//   [SECTION] Structure: requests, background builds, swap on the main thread
//   [SECTION] Per-frame update: input and shortcuts
//   [SECTION] Drawing
#include "app.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "bench_chart_panel.h"
#include "registry.h"

namespace viz {
namespace {

// Weight of the newest frame in the smoothed frame time: about the last 20 frames count,
// so the number is readable yet follows a change within a fraction of a second.
constexpr double kTimingSmoothing = 0.05;
// A press and release closer than this (pixels moved in between) is a click, not a drag.
constexpr float kClickTolerance = 4.0f;

float aspect_of(glm::ivec2 size) { return static_cast<float>(size.x) / static_cast<float>(std::max(size.y, 1)); }

}  // namespace

// ============================================================================
// [SECTION] Construction, scene loading, init/shutdown
// ============================================================================

App::App() : scene_(std::make_shared<accel::Scene>()) {
#ifdef ACCEL_SOURCE_DIR
  presets_ = lecture_presets(ACCEL_SOURCE_DIR);
#endif
  StructureRequest initial;
  initial.name = "bvh";
  initial.params = {"width=2"};  // the lecture's binary tree first; width=4 is one click away
  set_editor(initial);
  requested_ = initial;
}

App::~App() { shutdown(); }

std::optional<accel::Error> App::load_scene(const std::string& spec) {
  const auto start = std::chrono::steady_clock::now();
  accel::Result<accel::Scene> loaded = accel::load_scene(spec);
  const auto stop = std::chrono::steady_clock::now();
  if (!loaded) {
    panel_.load_error = loaded.error().message;
    return loaded.error();
  }
  scene_ = std::make_shared<const accel::Scene>(std::move(loaded.value()));
  scene_info_.spec = spec;
  scene_info_.name = scene_->name();
  scene_info_.triangles = scene_->triangle_count();
  scene_info_.vertices = scene_->vertex_count();
  scene_info_.degenerate = scene_->degenerate_count();
  scene_info_.bounds = scene_->bounds();
  scene_info_.load_ms = std::chrono::duration<double, std::milli>(stop - start).count();
  scene_uploaded_ = false;
  panel_.load_error.clear();
  // A new scene: the old ray, its comparison and the heat map no longer mean anything.
  ray_ = DebugRay{};
  highlights_dirty_ = true;
  compare_rows_.clear();
  heatmap_has_image_ = false;
  frame_scene();
  update_window_title();
  request_structure(request_from_editor());
  return std::nullopt;
}

std::optional<accel::Error> App::init(GLFWwindow* window, const std::string& shader_dir, const Fonts& fonts) {
  window_ = window;
  fonts_ = fonts;
  auto renderer = Renderer::create(shader_dir);
  if (!renderer) return renderer.error();
  renderer_.emplace(std::move(renderer.value()));
  bounds_lines_.emplace(GL_LINES);
  box_nodes_.emplace(NodeStyle::Shape::Box);
  sphere_nodes_.emplace(NodeStyle::Shape::Sphere);
  plane_nodes_.emplace(NodeStyle::Shape::Plane);
  segments_.emplace();
  highlight_tris_gl_.emplace(GL_TRIANGLES);
  highlight_lines_gl_.emplace(GL_LINES);
  heatmap_texture_.emplace();
  scene_uploaded_ = false;
  geometry_dirty_ = true;
  highlights_dirty_ = true;
  heatmap_uploaded_ = false;

  // A subtle box around the scene: shows its extent without competing with the mesh;
  // edges hidden by the mesh still show, fainter.
  bounds_style_.tint = glm::vec4(1.0f);
  bounds_style_.hidden_tint = glm::vec4(1.0f, 1.0f, 1.0f, 0.35f);

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
  return std::nullopt;
}

void App::request_load(std::string spec) { pending_loads_.push_back(std::move(spec)); }

void App::shutdown() {
  // Background jobs first: they may still read the scene and structure.
  build_job_.wait();
  heatmap_job_.wait();
  compare_job_.wait();
  sweep_job_.wait();
  // GL objects next: their destructors call into the context main() destroys next.
  heatmap_texture_.reset();
  highlight_lines_gl_.reset();
  highlight_tris_gl_.reset();
  segments_.reset();
  plane_nodes_.reset();
  sphere_nodes_.reset();
  box_nodes_.reset();
  bounds_lines_.reset();
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
  std::string title = "accelviz - " + (scene_info_.name.empty() ? scene_info_.spec : scene_info_.name);
  if (built_) title += " - " + built_->request.name;
  glfwSetWindowTitle(window_, title.c_str());
}

void App::apply_preset(const Preset& preset) {
  for (size_t i = 0; i < presets_.size(); ++i)
    if (presets_[i].name == preset.name) preset_index_ = static_cast<int>(i);
  if (!preset.structure.empty()) {
    StructureRequest r = request_from_editor();
    if (r.name != preset.structure) {
      r.name = preset.structure;
      r.params.clear();
      set_editor(r);
    }
  }
  if (load_scene(preset.scene)) return;  // the error is shown in the panel
  if (preset.has_camera) {
    camera_.look_at(preset.eye, preset.target, preset.fovy_deg, scene_->bounds());
    frame_requested_ = false;
  }
  saved_view_ = camera_.pinhole();
  if (preset.has_ray) {
    accel::Ray ray;
    ray.org = preset.ray_origin;
    ray.dir = glm::normalize(preset.ray_target - preset.ray_origin);
    set_ray(ray, "preset " + preset.name);
  } else {
    camera_.frame(scene_->bounds(), aspect_of(view_size()));
    frame_requested_ = false;
    shoot_ray_at_pixel(static_cast<float>(view_.x) + 0.5f * static_cast<float>(view_.z),
                       static_cast<float>(view_.y) + 0.5f * static_cast<float>(view_.w));
  }
}

// ============================================================================
// [SECTION] Structure: requests, background builds, swap on the main thread
// ============================================================================

StructureRequest App::request_from_editor() const {
  StructureRequest r;
  const auto& registry = accel::structure_registry();
  const auto& info = registry[static_cast<size_t>(std::clamp(editor_structure_, 0, int(registry.size()) - 1))];
  r.name = info.name;
  for (size_t i = 0; i < info.params.size() && i < editor_values_.size(); ++i)
    if (editor_explicit_[i]) r.params.push_back(info.params[i].name + "=" + editor_values_[i]);
  r.kernel = editor_kernel_;
  r.geometry.empty_cells = empty_cells_;
  return r;
}

void App::set_editor(const StructureRequest& request) {
  const auto& registry = accel::structure_registry();
  editor_structure_ = 0;
  for (size_t i = 0; i < registry.size(); ++i)
    if (registry[i].name == request.name) editor_structure_ = static_cast<int>(i);
  const auto& specs = registry[static_cast<size_t>(editor_structure_)].params;
  editor_values_.clear();
  editor_explicit_.clear();
  for (const auto& spec : specs) {
    const std::string value = param_value(request.params, spec.name);
    editor_values_.push_back(value.empty() ? spec.default_value : value);
    editor_explicit_.push_back(!value.empty());
  }
  editor_kernel_ = request.kernel;
}

void App::switch_structure(const std::string& name, const std::vector<std::string>& params) {
  StructureRequest r;
  r.name = name;
  r.params = params;
  r.kernel = editor_kernel_;
  set_editor(r);
  request_structure(request_from_editor());
}

void App::request_structure(const StructureRequest& request) {
  requested_ = request;
  if (build_job_.busy() && !synchronous_) {
    // The running build cannot be interrupted; only the newest request matters next.
    queued_request_ = request;
    return;
  }
  start_build(request);
}

void App::start_build(const StructureRequest& request) {
  build_error_.clear();
  auto scene = scene_;
  build_job_.start([scene, request](const std::atomic<bool>&) { return build_structure_now(scene, request); },
                   synchronous_);
  if (synchronous_) poll_build();
}

void App::poll_build() {
  if (!build_job_.ready()) return;
  accel::Result<BuiltPtr> result = build_job_.take();
  if (!result) {
    build_error_ = result.error().message;
  } else if (result.value()->scene == scene_) {
    install_structure(std::move(result.value()));
  }
  // else: built for a scene replaced meanwhile; its rebuild is queued.
  if (queued_request_) {
    const StructureRequest next = *queued_request_;
    queued_request_.reset();
    start_build(next);
  }
}

void App::install_structure(BuiltPtr built) {
  built_ = std::move(built);
  geometry_ = built_->geometry;
  geometry_dirty_ = true;
  depth_lo_ = std::min(depth_lo_, geometry_.max_depth);
  depth_hi_ = std::clamp(depth_hi_, depth_lo_, std::max(geometry_.max_depth, depth_lo_));
  if (depth_filter_ == DepthFilter::All) depth_hi_ = geometry_.max_depth;
  depth_one_ = std::min(depth_one_, geometry_.max_depth);
  // Millions of boxes are unreadable (and slow without a GPU): open such a structure with
  // the levels that fit a budget; "all depths" is one click away.
  constexpr size_t kFirstViewBudget = 250000;
  depth_auto_limited_ = false;
  if (depth_filter_ == DepthFilter::All && geometry_.nodes > kFirstViewBudget && !geometry_.uniform_depth) {
    const int d = depth_for_budget(geometry_, kFirstViewBudget);
    if (d >= 0 && d < geometry_.max_depth) {
      depth_filter_ = DepthFilter::Range;
      depth_lo_ = 0;
      depth_hi_ = d;
      depth_auto_limited_ = true;
    }
  }
  replay_ray();
  update_window_title();
}

void App::refresh_geometry() {
  if (!built_) return;
  GeometryOptions options = built_->request.geometry;
  options.empty_cells = empty_cells_;
  geometry_ = structure_geometry(*built_->structure, options);
  geometry_dirty_ = true;
}

// ============================================================================
// [SECTION] Per-frame update: input and shortcuts
// ============================================================================

void App::update(float dt) {
  time_ += dt;
  // Loads requested since the last frame; only the last one matters to the user, but a
  // failure of an earlier one would then go unreported, so run them in order.
  std::vector<std::string> loads;
  loads.swap(pending_loads_);
  for (const std::string& spec : loads) load_scene(spec);

  poll_build();
  poll_compare();
  update_camera_input();
  update_shortcuts();

  const double frame_ms = 1000.0 * static_cast<double>(dt);
  timing_.frame_ms = timing_.frame_ms == 0.0
                         ? frame_ms
                         : (1.0 - kTimingSmoothing) * timing_.frame_ms + kTimingSmoothing * frame_ms;
  timing_.fps = timing_.frame_ms > 0.0 ? 1000.0 / timing_.frame_ms : 0.0;

  if (!synchronous_ && ray_.player.advance(static_cast<double>(dt))) highlights_dirty_ = true;
  poll_heatmap(dt);

  apply_lecture_mode();
  dock_left_ = 0.0f;
  dock_right_ = ImGui::GetIO().DisplaySize.x;
  if (ui_visible_) {
    layout_windows();
    if (panels_.main) main_panel();
    if (panels_.ray) ray_panel();
    if (panels_.steps) steps_panel();
    if (panels_.code) code_panel();
    if (panels_.compare) compare_panel();
    if (panels_.sweep) sweep_panel();
    if (panels_.legend && heatmap_on_) legend_panel();
    bench_chart_window(chart_, layout_.chart.pos, layout_.chart.size, layout_.apply);
  }
  status_overlay();
  update_view_rect();
  if (highlights_dirty_ || highlight_step_ != ray_.player.step()) rebuild_highlights();
}

void App::update_camera_input() {
  const ImGuiIO& io = ImGui::GetIO();
  // The mouse belongs to ImGui while it hovers a window or drags a widget; a drag that
  // started over the scene keeps going even when it crosses a panel.
  if (io.MouseClicked[ImGuiMouseButton_Left] && !io.WantCaptureMouse) {
    mouse_pressed_in_view_ = true;
    mouse_press_pos_ = {io.MousePos.x, io.MousePos.y};
    mouse_drag_ = 0.0f;
  }
  if (!io.WantCaptureMouse || mouse_pressed_in_view_) {
    const float dx = io.MouseDelta.x;
    const float dy = io.MouseDelta.y;
    if (io.MouseDown[ImGuiMouseButton_Left] && mouse_pressed_in_view_) {
      mouse_drag_ += std::abs(dx) + std::abs(dy);
      // Orbit only once it is clearly a drag: a click must not turn the view.
      if (mouse_drag_ >= kClickTolerance) camera_.orbit(dx, dy);
    } else if (!io.WantCaptureMouse &&
               (io.MouseDown[ImGuiMouseButton_Right] || io.MouseDown[ImGuiMouseButton_Middle])) {
      // Deltas are in window coordinates, so pan with the window's height, not the
      // framebuffer's (they differ on HiDPI screens).
      camera_.pan(dx, dy, io.DisplaySize.y);
    }
    if (!io.WantCaptureMouse && io.MouseWheel != 0.0f) camera_.zoom(io.MouseWheel);
  }
  if (io.MouseReleased[ImGuiMouseButton_Left] && mouse_pressed_in_view_) {
    mouse_pressed_in_view_ = false;
    if (mouse_drag_ < kClickTolerance) {
      // A click: shoot through that pixel. Window coordinates -> framebuffer pixels.
      const float sx = io.DisplayFramebufferScale.x > 0.0f ? io.DisplayFramebufferScale.x : 1.0f;
      const float sy = io.DisplayFramebufferScale.y > 0.0f ? io.DisplayFramebufferScale.y : 1.0f;
      shoot_ray_at_pixel(mouse_press_pos_.x * sx, mouse_press_pos_.y * sy, shoot_from_saved_ || io.KeyShift);
    }
  }
}

void App::update_shortcuts() {
  std::vector<KeyPress> keys;
  keys.swap(pressed_keys_);
  // Typing "f" into the OBJ path field must not reframe the scene.
  if (ImGui::GetIO().WantCaptureKeyboard) return;
  for (const KeyPress& k : keys) {
    const size_t n = (k.mods & GLFW_MOD_SHIFT) ? 10 : 1;
    switch (k.key) {
      case GLFW_KEY_F: frame_scene(); break;
      case GLFW_KEY_H: ui_visible_ = !ui_visible_; break;
      case GLFW_KEY_L: lecture_mode_ = !lecture_mode_; break;
      case GLFW_KEY_SPACE: ray_.player.toggle(); break;
      case GLFW_KEY_RIGHT: ray_.player.pause(); ray_.player.step_forward(n); break;
      case GLFW_KEY_LEFT: ray_.player.pause(); ray_.player.step_back(n); break;
      case GLFW_KEY_HOME: ray_.player.pause(); ray_.player.seek(0); break;
      case GLFW_KEY_END: ray_.player.pause(); ray_.player.jump_to_end(); break;
      case GLFW_KEY_J: ray_.player.jump_to_hit(); break;
      case GLFW_KEY_RIGHT_BRACKET: ray_.player.set_speed(ray_.player.speed() * 1.5); break;
      case GLFW_KEY_LEFT_BRACKET: ray_.player.set_speed(ray_.player.speed() / 1.5); break;
      case GLFW_KEY_C: panels_.compare = true; start_compare(); break;
      case GLFW_KEY_M:
        // Cycle: off -> nodes -> triangles -> off.
        if (!heatmap_on_) {
          heatmap_on_ = true;
          heatmap_metric_ = accel::CostMetric::NodesVisited;
        } else if (heatmap_metric_ == accel::CostMetric::NodesVisited) {
          heatmap_metric_ = accel::CostMetric::PrimsTested;
        } else {
          heatmap_on_ = false;
        }
        break;
      default: break;
    }
  }
}

void App::note_docked_window() {
  // A window along the left or right edge of the display narrows the 3D view; one in the
  // middle (moved there by the user) floats over it.
  const float w = ImGui::GetIO().DisplaySize.x;
  const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  if (pos.x < 0.3f * w && pos.x + size.x < 0.5f * w) dock_left_ = std::max(dock_left_, pos.x + size.x);
  if (pos.x + size.x > 0.7f * w && pos.x > 0.5f * w) dock_right_ = std::min(dock_right_, pos.x);
}

void App::update_view_rect() {
  const ImGuiIO& io = ImGui::GetIO();
  const float w = io.DisplaySize.x;
  float left = ui_visible_ ? dock_left_ : 0.0f, right = ui_visible_ ? dock_right_ : w;
  // Too narrow a view is worse than panels over the scene (small windows, e.g. tests).
  if (right - left < 0.3f * w) {
    left = 0.0f;
    right = w;
  }
  const float sx = io.DisplayFramebufferScale.x > 0.0f ? io.DisplayFramebufferScale.x : 1.0f;
  const int fb_w = static_cast<int>(std::lround(w * sx));
  const int fb_h = static_cast<int>(std::lround(io.DisplaySize.y * (io.DisplayFramebufferScale.y > 0.0f ? io.DisplayFramebufferScale.y : 1.0f)));
  const int x0 = static_cast<int>(std::lround(left * sx)), x1 = static_cast<int>(std::lround(right * sx));
  view_ = {x0, 0, std::max(x1 - x0, 1), std::max(fb_h, 1)};
  if (fb_w > 0 && fb_h > 0) framebuffer_ = {fb_w, fb_h};
}

// ============================================================================
// [SECTION] Drawing
// ============================================================================

NodeFilter App::current_filter() const {
  NodeFilter f;
  f.hide_empty = hide_empty_leaves_ && !empty_cells_;
  switch (depth_filter_) {
    case DepthFilter::All: break;
    case DepthFilter::Leaves: f.leaves_only = true; break;
    case DepthFilter::One: f.depth_min = f.depth_max = depth_one_; break;
    case DepthFilter::Range:
      f.depth_min = depth_lo_;
      f.depth_max = depth_hi_;
      break;
  }
  return f;
}

void App::upload_geometry() {
  // Only the nodes the filter shows go to the GPU: re-done when the filter changes, never
  // per frame. (The vertex shader filters too, but then every instance still costs.)
  const NodeFilter f = current_filter();
  const auto boxes = filter_nodes(geometry_.boxes, f);
  const auto spheres = filter_nodes(geometry_.spheres, f);
  NodeFilter planes_filter = f;
  planes_filter.leaves_only = false;  // split planes belong to inner nodes
  planes_filter.hide_empty = false;
  box_nodes_->upload(boxes);
  sphere_nodes_->upload(spheres);
  plane_nodes_->upload(f.leaves_only ? std::vector<NodeInstance>{} : filter_nodes(geometry_.planes, planes_filter));
  drawn_nodes_ = boxes.size() + spheres.size();
  uploaded_filter_ = f;
  geometry_dirty_ = false;
}

void App::draw_structure(const FrameView&) {
  if (!built_ || !structure_matches_scene() || !show_nodes_) return;
  NodeStyle style;
  const bool by_count = coloring_ == 2 || (coloring_ == 0 && geometry_.uniform_depth);
  style.coloring = by_count ? NodeStyle::Coloring::Prims : NodeStyle::Coloring::Depth;
  style.max_depth = static_cast<float>(std::max(geometry_.max_depth, 1));
  style.max_prims = static_cast<float>(std::max<uint32_t>(geometry_.max_prims, 1));
  style.alpha = node_alpha_;
  // While a trace is shown the structure steps back so the highlights stand out.
  if (ray_.active && !ray_.player.empty()) style.alpha *= 0.6f;
  // The instances on the GPU are already filtered (upload_geometry); the shader's filter
  // stays open.
  // X-ray draws every node twice; beyond ~100k nodes that second pass is not worth it.
  constexpr size_t kMaxXrayNodes = 100000;
  const bool occluding = mesh_style_.mode == MeshStyle::Mode::Solid || mesh_style_.mode == MeshStyle::Mode::Translucent;
  style.hidden_alpha = xray_ && occluding && drawn_nodes_ <= kMaxXrayNodes ? 0.3f : 0.0f;
  renderer_->draw_nodes(*box_nodes_, style);
  renderer_->draw_nodes(*sphere_nodes_, style);
  if (show_planes_) {
    // Split planes: translucent, a fifth of the lines' opacity, so stacked planes stay readable.
    NodeStyle planes = style;
    planes.alpha = 0.2f * node_alpha_;
    planes.hidden_alpha = 0.0f;
    planes.depth_bias = 0.0f;
    renderer_->draw_nodes(*plane_nodes_, planes);
  }
}

void App::draw(int framebuffer_width, int framebuffer_height) {
  if (!renderer_ || framebuffer_width <= 0 || framebuffer_height <= 0) return;
  framebuffer_ = {framebuffer_width, framebuffer_height};
  if (!scene_uploaded_) {
    renderer_->set_scene(*scene_);
    std::vector<ColorVertex> lines;
    append_box_edges(lines, scene_->bounds(), glm::vec4(0.55f, 0.62f, 0.75f, 0.55f));
    bounds_lines_->upload(lines);
    scene_uploaded_ = true;
  }
  if (geometry_dirty_ || !(current_filter() == uploaded_filter_)) upload_geometry();
  if (highlights_upload_) {
    segments_->upload(highlight_segments_);
    highlight_tris_gl_->upload(highlight_triangles_, GL_DYNAMIC_DRAW);
    highlight_lines_gl_->upload(highlight_lines_, GL_DYNAMIC_DRAW);
    highlights_upload_ = false;
  }
  if (!heatmap_uploaded_ && heatmap_has_image_) {
    heatmap_texture_->upload(heatmap_image_.values.data(), heatmap_image_.width, heatmap_image_.height);
    heatmap_uploaded_ = true;
  }
  // The view keeps its rectangle from update(); clamp it to this framebuffer.
  view_.x = std::clamp(view_.x, 0, framebuffer_.x - 1);
  view_.z = std::clamp(view_.z, 1, framebuffer_.x - view_.x);
  view_.y = 0;
  view_.w = framebuffer_.y;
  const float aspect = aspect_of(view_size());
  // Frame once the panels are placed: the view's rectangle (and aspect) is known then.
  if (frame_requested_ && (!ui_visible_ || layout_frames_ == 0)) {
    camera_.frame(scene_->bounds(), aspect);
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
  renderer_->draw_mesh(mesh_style_);
  draw_structure(view);

  // Highlights of the debug ray's current step (rebuilt only when the step changes).
  LineStyle thin;
  thin.hidden_tint = glm::vec4(1.0f, 1.0f, 1.0f, 0.35f);
  renderer_->draw_lines(*highlight_lines_gl_, thin);
  renderer_->draw_triangles(*highlight_tris_gl_);
  LineStyle thick;
  thick.hidden_tint = glm::vec4(1.0f, 1.0f, 1.0f, 0.4f);
  thick.depth_bias = 0.001f;
  renderer_->draw_segments(*segments_, thick);

  renderer_->draw_lines(*bounds_lines_, bounds_style_);
  if (heatmap_on_ && heatmap_has_image_ && heatmap_shown_ == heatmap_inputs()) {
    OverlayStyle overlay;
    overlay.scale_max = std::max(heatmap_image_.p99_value, 1.0f);
    overlay.alpha = heatmap_alpha_;
    renderer_->draw_overlay(*heatmap_texture_, overlay);
  }
  renderer_->end_frame();
}

}  // namespace viz
