// Issue 12's bar for global localisation on real scans: 200 scans drawn at
// random (seeded) from each SLAM-corrected recording in ../shared/data are
// located against the whole map of their building with no prior pose, each
// with the scans of the metres before it placed by odometry, as the
// localisation component and replay do (RecentScans). That odometry is
// re-synthesised from the corrected poses with the evaluation's documented
// errors (1.5 % scale, 0.3 deg/m heading drift, 5 mm and 0.1 deg of noise per
// sqrt(m)). The recordings' corrected laser poses are the truth. Note that the maps
// (maps/real/*.xml, `structloc map build`) were built from these same
// recordings, so the map is as good as it gets for them; the scans still hold
// people, doors and clutter the map does not. The issue asks for at least
// 90 % right (within 0.2 m and 5 deg), the rest "ambiguous" or "not found",
// none confidently wrong; the test holds none wrong, at least 95 % right on
// Freiburg (measured: 100 %) and the 90 % on Intel (92 %).
// Label shared_data.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ostream>
#include <random>
#include <string>

#include "evaluation_odometry.hpp"
#include "structloc/localisation_core/global/global_localiser.hpp"
#include "structloc/localisation_core/global/recent_scans.hpp"
#include "structloc/map_building/posed_scans.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

struct Recording {
  const char* log;
  const char* map;
  int right_percent;  // least share placed right (see the figures in docs/design/method.md)
};

// How ctest lists the case: the recording's file name.
void PrintTo(const Recording& recording, std::ostream* out) {
  *out << recording.log;
}

class GlobalOnRealLog : public ::testing::TestWithParam<Recording> {};

TEST_P(GlobalOnRealLog, LocatesMostRandomScansAndIsNeverConfidentlyWrong) {
  const auto world = world_model::LoadWorldModel(testing::SourcePath(GetParam().map));
  const auto log = map_building::ReadPosedScans(
      testing::SourcePath("../shared/data/") + GetParam().log, map_building::PosedScanOptions{});
  ASSERT_GT(log.scans.size(), 500u);
  const localisation_core::GlobalLocaliserOptions options;
  const localisation_core::GlobalLocaliser localiser(world, options);

  std::mt19937 rng(12);
  std::uniform_int_distribution<size_t> pick(0, log.scans.size() - 1);
  constexpr int kScans = 200;
  std::vector<size_t> drawn(kScans);
  for (auto& index : drawn) index = pick(rng);
  std::sort(drawn.begin(), drawn.end());  // the log is read once, in order

  const auto odometry = testing::EvaluationOdometry(log, 7);
  localisation_core::RecentScans recent;

  int right = 0, ambiguous = 0, not_found = 0, wrong = 0;
  double seconds = 0.0, scans_combined = 0.0;
  size_t next = 0, searches = 0;
  for (size_t k = 0; k < log.scans.size() && next < drawn.size(); ++k) {
    const auto& scan = log.scans[k];
    recent.Add(scan.points, odometry[k]);
    if (drawn[next] != k) continue;
    const auto readings = recent.InNewestFrame();
    const auto t0 = std::chrono::steady_clock::now();
    const auto result = localiser.Locate(readings);
    ++searches;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const int times = static_cast<int>(std::count(drawn.begin(), drawn.end(), k));
    next += static_cast<size_t>(times);
    scans_combined += times * static_cast<double>(recent.Scans());
    const auto& truth = scan.laser_pose;
    const bool close =
        result.best &&
        std::hypot(result.best->pose.x - truth.x, result.best->pose.y - truth.y) <= 0.2 &&
        std::abs(geometry::WrapAngle(result.best->pose.theta - truth.theta)) <=
            5.0 * geometry::kPi / 180.0;
    const double truth_score = localiser.Score(readings, truth);
    const char* decision = localisation_core::ToString(result.decision);
    // The scans not placed right, with the score of the true pose for comparison.
    if (!close || result.decision != localisation_core::GlobalDecision::kFound)
      std::printf(
          "scan %zu (drawn %d x, %zu scans): %s %s best %.2f (%.2f %.2f %.1f) runner-up %.2f (%.2f "
          "%.2f %.1f) truth %.2f "
          "(%.2f %.2f %.1f)\n",
          scan.index, times, recent.Scans(), decision, close ? "close" : "far",
          result.best ? result.best->score : 0.0, result.best ? result.best->pose.x : 0.0,
          result.best ? result.best->pose.y : 0.0,
          result.best ? result.best->pose.theta * 180 / geometry::kPi : 0.0,
          result.runner_up ? result.runner_up->score : 0.0,
          result.runner_up ? result.runner_up->pose.x : 0.0,
          result.runner_up ? result.runner_up->pose.y : 0.0,
          result.runner_up ? result.runner_up->pose.theta * 180 / geometry::kPi : 0.0, truth_score,
          truth.x, truth.y, truth.theta * 180 / geometry::kPi);
    switch (result.decision) {
      case localisation_core::GlobalDecision::kFound:
        (close ? right : wrong) += times;
        EXPECT_TRUE(close) << "scan " << scan.index << " confidently placed at "
                           << result.best->pose.x << " " << result.best->pose.y << " "
                           << result.best->pose.theta << ", truth " << truth.x << " " << truth.y
                           << " " << truth.theta;
        break;
      case localisation_core::GlobalDecision::kAmbiguous:
        ambiguous += times;
        break;
      case localisation_core::GlobalDecision::kNotFound:
        not_found += times;
        break;
    }
  }
  std::printf(
      "%s: %d scans: %d right, %d ambiguous, %d not found, %d wrong; %.1f scans combined and "
      "%.0f ms per search on average (%zu candidate positions)\n",
      GetParam().log, kScans, right, ambiguous, not_found, wrong, scans_combined / kScans,
      1e3 * seconds / static_cast<double>(searches), localiser.CandidatePositions());
  EXPECT_EQ(wrong, 0);
  EXPECT_GE(right, kScans * GetParam().right_percent / 100);
}

INSTANTIATE_TEST_SUITE_P(
    SharedData, GlobalOnRealLog,
    ::testing::Values(Recording{"freiburg-079-corrected.log.gz", "maps/real/freiburg_079.xml", 95},
                      Recording{"intel-corrected.log.gz", "maps/real/intel.xml", 90}),
    [](const ::testing::TestParamInfo<Recording>& info) {
      return std::string(info.index == 0 ? "Freiburg079" : "Intel");
    });

}  // namespace
}  // namespace structloc
