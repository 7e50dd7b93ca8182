#include "tools/blackboard_editor.h"

#include <algorithm>
#include <cmath>

namespace viz {

BlackboardAction BlackboardEditor::update(const ClickResult& r, glm::vec2 press_point, glm::vec2 point,
                                          bool dragging, int vertex_at_press) {
  BlackboardAction action;
  drag_.reset();
  if (dragging && moving_ < 0 && vertex_at_press >= 0) moving_ = vertex_at_press;  // the drag grabbed a corner
  if (moving_ >= 0 && (dragging || r.drag_end)) {  // every frame of the drag moves it
    action.kind = BlackboardAction::Kind::MoveVertex;
    action.vertex = moving_;
    action.position = point;
    if (r.drag_end) moving_ = -1;
    return action;
  }
  if (dragging) drag_ = std::make_pair(press_point, point);
  if (r.drag_end && point != press_point) {
    action.kind = BlackboardAction::Kind::ShootRay;
    action.ray.org = accel::Vec3(press_point, 0.0f);
    action.ray.dir = accel::Vec3(point - press_point, 0.0f);
    return action;
  }
  if (!r.click) return action;
  pending_.push_back(press_point);
  if (pending_.size() < 3) return action;
  action.kind = BlackboardAction::Kind::AddTriangle;
  for (size_t k = 0; k < 3; ++k) {
    action.triangle[2 * k] = pending_[k].x;
    action.triangle[2 * k + 1] = pending_[k].y;
  }
  pending_.clear();
  return action;
}

float grid_spacing(float units_per_pixel, float min_pixels) {
  const float wanted = std::max(units_per_pixel * min_pixels, 1e-30f);
  float power = std::pow(10.0f, std::floor(std::log10(wanted)));
  for (;;) {
    for (float step : {1.0f, 2.0f, 5.0f})
      if (step * power >= wanted) return step * power;
    power *= 10.0f;
  }
}

}  // namespace viz
