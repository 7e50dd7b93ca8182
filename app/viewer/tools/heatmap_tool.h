#pragma once
// The cost heat map: on/off, metric, resolution and opacity, the background job tracing
// one primary ray per pixel (debounced while the view moves), the image and its GL
// texture, the main panel's section and the legend window.
#include <optional>
#include <string>

#include "built_structure.h"
#include "commands.h"
#include "heatmap.h"
#include "job.h"
#include "ray_gen.h"
#include "renderer.h"
#include "tool_host.h"
#include "tools/heatmap_scale.h"
#include "tools/tool.h"
#include "view_layout.h"

namespace viz {

/// What the heat map is of: the camera, the structure (nullptr: none for this scene) and
/// the 3D view's size in pixels.
struct HeatmapView {
  accel::PinholeCamera camera;
  BuiltPtr built;
  glm::ivec2 view_size{1, 1};
};

/// The heat map tool.
class HeatmapTool final : public Tool {
 public:
  // ---- The tool (tool.h)
  const char* name() const override { return "heat map"; }
  /// M cycles the metric.
  std::vector<KeyBinding> keys(ToolHost& host) override;
  void add_verbs(VerbTable& table, ToolHost& host) override;
  void init_gl() override;
  void release_gl() override;
  void wait() override { job_.wait(); }
  /// A new or edited scene: the image is of the old one.
  void on_event(ToolEvent event, ToolHost& host) override;
  /// A finished image, or a new one due (the camera, structure or metric changed).
  void update(ToolHost& host, float dt) override;
  /// Own: the "Cost heat map" section.
  void section(ToolHost& host, PanelSection section) override;
  /// The legend at the top of the view.
  void panels(ToolHost& host) override;
  void sync_gl(Renderer&, ToolHost&) override { upload_image(); }
  /// Over everything: the image.
  void draw(Renderer& renderer, ToolHost& host, DrawLayer layer) override;

  /// Takes a finished image; starts a new one once the view has been still for a moment.
  void update_image(float dt, const HeatmapView& view);
  /// Computes the image now, on this thread (scripts).
  void compute_now(const HeatmapView& view);
  /// Forgets the image (a new scene).
  void invalidate() { has_image_ = false; }
  /// Waits for the job.

  /// Whether the overlay is shown.
  bool on() const { return on_; }
  /// Shows or hides the overlay.
  void set_on(bool on) { on_ = on; }
  /// Chooses what a pixel counts.
  void set_metric(accel::CostMetric metric) { metric_ = metric; }
  /// The colour scale: automatic (0 .. the image's 99th percentile) or fixed to [lo, hi],
  /// which then stays across structures and views (heatmap-scale).
  void set_scale(const HeatmapScale& scale) { scale_ = scale; }
  /// "heat map: nodes, scale 0..12 (auto), mean 10.1, max 68" for print-heatmap.
  std::string summary() const;
  /// The difference view: the shown structure's cost minus `other`'s per pixel, on a
  /// diverging scale (nullopt: the plain heat map). `other` is built over the same scene
  /// when the image is computed (and kept while the scene stays).
  void set_difference(std::optional<StructureRequest> other);
  const std::optional<StructureRequest>& difference() const { return other_; }
  /// The last error of the difference view (the other structure failed to build).
  const std::string& error() const { return error_; }
  /// The M key: off -> nodes -> triangles -> off.
  void cycle();
  /// An image is being computed for the shown overlay.
  bool computing() const { return on_ && job_.busy(); }
  /// Size of the image being computed.
  glm::ivec2 computing_size() const { return running_.size; }

  /// The main panel's "Cost heat map" section.
  void settings_section();
  /// The legend window; `node_noun` names what the structure's nodes are ("cells").
  void legend(const PanelPlace& place, const std::string& node_noun, const HeatmapView& view);

  /// Creates the texture (context current).
  /// Uploads a new image (before the frame begins).
  void upload_image();
  /// Draws the overlay when it is up to date for `view`.
  void draw_image(Renderer& renderer, const HeatmapView& view);
  /// Releases the texture.

 private:
  /// What a cost image depends on: it is recomputed when any of this changes.
  struct Inputs {
    accel::PinholeCamera camera;
    const BuiltStructure* built = nullptr;
    accel::CostMetric metric = accel::CostMetric::NodesVisited;
    glm::ivec2 size{0, 0};
    int other_version = 0;  // the difference view's structure (set_difference bumps it)
    bool operator==(const Inputs& o) const {
      return camera.eye == o.camera.eye && camera.target == o.camera.target && camera.fovy_deg == o.camera.fovy_deg &&
             built == o.built && metric == o.metric && size == o.size && other_version == o.other_version;
    }
  };
  Inputs inputs(const HeatmapView& view) const;

  bool on_ = false;
  accel::CostMetric metric_ = accel::CostMetric::NodesVisited;
  int divisor_ = 4;  // image resolution = view / divisor
  float alpha_ = 0.78f;
  HeatmapScale scale_;
  /// A job's result: the image, and for the difference view the other structure's image
  /// and the other structure (built in the job when the scene changed).
  struct Images {
    accel::CostImage image, other;
    BuiltPtr other_built;
    bool difference = false;
    std::string error;
  };
  /// Runs on the job's thread: everything it reads is passed in (a copy of other_).
  static Images compute(const BuiltPtr& built, const Inputs& in, const std::optional<StructureRequest>& other,
                        BuiltPtr other_built, const std::atomic<bool>* cancel);
  void take(Images images);
  std::optional<StructureRequest> other_;
  int other_version_ = 0;
  BuiltPtr other_built_;  // the difference view's structure, for other_built_->scene
  std::string error_;
  Job<Images> job_;
  Inputs running_;  // inputs of the job in flight
  Inputs shown_;    // inputs of image_
  Inputs last_;     // inputs seen last frame (for the debounce)
  accel::CostImage image_;
  bool has_image_ = false;
  bool uploaded_ = true;
  double still_ = 0.0;  // seconds the inputs have been unchanged
  std::optional<HeatmapTexture> texture_;
};

}  // namespace viz
