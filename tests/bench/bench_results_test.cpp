// Bench statistics, results files and charts on values worked out by hand.

#include <gtest/gtest.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

#include "apps/voxgi/bench_results.hpp"
#include "apps/voxgi/report_charts.hpp"
#include "apps/voxgi/report_markdown.hpp"

namespace voxgi::cli {
namespace {

size_t count_of(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(BenchStatistics, SpreadPercentilesInterpolate) {
  const Spread s = spread_of({10, 1, 9, 2, 8, 3, 7, 4, 6, 5});
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 10.0);
  EXPECT_DOUBLE_EQ(s.median, 5.5);
  EXPECT_NEAR(s.p10, 1.9, 1e-12);  // 1 + 0.9 * (2 - 1)
  EXPECT_NEAR(s.p90, 9.1, 1e-12);
  const Spread one = spread_of({4.0});
  EXPECT_DOUBLE_EQ(one.p10, 4.0);
  EXPECT_DOUBLE_EQ(one.p90, 4.0);
  const Spread none = spread_of({});
  EXPECT_DOUBLE_EQ(none.median, 0.0);
}

TEST(BenchStatistics, FrameTotalsCountSkippedPassesAsZero) {
  using T = graph::Executor::PassTiming;
  const std::vector<std::vector<T>> frames = {
      {{"a", "x.a", 1.0, 0.1, ""}, {"b", "x.b", 4.0, 0.2, ""}},
      {{"a", "x.a", 2.0, 0.1, ""}, {"b", "x.b", 0.0, 0.0, "unchanged"}},
      {{"a", "x.a", 3.0, 0.1, ""}, {"b", "x.b", 0.0, 0.0, "unchanged"}}};
  const FrameTimes t = summarize_frames(frames);
  ASSERT_EQ(t.passes.size(), 2u);
  EXPECT_EQ(t.passes[0].pass, "a");
  EXPECT_DOUBLE_EQ(t.passes[0].gpu_ms.median, 2.0);
  EXPECT_DOUBLE_EQ(t.passes[0].share_ms, 2.0);
  EXPECT_EQ(t.passes[1].frames, 1u);
  EXPECT_EQ(t.passes[1].skipped, 2u);
  EXPECT_EQ(t.passes[1].skip_reason, "unchanged");
  EXPECT_DOUBLE_EQ(t.passes[1].gpu_ms.median, 4.0) << "over the frames it ran";
  EXPECT_DOUBLE_EQ(t.passes[1].share_ms, 0.0) << "over all frames";
  // Frame totals 5, 2, 3.
  EXPECT_DOUBLE_EQ(t.gpu_total_ms.median, 3.0);
  EXPECT_DOUBLE_EQ(t.gpu_total_ms.min, 2.0);
  EXPECT_DOUBLE_EQ(t.gpu_total_ms.max, 5.0);
  EXPECT_NEAR(t.cpu_total_ms.max, 0.3, 1e-12);
}

TEST(BenchStatistics, ParetoFrontKeepsOnlyUndominatedPoints) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // (time, error): (3, 0.2) (1, 0.5) (2, 0.6) (4, 0.1) (5, 0.1) (0.5, nan)
  const std::vector<size_t> front =
      pareto_front({3, 1, 2, 4, 5, 0.5}, {0.2, 0.5, 0.6, 0.1, 0.1, nan});
  EXPECT_EQ(front, (std::vector<size_t>{1, 0, 3}));
  EXPECT_TRUE(pareto_front({}, {}).empty());
}

ConfigResult sample_result(size_t index, const std::string& technique, double ms, double error) {
  ConfigResult r;
  r.index = index;
  r.id = "c00" + std::to_string(index);
  r.technique = technique;
  r.label = technique + (index ? " cones=" + std::to_string(index) : "");
  r.graph = "graphs/" + technique + ".json";
  r.scene = "cornell";
  r.camera = "default";
  r.width = 64;
  r.height = 48;
  r.overrides = {{"cones", std::to_string(index)}};
  r.swept = r.overrides;
  r.warmup_frames = 1;
  r.frames = 3;
  r.times.gpu_total_ms = {ms, ms * 0.9, ms * 1.2, ms * 0.95, ms * 1.1};
  r.times.cpu_total_ms = {0.5, 0.4, 0.6, 0.45, 0.55};
  PassTime pass;
  pass.pass = "gbuffer";
  pass.type = "common.gbuffer";
  pass.gpu_ms = r.times.gpu_total_ms;
  pass.share_ms = ms;
  pass.frames = 3;
  r.times.passes = {pass};
  image::ImageMetrics m;
  m.rel_mse = error;
  m.rmse = std::sqrt(error);
  m.ssim_luminance = 0.9;
  m.luminance_bias = -0.05;
  m.mean_luminance = 0.19;
  m.mean_luminance_reference = 0.2;
  m.compared_pixels = 64 * 48;
  m.hdr_flip = 0.25;
  r.full = m;
  if (index % 2) r.indirect = m;
  if (index == 1) {
    SameBounceResult same;
    same.bounces = 2;
    same.brdf = "diffuse";
    same.faces = "front";
    same.reference_set = {{"path_tracer.max_depth", "3"}, {"path_tracer.lambert", "true"}};
    same.reference_key = "fedcba9876543210";
    same.indirect = m;
    same.full_indirect = m;
    same.full_reference_key = "0123456789abcdef";
    same.missing_fraction = 0.125;
    same.reference_noise_rel_mse = 0.0625;
    r.same_bounce = same;
  }
  if (index == 2) {  // declared, but no same-bounce reference (an image-only reference)
    SameBounceResult same;
    same.bounces = 1;
    same.brdf = "full";
    r.same_bounce = same;
  }
  r.reference_key = "0123456789abcdef";
  r.image_png = "images/" + r.id + ".png";
  r.reference_png = "images/reference-0123456789abcdef.png";
  r.heat_map_png = "images/" + r.id + "-error.png";
  r.wall_seconds = 1.5;
  return r;
}

BenchResults sample_results() {
  BenchResults results;
  results.name = "sample";
  results.bench_file = "bench.json";
  results.bench_hash = "feedface";
  results.device = "test device";
  results.reference_graph = "graphs/default.json";
  results.reference_frames = 8;
  results.configurations_total = 4;
  results.shards = {"1/2"};
  results.results = {sample_result(0, "ambient", 1.0, 0.3),
                     sample_result(1, "vct, \"fast\"", 2.0, 0.1),
                     sample_result(2, "vct, \"fast\"", 3.0, 0.2)};
  return results;
}

TEST(BenchResults, JsonRoundTripKeepsEveryField) {
  const BenchResults original = sample_results();
  const nlohmann::json doc = to_json(original);
  EXPECT_EQ(doc["missing"], nlohmann::json::array({3}));
  const BenchResults back = results_from_json(doc, "results.json");
  EXPECT_EQ(to_json(back), doc);
  EXPECT_EQ(back.results[1].label, original.results[1].label);
  EXPECT_FALSE(back.results[0].indirect.has_value());
  ASSERT_TRUE(back.results[1].indirect.has_value());
  EXPECT_DOUBLE_EQ(back.results[1].indirect->rel_mse, 0.1);
  EXPECT_DOUBLE_EQ(back.results[1].full->hdr_flip, 0.25);
  EXPECT_FALSE(back.results[0].same_bounce.has_value());
  ASSERT_TRUE(back.results[1].same_bounce.has_value());
  EXPECT_EQ(back.results[1].same_bounce->reference_set.at("path_tracer.max_depth"), "3");
  EXPECT_DOUBLE_EQ(*back.results[1].same_bounce->missing_fraction, 0.125);
  EXPECT_DOUBLE_EQ(*back.results[1].same_bounce->reference_noise_rel_mse, 0.0625);
  EXPECT_EQ(back.results[1].same_bounce->faces, "front");
  ASSERT_TRUE(back.results[2].same_bounce.has_value());
  EXPECT_EQ(back.results[2].same_bounce->faces, "both");
  EXPECT_FALSE(back.results[2].same_bounce->indirect.has_value());
  EXPECT_FALSE(back.results[2].same_bounce->missing_fraction.has_value());
  EXPECT_FALSE(back.results[2].same_bounce->reference_noise_rel_mse.has_value());
  EXPECT_EQ(back.missing(), std::vector<size_t>{3});
}

TEST(BenchResults, ResultsWrittenBeforeFlipAndSameBounceStillRead) {
  nlohmann::json doc = to_json(sample_results());
  for (nlohmann::json& item : doc["results"]) {
    item.erase("same_bounce");
    item["metrics"]["full"].erase("hdr_flip");
  }
  const BenchResults back = results_from_json(doc, "old/results.json");
  EXPECT_FALSE(back.results[1].same_bounce.has_value());
  EXPECT_DOUBLE_EQ(back.results[1].full->hdr_flip, 0.0);
}

TEST(BenchResults, ResultsWrittenBeforeReferenceNoiseStillRead) {
  nlohmann::json doc = to_json(sample_results());
  doc["results"][1]["same_bounce"].erase("reference_noise_rel_mse");
  doc["results"][1]["same_bounce"].erase("faces");
  const BenchResults back = results_from_json(doc, "old/results.json");
  ASSERT_TRUE(back.results[1].same_bounce.has_value());
  EXPECT_FALSE(back.results[1].same_bounce->reference_noise_rel_mse.has_value());
  EXPECT_EQ(back.results[1].same_bounce->faces, "both") << "as references were then";
  EXPECT_DOUBLE_EQ(*back.results[1].same_bounce->missing_fraction, 0.125);
}

TEST(BenchResults, ReadingAWrongFileNamesTheField) {
  nlohmann::json doc = to_json(sample_results());
  doc["results"][1]["gpu_ms"]["p90"] = "fast";
  try {
    results_from_json(doc, "shard/results.json");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("shard/results.json: field 'results[1].gpu_ms.p90'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(results_from_json(nlohmann::json::object(), "x.json"), std::runtime_error);
  EXPECT_THROW(read_results("/nonexistent/results.json"), std::runtime_error);
}

TEST(BenchResults, CsvHasOneQuotedRowPerConfiguration) {
  const std::string csv = results_csv(sample_results());
  std::istringstream lines(csv);
  std::vector<std::string> rows;
  for (std::string line; std::getline(lines, line);) rows.push_back(line);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].rfind("index,id,technique,", 0), 0u);
  EXPECT_EQ(rows[2].rfind("1,c001,\"vct, \"\"fast\"\"\",", 0), 0u) << rows[2];
  // Same number of fields on every row (quoted commas aside): the header's.
  auto fields = [](const std::string& row) {
    size_t n = 1;
    bool quoted = false;
    for (char c : row) {
      if (c == '"') quoted = !quoted;
      if (c == ',' && !quoted) ++n;
    }
    return n;
  };
  for (const std::string& row : rows) EXPECT_EQ(fields(row), fields(rows[0])) << row;
  // The like-with-like columns come after the older ones, which keep their positions.
  EXPECT_NE(rows[0].find(",reference_key,reference_cache_hit,hdr_flip,indirect_hdr_flip,"
                         "indirect_bounces,indirect_brdf,same_bounce_rel_mse,"),
            std::string::npos)
      << rows[0];
  EXPECT_NE(rows[0].find(",full_indirect_rel_mse,"), std::string::npos);
  EXPECT_NE(rows[0].find(",missing_indirect_fraction,same_bounce_reference_key,gpu_memory_bytes,"
                         "same_bounce_reference_noise_rel_mse,indirect_faces"),
            std::string::npos);
  EXPECT_NE(rows[2].find(",2,diffuse,0.1,0.9,0.25,-0.05,0.1,0.9,0.25,-0.05,0.125,fedcba9876543210"),
            std::string::npos)
      << rows[2];
  EXPECT_EQ(rows[2].substr(rows[2].size() - 13), ",0.0625,front") << rows[2];
  EXPECT_EQ(rows[3].substr(rows[3].size() - 6), ",,both")
      << "no reference noise without a same-bounce reference";
}

TEST(BenchReport, LikeWithLikeTableAndChart) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("voxgi-bench-report-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  write_report(dir, sample_results());
  std::ifstream in(dir / "report.md");
  const std::string report{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_NE(report.find("| SSIM | FLIP | bias |"), std::string::npos);
  const size_t table = report.find("### Indirect light, like with like");
  ASSERT_NE(table, std::string::npos) << report;
  EXPECT_NE(report.find("| same-bounce bias | same-bounce relMSE | reference noise | "
                        "same-bounce FLIP | full bias | full relMSE | full FLIP | missing |",
                        table),
            std::string::npos);
  // c001 has both references, c002 only its declaration, c000 no declaration.
  EXPECT_NE(
      report.find(
          "| c001 | vct, \"fast\" | cones=1 | 2, diffuse, front faces | -0.05 | 0.1 | 0.0625 | "
          "0.25 | -0.05 | 0.1 | 0.25 | 0.125 |",
          table),
      std::string::npos)
      << report.substr(table);
  EXPECT_NE(
      report.find("| c002 | vct, \"fast\" | cones=2 | 1, full | — | — | — | — | — | — | — | — |",
                  table),
      std::string::npos)
      << report.substr(table);
  EXPECT_EQ(report.find("| c000 | ambient | cones=0 | ", table), std::string::npos);
  EXPECT_TRUE(
      std::filesystem::is_regular_file(dir / "charts" / "group0-same-bounce-error-vs-time.svg"));
  std::filesystem::remove_all(dir);
}

TEST(BenchCharts, ErrorAgainstTimeHasAPointPerConfigurationAndFronts) {
  const BenchResults results = sample_results();
  std::vector<const ConfigResult*> list;
  for (const ConfigResult& r : results.results) list.push_back(&r);
  const std::string svg = error_vs_time_svg(list, ErrorMetric::RelMse, "title <&>");
  EXPECT_EQ(svg.rfind("<svg ", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_NE(svg.find("title &lt;&amp;&gt;"), std::string::npos) << "text is escaped";
  // 3 points + 2 legend markers; one front with two points (vct: 2 ms/0.1 dominates 3 ms/0.2,
  // so only ambient's single point and vct's single point: no polyline needs 2 points).
  EXPECT_EQ(count_of(svg, "<circle"), 5u);
  EXPECT_EQ(count_of(svg, "<polyline"), 0u);
  const std::string indirect = error_vs_time_svg(list, ErrorMetric::IndirectRelMse, "t");
  EXPECT_EQ(count_of(indirect, "<circle"), 2u) << "only c001 has an indirect error";
  const std::string bars = pass_time_bars_svg(list, "passes");
  EXPECT_EQ(count_of(bars, "<rect"), 1u + 3u + 1u) << "background, one per pass, legend";
}

TEST(BenchCharts, FrontLineJoinsImprovingPoints) {
  BenchResults results = sample_results();
  results.results[2].full->rel_mse = 0.05;  // slower but better: on vct's front
  std::vector<const ConfigResult*> list;
  for (const ConfigResult& r : results.results) list.push_back(&r);
  EXPECT_EQ(count_of(error_vs_time_svg(list, ErrorMetric::RelMse, "t"), "<polyline"), 1u);
}

}  // namespace
}  // namespace voxgi::cli
