// The report's error-against-cost tables on values worked out by hand.

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "apps/voxgi/report_convergence.hpp"

namespace voxgi::cli {
namespace {

ConfigResult swept_result(const std::string& technique, std::map<std::string, std::string> swept,
                          double rel_mse, std::optional<double> noise) {
  ConfigResult r;
  r.technique = technique;
  r.swept = swept;
  r.overrides = swept;
  SameBounceResult same;
  image::ImageMetrics m;
  m.rel_mse = rel_mse;
  same.indirect = m;
  same.reference_noise_rel_mse = noise;
  r.same_bounce = same;
  return r;
}

// Ids by position, as the bench numbers configurations.
std::vector<ConfigResult> numbered(std::vector<ConfigResult> results) {
  for (size_t i = 0; i < results.size(); ++i) {
    results[i].index = i;
    char id[24];
    std::snprintf(id, sizeof id, "c%zu", i);
    results[i].id = id;
  }
  return results;
}

std::vector<const ConfigResult*> pointers(const std::vector<ConfigResult>& results) {
  std::vector<const ConfigResult*> out;
  for (const ConfigResult& r : results) out.push_back(&r);
  return out;
}

// dvs over cones 4 / 9 / 16 and resolution 32 / 128, written out of order (and "16" before
// "9", which sorts before it as text). Errors with a noise of 0.001 in each: net
//   cones  4: 0.009 (32)  0.005 (128)
//   cones  9: 0.007       0.003
//   cones 16: 0.006       0.0035   (up 1/6 over 9 cones at 128)
std::vector<ConfigResult> dvs_sweep() {
  const auto cfg = [](const char* cones, const char* res, double net) {
    return swept_result("dvs", {{"dvs.cones", cones}, {"voxel.resolution", res}}, net + 0.001,
                        0.001);
  };
  return numbered({cfg("16", "128", 0.0035), cfg("4", "32", 0.009), cfg("9", "32", 0.007),
                   cfg("16", "32", 0.006), cfg("4", "128", 0.005), cfg("9", "128", 0.003)});
}

TEST(BenchConvergence, GridOrdersSettingsNumericallyAndNetsOutTheNoise) {
  const std::vector<ConfigResult> results = dvs_sweep();
  const std::vector<ConvergenceGrid> grids = convergence_grids(pointers(results));
  ASSERT_EQ(grids.size(), 1u);
  const ConvergenceGrid& g = grids[0];
  EXPECT_EQ(g.row_key, "dvs.cones");
  EXPECT_EQ(g.column_key, "voxel.resolution");
  EXPECT_EQ(g.rows, (std::vector<std::string>{"4", "9", "16"}));
  EXPECT_EQ(g.columns, (std::vector<std::string>{"32", "128"}));
  EXPECT_NEAR(g.at(0, 0).net, 0.009, 1e-12);
  EXPECT_NEAR(g.at(0, 0).raw, 0.010, 1e-12);
  EXPECT_NEAR(g.at(2, 1).net, 0.0035, 1e-12);
  EXPECT_EQ(g.at(2, 1).result, &results[0]);
  EXPECT_FALSE(error_rise(g.at(0, 0), g.at(0, 1))) << "falls with resolution";
  EXPECT_FALSE(error_rise(g.at(1, 1), g.at(1, 1))) << "equal is no rise";
  ASSERT_TRUE(error_rise(g.at(1, 1), g.at(2, 1)));
  EXPECT_NEAR(*error_rise(g.at(1, 1), g.at(2, 1)), 0.5 / 3.0, 1e-9);
}

TEST(BenchConvergence, MarkdownMarksEachRiseAndGivesTheCostRatio) {
  const std::vector<ConfigResult> results = dvs_sweep();
  const std::string md = convergence_markdown(convergence_grids(pointers(results)));
  EXPECT_NE(md.find("### Error against cost"), std::string::npos);
  EXPECT_NE(md.find("**dvs** (rows `dvs.cones`)"), std::string::npos) << md;
  EXPECT_NE(md.find("| `voxel.resolution` | 32 | 128 |\n|---|---:|---:|\n"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| 4 | 0.009 | 0.005 |\n| 9 | 0.007 | 0.003 |\n"), std::string::npos) << md;
  EXPECT_NE(md.find("| 16 | 0.006 | 0.0035 ↑ +16.7% over 9 |\n"), std::string::npos) << md;
  // Costliest (16 cones, 128) over cheapest (4 cones, 32): 0.0035 / 0.009 net, 0.0045 / 0.010.
  EXPECT_NE(md.find("Costliest over cheapest (c0 over c1): 0.3889 (0.45 with the noise)"),
            std::string::npos)
      << md;
}

TEST(BenchConvergence, OneSettingSweepsHaveOneColumn) {
  const std::vector<ConfigResult> results = {
      swept_result("dvs-bounces", {{"dvs.bounces", "0"}}, 0.004, std::nullopt),
      swept_result("dvs-bounces", {{"dvs.bounces", "1"}}, 0.005, std::nullopt)};
  const std::vector<ConvergenceGrid> grids = convergence_grids(pointers(results));
  ASSERT_EQ(grids.size(), 1u);
  EXPECT_TRUE(grids[0].column_key.empty());
  const std::string md = convergence_markdown(grids);
  EXPECT_NE(md.find("| `dvs.bounces` | error |\n|---|---:|\n| 0 | 0.004 |\n"
                    "| 1 | 0.005 ↑ +25.0% over 0 |\n"),
            std::string::npos)
      << md;
}

TEST(BenchConvergence, TechniquesThatCannotBeLaidOutHaveNoGrid) {
  std::vector<ConfigResult> results = {swept_result("named", {{"mode", "fast"}}, 0.01, 0.0),
                                       swept_result("named", {{"mode", "slow"}}, 0.02, 0.0),
                                       swept_result("single", {{"cones", "4"}}, 0.01, 0.0),
                                       swept_result("not finite", {{"cones", "nan"}}, 0.01, 0.0),
                                       swept_result("not finite", {{"cones", "4"}}, 0.01, 0.0),
                                       swept_result("twice", {{"cones", "4"}}, 0.01, 0.0),
                                       swept_result("twice", {{"cones", "4"}}, 0.02, 0.0),
                                       swept_result("undeclared", {{"cones", "4"}}, 0.01, 0.0),
                                       swept_result("undeclared", {{"cones", "9"}}, 0.01, 0.0)};
  results[8].same_bounce.reset();
  EXPECT_TRUE(convergence_grids(pointers(results)).empty());
  EXPECT_EQ(convergence_markdown({}), "");
}

}  // namespace
}  // namespace voxgi::cli
