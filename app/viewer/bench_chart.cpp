#include "bench_chart.h"

#include "geometry.h"
#include "input_files.h"
#include "registry.h"
#include "text_format.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "check.h"

namespace viz {
namespace {

using Json = nlohmann::json;

// The row's fields by JSON type. Member pointers keep the key list and the struct in one
// place, so a key added to the bench needs one line here.
struct StringField {
  const char* key;
  std::string BenchRow::*member;
};
struct CountField {
  const char* key;
  uint64_t BenchRow::*member;
};
struct NumberField {
  const char* key;
  double BenchRow::*member;
};
constexpr StringField kStrings[] = {
    {"scene", &BenchRow::scene},   {"structure", &BenchRow::structure}, {"params", &BenchRow::params},
    {"kernel", &BenchRow::kernel}, {"rays", &BenchRow::rays},
};
constexpr CountField kCounts[] = {
    {"n_rays", &BenchRow::n_rays},         {"memory_bytes", &BenchRow::memory_bytes},
    {"threads", &BenchRow::threads},       {"false_miss", &BenchRow::false_miss},
    {"false_hit", &BenchRow::false_hit},   {"wrong_prim", &BenchRow::wrong_prim},
    {"wrong_t", &BenchRow::wrong_t},
};
constexpr NumberField kNumbers[] = {
    {"build_ms", &BenchRow::build_ms},           {"mrays_1t", &BenchRow::mrays_1t},
    {"mrays_mt", &BenchRow::mrays_mt},           {"max_rel_t_err", &BenchRow::max_rel_t_err},
    {"mean_rel_t_err", &BenchRow::mean_rel_t_err},
};

/// A JSON value as it appears in the file, shortened for a one-line message.
std::string shown(const Json& value) {
  std::string text = value.dump();
  constexpr size_t kMax = 40;
  if (text.size() > kMax) text = text.substr(0, kMax - 3) + "...";
  return text;
}

std::string type_name(const Json& value) {
  return value.is_number() ? "a number" : value.is_string() ? "a string" : value.is_object() ? "an object"
       : value.is_array()  ? "an array" : value.is_boolean() ? "a boolean" : "null";
}

/// Fills `row` from `object`; returns the message after "NAME: row N: ", or "".
std::string parse_row(const Json& object, BenchRow& row) {
  if (!object.is_object()) return "expected an object, got " + type_name(object);
  for (const StringField& f : kStrings) {
    const auto it = object.find(f.key);
    if (it == object.end()) return std::string("missing key '") + f.key + "'";
    if (!it->is_string()) return std::string("'") + f.key + "' must be a string, got " + shown(*it);
    row.*f.member = it->get<std::string>();
  }
  for (const CountField& f : kCounts) {
    const auto it = object.find(f.key);
    if (it == object.end()) return std::string("missing key '") + f.key + "'";
    // nlohmann stores non-negative integers as unsigned: -1 and 2.5 both fail here.
    if (!it->is_number_unsigned())
      return std::string("'") + f.key + "' must be a non-negative integer, got " + shown(*it);
    row.*f.member = it->get<uint64_t>();
  }
  for (const NumberField& f : kNumbers) {
    const auto it = object.find(f.key);
    if (it == object.end()) return std::string("missing key '") + f.key + "'";
    if (!it->is_number() || !(it->get<double>() >= 0.0) || !std::isfinite(it->get<double>()))
      return std::string("'") + f.key + "' must be a non-negative number, got " + shown(*it);
    row.*f.member = it->get<double>();
  }
  if (row.n_rays == 0) return "'n_rays' must be at least 1, got 0";
  // Optional: the bench omits the embree ratios on Embree rows and the peer ratios on peer
  // rows, writes null without them; older files have no peer (or 1t) keys at all.
  for (const auto& [key, member] : {std::pair{"embree_ratio_mt", &BenchRow::embree_ratio_mt},
                                    std::pair{"embree_ratio_1t", &BenchRow::embree_ratio_1t},
                                    std::pair{"peer_ratio_mt", &BenchRow::peer_ratio_mt},
                                    std::pair{"peer_ratio_1t", &BenchRow::peer_ratio_1t}}) {
    const auto it = object.find(key);
    if (it == object.end() || it->is_null()) continue;
    if (!it->is_number() || !(it->get<double>() >= 0.0))
      return std::string("'") + key + "' must be a non-negative number or null, got " + shown(*it);
    row.*member = it->get<double>();
  }
  return "";
}

using accel::with_separators;

/// "%g" without an exponent for tick values: 0.5, 20, 2.5, 1000.
std::string plain_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

/// 10^e exactly as the decimal literal "1e<e>" reads (std::pow may be off by an ulp).
double decade(int e) { return std::strtod(("1e" + std::to_string(e)).c_str(), nullptr); }

template <class T>
void append_unique(std::vector<T>& list, const T& value) {
  if (std::find(list.begin(), list.end(), value) == list.end()) list.push_back(value);
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Loading

std::string BenchGroup::label() const {
  const size_t slash = scene.find_last_of("/\\");
  return (slash == std::string::npos ? scene : scene.substr(slash + 1)) + ", " + rays;
}

accel::Result<BenchData> parse_bench_json(const std::string& text, const std::string& name) {
  Json root;
  try {
    root = Json::parse(text);
  } catch (const Json::exception& e) {
    // Any of nlohmann's errors, not only parse_error: a number too big for a double
    // ("2e308") is out_of_range (fuzz_bench_json found it). what() is
    // "[json.exception.parse_error.101] parse error at line 2, column 5: ...": the
    // bracketed id means nothing to a user.
    std::string message = e.what();
    if (const size_t close = message.find("] "); message.starts_with("[json.") && close != std::string::npos)
      message = message.substr(close + 2);
    std::replace(message.begin(), message.end(), '\n', ' ');
    return accel::make_error(name + ": not valid JSON: " + message);
  }
  if (!root.is_array())
    return accel::make_error(name + ": expected a JSON array of rows (accelviz-cli bench --out-json), got " +
                             type_name(root));
  if (root.empty()) return accel::make_error(name + ": no rows (the array is empty)");
  BenchData data;
  data.path = name;
  for (size_t i = 0; i < root.size(); ++i) {
    BenchRow row;
    if (const std::string error = parse_row(root[i], row); !error.empty())
      return accel::make_error(name + ": row " + std::to_string(i + 1) + ": " + error);
    auto group = std::find_if(data.groups.begin(), data.groups.end(),
                              [&](const BenchGroup& g) { return g.scene == row.scene && g.rays == row.rays; });
    if (group == data.groups.end()) {
      data.groups.push_back(BenchGroup{row.scene, row.rays, row.n_rays, {}});
      group = data.groups.end() - 1;
    }
    group->rows.push_back(data.rows.size());
    data.rows.push_back(std::move(row));
  }
  return data;
}

accel::Result<BenchData> load_bench_json(const std::string& path) {
  auto text = accel::read_input_file(path, "the file");
  if (!text) return text.error();
  return parse_bench_json(text.value(), path);
}

// ---------------------------------------------------------------------------------------
// Axes

float ChartAxis::unit(double v) const {
  if (log) return static_cast<float>((std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)));
  return static_cast<float>((v - lo) / (hi - lo));
}

ChartAxis log_decade_axis(double min, double max, bool power_labels) {
  ACCEL_CHECK(min > 0.0 && min <= max);
  // The small epsilon keeps 1e-3 (whose log10 is -2.9999999999999996) in its own decade.
  const int e_lo = static_cast<int>(std::floor(std::log10(min) + 1e-9));
  int e_hi = static_cast<int>(std::ceil(std::log10(max) - 1e-9));
  if (e_hi <= e_lo) e_hi = e_lo + 1;
  ChartAxis axis;
  axis.log = true;
  axis.power_labels = power_labels;
  axis.lo = decade(e_lo);
  axis.hi = decade(e_hi);
  const int decades = e_hi - e_lo;
  const int label_every = decades > 8 ? 2 : 1;
  for (int e = e_lo; e <= e_hi; ++e) {
    AxisTick t;
    t.value = decade(e);
    t.pos = static_cast<float>(e - e_lo) / static_cast<float>(decades);
    t.exponent = e;
    t.labelled = (e - e_lo) % label_every == 0;
    t.label = power_labels ? "1e" + std::to_string(e) : plain_number(t.value);
    axis.ticks.push_back(t);
    if (e == e_hi || decades > 4) continue;
    for (int m = 2; m <= 9; ++m) {
      AxisTick minor;
      minor.value = m * t.value;
      minor.pos = axis.unit(minor.value);
      minor.major = minor.labelled = false;
      minor.exponent = e;
      axis.ticks.push_back(minor);
    }
  }
  return axis;
}

ChartAxis linear_zero_axis(double max, int target_ticks) {
  ChartAxis axis;
  axis.lo = 0.0;
  if (!(max > 0.0) || !std::isfinite(max)) max = 1.0;
  target_ticks = std::max(target_ticks, 1);
  // The smallest nice step that covers max in at most target_ticks + 1 intervals (0..3 in
  // steps of 0.5 reads better than 0..3 in steps of 1 or 0..5 in steps of 1).
  const int most = target_ticks + 1;
  const double base = decade(static_cast<int>(std::floor(std::log10(max / most))));
  double step = 10.0 * base;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    if (std::ceil(max / (m * base) - 1e-9) <= most) {
      step = m * base;
      break;
    }
  }
  const int intervals = std::max(1, static_cast<int>(std::ceil(max / step - 1e-9)));
  axis.hi = step * intervals;
  for (int i = 0; i <= intervals; ++i) {
    AxisTick t;
    t.value = step * i;
    t.pos = static_cast<float>(i) / static_cast<float>(intervals);
    t.label = plain_number(t.value);  // %.10g: 0.3, not 0.30000000000000004
    axis.ticks.push_back(t);
  }
  return axis;
}

// ---------------------------------------------------------------------------------------
// The chart

namespace {

/// Bench rows that are no registry structure: the peers' (app/cli/bench.cpp names them).
/// Their labels and their place after the registry's structures are the chart's own.
struct ExternalStructure {
  const char* name;
  const char* label;
};
constexpr ExternalStructure kExternal[] = {
    {"embree-medium", "Embree med"}, {"embree-high", "Embree high"},    {"tinybvh-bvh8", "tinybvh 8"},
    {"tinybvh-bvh4", "tinybvh 4"},   {"tinybvh-bvh8-hq", "tinybvh 8 HQ"},
};
/// The peers' kernels in legend order, with their legend names.
constexpr ExternalStructure kPeerKernels[] = {{"embree", "Embree"}, {"tinybvh", "tinybvh"}};

}  // namespace

int kernel_order(const std::string& kernel) {
  // The core's kernels in its order, then the peers' (Embree, tinybvh), then any other.
  constexpr int kCore = static_cast<int>(std::size(accel::kAllKernels));
  for (int i = 0; i < kCore; ++i)
    if (kernel == accel::kernel_name(accel::kAllKernels[i])) return i;
  constexpr int kPeers = static_cast<int>(std::size(kPeerKernels));
  for (int i = 0; i < kPeers; ++i)
    if (kernel == kPeerKernels[i].name) return kCore + i;
  return kCore + kPeers;
}

std::string kernel_label(const std::string& kernel) {
  for (const ExternalStructure& k : kPeerKernels)
    if (kernel == k.name) return k.label;
  return kernel;
}

int structure_order(const std::string& structure) {
  // The registry's lecture order with the reference (brute force) last: it is the slow
  // oracle, not one of the structures compared.
  const auto& registry = accel::structure_registry();
  int order = 0;
  for (const bool reference : {false, true})
    for (const accel::StructureInfo& info : registry) {
      if (info.reference != reference) continue;
      if (info.name == structure) return order;
      ++order;
    }
  for (const ExternalStructure& e : kExternal) {
    if (structure == e.name) return order;
    ++order;
  }
  return order;
}

std::string structure_label(const std::string& structure) {
  auto info = accel::find_structure(structure);
  if (info) return info.value()->label;
  for (const ExternalStructure& e : kExternal)
    if (structure == e.name) return e.label;
  return structure;
}

std::string set_chart_option(ChartOptions& options, const std::string& key_value) {
  const size_t eq = key_value.find('=');
  const std::string key = key_value.substr(0, eq), value = eq == std::string::npos ? "" : key_value.substr(eq + 1);
  if (key == "x") {
    if (value == "errors") options.x = ChartX::ErrorRate;
    else if (value == "t-error") options.x = ChartX::MaxRelTErr;
    else return "x: expected errors or t-error, got '" + value + "'";
  } else if (key == "speed") {
    if (value == "mt") options.speed = ChartSpeed::AllThreads;
    else if (value == "1t") options.speed = ChartSpeed::OneThread;
    else return "speed: expected mt or 1t, got '" + value + "'";
  } else if (key == "y") {
    if (value == "linear") options.log_y = false;
    else if (value == "log") options.log_y = true;
    else return "y: expected linear or log, got '" + value + "'";
  } else if (key == "labels") {
    if (value == "on") options.labels = true;
    else if (value == "off") options.labels = false;
    else return "labels: expected on or off, got '" + value + "'";
  } else if (key == "group") {
    int n = 0;
    const char* end = value.data() + value.size();
    const auto [ptr, ec] = std::from_chars(value.data(), end, n);
    if (value.empty() || ec != std::errc() || ptr != end || n < 1)
      return "group: expected a group number from 1, got '" + value + "'";
    options.group = static_cast<size_t>(n - 1);
  } else {
    return "unknown chart setting '" + key_value + "' (x=errors|t-error, speed=mt|1t, y=linear|log, labels=on|off, "
           "group=N)";
  }
  return "";
}

std::string format_peer_ratio(const BenchRow& row) {
  if (row.is_peer()) return "(a peer)";
  if (!row.peer_ratio_mt && !row.peer_ratio_1t) return "- (none in the file)";
  char text[96];
  if (row.peer_ratio_mt && row.peer_ratio_1t)
    std::snprintf(text, sizeof text, "%.2fx the fastest peer with all threads, %.2fx with 1", *row.peer_ratio_mt,
                  *row.peer_ratio_1t);
  else if (row.peer_ratio_mt)
    std::snprintf(text, sizeof text, "%.2fx the fastest peer with all threads", *row.peer_ratio_mt);
  else
    std::snprintf(text, sizeof text, "%.2fx the fastest peer with 1 thread", *row.peer_ratio_1t);
  return text;
}

std::string format_error_rate(uint64_t wrong, uint64_t rays) {
  std::string text = with_separators(wrong) + " of " + with_separators(rays);
  if (wrong == 0 || rays == 0) return text;
  char rate[32];
  std::snprintf(rate, sizeof rate, " (%.3g%%)", 100.0 * static_cast<double>(wrong) / static_cast<double>(rays));
  return text + rate;
}

ChartModel make_chart(const BenchData& data, const ChartOptions& options) {
  ACCEL_CHECK(!data.groups.empty());
  const BenchGroup& group = data.groups[std::min(options.group, data.groups.size() - 1)];
  ChartModel m;
  const bool errors = options.x == ChartX::ErrorRate;
  const bool all_threads = options.speed == ChartSpeed::AllThreads;

  // Values, the legend's lists and the ranges.
  double x_min = 0.0, x_max = 0.0, y_min = 0.0, y_max = 0.0;
  uint64_t threads = 0, n_rays = 0;
  for (size_t index : group.rows) {
    const BenchRow& r = data.rows[index];
    ChartPoint p;
    p.row = index;
    p.x = errors ? r.error_rate() : r.max_rel_t_err;
    p.y = all_threads ? r.mrays_mt : r.mrays_1t;
    p.zero = p.x == 0.0;
    if (!p.zero) {
      x_min = x_min == 0.0 ? p.x : std::min(x_min, p.x);
      x_max = std::max(x_max, p.x);
    }
    if (p.y > 0.0) y_min = y_min == 0.0 ? p.y : std::min(y_min, p.y);
    y_max = std::max(y_max, p.y);
    threads = std::max(threads, r.threads);
    n_rays = std::max(n_rays, r.n_rays);
    append_unique(m.kernels, r.kernel);
    append_unique(m.structures, r.structure);
    if (r.is_peer() && (!m.baseline_y || p.y > *m.baseline_y)) {
      m.baseline_y = p.y;
      m.baseline_row = index;
    }
    m.points.push_back(p);
  }
  std::stable_sort(m.kernels.begin(), m.kernels.end(),
                   [](const std::string& a, const std::string& b) { return kernel_order(a) < kernel_order(b); });
  std::stable_sort(m.structures.begin(), m.structures.end(), [](const std::string& a, const std::string& b) {
    return structure_order(a) < structure_order(b);
  });

  // x: decades over the positive values. With none, a range that still says something: the
  // smallest non-zero error rate of these rays is 1/n_rays.
  if (x_max > 0.0) {
    m.x = log_decade_axis(x_min, x_max, true);
  } else if (errors) {
    const double smallest = 1.0 / static_cast<double>(n_rays);
    m.x = log_decade_axis(smallest, 100.0 * smallest, true);
  } else {
    m.x = log_decade_axis(1e-8, 1e-6, true);
  }
  // Error rates also as percentages under the decades: "1e-3" is "0.1%" to most readers.
  if (errors) {
    for (AxisTick& t : m.x.ticks)
      if (t.major) t.note = plain_number(100.0 * t.value) + "%";
  }
  // y: from 0 (honest bar-chart-like comparison), or decades when speeds differ by 100x.
  // 4% headroom keeps the fastest point off the top edge.
  m.y = options.log_y && y_min > 0.0 ? log_decade_axis(y_min, y_max, false) : linear_zero_axis(y_max * 1.04);

  // The band: its points evenly spaced in legend order (kernel, then structure).
  std::vector<ChartPoint*> zero;
  for (ChartPoint& p : m.points)
    if (p.zero) zero.push_back(&p);
  std::stable_sort(zero.begin(), zero.end(), [&](const ChartPoint* a, const ChartPoint* b) {
    const BenchRow &ra = data.rows[a->row], &rb = data.rows[b->row];
    const int ka = kernel_order(ra.kernel), kb = kernel_order(rb.kernel);
    return ka != kb ? ka < kb : structure_order(ra.structure) < structure_order(rb.structure);
  });
  m.zero_band = std::min(ChartModel::kBandBase + ChartModel::kBandPerPoint * static_cast<float>(zero.size()),
                         ChartModel::kBandMax);
  // 8% margins keep the outer markers off the y axis and the band's edge.
  for (size_t i = 0; i < zero.size(); ++i)
    zero[i]->fx = m.zero_band * (0.08f + 0.84f * (static_cast<float>(i) + 0.5f) / static_cast<float>(zero.size()));
  const float span = 1.0f - m.x_start();
  for (ChartPoint& p : m.points) {
    if (!p.zero) p.fx = m.x_start() + span * std::clamp(m.x.unit(p.x), 0.0f, 1.0f);
    p.fy = m.y.log ? (p.y > 0.0 ? std::clamp(m.y.unit(p.y), 0.0f, 1.0f) : 0.0f) : std::clamp(m.y.unit(p.y), 0.0f, 1.0f);
  }
  if (m.baseline_y && (!m.y.log || *m.baseline_y > 0.0)) m.baseline_fy = std::clamp(m.y.unit(*m.baseline_y), 0.0f, 1.0f);

  m.x_title = errors ? "error rate: wrong answers / rays (log scale)" : "largest relative t error (log scale)";
  m.y_title = all_threads ? "Mrays/s, " + std::to_string(threads) + (threads == 1 ? " thread" : " threads")
                          : std::string("Mrays/s, 1 thread");
  if (m.y.log) m.y_title += " (log scale)";
  m.zero_label = errors ? "0 errors" : "exact t";
  return m;
}

// ---------------------------------------------------------------------------------------
// Window state

accel::Status load_bench_into(BenchChartState& state, const std::string& path) {
  auto loaded = load_bench_json(path);
  if (!loaded) {
    state.error = loaded.error().message;
    return loaded.error();
  }
  state.data = std::move(loaded.value());
  state.options.group = 0;
  state.error.clear();
  state.path_field = path;
  state.open = true;
  return {};
}

}  // namespace viz
