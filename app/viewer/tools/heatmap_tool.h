#pragma once
// The cost heat map: on/off, metric, resolution and opacity, the background job tracing
// one primary ray per pixel (debounced while the view moves), the image and its GL
// texture, the main panel's section and the legend window.
#include <optional>

#include "heatmap.h"
#include "ray_gen.h"
#include "renderer.h"
#include "view_layout.h"
#include "workbench.h"

namespace viz {

/// What the heat map is of: the camera, the structure (nullptr: none for this scene) and
/// the 3D view's size in pixels.
struct HeatmapView {
  accel::PinholeCamera camera;
  BuiltPtr built;
  glm::ivec2 view_size{1, 1};
};

/// The heat map tool.
class HeatmapTool {
 public:
  /// Takes a finished image; starts a new one once the view has been still for a moment.
  void update(float dt, const HeatmapView& view);
  /// Computes the image now, on this thread (scripts).
  void compute_now(const HeatmapView& view);
  /// Forgets the image (a new scene).
  void invalidate() { has_image_ = false; }
  /// Waits for the job.
  void wait() { job_.wait(); }

  /// Whether the overlay is shown.
  bool on() const { return on_; }
  /// Shows or hides the overlay.
  void set_on(bool on) { on_ = on; }
  /// Chooses what a pixel counts.
  void set_metric(accel::CostMetric metric) { metric_ = metric; }
  /// The M key: off -> nodes -> triangles -> off.
  void cycle();
  /// An image is being computed for the shown overlay.
  bool computing() const { return on_ && job_.busy(); }
  /// Size of the image being computed.
  glm::ivec2 computing_size() const { return running_.size; }

  /// The main panel's "Cost heat map" section.
  void section();
  /// The legend window; `node_noun` names what the structure's nodes are ("cells").
  void legend(const PanelPlace& place, const std::string& node_noun, const HeatmapView& view);

  /// Creates the texture (context current).
  void init_gl();
  /// Uploads a new image (before the frame begins).
  void sync_gl();
  /// Draws the overlay when it is up to date for `view`.
  void draw(Renderer& renderer, const HeatmapView& view);
  /// Releases the texture.
  void release_gl();

 private:
  /// What a cost image depends on: it is recomputed when any of this changes.
  struct Inputs {
    accel::PinholeCamera camera;
    const BuiltStructure* built = nullptr;
    accel::CostMetric metric = accel::CostMetric::NodesVisited;
    glm::ivec2 size{0, 0};
    bool operator==(const Inputs& o) const {
      return camera.eye == o.camera.eye && camera.target == o.camera.target && camera.fovy_deg == o.camera.fovy_deg &&
             built == o.built && metric == o.metric && size == o.size;
    }
  };
  Inputs inputs(const HeatmapView& view) const;

  bool on_ = false;
  accel::CostMetric metric_ = accel::CostMetric::NodesVisited;
  int divisor_ = 4;  // image resolution = view / divisor
  float alpha_ = 0.78f;
  Job<accel::CostImage> job_;
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
