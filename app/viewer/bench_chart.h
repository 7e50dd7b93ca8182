#pragma once
// The speed-against-error chart of `accelviz-cli bench --out-json` results, without a
// window: loading and validating the JSON, the (scene, rays) groups, and every coordinate
// and tick of the chart. tools/bench_chart_tool.cpp only draws what this computes, so the
// numbers a lecturer reads off the chart are unit-tested (tests/app/test_bench_chart.cpp).
//
// The chart: one point per bench row of the chosen group. y = Mrays/s (all threads, or one);
// x = error rate = (false misses + false hits + wrong triangles) / rays on a log axis, or the
// largest relative t error. A log axis has no place for 0, yet "no error at all" is the
// answer a watertight kernel should give, so exact zeros go to a separate band at the left.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "result.h"

namespace viz {

/// One row of the bench's JSON array (app/cli/bench.cpp, function `json`, writes it).
struct BenchRow {
  std::string scene;      ///< OBJ path or procedural:NAME
  /// Registry name, or a peer's: embree-medium / embree-high, tinybvh-bvh8 / tinybvh-bvh4 /
  /// tinybvh-bvh8-hq.
  std::string structure;
  std::string params;     ///< "key=value ..." as given to the bench ("" = defaults)
  std::string kernel;     ///< watertight, moller, double, or a peer's: embree, tinybvh
  std::string rays;       ///< the ray set: primary:W:H, random:N:SEED or a rays file
  uint64_t n_rays = 0;    ///< rays traced (> 0)
  double build_ms = 0.0;
  uint64_t memory_bytes = 0;
  double mrays_1t = 0.0;  ///< million rays per second, one thread
  double mrays_mt = 0.0;  ///< million rays per second, `threads` threads
  uint64_t threads = 0;
  uint64_t false_miss = 0;  ///< misses where the double reference hits
  uint64_t false_hit = 0;   ///< hits where the reference misses
  uint64_t wrong_prim = 0;  ///< hits on a triangle the reference does not hit at that t
  uint64_t wrong_t = 0;     ///< right triangle, t outside the tolerance (not in the error rate)
  double max_rel_t_err = 0.0;
  double mean_rel_t_err = 0.0;
  /// mrays_mt over the faster Embree row's; absent on Embree rows and when the bench had
  /// no Embree (the JSON's null).
  std::optional<double> embree_ratio_mt;
  /// The same for mrays_1t (optional key: newer benches write it).
  std::optional<double> embree_ratio_1t;
  /// mrays_mt over the fastest peer row's (Embree or tinybvh) on the same rays; absent on
  /// peer rows, without peers and in files older than the key (the JSON's null or no key).
  std::optional<double> peer_ratio_mt;
  /// The same for mrays_1t.
  std::optional<double> peer_ratio_1t;

  /// An Embree row (kernel "embree"): the baseline of the embree_ratio_* columns.
  bool is_embree() const { return kernel == "embree"; }
  /// A peer row: another library's answer to the same rays (Embree or tinybvh), the
  /// baseline of peer_ratio_*.
  bool is_peer() const { return is_peer_kernel(kernel); }
  /// Kernels of the peers' rows: "embree", "tinybvh".
  static bool is_peer_kernel(const std::string& kernel) { return kernel == "embree" || kernel == "tinybvh"; }
  /// Rays whose answer is wrong: false misses + false hits + wrong triangles.
  uint64_t wrong_answers() const { return false_miss + false_hit + wrong_prim; }
  /// wrong_answers() / n_rays, in [0, 1].
  double error_rate() const {
    return n_rays > 0 ? static_cast<double>(wrong_answers()) / static_cast<double>(n_rays) : 0.0;
  }
};

/// Rows measured on the same scene with the same rays: only these are comparable.
struct BenchGroup {
  std::string scene, rays;
  uint64_t n_rays = 0;        ///< of its first row
  std::vector<size_t> rows;   ///< indices into BenchData::rows, in file order
  /// "bunny.obj, primary:1024:1024": the scene's file name (no directories) and the rays.
  std::string label() const;
};

/// A loaded bench JSON file.
struct BenchData {
  std::string path;              ///< as given to load_bench_json
  std::vector<BenchRow> rows;    ///< in file order, at least one
  std::vector<BenchGroup> groups;  ///< in order of first appearance
};

/// Parses the text of a bench JSON file; `name` (the path) starts every error message.
/// Valid: an array of at least one object, each with the keys and types of BenchRow
/// (strings; non-negative integers; finite non-negative numbers; n_rays > 0;
/// embree_ratio_mt, embree_ratio_1t, peer_ratio_mt and peer_ratio_1t a number, null or absent);
/// other keys are ignored. Errors are one line:
/// "NAME: not valid JSON: ...", "NAME: expected a JSON array of rows ...",
/// "NAME: row 3: missing key 'mrays_mt'", "NAME: row 3: 'n_rays' must be ..., got ...";
/// rows count from 1.
accel::Result<BenchData> parse_bench_json(const std::string& text, const std::string& name);

/// Reads and parses a bench JSON file; "PATH: cannot read the file" when it cannot be read.
accel::Result<BenchData> load_bench_json(const std::string& path);

// ---------------------------------------------------------------------------------------
// Axes

/// One tick of an axis.
struct AxisTick {
  double value = 0.0;
  float pos = 0.0f;     ///< 0 at the axis' lo, 1 at its hi
  bool major = true;    ///< labelled, with a grid line; minor ticks get a faint line only
  bool labelled = true; ///< major ticks of a long log axis are labelled every second decade
  std::string label;    ///< "20", "0.5", "100"; "1e-7" on a power-labelled axis
  int exponent = 0;     ///< log axis: value = 10^exponent on major ticks
  std::string note;     ///< a second, smaller label under it ("0.1%" for an error rate of 1e-3), or ""
};

/// A linear or logarithmic axis from lo to hi with its ticks.
struct ChartAxis {
  double lo = 0.0, hi = 1.0;
  bool log = false;
  /// Draw the decades as 10 with a superscript exponent (labels are then "1e-3"); else
  /// plain numbers ("0.1", "100").
  bool power_labels = false;
  std::vector<AxisTick> ticks;
  /// Where `v` lies: 0 at lo, 1 at hi (log10 spacing on a log axis), not clamped.
  /// On a log axis v must be > 0.
  float unit(double v) const;
};

/// Log axis over whole decades: lo = 10^floor(log10(min)), hi = 10^ceil(log10(max)) (one
/// decade at least). Major ticks on every decade, labelled on every one up to 8 decades and
/// every second one beyond; minor ticks at 2..9 x 10^k when it spans at most 4 decades.
/// Labels: "1e-3" with `power_labels`, else plain ("0.01", "1000"). Needs 0 < min <= max.
ChartAxis log_decade_axis(double min, double max, bool power_labels);

/// Linear axis from 0 to a multiple of a "nice" step >= max: the smallest step of 1, 2, 2.5
/// or 5 times a power of ten that needs at most target_ticks + 1 intervals; a tick on every
/// interval. max <= 0 gives 0..1.
ChartAxis linear_zero_axis(double max, int target_ticks = 5);

// ---------------------------------------------------------------------------------------
// The chart

/// What x shows.
enum class ChartX {
  ErrorRate,  ///< wrong answers / rays
  MaxRelTErr, ///< the largest relative t error of the row (exactness of the hit distance)
};
/// Which throughput y shows.
enum class ChartSpeed { AllThreads, OneThread };

/// The chart's settings (the window's combo and toggles, and `show-chart` in scripts).
struct ChartOptions {
  size_t group = 0;  ///< index into BenchData::groups (clamped)
  ChartX x = ChartX::ErrorRate;
  ChartSpeed speed = ChartSpeed::AllThreads;
  bool log_y = false;  ///< decades on y instead of a linear axis from 0
  bool labels = true;  ///< short structure labels next to the points
};

/// Sets one option from "key=value", the form scripts use: x=errors|t-error,
/// speed=mt|1t, y=linear|log, labels=on|off, group=N (1-based; only checked against the
/// data when applied). Returns an error message naming the key and the valid values, or "".
std::string set_chart_option(ChartOptions& options, const std::string& key_value);

/// One row of the group, placed on the chart.
struct ChartPoint {
  size_t row = 0;       ///< index into BenchData::rows
  double x = 0.0;       ///< the x value (error rate or max rel t error)
  double y = 0.0;       ///< Mrays/s
  bool zero = false;    ///< x == 0: drawn in the zero band
  float fx = 0.0f;      ///< 0 (left edge of the zero band) .. 1 (right end of the x axis)
  float fy = 0.0f;      ///< 0 (bottom) .. 1 (top)
};

/// Everything the panel draws, in unit coordinates (fx, fy in 0..1).
struct ChartModel {
  ChartAxis x;  ///< the log axis for x > 0; it spans fx = x_start() .. 1
  ChartAxis y;
  std::vector<ChartPoint> points;  ///< file order
  std::string x_title, y_title, zero_label;
  std::vector<std::string> kernels;     ///< kernels in this group, legend order
  std::vector<std::string> structures;  ///< structures in this group, legend order
  /// y of the fastest peer row (Embree or tinybvh: the dashed baseline), if the group has
  /// peer rows; baseline_row is that row (index into BenchData::rows; the first on a tie).
  std::optional<double> baseline_y;
  std::optional<float> baseline_fy;
  std::optional<size_t> baseline_row;
  /// Width of the zero band as a fraction of the chart's width: kBandBase, plus
  /// kBandPerPoint for each point in it (at most kBandMax), so that its points do not pile up.
  float zero_band = kBandBase;
  static constexpr float kBandBase = 0.1f, kBandPerPoint = 0.012f, kBandMax = 0.25f;
  /// The gap between the band and the log axis (where the axis is drawn broken).
  static constexpr float kZeroGap = 0.04f;
  /// fx where the log axis begins.
  float x_start() const { return zero_band + kZeroGap; }
};

/// Places the rows of options.group on the chart. x has no scale inside the zero band, so
/// its points are spread evenly across it, ordered by kernel and then structure (legend
/// order): same-speed rows stay apart and each kernel forms a cluster. The x axis covers
/// the positive values only (when there are none, a default range: around 1/n_rays for the
/// error rate, 1e-8..1e-6 for t errors). Needs a non-empty `data`.
ChartModel make_chart(const BenchData& data, const ChartOptions& options);

/// Legend order of the kernels: the core's (watertight, moller, double), the peers' (embree,
/// tinybvh), then any other.
int kernel_order(const std::string& kernel);
/// The legend's name of a kernel: "Embree", "tinybvh" for the peers, else the name itself.
std::string kernel_label(const std::string& kernel);
/// Legend order of the structures: the registry's in lecture order with the reference
/// (brute force) last, then the peers' (Embree medium and high; tinybvh BVH8, BVH4, BVH8
/// HQ), then any other.
int structure_order(const std::string& structure);
/// The label of a bench row's structure: the registry's ("kd-tree"), the chart's for the
/// peers ("Embree med", "Embree high", "tinybvh 8", "tinybvh 4", "tinybvh 8 HQ"), else the
/// name itself.
std::string structure_label(const std::string& structure);
/// The tooltip's line on a row against the fastest peer: "0.92x the fastest peer with all
/// threads, 0.85x with 1"; "(a peer)" on peer rows; without a ratio (no peer rows, or a file older than the key)
/// "- (none in the file)".
std::string format_peer_ratio(const BenchRow& row);

/// "650 of 20,000 (3.25%)": wrong answers, rays and the rate to 3 significant digits;
/// "0 of 20,000" when there is none (a percentage would suggest a rounded small number).
std::string format_error_rate(uint64_t wrong, uint64_t rays);

// ---------------------------------------------------------------------------------------
// Window state

/// What the chart window keeps between frames (owned by App).
struct BenchChartState {
  bool open = false;               ///< the "Speed vs error" window is shown
  std::string path_field;          ///< the text field of the path to load
  std::optional<BenchData> data;   ///< the file loaded last (kept when a later load fails)
  std::string error;               ///< the last load's error, "" after a success
  ChartOptions options;
};

/// Loads `path` into `state`: on success replaces the data, selects the first group, clears
/// the error and opens the window; on failure keeps the previous data and returns (and
/// stores) the one-line error.
accel::Status load_bench_into(BenchChartState& state, const std::string& path);

}  // namespace viz
