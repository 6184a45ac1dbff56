// The evaluation tools behind issue 41's figures (structloc_relative_error,
// structloc_map_straightness, structloc_path_scan_fit, structloc_revisit_fit)
// run on inputs whose answers are known: an exact path, the same path scaled
// or bent, a square map and one with a turned wall, so that a figure the docs
// quote from them is a figure they can get right.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "structloc/log_formats/recording_writers.hpp"
#include "structloc/log_formats/tum_reader.hpp"
#include "structloc/simulation_core/recorder.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using geometry::Pose2D;
using testing::TempDir;

constexpr double kPi = 3.14159265358979323846;

testing::CliResult RunTool(const std::string& tool, const std::vector<std::string>& args) {
  // The evaluation tools are built beside the tests, not among the programs.
  return testing::RunExecutable("../tests/" + tool, args);
}

// `text` from the first `label` on (a failure naming the text when it has none).
std::string From(const std::string& text, const std::string& label) {
  const size_t at = text.find(label);
  EXPECT_NE(at, std::string::npos) << label << " is not in\n" << text;
  return at == std::string::npos ? std::string() : text.substr(at);
}

// The number after `label` in `text` (NaN when it is not there).
double NumberAfter(const std::string& text, const std::string& label) {
  const size_t at = text.find(label);
  double value = std::nan("");
  if (at != std::string::npos) std::sscanf(text.c_str() + at + label.size(), "%lf", &value);
  return value;
}

// `poses` one a second, written as a TUM file `name` in `dir`.
std::string WriteTum(const TempDir& dir, const std::string& name,
                     const std::vector<Pose2D>& poses) {
  log_formats::TumWriter tum(dir / name);
  for (size_t i = 0; i < poses.size(); ++i) tum.Pose(static_cast<double>(i), poses[i]);
  tum.Close();
  return dir / name;
}

// A 10 x 6 m loop driven at 0.1 m a pose, turning on the spot at the corners.
std::vector<Pose2D> Loop() {
  std::vector<Pose2D> poses;
  Pose2D at{0, 0, 0};
  for (const double side : {10.0, 6.0, 10.0, 6.0}) {
    for (int k = 0; k < std::lround(side / 0.1); ++k) {
      poses.push_back(at);
      at = geometry::Compose(at, Pose2D{0.1, 0, 0});
    }
    at.theta = geometry::WrapAngle(at.theta + kPi / 2);
  }
  return poses;
}

TEST(RelativeError, AnExactPathHasNoErrorAndItsOwnLength) {
  const TempDir dir;
  const std::string path = WriteTum(dir, "path.tum", Loop());
  const auto run = RunTool("structloc_relative_error", {path, path, "1", "5"});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("over 1 m: 0.0 +- 0.0 mm, 0.00 +- 0.00 deg"), std::string::npos)
      << run.output;
  EXPECT_NEAR(NumberAfter(run.output, "length ratio "), 1.0, 1e-4) << run.output;
}

// Scaled by 1.01, every relation is 1 % longer: a 1 m one 10 mm off, and the
// ratio 1.0100 over every distance.
TEST(RelativeError, AScaledPathShowsItsScaleAtEveryDistance) {
  const TempDir dir;
  std::vector<Pose2D> scaled = Loop();
  for (auto& p : scaled) p = {1.01 * p.x, 1.01 * p.y, p.theta};
  const auto run = RunTool("structloc_relative_error",
                           {WriteTum(dir, "scaled.tum", scaled), WriteTum(dir, "ref.tum", Loop())});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NEAR(NumberAfter(run.output, "over 1 m: "), 10.0, 0.5) << run.output;
  for (const std::string over : {"over 1 m", "over 5 m", "over 20 m"}) {
    const std::string from = From(run.output, over);
    EXPECT_NEAR(NumberAfter(from, "length ratio "), 1.01, 1e-4) << over << "\n" << run.output;
  }
}

// Bent (its heading drifting 1 deg a metre), relations far apart are off
// though nothing is scaled: the ratio stays near 1 over short distances.
TEST(RelativeError, ABentPathIsOffButNotScaled) {
  const TempDir dir;
  const auto reference = Loop();
  std::vector<Pose2D> bent{reference.front()};
  for (size_t i = 1; i < reference.size(); ++i) {
    Pose2D step = geometry::Between(reference[i - 1], reference[i]);
    step.theta += std::hypot(step.x, step.y) * kPi / 180.0;
    bent.push_back(geometry::Compose(bent.back(), step));
  }
  const auto run = RunTool("structloc_relative_error",
                           {WriteTum(dir, "bent.tum", bent), WriteTum(dir, "ref.tum", reference)});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NEAR(NumberAfter(run.output, "length ratio "), 1.0, 2e-3) << run.output;
  const std::string over5 = From(run.output, "over 5 m");
  EXPECT_GT(NumberAfter(over5, "over 5 m: "), 50.0) << run.output;
}

TEST(RelativeError, PosesTheEstimateLacksAreCounted) {
  const TempDir dir;
  const auto reference = Loop();
  const std::vector<Pose2D> first_half(reference.begin(), reference.begin() + 160);
  const auto run = RunTool("structloc_relative_error", {WriteTum(dir, "half.tum", first_half),
                                                        WriteTum(dir, "ref.tum", reference), "1"});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NEAR(NumberAfter(run.output, "relations, "), 160.0, 10.0) << run.output;
}

// A world of the given walls (x1 y1 x2 y2 each), written as `name` in `dir`.
std::string WriteWorld(const TempDir& dir, const std::string& name,
                       const std::vector<std::vector<double>>& walls) {
  std::string xml = "<world name=\"test\">\n";
  for (size_t i = 0; i < walls.size(); ++i) {
    const auto& w = walls[i];
    char line[200];
    std::snprintf(line, sizeof line,
                  "  <wall id=\"%zu\" x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\"/>\n", i + 1, w[0],
                  w[1], w[2], w[3]);
    xml += line;
  }
  return dir.Write(name, xml + "</world>\n");
}

TEST(MapStraightness, ASquareBuildingIsStraight) {
  const TempDir dir;
  const std::string world = WriteWorld(
      dir, "square.xml", {{0, 0, 20, 0}, {20, 0, 20, 10}, {20, 10, 0, 10}, {0, 10, 0, 0}});
  const auto run = RunTool("structloc_map_straightness", {world});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NEAR(NumberAfter(run.output, "axes at "), 0.0, 1e-6) << run.output;
  EXPECT_NE(run.output.find("100 % of 60 m of walls"), std::string::npos) << run.output;
}

// One of four 20 m walls turned by 2 deg: the axes follow it by a quarter
// (0.5 deg), a quarter of the length is off them by more than 1 deg, and the
// bands differ by the turn's share of theirs (1 deg).
TEST(MapStraightness, ATurnedWallIsFoundInItsBand) {
  const TempDir dir;
  const double dy = 20.0 * std::tan(2.0 * kPi / 180.0);
  const std::string world = WriteWorld(
      dir, "turned.xml", {{0, 0, 20, 0}, {0, 10, 20, 10}, {30, 0, 50, dy}, {30, 10, 50, 10}});
  const auto run = RunTool("structloc_map_straightness", {world, "2", "25"});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NEAR(NumberAfter(run.output, "axes at "), 0.5, 0.01) << run.output;
  EXPECT_NE(run.output.find("75 % of 80 m of walls"), std::string::npos) << run.output;
  const std::string first = From(run.output, "x    0.0 to   25.0 m");
  const std::string second = From(run.output, "x   25.0 to   50.0 m");
  EXPECT_NEAR(NumberAfter(second, "mean deviation ") - NumberAfter(first, "mean deviation "), 1.0,
              0.02)
      << run.output;
}

// The simulated office tour (60 s, 598 scans, people walking) against its
// exact path and the same path scaled by 1.01: the scans prefer about 1 for
// the first and 1 / 1.01 for the second, whose points lie farther off.
TEST(PathScanFit, FindsAPathScaledAgainstItsScans) {
  const TempDir dir;
  simulation_core::RecordScenario(
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/office_people.xml")),
      dir.Path());
  log_formats::TumWriter scaled(dir / "scaled.tum");
  for (const auto& p : log_formats::ReadTum(dir / "truth.tum"))
    scaled.Pose(p.stamp, {1.01 * p.pose.x, 1.01 * p.pose.y, p.pose.theta});
  scaled.Close();
  const auto exact = RunTool("structloc_path_scan_fit", {dir / "run.clf", dir / "truth.tum"});
  const auto off = RunTool("structloc_path_scan_fit", {dir / "run.clf", dir / "scaled.tum"});
  ASSERT_EQ(exact.exit_code, 0) << exact.output;
  ASSERT_EQ(off.exit_code, 0) << off.output;
  EXPECT_NEAR(NumberAfter(exact.output, "best scaled by "), 1.0, 0.003) << exact.output;
  EXPECT_NEAR(NumberAfter(off.output, "best scaled by "), 1.0 / 1.01, 0.003) << off.output;
  EXPECT_GT(NumberAfter(off.output, "earlier scan by "),
            NumberAfter(exact.output, "earlier scan by "))
      << exact.output << off.output;
}

TEST(RevisitFit, PrefersTheExactPathToOneBentBetweenPasses) {
  // Two loops of a tour, driven the same way round: each place seen twice
  // alike.
  const TempDir dir;
  simulation_core::RecordScenario(
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/symmetric_office.xml")),
      dir.Path());
  // The truth turned about its first pose by an angle growing along the log
  // (1 deg in all): each step nearly exact, the passes of one place apart.
  const auto truth = log_formats::ReadTum(dir / "truth.tum");
  ASSERT_FALSE(truth.empty());
  log_formats::TumWriter bent(dir / "bent.tum");
  const Pose2D first = truth.front().pose;
  for (size_t i = 0; i < truth.size(); ++i) {
    const double turn = (kPi / 180.0) * static_cast<double>(i) / static_cast<double>(truth.size());
    const Pose2D from_first = geometry::Between(first, truth[i].pose);
    bent.Pose(truth[i].stamp,
              geometry::Compose(first, geometry::Compose({0.0, 0.0, turn}, from_first)));
  }
  bent.Close();
  const auto fit =
      RunTool("structloc_revisit_fit", {dir / "run.clf", dir / "truth.tum", dir / "bent.tum"});
  ASSERT_EQ(fit.exit_code, 0) << fit.output;
  const double pairs = NumberAfter(fit.output, "");  // the line starts with the count
  const double exact = NumberAfter(fit.output, "earlier scan by A ");
  const double off = NumberAfter(fit.output, "mm, B ");
  const double best = NumberAfter(fit.output, "poses near them ");
  EXPECT_GE(pairs, 10.0) << fit.output;
  EXPECT_LT(exact, off) << fit.output;
  // The exact path is about as good as the scans allow, the bent one not.
  EXPECT_LE(best, exact) << fit.output;
  EXPECT_LT(exact - best, 0.2 * (off - best)) << fit.output;
  EXPECT_GT(NumberAfter(fit.output, "A fits better in "), 0.8 * pairs) << fit.output;
}

}  // namespace
}  // namespace structloc
