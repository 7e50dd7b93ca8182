// The bench chart's model: loading and validating the JSON, axes, the zero band, groups.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "bench_chart.h"
#include "geometry.h"
#include "registry.h"
#include "viewer_test_support.h"

namespace viz {
namespace {


// ---------------------------------------------------------------------------------------
// Bench chart: loading, validation, axes, the zero band, groups

/// One bench row as the CLI writes it, with `changes` (key -> JSON literal, or "" to drop
/// the key) applied.
std::string bench_row(const std::map<std::string, std::string>& changes = {}) {
  std::map<std::string, std::string> fields = {
      {"scene", "\"procedural:cornell\""}, {"structure", "\"bvh\""}, {"params", "\"\""},
      {"kernel", "\"watertight\""}, {"rays", "\"random:2000:1\""}, {"n_rays", "2000"},
      {"build_ms", "0.6"}, {"memory_bytes", "13936"}, {"mrays_1t", "3.5"}, {"mrays_mt", "6.25"},
      {"threads", "2"}, {"false_miss", "0"}, {"false_hit", "0"}, {"wrong_prim", "0"}, {"wrong_t", "0"},
      {"max_rel_t_err", "6.2e-06"}, {"mean_rel_t_err", "7.1e-08"}, {"embree_ratio_mt", "0.5"}};
  for (const auto& [key, value] : changes) {
    if (value.empty()) fields.erase(key);
    else fields[key] = value;
  }
  std::string text = "{";
  for (const auto& [key, value] : fields) text += (text.size() > 1 ? ", \"" : "\"") + key + "\": " + value;
  return text + "}";
}

/// A JSON array of the given rows.
std::string bench_array(const std::vector<std::string>& rows) {
  std::string text = "[\n";
  for (size_t i = 0; i < rows.size(); ++i) text += "  " + rows[i] + (i + 1 < rows.size() ? ",\n" : "\n");
  return text + "]\n";
}

BenchData parsed_bench(const std::vector<std::string>& rows) {
  auto parsed = parse_bench_json(bench_array(rows), "t.json");
  EXPECT_TRUE(parsed.ok()) << parsed.error().message;
  return parsed.ok() ? parsed.value() : BenchData{};
}

TEST(BenchChart, LoadsTheCheckedInFile) {
  // Made by accelviz-cli bench (tests/app/data/README.md says how): two groups, the first
  // with every structure, three kernels and both peers (Embree, tinybvh), the second with
  // no wrong answer in the core's kernels.
  auto loaded = load_bench_json(ACCEL_TEST_DATA_DIR "/bench_chart.json");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const BenchData& d = loaded.value();
  ASSERT_EQ(d.rows.size(), 29u);
  ASSERT_EQ(d.groups.size(), 2u);
  EXPECT_EQ(d.groups[0].label(), "bunny.obj, bunny_edges_20k.txt");
  EXPECT_EQ(d.groups[0].rows.size(), 20u);
  EXPECT_EQ(d.groups[1].label(), "procedural:cornell, random:2000:1");
  EXPECT_EQ(d.groups[1].rows.size(), 9u);
  EXPECT_EQ(d.groups[1].n_rays, 2000u);
  size_t embree = 0, tinybvh = 0;
  for (const BenchRow& r : d.rows) {
    EXPECT_GT(r.mrays_mt, 0.0);
    if (r.is_embree()) {
      ++embree;
      EXPECT_TRUE(r.is_peer());
      EXPECT_FALSE(r.embree_ratio_mt.has_value());
    } else {
      EXPECT_TRUE(r.embree_ratio_mt.has_value()) << r.structure;
      EXPECT_TRUE(r.embree_ratio_1t.has_value()) << r.structure;
    }
    if (r.kernel == "tinybvh") {
      ++tinybvh;
      EXPECT_TRUE(r.is_peer());
      EXPECT_FALSE(r.is_embree());
      EXPECT_TRUE(r.structure.starts_with("tinybvh-")) << r.structure;
    }
    // The bench writes peer ratios on every row but the peers' own.
    EXPECT_EQ(r.peer_ratio_mt.has_value(), !r.is_peer()) << r.structure;
    EXPECT_EQ(r.peer_ratio_1t.has_value(), !r.is_peer()) << r.structure;
    if (r.kernel == "watertight" || r.kernel == "double") {
      EXPECT_EQ(r.wrong_answers(), 0u) << r.structure;
    }
  }
  EXPECT_EQ(embree, 4u);
  EXPECT_EQ(tinybvh, 6u);

  const ChartModel m = make_chart(d, ChartOptions{});
  EXPECT_EQ(m.points.size(), 20u);
  EXPECT_EQ(m.kernels, (std::vector<std::string>{"watertight", "moller", "double", "embree", "tinybvh"}));
  EXPECT_EQ(m.structures, (std::vector<std::string>{"grid", "octree", "kdtree", "bvh", "spheretree", "embree-medium",
                                                    "embree-high", "tinybvh-bvh8", "tinybvh-bvh4", "tinybvh-bvh8-hq"}));
  // The baseline is the fastest peer row of the group, and each accelviz row's peer ratio
  // is its speed over that row's (the file's ratios are rounded to 4 digits).
  ASSERT_TRUE(m.baseline_y.has_value());
  ASSERT_TRUE(m.baseline_row.has_value());
  const BenchRow& fastest = d.rows[*m.baseline_row];
  EXPECT_TRUE(fastest.is_peer());
  for (size_t i : d.groups[0].rows) {
    const BenchRow& r = d.rows[i];
    if (r.is_peer()) {
      EXPECT_LE(r.mrays_mt, *m.baseline_y) << r.structure;
    } else {
      EXPECT_NEAR(*r.peer_ratio_mt, r.mrays_mt / fastest.mrays_mt, 1e-3) << r.structure << " " << r.kernel;
    }
  }
  EXPECT_DOUBLE_EQ(*m.baseline_y, fastest.mrays_mt);
}

TEST(BenchChart, BadFilesGiveOneLineNamingFileRowAndKey) {
  struct Case {
    std::string text;
    std::string expected;  // the whole message
  };
  const std::string good = bench_row();
  const Case cases[] = {
      {"", "t.json: not valid JSON: parse error at line 1, column 1: "},
      {"[{\"scene\": \n", "t.json: not valid JSON: parse error at line 2, column 1: "},
      // A number beyond double's range is nlohmann's out_of_range, not a parse_error (fuzz_bench_json).
      {bench_array({bench_row({{"build_ms", "2e308"}})}), "t.json: not valid JSON: number overflow parsing '2e308'"},
      {"{\"rows\": []}", "t.json: expected a JSON array of rows (accelviz-cli bench --out-json), got an object"},
      {"[]", "t.json: no rows (the array is empty)"},
      {"[" + good + ", 7]", "t.json: row 2: expected an object, got a number"},
      {bench_array({good, bench_row({{"mrays_mt", ""}})}), "t.json: row 2: missing key 'mrays_mt'"},
      {bench_array({bench_row({{"scene", ""}})}), "t.json: row 1: missing key 'scene'"},
      {bench_array({bench_row({{"n_rays", "\"2000\""}})}),
       "t.json: row 1: 'n_rays' must be a non-negative integer, got \"2000\""},
      {bench_array({bench_row({{"false_hit", "-1"}})}), "t.json: row 1: 'false_hit' must be a non-negative integer, got -1"},
      {bench_array({bench_row({{"threads", "2.5"}})}), "t.json: row 1: 'threads' must be a non-negative integer, got 2.5"},
      {bench_array({bench_row({{"n_rays", "0"}})}), "t.json: row 1: 'n_rays' must be at least 1, got 0"},
      {bench_array({bench_row({{"kernel", "3"}})}), "t.json: row 1: 'kernel' must be a string, got 3"},
      {bench_array({bench_row({{"build_ms", "-0.5"}})}), "t.json: row 1: 'build_ms' must be a non-negative number, got -0.5"},
      {bench_array({bench_row({{"mrays_1t", "null"}})}), "t.json: row 1: 'mrays_1t' must be a non-negative number, got null"},
      {bench_array({bench_row({{"embree_ratio_mt", "\"fast\""}})}),
       "t.json: row 1: 'embree_ratio_mt' must be a non-negative number or null, got \"fast\""},
  };
  for (const Case& c : cases) {
    auto parsed = parse_bench_json(c.text, "t.json");
    ASSERT_FALSE(parsed.ok()) << c.text;
    const std::string& message = parsed.error().message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    if (c.expected.ends_with(": ")) {
      EXPECT_TRUE(message.starts_with(c.expected)) << message;
    } else {
      EXPECT_EQ(message, c.expected);
    }
  }
  auto missing = load_bench_json("/nonexistent/bench.json");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().message, "/nonexistent/bench.json: cannot read the file");

  // embree_ratio_mt may be null or absent (Embree rows, benches without Embree); unknown
  // keys are ignored.
  const BenchData d = parsed_bench({bench_row({{"embree_ratio_mt", "null"}}), bench_row({{"embree_ratio_mt", ""}}),
                                    bench_row({{"future_key", "[1, 2]"}, {"embree_ratio_1t", "0.25"}})});
  ASSERT_EQ(d.rows.size(), 3u);
  EXPECT_FALSE(d.rows[0].embree_ratio_mt.has_value());
  EXPECT_FALSE(d.rows[1].embree_ratio_mt.has_value());
  EXPECT_FALSE(d.rows[1].embree_ratio_1t.has_value());
  EXPECT_DOUBLE_EQ(d.rows[2].embree_ratio_mt.value(), 0.5);
  EXPECT_DOUBLE_EQ(d.rows[2].embree_ratio_1t.value(), 0.25);
  auto bad_1t = parse_bench_json(bench_array({bench_row({{"embree_ratio_1t", "true"}})}), "t.json");
  ASSERT_FALSE(bad_1t.ok());
  EXPECT_EQ(bad_1t.error().message, "t.json: row 1: 'embree_ratio_1t' must be a non-negative number or null, got true");
}

TEST(BenchChart, PeerRatiosAreOptionalNumbers) {
  // peer_ratio_mt / _1t: a number, null (a run without peers) or absent (peer rows, files
  // older than the key), like the Embree ratios.
  const BenchData d = parsed_bench({bench_row({{"peer_ratio_mt", "0.92"}, {"peer_ratio_1t", "0.85"}}),
                                    bench_row({{"peer_ratio_mt", "null"}, {"peer_ratio_1t", "null"}}),
                                    bench_row(), bench_row({{"peer_ratio_mt", "1.5"}})});
  ASSERT_EQ(d.rows.size(), 4u);
  EXPECT_DOUBLE_EQ(d.rows[0].peer_ratio_mt.value(), 0.92);
  EXPECT_DOUBLE_EQ(d.rows[0].peer_ratio_1t.value(), 0.85);
  EXPECT_FALSE(d.rows[1].peer_ratio_mt.has_value());
  EXPECT_FALSE(d.rows[1].peer_ratio_1t.has_value());
  EXPECT_FALSE(d.rows[2].peer_ratio_mt.has_value());
  EXPECT_FALSE(d.rows[2].peer_ratio_1t.has_value());
  EXPECT_DOUBLE_EQ(d.rows[3].peer_ratio_mt.value(), 1.5);
  EXPECT_FALSE(d.rows[3].peer_ratio_1t.has_value());
  EXPECT_EQ(format_peer_ratio(d.rows[0]), "0.92x the fastest peer with all threads, 0.85x with 1");
  EXPECT_EQ(format_peer_ratio(d.rows[1]), "- (none in the file)");
  EXPECT_EQ(format_peer_ratio(d.rows[3]), "1.50x the fastest peer with all threads");
  const BenchData peer = parsed_bench({bench_row({{"structure", "\"tinybvh-bvh8\""}, {"kernel", "\"tinybvh\""}})});
  EXPECT_EQ(format_peer_ratio(peer.rows[0]), "(a peer)");
  for (const char* key : {"peer_ratio_mt", "peer_ratio_1t"}) {
    auto bad = parse_bench_json(bench_array({bench_row({{key, "\"fast\""}})}), "t.json");
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().message,
              std::string("t.json: row 1: '") + key + "' must be a non-negative number or null, got \"fast\"");
  }
  auto negative = parse_bench_json(bench_array({bench_row({{"peer_ratio_1t", "-0.5"}})}), "t.json");
  ASSERT_FALSE(negative.ok());
}

TEST(BenchChart, BaselineIsTheFastestPeer) {
  // Embree and tinybvh rows are both peers; the dashed line is at the fastest of them, for
  // the speed shown (here tinybvh with all threads, Embree with one). The peers' wrong
  // answers place them on the error axis like any row.
  const BenchData d = parsed_bench({
      bench_row({{"mrays_mt", "6"}, {"mrays_1t", "3"}, {"peer_ratio_mt", "0.6667"}, {"peer_ratio_1t", "0.75"}}),
      bench_row({{"structure", "\"embree-medium\""}, {"kernel", "\"embree\""}, {"embree_ratio_mt", ""},
                 {"mrays_mt", "7"}, {"mrays_1t", "4"}, {"false_hit", "4"}}),
      bench_row({{"structure", "\"tinybvh-bvh8\""}, {"kernel", "\"tinybvh\""}, {"mrays_mt", "9"},
                 {"mrays_1t", "3.5"}, {"wrong_prim", "20"}}),
      bench_row({{"structure", "\"tinybvh-bvh4\""}, {"kernel", "\"tinybvh\""}, {"mrays_mt", "8"}, {"mrays_1t", "3.9"}}),
  });
  EXPECT_FALSE(d.rows[0].is_peer());
  EXPECT_TRUE(d.rows[1].is_peer() && d.rows[1].is_embree());
  EXPECT_TRUE(d.rows[2].is_peer() && !d.rows[2].is_embree());
  ChartOptions o;
  ChartModel m = make_chart(d, o);
  ASSERT_TRUE(m.baseline_y.has_value());
  EXPECT_DOUBLE_EQ(*m.baseline_y, 9.0);
  EXPECT_EQ(m.baseline_row, std::optional<size_t>(2));
  EXPECT_DOUBLE_EQ(m.y.hi, 10.0);
  EXPECT_FLOAT_EQ(m.baseline_fy.value(), 0.9f);
  EXPECT_EQ(m.kernels, (std::vector<std::string>{"watertight", "embree", "tinybvh"}));
  EXPECT_EQ(m.structures,
            (std::vector<std::string>{"bvh", "embree-medium", "tinybvh-bvh8", "tinybvh-bvh4"}));
  // Wrong answers of the peers: off the band, on the log axis (4 and 20 of 2000).
  EXPECT_FALSE(m.points[1].zero);
  EXPECT_FALSE(m.points[2].zero);
  EXPECT_TRUE(m.points[3].zero);
  EXPECT_DOUBLE_EQ(m.points[2].x, 0.01);
  EXPECT_DOUBLE_EQ(m.x.lo, 1e-3);
  EXPECT_FLOAT_EQ(m.points[2].fx, 1.0f);
  o.speed = ChartSpeed::OneThread;
  m = make_chart(d, o);
  EXPECT_DOUBLE_EQ(*m.baseline_y, 4.0);
  EXPECT_EQ(m.baseline_row, std::optional<size_t>(1));

  // No peer at all: no baseline.
  const ChartModel none = make_chart(parsed_bench({bench_row()}), ChartOptions{});
  EXPECT_FALSE(none.baseline_y.has_value());
  EXPECT_FALSE(none.baseline_row.has_value());
}

TEST(BenchChart, ErrorRateCountsWrongAnswersNotWrongT) {
  const BenchData d = parsed_bench(
      {bench_row({{"n_rays", "600"}, {"false_miss", "1"}, {"false_hit", "2"}, {"wrong_prim", "3"}, {"wrong_t", "4"}})});
  const BenchRow& r = d.rows[0];
  EXPECT_EQ(r.wrong_answers(), 6u);
  EXPECT_DOUBLE_EQ(r.error_rate(), 0.01);
  EXPECT_EQ(format_error_rate(650, 20000), "650 of 20,000 (3.25%)");
  EXPECT_EQ(format_error_rate(0, 2000), "0 of 2,000");
  EXPECT_EQ(format_error_rate(1, 1000000), "1 of 1,000,000 (0.0001%)");
}

TEST(BenchChart, LogAxisCoversWholeDecades) {
  const ChartAxis a = log_decade_axis(0.0054, 0.00915, true);
  EXPECT_TRUE(a.log);
  EXPECT_DOUBLE_EQ(a.lo, 1e-3);
  EXPECT_DOUBLE_EQ(a.hi, 1e-2);
  std::vector<std::string> labels;
  size_t minor = 0;
  for (const AxisTick& t : a.ticks) {
    if (t.major) labels.push_back(t.label);
    else ++minor;
  }
  EXPECT_EQ(labels, (std::vector<std::string>{"1e-3", "1e-2"}));
  EXPECT_EQ(minor, 8u);  // 2..9 x 1e-3
  EXPECT_NEAR(a.unit(2e-3), std::log10(2.0), 1e-6);
  EXPECT_NEAR(a.unit(std::sqrt(1e-5)), 0.5, 1e-6);
  EXPECT_EQ(a.ticks.front().exponent, -3);

  // An exact decade still gets one decade of room; exact powers stay in their decade.
  const ChartAxis one = log_decade_axis(1e-3, 1e-3, true);
  EXPECT_DOUBLE_EQ(one.lo, 1e-3);
  EXPECT_DOUBLE_EQ(one.hi, 1e-2);
  const ChartAxis two = log_decade_axis(1e-3, 1e-1, true);
  EXPECT_DOUBLE_EQ(two.lo, 1e-3);
  EXPECT_DOUBLE_EQ(two.hi, 1e-1);

  // Twelve decades: no minor ticks, every second decade labelled.
  const ChartAxis wide = log_decade_axis(3e-12, 0.5, true);
  EXPECT_EQ(wide.ticks.size(), 13u);
  size_t labelled = 0;
  for (const AxisTick& t : wide.ticks) {
    EXPECT_TRUE(t.major);
    labelled += t.labelled;
  }
  EXPECT_EQ(labelled, 7u);

  // Plain labels (the speed axis).
  std::vector<std::string> plain;
  for (const AxisTick& t : log_decade_axis(0.5, 40.0, false).ticks)
    if (t.major) plain.push_back(t.label);
  EXPECT_EQ(plain, (std::vector<std::string>{"0.1", "1", "10", "100"}));
}

TEST(BenchChart, LinearAxisUsesNiceSteps) {
  auto labels = [](const ChartAxis& a) {
    std::vector<std::string> out;
    for (const AxisTick& t : a.ticks) out.push_back(t.label);
    return out;
  };
  const ChartAxis a = linear_zero_axis(9.35);
  EXPECT_FALSE(a.log);
  EXPECT_DOUBLE_EQ(a.hi, 10.0);
  EXPECT_EQ(labels(a), (std::vector<std::string>{"0", "2", "4", "6", "8", "10"}));
  EXPECT_FLOAT_EQ(a.ticks[1].pos, 0.2f);
  EXPECT_EQ(labels(linear_zero_axis(2.6)), (std::vector<std::string>{"0", "0.5", "1", "1.5", "2", "2.5", "3"}));
  EXPECT_EQ(labels(linear_zero_axis(0.7)), (std::vector<std::string>{"0", "0.2", "0.4", "0.6", "0.8"}));
  EXPECT_EQ(labels(linear_zero_axis(130.0)), (std::vector<std::string>{"0", "25", "50", "75", "100", "125", "150"}));
  EXPECT_DOUBLE_EQ(linear_zero_axis(0.0).hi, 1.0);
  EXPECT_FLOAT_EQ(a.unit(5.0), 0.5f);
}

TEST(BenchChart, ZeroErrorRowsGoToTheBand) {
  // Two exact kernels (zero errors) and Moller with errors; Embree as the baseline.
  const BenchData d = parsed_bench({
      bench_row({{"structure", "\"grid\""}, {"mrays_mt", "2"}}),
      bench_row({{"structure", "\"bvh\""}, {"kernel", "\"double\""}, {"mrays_mt", "4"}}),
      bench_row({{"structure", "\"bvh\""}, {"mrays_mt", "5"}}),
      bench_row({{"structure", "\"bvh\""}, {"kernel", "\"moller\""}, {"false_miss", "2"}, {"mrays_mt", "6"}}),
      bench_row({{"structure", "\"embree-high\""}, {"kernel", "\"embree\""}, {"embree_ratio_mt", ""},
                 {"wrong_prim", "20"}, {"mrays_mt", "9.5"}}),
  });
  const ChartModel m = make_chart(d, ChartOptions{});
  ASSERT_EQ(m.points.size(), 5u);
  EXPECT_FLOAT_EQ(m.zero_band, ChartModel::kBandBase + 3 * ChartModel::kBandPerPoint);
  EXPECT_EQ(m.zero_label, "0 errors");
  // The x axis covers only the positive error rates: 2/2000 and 20/2000.
  EXPECT_DOUBLE_EQ(m.x.lo, 1e-3);
  EXPECT_DOUBLE_EQ(m.x.hi, 1e-2);
  EXPECT_EQ(m.x.ticks.front().note, "0.1%");
  // In the band, spread in legend order: watertight grid, watertight bvh, double bvh.
  const ChartPoint &grid = m.points[0], &bvh_double = m.points[1], &bvh = m.points[2];
  for (const ChartPoint* p : {&grid, &bvh_double, &bvh}) {
    EXPECT_TRUE(p->zero);
    EXPECT_GT(p->fx, 0.0f);
    EXPECT_LT(p->fx, m.zero_band);
  }
  EXPECT_LT(grid.fx, bvh.fx);
  EXPECT_LT(bvh.fx, bvh_double.fx);
  // Off the band: on the log axis, after the gap.
  const ChartPoint &moller = m.points[3], &embree = m.points[4];
  EXPECT_FALSE(moller.zero);
  EXPECT_DOUBLE_EQ(moller.x, 0.001);
  EXPECT_FLOAT_EQ(moller.fx, m.x_start());
  EXPECT_FLOAT_EQ(embree.fx, 1.0f);
  // y: 0..10 linear; the baseline is Embree's speed.
  EXPECT_DOUBLE_EQ(m.y.hi, 10.0);
  EXPECT_FLOAT_EQ(moller.fy, 0.6f);
  ASSERT_TRUE(m.baseline_y.has_value());
  EXPECT_DOUBLE_EQ(*m.baseline_y, 9.5);
  EXPECT_FLOAT_EQ(m.baseline_fy.value(), 0.95f);
  EXPECT_EQ(m.y_title, "Mrays/s, 2 threads");

  // No error anywhere: the band holds everything, and the axis still spans 1/n_rays.
  const BenchData exact = parsed_bench({bench_row(), bench_row({{"kernel", "\"double\""}})});
  const ChartModel e = make_chart(exact, ChartOptions{});
  EXPECT_TRUE(e.points[0].zero && e.points[1].zero);
  EXPECT_LE(e.x.lo, 1.0 / 2000.0);
  EXPECT_GE(e.x.hi, 1.0 / 2000.0);

  // t error as x: exact t goes to the band too.
  ChartOptions t_error;
  t_error.x = ChartX::MaxRelTErr;
  const ChartModel t = make_chart(parsed_bench({bench_row(), bench_row({{"max_rel_t_err", "0"}})}), t_error);
  EXPECT_FALSE(t.points[0].zero);
  EXPECT_TRUE(t.points[1].zero);
  EXPECT_EQ(t.zero_label, "exact t");
  EXPECT_DOUBLE_EQ(t.x.lo, 1e-6);
  EXPECT_TRUE(t.x.ticks.front().note.empty());
}

TEST(BenchChart, GroupsSpeedAndLogY) {
  const BenchData d = parsed_bench({
      bench_row({{"mrays_mt", "4"}, {"mrays_1t", "2"}}),
      bench_row({{"rays", "\"primary:64:64\""}, {"n_rays", "4096"}, {"mrays_mt", "40"}, {"threads", "8"}}),
      bench_row({{"structure", "\"grid\""}, {"mrays_mt", "0.5"}}),
      bench_row({{"scene", "\"../shared/scenes/bunny.obj\""}}),
  });
  ASSERT_EQ(d.groups.size(), 3u);
  EXPECT_EQ(d.groups[0].rows, (std::vector<size_t>{0, 2}));
  EXPECT_EQ(d.groups[1].rows, (std::vector<size_t>{1}));
  EXPECT_EQ(d.groups[1].n_rays, 4096u);
  EXPECT_EQ(d.groups[2].label(), "bunny.obj, random:2000:1");

  ChartOptions o;
  ChartModel m = make_chart(d, o);
  ASSERT_EQ(m.points.size(), 2u);
  EXPECT_EQ(m.points[0].row, 0u);
  EXPECT_EQ(m.points[1].row, 2u);
  EXPECT_DOUBLE_EQ(m.points[0].y, 4.0);
  EXPECT_FALSE(m.baseline_y.has_value());
  o.group = 1;
  m = make_chart(d, o);
  ASSERT_EQ(m.points.size(), 1u);
  EXPECT_EQ(m.points[0].row, 1u);
  EXPECT_EQ(m.y_title, "Mrays/s, 8 threads");
  o.group = 99;  // clamped to the last group
  EXPECT_EQ(make_chart(d, o).points[0].row, 3u);

  o.group = 0;
  o.speed = ChartSpeed::OneThread;
  m = make_chart(d, o);
  EXPECT_DOUBLE_EQ(m.points[0].y, 2.0);
  EXPECT_EQ(m.y_title, "Mrays/s, 1 thread");
  o.speed = ChartSpeed::AllThreads;
  o.log_y = true;
  m = make_chart(d, o);
  EXPECT_TRUE(m.y.log);
  EXPECT_DOUBLE_EQ(m.y.lo, 0.1);
  EXPECT_DOUBLE_EQ(m.y.hi, 10.0);
  EXPECT_NEAR(m.points[0].fy, std::log10(40.0) / 2.0, 1e-6);
  EXPECT_EQ(m.y_title, "Mrays/s, 2 threads (log scale)");
}

TEST(BenchChart, OptionsAndWindowState) {
  ChartOptions o;
  EXPECT_EQ(set_chart_option(o, "x=t-error"), "");
  EXPECT_EQ(o.x, ChartX::MaxRelTErr);
  EXPECT_EQ(set_chart_option(o, "speed=1t"), "");
  EXPECT_EQ(o.speed, ChartSpeed::OneThread);
  EXPECT_EQ(set_chart_option(o, "y=log"), "");
  EXPECT_TRUE(o.log_y);
  EXPECT_EQ(set_chart_option(o, "labels=off"), "");
  EXPECT_FALSE(o.labels);
  EXPECT_EQ(set_chart_option(o, "group=3"), "");
  EXPECT_EQ(o.group, 2u);
  EXPECT_EQ(set_chart_option(o, "speed=fast"), "speed: expected mt or 1t, got 'fast'");
  EXPECT_EQ(set_chart_option(o, "group=x"), "group: expected a group number from 1, got 'x'");

  BenchChartState state;
  accel::Status st = load_bench_into(state, ACCEL_TEST_DATA_DIR "/bench_chart.json");
  ASSERT_TRUE(st.ok()) << st.error().message;
  EXPECT_TRUE(state.open);
  ASSERT_TRUE(state.data.has_value());
  state.options.group = 1;
  // A failed load keeps what is shown and reports the error.
  st = load_bench_into(state, ACCEL_TEST_DATA_DIR "/bench_malformed.json");
  ASSERT_FALSE(st.ok());
  EXPECT_TRUE(st.error().message.starts_with(ACCEL_TEST_DATA_DIR "/bench_malformed.json: not valid JSON: "));
  EXPECT_EQ(state.error, st.error().message);
  ASSERT_TRUE(state.data.has_value());
  EXPECT_EQ(state.data->rows.size(), 29u);
  EXPECT_EQ(state.options.group, 1u);
}

TEST(BenchChart, LabelsAndOrderFromTheRegistry) {
  // Registry structures: the registry's label, its lecture order with the reference last.
  for (const accel::StructureInfo& info : accel::structure_registry())
    EXPECT_EQ(structure_label(info.name), info.label);
  EXPECT_LT(structure_order("grid"), structure_order("kdtree"));
  EXPECT_LT(structure_order("spheretree"), structure_order("brute"));
  // The Embree baselines keep the chart's labels and come after every registry structure.
  EXPECT_EQ(structure_label("embree-medium"), "Embree med");
  EXPECT_EQ(structure_label("embree-high"), "Embree high");
  EXPECT_LT(structure_order("brute"), structure_order("embree-medium"));
  EXPECT_LT(structure_order("embree-medium"), structure_order("embree-high"));
  // tinybvh's rows: after Embree's, in the bench's order, with short labels.
  EXPECT_EQ(structure_label("tinybvh-bvh8"), "tinybvh 8");
  EXPECT_EQ(structure_label("tinybvh-bvh4"), "tinybvh 4");
  EXPECT_EQ(structure_label("tinybvh-bvh8-hq"), "tinybvh 8 HQ");
  EXPECT_LT(structure_order("embree-high"), structure_order("tinybvh-bvh8"));
  EXPECT_LT(structure_order("tinybvh-bvh8"), structure_order("tinybvh-bvh4"));
  EXPECT_LT(structure_order("tinybvh-bvh4"), structure_order("tinybvh-bvh8-hq"));
  // Anything else: its name, last.
  EXPECT_EQ(structure_label("mystery"), "mystery");
  EXPECT_LT(structure_order("tinybvh-bvh8-hq"), structure_order("mystery"));
  // Kernels: the core's order, then the peers (Embree, tinybvh), then any other.
  for (size_t i = 0; i < std::size(accel::kAllKernels); ++i)
    EXPECT_EQ(kernel_order(std::string(accel::kernel_name(accel::kAllKernels[i]))), static_cast<int>(i));
  const int core = static_cast<int>(std::size(accel::kAllKernels));
  EXPECT_EQ(kernel_order("embree"), core);
  EXPECT_EQ(kernel_order("tinybvh"), core + 1);
  EXPECT_EQ(kernel_order("mystery"), core + 2);
  EXPECT_EQ(kernel_label("embree"), "Embree");
  EXPECT_EQ(kernel_label("tinybvh"), "tinybvh");
  EXPECT_EQ(kernel_label("moller"), "moller");
  EXPECT_TRUE(BenchRow::is_peer_kernel("tinybvh"));
  EXPECT_FALSE(BenchRow::is_peer_kernel("watertight"));
}

}  // namespace
}  // namespace viz
