// The "Speed vs error" window: draws the ChartModel of bench_chart.h with ImDrawList.
// Index:
//   [SECTION] Colours, markers, text helpers
//   [SECTION] The chart: frame, zero band, ticks, baseline, points, legend, tooltip
//   [SECTION] The window and the main panel's section
#include "tools/bench_chart_tool.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "bench_chart_verbs.h"
#include "panels.h"
#include "window_layout.h"

namespace viz {
using ui::fmt;
namespace {

// ============================================================================
// [SECTION] Colours, markers, text helpers
// ============================================================================

// Okabe-Ito colours: distinguishable with the common colour-vision deficiencies and on a
// projector. The reference kernels are cool, the fast inexact one warm; the peers each
// have their own: Embree neutral, tinybvh bluish green.
ImU32 kernel_color(const std::string& kernel, float alpha = 1.0f) {
  ImVec4 c;
  switch (kernel_order(kernel)) {
    case 0: c = ImVec4(0.34f, 0.71f, 0.91f, 1.0f); break;   // watertight: sky blue
    case 1: c = ImVec4(0.90f, 0.62f, 0.0f, 1.0f); break;    // moller: orange
    case 2: c = ImVec4(0.80f, 0.47f, 0.65f, 1.0f); break;   // double: reddish purple
    case 3: c = ImVec4(0.92f, 0.92f, 0.92f, 1.0f); break;   // embree: white
    case 4: c = ImVec4(0.0f, 0.70f, 0.52f, 1.0f); break;    // tinybvh: bluish green (lightened)
    default: c = ImVec4(0.94f, 0.89f, 0.26f, 1.0f); break;  // anything else: yellow
  }
  c.w = alpha;
  return ImGui::ColorConvertFloat4ToU32(c);
}

enum class Shape {
  Square, Diamond, TriangleUp, Circle, TriangleDown, Cross, StarOutline, Star, HexagonOutline, Plus, Hexagon, Ring
};

/// One marker shape per structure (structure_order's order), so a printed chart in grey
/// still tells the structures apart: the registry's, Embree's stars (medium outlined, high
/// filled), tinybvh's hexagons (binned outlined, HQ filled) and its BVH4 plus, then rings.
Shape structure_shape(const std::string& structure) {
  static const Shape kShapes[] = {Shape::Square,      Shape::Diamond, Shape::TriangleUp,     Shape::Circle,
                                  Shape::TriangleDown, Shape::Cross,  Shape::StarOutline,    Shape::Star,
                                  Shape::HexagonOutline, Shape::Plus, Shape::Hexagon,        Shape::Ring};
  return kShapes[std::min<size_t>(static_cast<size_t>(structure_order(structure)), std::size(kShapes) - 1)];
}

void draw_marker(ImDrawList* dl, Shape shape, ImVec2 c, float r, ImU32 fill) {
  const ImU32 outline = IM_COL32(10, 12, 16, 230);  // separates overlapping markers
  const float t = std::max(1.0f, 0.14f * r);
  auto star = [&](float inner) {
    ImVec2 pts[10];
    for (int i = 0; i < 10; ++i) {
      const float a = -1.5707963f + static_cast<float>(i) * 0.62831853f;
      const float rr = (i % 2 == 0 ? 1.25f : inner) * r;
      pts[i] = ImVec2(c.x + rr * std::cos(a), c.y + rr * std::sin(a));
    }
    return std::to_array(pts);
  };
  auto hexagon = [&] {
    std::array<ImVec2, 6> pts;
    for (size_t i = 0; i < 6; ++i) {
      const float a = -1.5707963f + static_cast<float>(i) * 1.0471976f;
      pts[i] = ImVec2(c.x + 1.1f * r * std::cos(a), c.y + 1.1f * r * std::sin(a));
    }
    return pts;
  };
  switch (shape) {
    case Shape::Hexagon: {
      const auto p = hexagon();
      dl->AddConvexPolyFilled(p.data(), 6, fill);
      dl->AddPolyline(p.data(), 6, outline, ImDrawFlags_Closed, t);
      break;
    }
    case Shape::HexagonOutline: {
      const auto p = hexagon();
      dl->AddPolyline(p.data(), 6, fill, ImDrawFlags_Closed, 2.0f * t);
      break;
    }
    case Shape::Plus:
      dl->AddLine(ImVec2(c.x - 1.15f * r, c.y), ImVec2(c.x + 1.15f * r, c.y), fill, 2.5f * t);
      dl->AddLine(ImVec2(c.x, c.y - 1.15f * r), ImVec2(c.x, c.y + 1.15f * r), fill, 2.5f * t);
      break;
    case Shape::Square:
      dl->AddRectFilled(ImVec2(c.x - 0.85f * r, c.y - 0.85f * r), ImVec2(c.x + 0.85f * r, c.y + 0.85f * r), fill);
      dl->AddRect(ImVec2(c.x - 0.85f * r, c.y - 0.85f * r), ImVec2(c.x + 0.85f * r, c.y + 0.85f * r), outline, 0.0f, 0, t);
      break;
    case Shape::Diamond: {
      const ImVec2 p[4] = {{c.x, c.y - 1.2f * r}, {c.x + 1.2f * r, c.y}, {c.x, c.y + 1.2f * r}, {c.x - 1.2f * r, c.y}};
      dl->AddConvexPolyFilled(p, 4, fill);
      dl->AddPolyline(p, 4, outline, ImDrawFlags_Closed, t);
      break;
    }
    case Shape::TriangleUp:
    case Shape::TriangleDown: {
      const float s = shape == Shape::TriangleUp ? 1.0f : -1.0f;
      const ImVec2 p[3] = {{c.x, c.y - s * 1.25f * r}, {c.x + 1.15f * r, c.y + s * 0.85f * r},
                           {c.x - 1.15f * r, c.y + s * 0.85f * r}};
      dl->AddTriangleFilled(p[0], p[1], p[2], fill);
      dl->AddPolyline(p, 3, outline, ImDrawFlags_Closed, t);
      break;
    }
    case Shape::Circle:
      dl->AddCircleFilled(c, r, fill, 20);
      dl->AddCircle(c, r, outline, 20, t);
      break;
    case Shape::Ring:
      dl->AddCircle(c, r, fill, 20, 2.5f * t);
      break;
    case Shape::Cross:
      dl->AddLine(ImVec2(c.x - r, c.y - r), ImVec2(c.x + r, c.y + r), fill, 2.5f * t);
      dl->AddLine(ImVec2(c.x - r, c.y + r), ImVec2(c.x + r, c.y - r), fill, 2.5f * t);
      break;
    case Shape::Star: {
      // Concave: a fan of triangles from the centre (a star is star-shaped around it).
      const auto p = star(0.5f);
      for (int i = 0; i < 10; ++i) dl->AddTriangleFilled(c, p[static_cast<size_t>(i)], p[static_cast<size_t>((i + 1) % 10)], fill);
      dl->AddPolyline(p.data(), 10, outline, ImDrawFlags_Closed, t);
      break;
    }
    case Shape::StarOutline: {
      const auto p = star(0.5f);
      dl->AddPolyline(p.data(), 10, fill, ImDrawFlags_Closed, 2.0f * t);
      break;
    }
  }
}

ImVec2 text_size(const char* text, float scale = 1.0f) {
  const ImVec2 s = ImGui::CalcTextSize(text);
  return ImVec2(s.x * scale, s.y * scale);
}

constexpr float kSmall = 0.75f;  // superscripts and notes, relative to the font size

/// Width of the superscript's minus: the font's hyphen is too thin to read at that size.
float minus_width() { return 0.42f * ImGui::GetFontSize(); }

float power_label_width(const AxisTick& tick) {
  const std::string digits = std::to_string(std::abs(tick.exponent));
  return text_size("10").x + (tick.exponent < 0 ? minus_width() : 0.0f) + text_size(digits.c_str(), kSmall).x;
}

/// A decade label: "10" and the exponent raised in a smaller font; `center_x` centres it
/// on pos.x, else it starts there.
void power_label(ImDrawList* dl, const AxisTick& tick, ImVec2 pos, ImU32 color, bool center_x) {
  const float em = ImGui::GetFontSize();
  const std::string digits = std::to_string(std::abs(tick.exponent));
  float x = center_x ? pos.x - 0.5f * power_label_width(tick) : pos.x;
  dl->AddText(ImVec2(x, pos.y + 0.2f * em), color, "10");
  x += text_size("10").x;
  const float sup_y = pos.y - 0.08f * em;
  if (tick.exponent < 0) {
    const float mid = sup_y + 0.42f * kSmall * em + 0.5f;
    dl->AddLine(ImVec2(x + 0.06f * em, mid), ImVec2(x + minus_width() - 0.06f * em, mid), color, 1.6f);
    x += minus_width();
  }
  dl->AddText(ImGui::GetFont(), kSmall * em, ImVec2(x, sup_y), color, digits.c_str());
}

bool overlaps(const ImVec4& a, const ImVec4& b) { return a.x < b.z && b.x < a.z && a.y < b.w && b.y < a.w; }

// ============================================================================
// [SECTION] The chart: frame, zero band, ticks, baseline, points, legend, tooltip
// ============================================================================

/// The whole row, for the point under the mouse.
void row_tooltip(const BenchRow& r) {
  ImGui::BeginTooltip();
  ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(kernel_color(r.kernel)), "%s", r.structure.c_str());
  ImGui::SameLine();
  ImGui::TextDisabled("%s", r.params.empty() ? "(default parameters)" : r.params.c_str());
  if (ImGui::BeginTable("row", 2, ImGuiTableFlags_SizingFixedFit)) {
    auto row = [](const char* label, const std::string& value) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextDisabled("%s", label);
      ImGui::TableSetColumnIndex(1);
      ImGui::TextUnformatted(value.c_str());
    };
    row("kernel", r.is_embree()         ? "Embree (rtcIntersect1): a peer, the baseline of the Embree ratio"
                  : r.kernel == "tinybvh" ? "tinybvh (its own CPU traversal): a peer"
                                          : r.kernel);
    row("Mrays/s", fmt("%.3g", r.mrays_mt) + " with " + std::to_string(r.threads) + " threads, " +
                       fmt("%.3g", r.mrays_1t) + " with 1");
    std::string ratio = r.is_embree() ? "(baseline)" : r.embree_ratio_mt ? fmt("%.2fx with all threads", *r.embree_ratio_mt)
                                                                         : "- (no Embree rows)";
    if (r.embree_ratio_1t) ratio += fmt(", %.2fx with 1", *r.embree_ratio_1t);
    row("vs Embree", ratio);
    row("vs fastest peer", format_peer_ratio(r));
    row("wrong answers", format_error_rate(r.wrong_answers(), r.n_rays));
    row("", std::to_string(r.false_miss) + " false misses, " + std::to_string(r.false_hit) + " false hits, " +
                std::to_string(r.wrong_prim) + " wrong triangles");
    row("t error", "max " + fmt("%.2g", r.max_rel_t_err) + ", mean " + fmt("%.2g", r.mean_rel_t_err) + " (relative); " +
                       std::to_string(r.wrong_t) + " beyond tolerance");
    row("build", fmt("%.3g ms", r.build_ms) + ", " + ui::format_bytes(static_cast<size_t>(r.memory_bytes)));
    row("rays", r.rays);
    ImGui::EndTable();
  }
  ImGui::EndTooltip();
}

/// Where the chart's parts go in its rectangle [origin, origin + size]: y labels left, x
/// labels and title below, legend right; the plot frame [p0, p1] between them.
struct ChartFrame {
  float em = ImGui::GetFontSize();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  ImU32 text = ImGui::GetColorU32(ImGuiCol_Text);
  ImU32 dim = ImGui::GetColorU32(ImGuiCol_TextDisabled);
  ImVec2 origin, size;
  float legend_w = 0.0f;  // 0: no legend (a narrow window)
  float below = 0.0f;     // under the frame: tick labels (+ notes) and the x title
  ImVec2 p0, p1;          // the plot frame: top-left, bottom-right
  // Data area: a margin inside the frame on the right and top so edge markers stay inside.
  float inset = 0.7f * em;
  float band_x1 = 0.0f, axis_x0 = 0.0f;  // the zero band's right edge; where the log axis starts
  float marker_r = 0.36f * em;

  float px(float fx) const { return p0.x + fx * (p1.x - inset - p0.x); }
  float py(float fy) const { return p1.y - fy * (p1.y - inset - p0.y); }
  bool too_small() const { return p1.x - p0.x < 6.0f * em || p1.y - p0.y < 4.0f * em; }
};

ChartFrame chart_frame(const ChartModel& m, ImVec2 origin, ImVec2 size) {
  ChartFrame f;
  const float em = f.em;
  f.origin = origin;
  f.size = size;
  float y_label_w = 0.0f;
  for (const AxisTick& t : m.y.ticks)
    if (t.major && t.labelled) y_label_w = std::max(y_label_w, text_size(t.label.c_str()).x);
  f.legend_w = size.x >= 36.0f * em ? 11.5f * em : 0.0f;
  f.p0 = ImVec2(origin.x + y_label_w + 0.8f * em, origin.y + 1.6f * em);
  const bool notes = std::any_of(m.x.ticks.begin(), m.x.ticks.end(), [](const AxisTick& t) { return !t.note.empty(); });
  f.below = notes ? 4.1f * em : 3.0f * em;
  f.p1 = ImVec2(origin.x + size.x - f.legend_w - 0.6f * em, origin.y + size.y - f.below);
  f.band_x1 = f.px(m.zero_band);
  f.axis_x0 = f.px(m.x_start());
  return f;
}

/// The frame and the zero band with its title at its top (one line if it fits, else two);
/// the title's rectangle goes to `taken`.
void draw_zero_band(const ChartFrame& f, const ChartModel& m, std::vector<ImVec4>& taken) {
  const float em = f.em;
  f.dl->AddRectFilled(f.p0, f.p1, IM_COL32(255, 255, 255, 8));
  f.dl->AddRectFilled(ImVec2(f.p0.x, f.p0.y), ImVec2(f.band_x1, f.p1.y), IM_COL32(90, 200, 120, 30));
  f.dl->AddLine(ImVec2(f.band_x1, f.p0.y), ImVec2(f.band_x1, f.p1.y), IM_COL32(90, 200, 120, 90), 1.0f);
  const std::string& label = m.zero_label;
  const float band_w = f.band_x1 - f.p0.x;
  const ImU32 green = IM_COL32(140, 225, 160, 255);
  std::vector<std::string> lines{label};
  if (const size_t space = label.find(' '); text_size(label.c_str()).x > band_w - 4.0f && space != std::string::npos)
    lines = {label.substr(0, space), label.substr(space + 1)};
  float y = f.p0.y + 0.2f * em;
  for (const std::string& l : lines) {
    const ImVec2 ts = text_size(l.c_str());
    const ImVec2 q(f.p0.x + 0.5f * (band_w - ts.x), y);
    f.dl->AddText(q, green, l.c_str());
    taken.push_back(ImVec4(q.x, q.y, q.x + ts.x, q.y + ts.y));
    y += ts.y;
  }
}

/// The grid with its ticks; the axes: y at the left edge, x broken between the band and the
/// log axis (0 is not on it).
void draw_grid_and_axes(const ChartFrame& f, const ChartModel& m) {
  const float em = f.em;
  const ImVec2 p0 = f.p0, p1 = f.p1;
  const ImU32 grid_major = IM_COL32(255, 255, 255, 34), grid_minor = IM_COL32(255, 255, 255, 13);
  for (const AxisTick& t : m.x.ticks) {
    const float x = f.px(m.x_start() + (1.0f - m.x_start()) * t.pos);
    f.dl->AddLine(ImVec2(x, p0.y), ImVec2(x, p1.y), t.major ? grid_major : grid_minor);
    f.dl->AddLine(ImVec2(x, p1.y), ImVec2(x, p1.y + (t.major ? 0.35f : 0.2f) * em), f.dim);
  }
  for (const AxisTick& t : m.y.ticks) {
    const float y = f.py(t.pos);
    f.dl->AddLine(ImVec2(p0.x, y), ImVec2(p1.x, y), t.major ? grid_major : grid_minor);
    f.dl->AddLine(ImVec2(p0.x - (t.major ? 0.35f : 0.2f) * em, y), ImVec2(p0.x, y), f.dim);
  }
  const float band_x1 = f.band_x1, axis_x0 = f.axis_x0;
  f.dl->AddLine(ImVec2(p0.x, p0.y), ImVec2(p0.x, p1.y), f.dim, 1.5f);
  f.dl->AddLine(ImVec2(p0.x, p1.y), ImVec2(band_x1 + 0.25f * (axis_x0 - band_x1), p1.y), f.dim, 1.5f);
  f.dl->AddLine(ImVec2(axis_x0 - 0.25f * (axis_x0 - band_x1), p1.y), ImVec2(p1.x, p1.y), f.dim, 1.5f);
  for (float frac : {0.25f, 0.75f}) {
    const float x = band_x1 + frac * (axis_x0 - band_x1);
    f.dl->AddLine(ImVec2(x - 0.2f * em, p1.y + 0.35f * em), ImVec2(x + 0.2f * em, p1.y - 0.35f * em), f.dim, 1.5f);
  }
}

/// The tick labels (the x ticks' notes under theirs) and the axis titles.
void draw_tick_labels(const ChartFrame& f, const ChartModel& m) {
  const float em = f.em;
  const float label_y = f.p1.y + 0.45f * em;
  {
    const float x = f.px(0.5f * m.zero_band);
    f.dl->AddText(ImVec2(x - 0.5f * text_size("0").x, label_y + 0.2f * em), f.text, "0");
  }
  for (const AxisTick& t : m.x.ticks) {
    if (!t.major || !t.labelled) continue;
    const float x = f.px(m.x_start() + (1.0f - m.x_start()) * t.pos);
    if (m.x.power_labels) power_label(f.dl, t, ImVec2(x, label_y), f.text, true);
    else f.dl->AddText(ImVec2(x - 0.5f * text_size(t.label.c_str()).x, label_y), f.text, t.label.c_str());
    if (!t.note.empty()) {
      const ImVec2 ns = text_size(t.note.c_str(), kSmall);
      f.dl->AddText(ImGui::GetFont(), kSmall * em, ImVec2(x - 0.5f * ns.x, label_y + 1.3f * em),
                    ImGui::GetColorU32(ImGuiCol_Text, 0.7f), t.note.c_str());
    }
  }
  for (const AxisTick& t : m.y.ticks) {
    if (!t.major || !t.labelled) continue;
    const float y = f.py(t.pos) - 0.5f * em;
    if (m.y.power_labels)
      power_label(f.dl, t, ImVec2(f.p0.x - 0.5f * em - power_label_width(t), y - 0.2f * em), f.text, false);
    else f.dl->AddText(ImVec2(f.p0.x - 0.5f * em - text_size(t.label.c_str()).x, y), f.text, t.label.c_str());
  }
  const ImVec2 xt = text_size(m.x_title.c_str());
  f.dl->AddText(ImVec2(0.5f * (f.axis_x0 + f.p1.x) - 0.5f * xt.x, f.p1.y + f.below - 1.25f * em), f.text,
                m.x_title.c_str());
  f.dl->AddText(ImVec2(f.origin.x, f.origin.y), f.text, m.y_title.c_str());
}

/// The fastest peer's speed as a dashed line across the plot in its kernel's colour,
/// labelled where nothing in `taken` is; the label and the line go to `taken`.
void draw_baseline(const ChartFrame& f, const BenchData& data, const ChartModel& m, const std::string& kernel,
                   std::vector<ImVec4>& taken) {
  const float em = f.em;
  const ImVec2 p0 = f.p0, p1 = f.p1;
  const float y = f.py(*m.baseline_fy);
  const ImU32 c = kernel_color(kernel, 0.55f);
  for (float x = p0.x; x < p1.x; x += 0.9f * em)
    f.dl->AddLine(ImVec2(x, y), ImVec2(std::min(x + 0.5f * em, p1.x), y), c, 1.5f);
  const std::string label_text =
      "fastest peer" + (m.baseline_row ? " (" + structure_label(data.rows[*m.baseline_row].structure) + ")" : "");
  const char* label = label_text.c_str();
  const ImVec2 ts = text_size(label);
  bool placed = false;
  for (float fx : {0.02f, 0.35f, 0.65f}) {
    for (float dy : {-1.1f * em, 0.1f * em}) {
      const float x = f.axis_x0 + fx * (p1.x - f.axis_x0);
      const ImVec4 box(x, y + dy, x + ts.x, y + dy + ts.y);
      if (placed || box.z > p1.x || box.y < p0.y || box.w > p1.y ||
          std::any_of(taken.begin(), taken.end(), [&](const ImVec4& t) { return overlaps(box, t); }))
        continue;
      f.dl->AddText(ImVec2(box.x, box.y), kernel_color(kernel, 0.8f), label);
      // Point labels keep half an em from it: "Embree high fastest peer (...)" would
      // read as one label.
      taken.push_back(ImVec4(box.x - 0.5f * em, box.y, box.z + 0.5f * em, box.w));
      placed = true;
    }
  }
  taken.push_back(ImVec4(p0.x, y - 1.0f, p1.x, y + 1.0f));  // point labels keep off the line
}

/// The points' indices, peers first so that the structures' markers stay on top of the peers'.
std::vector<size_t> peers_first(const BenchData& data, const ChartModel& m) {
  std::vector<size_t> order(m.points.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return data.rows[m.points[a].row].is_peer() > data.rows[m.points[b].row].is_peer();
  });
  return order;
}

/// Each point's name beside its marker at `where[i]`: right, left, above or below, the first
/// place free of the rectangles in `taken` (point i's own marker, taken[first_marker + i],
/// is not in the way).
void draw_point_labels(const ChartFrame& f, const BenchData& data, const ChartModel& m,
                       const std::vector<size_t>& order, const std::vector<ImVec2>& where, size_t first_marker,
                       std::vector<ImVec4>& taken) {
  const float em = f.em, r = f.marker_r;
  // Rows that share structure and kernel (a parameter study) are told apart by their
  // parameters.
  auto twins = [&](const BenchRow& row) {
    return std::count_if(m.points.begin(), m.points.end(), [&](const ChartPoint& p) {
      const BenchRow& other = data.rows[p.row];
      return other.structure == row.structure && other.kernel == row.kernel;
    });
  };
  for (size_t i : order) {
    const BenchRow& row = data.rows[m.points[i].row];
    std::string name = structure_label(row.structure);
    if (!row.params.empty() && twins(row) > 1)
      name += " " + (row.params.size() > 18 ? row.params.substr(0, 16) + ".." : row.params);
    const ImVec2 ts = text_size(name.c_str());
    const ImVec2 c = where[i];
    const ImVec2 candidates[] = {{c.x + r + 0.25f * em, c.y - 0.5f * ts.y},
                                 {c.x - r - 0.25f * em - ts.x, c.y - 0.5f * ts.y},
                                 {c.x - 0.5f * ts.x, c.y - r - ts.y},
                                 {c.x - 0.5f * ts.x, c.y + r}};
    for (const ImVec2& q : candidates) {
      const ImVec4 box(q.x, q.y, q.x + ts.x, q.y + ts.y);
      if (box.x < f.p0.x || box.z > f.p1.x || box.y < f.p0.y || box.w > f.p1.y) continue;
      bool free = true;
      for (size_t k = 0; k < taken.size() && free; ++k) {
        if (k == first_marker + i) continue;
        free = !overlaps(box, taken[k]);
      }
      if (!free) continue;
      f.dl->AddText(q, kernel_color(row.kernel, 0.9f), name.c_str());
      taken.push_back(box);
      break;
    }
  }
}

/// Hover: the nearest point under the mouse gets a ring and the full row.
void hover_point(const ChartFrame& f, const BenchData& data, const ChartModel& m, const std::vector<ImVec2>& where) {
  const float r = f.marker_r;
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  size_t best = m.points.size();
  float best_d2 = (1.2f * r + 4.0f) * (1.2f * r + 4.0f);
  for (size_t i = 0; i < m.points.size(); ++i) {
    const float dx = where[i].x - mouse.x, dy = where[i].y - mouse.y;
    if (dx * dx + dy * dy <= best_d2) {
      best_d2 = dx * dx + dy * dy;
      best = i;
    }
  }
  if (best < m.points.size()) {
    f.dl->AddCircle(where[best], 2.0f * r, IM_COL32(255, 255, 255, 220), 24, 2.0f);
    row_tooltip(data.rows[m.points[best].row]);
  }
}

/// Legend, right of the plot: colours are kernels, shapes are structures, and the fastest
/// peer's dashes (in `baseline_kernel`'s colour).
void draw_legend(const ChartFrame& f, const ChartModel& m, const std::string& baseline_kernel) {
  const float em = f.em;
  ImDrawList* dl = f.dl;
  float x = f.origin.x + f.size.x - f.legend_w + 0.6f * em, y = f.p0.y;
  const float line = 1.45f * em;
  dl->AddText(ImVec2(x, y), f.dim, "kernel (colour)");
  y += line;
  for (const std::string& k : m.kernels) {
    dl->AddRectFilled(ImVec2(x, y + 0.2f * em), ImVec2(x + 0.9f * em, y + 1.0f * em), kernel_color(k), 2.0f);
    dl->AddText(ImVec2(x + 1.4f * em, y), f.text, kernel_label(k).c_str());
    y += line;
  }
  y += 0.5f * em;
  dl->AddText(ImVec2(x, y), f.dim, "structure (shape)");
  y += line;
  for (const std::string& s : m.structures) {
    const ImVec2 c(x + 0.45f * em, y + 0.6f * em);
    draw_marker(dl, structure_shape(s), c, f.marker_r, IM_COL32(215, 218, 225, 255));
    dl->AddText(ImVec2(x + 1.4f * em, y), f.text, structure_label(s).c_str());
    y += line;
  }
  if (m.baseline_fy) {
    y += 0.5f * em;
    const ImU32 c = kernel_color(baseline_kernel, 0.7f);
    for (float d = 0.0f; d < 1.0f * em; d += 0.45f * em)
      dl->AddLine(ImVec2(x + d, y + 0.6f * em), ImVec2(x + d + 0.25f * em, y + 0.6f * em), c, 1.5f);
    dl->AddText(ImVec2(x + 1.4f * em, y), f.text, "fastest peer");
  }
}

/// Draws the chart of `m` into the rectangle [origin, origin + size].
void draw_chart(const BenchData& data, const ChartModel& m, const ChartOptions& options, ImVec2 origin, ImVec2 size) {
  const ChartFrame f = chart_frame(m, origin, size);
  if (f.too_small()) {
    f.dl->AddText(origin, f.dim, "(window too small for the chart)");
    return;
  }
  std::vector<ImVec4> taken;  // rectangles of text and markers drawn in the plot: labels avoid them
  draw_zero_band(f, m, taken);
  draw_grid_and_axes(f, m);
  draw_tick_labels(f, m);

  // The points: markers first in `taken`, indexed like m.points; then the labels.
  const float r = f.marker_r;
  std::vector<ImVec2> where(m.points.size());
  const size_t first_marker = taken.size();
  for (size_t i = 0; i < m.points.size(); ++i) {
    const ChartPoint& p = m.points[i];
    where[i] = ImVec2(f.px(p.fx), f.py(p.fy));
    taken.push_back(ImVec4(where[i].x - r, where[i].y - r, where[i].x + r, where[i].y + r));
  }
  f.dl->PushClipRect(f.p0, f.p1, true);
  const std::string baseline_kernel = m.baseline_row ? data.rows[*m.baseline_row].kernel : std::string("embree");
  if (m.baseline_fy) draw_baseline(f, data, m, baseline_kernel, taken);
  const std::vector<size_t> order = peers_first(data, m);
  for (size_t i : order) {
    const BenchRow& row = data.rows[m.points[i].row];
    draw_marker(f.dl, structure_shape(row.structure), where[i], r, kernel_color(row.kernel));
  }
  if (options.labels) draw_point_labels(f, data, m, order, where, first_marker, taken);
  f.dl->PopClipRect();

  if (ImGui::IsItemHovered()) hover_point(f, data, m, where);
  if (f.legend_w > 0.0f) draw_legend(f, m, baseline_kernel);
}

/// The file row: path field, Load button, the loaded file, the last error.
void file_row(BenchChartState& state, float field_width) {
  ImGui::SetNextItemWidth(field_width);
  const bool entered = ImGui::InputTextWithHint("##bench_json", "bench.json (accelviz-cli bench --out-json)",
                                                &state.path_field, ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Load") || entered) && !state.path_field.empty()) load_bench_into(state, state.path_field);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("read a JSON file written by accelviz-cli bench --out-json FILE");
  if (!state.error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.42f, 0.38f, 1.0f));
    ImGui::TextWrapped("%s", state.error.c_str());
    ImGui::PopStyleColor();
  }
}

}  // namespace

// ============================================================================
// [SECTION] The window and the main panel's section
// ============================================================================

void bench_chart_window(BenchChartState& state, glm::vec2 pos, glm::vec2 size, bool apply_layout) {
  if (!state.open) return;
  const ImGuiCond cond = apply_layout ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
  ImGui::SetNextWindowPos(ImVec2(pos.x, pos.y), cond);
  ImGui::SetNextWindowSize(ImVec2(size.x, size.y), cond);
  ImGui::SetNextWindowBgAlpha(1.0f);
  if (!ImGui::Begin("Speed vs error", &state.open)) {
    ImGui::End();
    return;
  }
  const float em = ImGui::GetFontSize();
  if (!state.data) {
    file_row(state, 20.0f * em);
    ImGui::TextWrapped("Load the JSON of a benchmark run (accelviz-cli bench ... --out-json FILE), or start the "
                       "viewer with --bench-json FILE.");
    ImGui::End();
    return;
  }
  const BenchData& data = *state.data;
  ChartOptions& o = state.options;
  o.group = std::min(o.group, data.groups.size() - 1);

  // ---- Controls: which rows, which x, which speed.
  auto group_label = [&](size_t i) {
    return std::to_string(i + 1) + ": " + data.groups[i].label() + " (" + std::to_string(data.groups[i].rows.size()) +
           " rows)";
  };
  ImGui::SetNextItemWidth(std::min(24.0f * em, ImGui::GetContentRegionAvail().x));
  if (ImGui::BeginCombo("##group", group_label(o.group).c_str())) {
    for (size_t i = 0; i < data.groups.size(); ++i)
      if (ImGui::Selectable(group_label(i).c_str(), i == o.group)) o.group = i;
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("scene and rays: only rows measured on the same rays compare");
  ImGui::SameLine();
  ImGui::TextDisabled("%s", data.path.c_str());
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", data.path.c_str());

  int x = static_cast<int>(o.x);
  ImGui::TextUnformatted("x:");
  ImGui::SameLine();
  ImGui::RadioButton("error rate", &x, 0);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("(false misses + false hits + wrong triangles) / rays, against the double reference");
  ImGui::SameLine();
  ImGui::RadioButton("t error", &x, 1);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the largest relative error of the hit distance t");
  o.x = static_cast<ChartX>(x);
  ImGui::SameLine(0.0f, 1.5f * em);
  int speed = static_cast<int>(o.speed);
  ImGui::TextUnformatted("y:");
  ImGui::SameLine();
  ImGui::RadioButton("all threads", &speed, 0);
  ImGui::SameLine();
  ImGui::RadioButton("1 thread", &speed, 1);
  o.speed = static_cast<ChartSpeed>(speed);
  ImGui::SameLine();
  ImGui::Checkbox("log", &o.log_y);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("log scale on y (speeds that differ by 100x)");
  ImGui::SameLine(0.0f, 1.5f * em);
  ImGui::Checkbox("labels", &o.labels);

  const ChartModel m = make_chart(data, o);
  char caption[320];
  std::snprintf(caption, sizeof caption,
                "Up and left is better: faster and fewer wrong answers. Colour = ray/triangle test or peer "
                "library, shape = structure; the dashed line is the fastest peer; the green band holds the rows with %s; hover a point for its numbers.",
                o.x == ChartX::ErrorRate ? "no wrong answer" : "exact hit distances");
  if (ImGui::GetContentRegionAvail().y < 22.0f * em) {
    // A small window keeps its height for the chart: the caption becomes a tooltip.
    ImGui::SameLine();
    ui::help_marker(caption);
  } else {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabled("%s", caption);
    ImGui::PopTextWrapPos();
  }

  // ---- The chart fills the rest; the invisible button owns the mouse (no window drag).
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const ImVec2 chart_size(std::max(avail.x, 1.0f), std::max(avail.y, 1.0f));
  ImGui::InvisibleButton("##chart", chart_size);
  draw_chart(data, m, o, origin, chart_size);
  ImGui::End();
}

void bench_chart_section(BenchChartState& state) {
  const float em = ImGui::GetFontSize();
  file_row(state, 12.0f * em);
  ImGui::BeginDisabled(!state.data);
  if (ImGui::Button(state.open ? "Hide chart" : "Show chart")) state.open = !state.open;
  ImGui::EndDisabled();
  if (state.data) {
    ImGui::SameLine();
    ImGui::TextDisabled("%zu rows, %zu groups", state.data->rows.size(), state.data->groups.size());
  }
}

// ---------------------------------------------------------------------------------------
// Script verbs (bench_chart_verbs.h)

void BenchChartTool::add_verbs(VerbTable& table, ToolHost& host) {
  // The runs need only the chart's state (bench_chart.h), so they bind to it.
  ToolVerbs<BenchChartState> verbs(table, state_, host);
  bench_chart_verbs(verbs);
}

void BenchChartTool::section(ToolHost&, PanelSection section) {
  if (section == PanelSection::Own && ImGui::CollapsingHeader("Speed vs error chart")) bench_chart_section(state_);
}

void BenchChartTool::panels(ToolHost& host) {
  const WindowLayout& layout = host.layout();
  bench_chart_window(state_, layout.rects().chart.pos, layout.rects().chart.size, layout.applying());
}

}  // namespace viz
