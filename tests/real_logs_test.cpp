// The replay reads the real CARMEN logs in ../shared/data without error (their
// quirks: 361-beam FLASER, ~81 m max-range values, non-monotonic stamps,
// GMapping's NEFF lines), in --no-map mode since there is no world model for them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "replay.hpp"

namespace structloc {
namespace {

class RealLog : public ::testing::TestWithParam<const char*> {};

TEST_P(RealLog, ReplaysWithoutErrorInNoMapMode) {
  const std::string path = std::string(STRUCTLOC_SOURCE_DIR) + "/../shared/data/" + GetParam();
  if (!std::filesystem::exists(path))
    GTEST_SKIP() << path << " is not here (shared/ beside the checkout)";
  replay::ReplayOptions o;
  o.no_map = true;
  o.log_path = path;
  o.initial_pose = geometry::Pose2D{};
  o.out_tum = "/tmp/structloc_real_log_" + std::to_string(getpid()) + ".tum";
  const auto report = replay::RunReplay(o);
  EXPECT_EQ(report.log.malformed, 0u);
  EXPECT_GT(report.log.scans, 500u);
  EXPECT_GT(report.scans_used, report.log.scans * 99 / 100);
  size_t rejected = 0;
  for (const auto& [why, n] : report.scans_rejected) rejected += n;
  EXPECT_EQ(report.scans_used + rejected, report.log.scans);
  std::ifstream tum(o.out_tum);
  size_t lines = 0;
  for (std::string line; std::getline(tum, line);) lines += !line.empty() && line[0] != '#';
  EXPECT_EQ(lines, report.scans_used);
  std::remove(o.out_tum.c_str());
}

INSTANTIATE_TEST_SUITE_P(SharedData, RealLog,
                         ::testing::Values("mit-csail.clf.gz", "freiburg-079-corrected.log.gz",
                                           "intel-corrected.log.gz"),
                         [](const auto& info) {
                           std::string name = info.param;
                           return name.substr(0, name.find('-'));
                         });

}  // namespace
}  // namespace structloc
