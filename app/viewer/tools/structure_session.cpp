#include "tools/structure_session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "batch.h"
#include "camera_control.h"
#include "rays_io.h"
#include "tools/ray_debugger.h"
#include "browser.h"
#include "panels.h"
#include "memory_budget.h"
#include "ray_gen.h"
#include "registry.h"
#include "tools/structure_session_verbs.h"

namespace viz {
using ui::fmt;
StructureSession::StructureSession() : scene_(std::make_shared<accel::Scene>()) {
#ifdef ACCEL_SOURCE_DIR
  presets_ = lecture_presets(ACCEL_SOURCE_DIR);
#endif
  StructureRequest initial;
  initial.name = "bvh";
  initial.params = {"width=2"};  // the lecture's binary tree first; width=4 is one click away
  editor_.set(initial);
  requested_ = initial;
}

accel::Status StructureSession::load_scene(const std::string& spec) {
  const auto start = std::chrono::steady_clock::now();
  accel::Result<accel::Scene> loaded = accel::load_scene(spec);
  const auto stop = std::chrono::steady_clock::now();
  if (!loaded) {
    panel_.load_error = loaded.error().message;
    browser::log_line(panel_.load_error);  // the page's console has it too
    return loaded.error();
  }
  install_scene(spec, std::move(loaded), std::chrono::duration<double, std::milli>(stop - start).count());
  return {};
}

void StructureSession::load_scene_in_background(const std::string& spec) {
  if (synchronous_) {
    (void)load_scene(spec);  // the error is shown in the panel
    return;
  }
  if (load_job_.busy()) {  // the running load cannot be interrupted: drop its result instead
    load_dropped_ = true;
    next_load_ = spec;
    return;
  }
  // The page downloads a file it does not hold yet here, in the main loop, which may wait
  // for it; the job's fibre then reads it from the page's file system (natively: nothing).
  if (accel::Status fetched = accel::fetch_scene_file(spec); !fetched) {
    panel_.load_error = fetched.error().message;
    browser::log_line(panel_.load_error);
    return;
  }
  loading_spec_ = spec;
  load_dropped_ = false;
  panel_.load_error.clear();
  load_job_.start([spec](const std::atomic<bool>&) { return accel::load_scene(spec); });
}

void StructureSession::cancel_load() {
  load_dropped_ = load_job_.busy();
  next_load_.reset();
}

void StructureSession::poll_load() {
  if (!load_job_.ready()) return;
  const double ms = 1000.0 * load_job_.seconds();
  accel::Result<accel::Scene> loaded = load_job_.take();
  if (!load_dropped_) {
    if (loaded) {
      install_scene(loading_spec_, std::move(loaded), ms);
    } else {
      panel_.load_error = loaded.error().message;
      browser::log_line(panel_.load_error);
    }
  }
  load_dropped_ = false;
  if (next_load_) {
    const std::string next = *next_load_;
    next_load_.reset();
    load_scene_in_background(next);
  }
}

void StructureSession::install_scene(const std::string& spec, accel::Result<accel::Scene> loaded, double load_ms) {
  scene_ = std::make_shared<const accel::Scene>(std::move(loaded.value()));
  scene_info_.spec = spec;
  scene_info_.name = scene_->name();
  scene_info_.triangles = scene_->triangle_count();
  scene_info_.vertices = scene_->vertex_count();
  scene_info_.degenerate = scene_->degenerate_count();
  scene_info_.bounds = scene_->bounds();
  scene_info_.load_ms = load_ms;
  scene_uploaded_ = false;
  panel_.load_error.clear();
  // The combo shows what is loaded: its preset, or no preset at all (then the file's name).
  preset_index_ = preset_for_scene(presets_, spec);
  events_.scene_loaded = true;
  rebuild();
}

void StructureSession::set_scene(accel::Scene scene, const std::string& spec, bool edit) {
  const bool new_scene_pending = events_.scene_loaded;
  install_scene(spec, std::move(scene), 0.0);
  if (edit && !new_scene_pending) {
    events_.scene_loaded = false;
    events_.scene_edited = true;
  }
}

accel::Status StructureSession::load_preset_scene(const Preset& preset) {
  if (!preset.structure.empty() && editor_.info().name != preset.structure) {
    StructureRequest r = editor_.request();
    r.name = preset.structure;
    r.params.clear();
    editor_.set(r);
  }
  accel::Status st = load_scene(preset.scene);
  for (size_t i = 0; i < presets_.size(); ++i)
    if (presets_[i].name == preset.name) preset_index_ = static_cast<int>(i);
  return st;
}

void StructureSession::poll() {
  // Loads requested since the last frame; only the last one matters to the user, but a
  // failure of an earlier one would then go unreported, so run them in order.
  std::vector<std::string> loads;
  loads.swap(pending_loads_);
  for (const std::string& spec : loads) load_scene_in_background(spec);  // errors are shown in the panel
  poll_load();
  poll_build();
}

void StructureSession::poll_build() {
  // Cancelled builds (superseded by a newer request) never come out of poll().
  std::optional<accel::Result<BuiltPtr>> result = builds_.poll();
  if (!result) return;
  if (!*result) {
    build_error_ = result->error().message;
    if (requested_.build_call_limit) {
      // A failed build's replay: nothing is left to query or draw, not even the structure
      // shown before it (a debug ray would walk that one); the construction shows the replay.
      built_.reset();
      events_.structure_installed = true;
      build_error_ = "the failed build's replay: no structure to query (" + build_error_ + ")";
    }
    browser::log_line(build_error_);
  } else if (result->value()->scene == scene_) {
    install(std::move(result->value()));
  }
  // else: built for a scene replaced meanwhile; its rebuild is under way.
}

SessionEvents StructureSession::take_events() {
  SessionEvents e = events_;
  events_ = {};
  return e;
}

StructureRequest StructureSession::editor_request() const {
  StructureRequest r = editor_.request();
  r.geometry.empty_cells = empty_cells_;
  if (editor_.info().student) r.build_call_limit = build_call_limit_;
  return r;
}

void StructureSession::switch_structure(const std::string& name, const std::vector<std::string>& params,
                                        size_t build_call_limit) {
  StructureRequest r;
  r.name = name;
  r.params = params;
  r.kernel = editor_.kernel();
  editor_.set(r);
  build_call_limit_ = build_call_limit;
  rebuild();
}

void StructureSession::set_kernel(accel::Kernel kernel) {
  editor_.set_kernel(kernel);
  rebuild();
}

void StructureSession::request(const StructureRequest& request) {
  requested_ = request;
  // A newer request makes the last error stale too (it was about an older one).
  build_error_.clear();
  builds_.request(scene_, request, synchronous_);
  if (synchronous_) poll_build();
}

void StructureSession::install(BuiltPtr built) {
  built_ = std::move(built);
  events_.structure_installed = true;
}

accel::Status StructureSession::need_structure() const {
  if (!build_error_.empty()) return accel::make_error(build_error_);
  if (!matches_scene()) return accel::make_error("no structure built for this scene");
  return {};
}

std::string StructureSession::window_title() const {
  std::string title = "accelviz - " + (scene_info_.name.empty() ? scene_info_.spec : scene_info_.name);
  if (built_) title += " - " + built_->request.name;
  return title;
}

SceneActions StructureSession::scene_section(bool has_saved_view) {
  SceneActions actions;
  const float em = ImGui::GetFontSize();
  if (!presets_.empty()) {
    preset_index_ = std::clamp(preset_index_, -1, static_cast<int>(presets_.size()) - 1);
    const std::string shown =
        preset_index_ >= 0 ? presets_[static_cast<size_t>(preset_index_)].name : scene_label(scene_info_.spec);
    ImGui::SetNextItemWidth(12.0f * em);
    if (ImGui::BeginCombo("##preset", shown.c_str())) {
      for (int i = 0; i < static_cast<int>(presets_.size()); ++i) {
        const Preset& p = presets_[static_cast<size_t>(i)];
        if (ImGui::Selectable(p.name.c_str(), i == preset_index_)) preset_index_ = i;
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.description.c_str());
      }
      ImGui::EndCombo();
    }
    ImGui::SameLine();
    if (ImGui::Button("Load preset") && preset_index_ >= 0) actions.load_preset = preset_index_;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("scene, saved camera and saved ray");
  }
  ImGui::SetNextItemWidth(12.0f * em);
  const bool entered = ImGui::InputTextWithHint("##obj", "path/to/mesh.obj|ply|stl|gltf|glb", &panel_.obj_path,
                                                ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  const bool clicked = ImGui::Button("Load mesh");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("OBJ, PLY, STL, glTF 2.0 or GLB (or drop the file onto the window)");
  if ((entered || clicked) && !panel_.obj_path.empty()) load_scene_in_background(panel_.obj_path);  // error shown below
  if (load_job_.busy() && !load_dropped_) {
    // A 10M-triangle mesh takes seconds to parse: the time so far says it is alive.
    ImGui::Text("loading %s ... %.1f s", scene_label(loading_spec_).c_str(), load_job_.seconds());
    ImGui::SameLine();
    if (ImGui::Button("Cancel##load")) cancel_load();
  }
  if (!panel_.load_error.empty()) ui::error_text(panel_.load_error, 19.0f * em);

  if (ImGui::BeginTable("scene", 2, ImGuiTableFlags_SizingFixedFit)) {
    ui::path_row("scene", scene_info_.name.empty() ? scene_info_.spec : scene_info_.name);
    ui::stat_row("triangles", ui::with_separators(scene_info_.triangles) +
                                  (scene_info_.degenerate ? " (" + ui::with_separators(scene_info_.degenerate) +
                                                                " degenerate)"
                                                          : ""));
    ui::stat_row("size", scene_info_.bounds.empty() ? "(empty)" : ui::format_vec(scene_info_.bounds.extent()));
    ui::stat_row("load time", fmt("%.1f ms", scene_info_.load_ms));
    ImGui::EndTable();
  }
  if (ImGui::Button("Frame scene (F)")) actions.frame = true;
  ImGui::SameLine();
  if (ImGui::Button("Save view")) actions.save_view = true;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("remember this camera (shift-click then shoots from it)");
  if (has_saved_view) {
    ImGui::SameLine();
    if (ImGui::Button("Go to saved")) actions.go_to_saved = true;
  }
  return actions;
}

void StructureSession::structure_section() {
  const float em = ImGui::GetFontSize();
  const std::string chosen = editor_.structure_combo();
  if (!chosen.empty()) switch_structure(chosen, {});
  if (editor_.kernel_combo()) rebuild();
  // Every change rebuilds in the background; the old structure stays drawn meanwhile.
  if (editor_.parameter_widgets(scene_->planar())) rebuild();

  if (builds_.busy()) {
    // Determinate: the builders report the fraction done through the BuildControl.
    const double fraction = builds_.fraction();
    char overlay[96];
    std::snprintf(overlay, sizeof overlay, "building %s ... %.0f%%, %.1f s", requested_.name.c_str(),
                  100.0 * fraction, builds_.seconds());
    ImGui::ProgressBar(static_cast<float>(fraction), ImVec2(14.0f * em, 0.0f), overlay);
    ImGui::SameLine();
    if (ImGui::Button("Cancel##build")) {
      builds_.cancel();
      build_error_ = requested_.name + ": build cancelled (change a parameter or press Rebuild to build again)";
    }
  }
  if (!build_error_.empty()) {
    ui::error_text(build_error_, 19.0f * em);
    if (ImGui::Button("Rebuild")) rebuild();
  }
  memory_limit_widget();
  if (!built_) return;
  const accel::BuildStats& s = built_->stats;
  if (ImGui::BeginTable("build", 2, ImGuiTableFlags_SizingFixedFit)) {
    ui::stat_row("built", built_->request.name + (built_->scene == scene_ ? "" : " (old scene)"));
    ui::stat_row("build time", fmt("%.2f ms", s.build_ms));
    ui::stat_row("memory", ui::format_bytes(s.memory_bytes));
    ui::stat_row(built_->info->node_noun.c_str(),
                 ui::with_separators(s.nodes) + " (" + ui::with_separators(s.leaves) + " leaves)");
    if (s.empty_leaves) ui::stat_row("empty", ui::with_separators(s.empty_leaves));
    ui::stat_row("max depth", std::to_string(s.max_depth));
    ui::stat_row("refs / triangle", fmt("%.2f", s.refs_per_prim()));
    ui::stat_row("largest leaf", std::to_string(s.max_leaf_size));
    ui::stat_row("SAH cost", std::isnan(s.sah_cost) ? std::string("-") : fmt("%.2f", s.sah_cost));
    for (const auto& [key, value] : s.extra) ui::text_row(key.c_str(), value);
    ImGui::EndTable();
  }
}

void StructureSession::set_memory_limit(size_t bytes) {
  builds_.set_memory_limit(bytes);
  memory_limit_text_ = bytes ? accel::format_bytes(double(bytes)) : "";
  memory_limit_error_.clear();
  rebuild();
}

void StructureSession::memory_limit_widget() {
  const float em = ImGui::GetFontSize();
  ImGui::SetNextItemWidth(7.0f * em);
  const std::string hint = accel::format_bytes(double(accel::default_memory_limit()));
  if (ImGui::InputTextWithHint("memory limit", hint.c_str(), &memory_limit_text_, ImGuiInputTextFlags_EnterReturnsTrue)) {
    if (memory_limit_text_.empty()) {
      set_memory_limit(0);
    } else if (auto bytes = accel::parse_memory_size(memory_limit_text_, "memory limit")) {
      set_memory_limit(bytes.value());
    } else {
      memory_limit_error_ = bytes.error().message;
    }
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("what a build may allocate, e.g. 512M, 4G or 25%%; empty: half of this machine's memory (%s).\n"
                      "A build over it stops with an error naming the parameter to lower.",
                      hint.c_str());
  if (!memory_limit_error_.empty()) ui::error_text(memory_limit_error_, 19.0f * em);
}

void StructureSession::init_gl() {
  bounds_lines_.emplace(GL_LINES);
  scene_uploaded_ = false;
}

void StructureSession::upload(Renderer& renderer) {
  if (scene_uploaded_ || !bounds_lines_) return;
  renderer.set_scene(*scene_);
  std::vector<ColorVertex> lines;
  append_box_edges(lines, scene_->bounds(), glm::vec4(0.55f, 0.62f, 0.75f, 0.55f));
  bounds_lines_->upload(lines);
  scene_uploaded_ = true;
}

void StructureSession::draw_bounds(Renderer& renderer) const {
  if (!bounds_lines_) return;
  // A subtle box around the scene: shows its extent without competing with the mesh;
  // edges hidden by the mesh still show, fainter.
  LineStyle style;
  style.tint = glm::vec4(1.0f);
  style.hidden_tint = glm::vec4(1.0f, 1.0f, 1.0f, 0.35f);
  renderer.draw_lines(*bounds_lines_, style);
}

void StructureSession::wait() { builds_.wait(); }

void StructureSession::release_gl() { bounds_lines_.reset(); }

// ---------------------------------------------------------------------------------------
// Script verbs (tools/structure_session_verbs.h)

void StructureSession::add_verbs(VerbTable& table, ToolHost& host) {
  ToolVerbs<StructureSession> verbs(table, *this, host);
  structure_session_verbs(verbs);
}

// ---------------------------------------------------------------------------------------
// The tool's frame and its saved state

void StructureSession::update(ToolHost& host, float) {
  poll();
  host.sync_session();
}

void StructureSession::section(ToolHost& host, PanelSection section) {
  if (section == PanelSection::Structure) structure_section();
  if (section != PanelSection::Scene) return;
  RayDebugger& ray = host.ray();
  CameraControl& camera = host.camera();
  const SceneActions a = scene_section(ray.saved_view().has_value());
  if (a.load_preset >= 0) (void)host.apply_preset(presets()[static_cast<size_t>(a.load_preset)]);  // shown in the panel
  if (a.frame) camera.request_frame();
  if (a.save_view) ray.save_view(camera.pinhole());
  if (a.go_to_saved && ray.saved_view()) {
    const accel::PinholeCamera& v = *ray.saved_view();
    camera.look_at(v.eye, v.target, v.fovy_deg, scene());
  }
}

void StructureSession::save_state(std::string& out, const ToolHost& host) const {
  using accel::format_ray_number;
  const std::string& spec = scene_info_.spec;
  const bool file_scene = !spec.empty() && spec.rfind("procedural:", 0) != 0;
  const bool board = scene().planar();
  if (board) {
    out += "# the blackboard's triangles are not part of the state: save them with its Save button\n";
    out += "mode 2d\n";
  } else if (!spec.empty()) {
    std::error_code ec;
    out += "scene " + (file_scene ? std::filesystem::absolute(spec, ec).native() : spec) + "\n";
  }
  const StructureRequest request = current_request();
  out += "structure " + request.name;
  for (const std::string& p : request.params) out += " " + p;
  out += "\n";
  if (request.kernel != accel::Kernel::Watertight && !board)
    out += "kernel " + std::string(accel::kernel_name(request.kernel)) + "\n";
  const accel::PinholeCamera cam = host.camera().pinhole();
  if (!board) {
    out += "camera";
    for (float v : {cam.eye.x, cam.eye.y, cam.eye.z, cam.target.x, cam.target.y, cam.target.z, cam.fovy_deg}) {
      out += ' ';
      out += format_ray_number(v);
    }
    out += "\n";
  }
  // A failed build's replay: reopened as one (its structure line then builds only as far);
  // there is no structure to trace a ray through (RayDebugger writes no ray then).
  if (request.build_call_limit) out += "construct-until " + std::to_string(request.build_call_limit) + "\n";
}

}  // namespace viz
