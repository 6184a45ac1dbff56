// Issue 12's tracking bars on the two SLAM-corrected real recordings in
// ../shared/data (label shared_data): odometry re-synthesised from the
// corrected poses (perfect, and with 1.5 % scale error, 0.3 deg/m heading
// drift and noise), localised with the SICK LMS 2xx preset against
//   - the shipped maps of maps/real/ (built from the whole recording), and
//   - maps built from one part of the recording and a 5 cm grid ray-cast from
//     that part, localised on another part (Freiburg: built from scans 719-4790,
//     localised on 0-718; Intel: built from 182-909, localised on 0-181, which
//     those parts cover), and
//   - the map imported from a 5 cm grid ray-cast from the whole recording.
// Every scan scored; position RMSE and max and heading RMSE against the
// corrected poses, and the longest lost period; and the same bars when replay
// starts without an initial pose.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_runner.hpp"
#include "structloc/replay/replay.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"
#include "tum_first_pose.hpp"

namespace structloc {
namespace {

constexpr const char* kMissing =
    "shared/ is not beside the checkout (run `ctest -LE shared_data` without it): ";

struct Recording {
  const char* name;       // maps/real/NAME.xml
  const char* log;        // in ../shared/data
  const char* map_part;   // --scans of the part the split map is built from
  const char* test_part;  // --scans of the part localised on
  bool restamp;           // key scans without motion times (Intel)
};

void PrintTo(const Recording& r, std::ostream* out) {
  *out << r.name;
}

const Recording kFreiburg{"freiburg_079", "freiburg-079-corrected.log.gz", "719:", "0:719", false};
const Recording kIntel{"intel", "intel-corrected.log.gz", "182:", "0:182", true};

std::string SharedData(const std::string& name) {
  return testing::SourcePath("../shared/data/" + name);
}

struct Evaluation {
  std::string log, truth;
};

// Poses in a TUM file: the log's scans, one each.
size_t PoseCount(const std::string& tum) {
  std::ifstream in(tum);
  std::string line;
  size_t n = 0;
  while (std::getline(in, line)) n += !line.empty() && line[0] != '#';
  return n;
}

// The evaluation log and its truth for `part` of the recording, perfect or perturbed odometry.
Evaluation Synthesise(const testing::TempDir& temp, const Recording& r, const std::string& part,
                      bool perturbed) {
  const std::string tag =
      std::string(r.name) + (perturbed ? "_perturbed" : "_perfect") + (part.empty() ? "" : "_part");
  Evaluation e{temp / (tag + ".log"), temp / (tag + ".tum")};
  std::vector<std::string> args = {
      "synthesise-odometry", "--log", SharedData(r.log), "--out", e.log, "--truth", e.truth};
  if (perturbed) {
    for (const char* a : {"--scale-error", "0.015", "--heading-drift", "0.3", "--noise-xy", "0.005",
                          "--noise-theta", "0.1"})
      args.push_back(a);
  }
  if (r.restamp) {
    args.push_back("--restamp");
    args.push_back("0.5");
  }
  if (!part.empty()) {
    args.push_back("--scans");
    args.push_back(part);
  }
  const auto result = testing::RunCli(args);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  return e;
}

enum class Start { kFirstTruePose, kGlobally };

void ExpectBars(const std::string& what, const std::string& map, const Evaluation& e,
                double max_rmse_m, Start start = Start::kFirstTruePose) {
  const testing::TempDir temp;
  replay::ReplayOptions o;
  o.map_path = map;
  o.log_path = e.log;
  o.truth_path = e.truth;
  o.params_path = testing::SourcePath("maps/params/sick_lms2xx.xml");
  if (start == Start::kFirstTruePose) o.initial_pose = testing::FirstTumPose(e.truth);
  o.out_tum = temp / "estimate.tum";
  const auto report = replay::RunReplay(o);
  // Scans before the one tracking started from are not tracked, so not scored.
  size_t untracked = 0;
  if (start == Start::kGlobally) {
    // Found within the first seconds of the recording (a robot turning on
    // the spot, as Intel's does at its start, shows one place at first).
    ASSERT_FALSE(report.global_attempts.empty()) << what;
    untracked = (report.commit ? report.commit->scan : report.global_attempts.back().scan) - 1;
    std::cout << what << ": found at scan " << untracked + 1 << std::endl;
    EXPECT_LE(untracked + 1, 10u) << what;
  }
  ASSERT_TRUE(report.estimate_error) << what;
  const auto& error = *report.estimate_error;
  // Every scan from there on was localised and scored against the truth: a
  // replay that dropped scans, or scored few of them, does not pass.
  const size_t scans = PoseCount(e.truth);
  ASSERT_GT(scans, untracked) << what;
  EXPECT_EQ(report.scans_used, scans - untracked) << what;
  EXPECT_EQ(error.matched, scans - untracked) << what;
  std::cout << what << ": " << error.matched << " of " << scans << " scans scored, RMSE "
            << 1000 * error.position_rmse_m << " mm, max " << 1000 * error.position_max_m
            << " mm, heading RMSE " << error.heading_rmse_rad * 180 / geometry::kPi
            << " deg, longest lost " << report.longest_lost_s << " s, re-acquired "
            << report.reacquisitions.size() << " times, " << report.kidnap_searches
            << " searches in doubt" << std::endl;
  EXPECT_LE(error.position_rmse_m, max_rmse_m) << what;
  // Nobody carried these robots: a kidnapping reported is a wrong jump.
  EXPECT_TRUE(report.kidnappings.empty()) << what;
  EXPECT_LE(error.position_max_m, 0.2) << what;
  // 1 deg turns a reading 3 m away (the middle of these buildings' ranges)
  // by 52 mm, the position bar's size; the rows measure 0.3-0.7 deg.
  EXPECT_LE(error.heading_rmse_rad, 1.0 * geometry::kPi / 180) << what;
  EXPECT_LE(report.longest_lost_s, 2.0) << what;
}

class RealTracking : public ::testing::TestWithParam<Recording> {};

// The bars: RMSE <= 30 mm with perfect odometry (never make a good
// pose worse), <= 50 mm with the systematic errors; max <= 200 mm; never lost
// for more than 2 s.
TEST_P(RealTracking, MeetsTheBarsOnTheShippedMap) {
  const auto& r = GetParam();
  ASSERT_TRUE(std::filesystem::exists(SharedData(r.log))) << kMissing << SharedData(r.log);
  const testing::TempDir temp;
  const std::string map = testing::SourcePath(std::string("maps/real/") + r.name + ".xml");
  ExpectBars(std::string(r.name) + ", perfect odometry", map, Synthesise(temp, r, "", false),
             0.030);
  ExpectBars(std::string(r.name) + ", perturbed odometry", map, Synthesise(temp, r, "", true),
             0.050);
}

// Maps from another part of the recording, built and ray-cast from it: the
// same bars on both.
TEST_P(RealTracking, MeetsTheBarsOnMapsOfAnotherPart) {
  const auto& r = GetParam();
  ASSERT_TRUE(std::filesystem::exists(SharedData(r.log))) << kMissing << SharedData(r.log);
  const testing::TempDir temp;
  const std::string built = temp / "built.xml", grid = temp / "grid.yaml",
                    imported = temp / "imported.xml";
  auto run = [](const std::vector<std::string>& args) {
    const auto result = testing::RunCli(args, std::chrono::seconds(600));
    ASSERT_EQ(result.exit_code, 0) << result.output;
  };
  run({"map", "build", "--log", SharedData(r.log), "--scans", r.map_part, "--out", built,
       "--quiet"});
  run({"map", "grid", "--log", SharedData(r.log), "--scans", r.map_part, "--out", grid});
  run({"map", "import", "--grid", grid, "--out", imported});
  for (bool perturbed : {false, true}) {
    const Evaluation e = Synthesise(temp, r, r.test_part, perturbed);
    const std::string odometry = perturbed ? "perturbed" : "perfect";
    ExpectBars(std::string(r.name) + ", built map, " + odometry + " odometry", built, e,
               perturbed ? 0.050 : 0.030);
    ExpectBars(std::string(r.name) + ", grid map, " + odometry + " odometry", imported, e,
               perturbed ? 0.050 : 0.030);
  }
}

// The map imported from a 5 cm grid of the whole recording.
TEST_P(RealTracking, MeetsTheBarsOnTheMapOfTheWholeRecordingsGrid) {
  const auto& r = GetParam();
  ASSERT_TRUE(std::filesystem::exists(SharedData(r.log))) << kMissing << SharedData(r.log);
  const testing::TempDir temp;
  const std::string grid = temp / "grid.yaml", imported = temp / "imported.xml";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"map", "grid", "--log", SharedData(r.log), "--out", grid},
        std::vector<std::string>{"map", "import", "--grid", grid, "--out", imported}}) {
    const auto result = testing::RunCli(args, std::chrono::seconds(600));
    ASSERT_EQ(result.exit_code, 0) << result.output;
  }
  ExpectBars(std::string(r.name) + ", whole recording's grid map, perfect odometry", imported,
             Synthesise(temp, r, "", false), 0.030);
  ExpectBars(std::string(r.name) + ", whole recording's grid map, perturbed odometry", imported,
             Synthesise(temp, r, "", true), 0.050);
}

// Without an initial pose: replay locates the robot globally from its first
// scans (each with the ones before it, placed by the log's odometry) and then
// meets the same bars as when given the first true pose.
TEST_P(RealTracking, StartsWithoutAnInitialPoseAndMeetsTheBars) {
  const auto& r = GetParam();
  ASSERT_TRUE(std::filesystem::exists(SharedData(r.log))) << kMissing << SharedData(r.log);
  const testing::TempDir temp;
  ExpectBars(std::string(r.name) + ", shipped map, perturbed odometry, no initial pose",
             testing::SourcePath(std::string("maps/real/") + r.name + ".xml"),
             Synthesise(temp, r, "", true), 0.050, Start::kGlobally);
}

// Without --params, replay takes the preset the scans' geometry names: the
// SICK LMS 2xx one for these recordings' lasers, so the same figures as with
// it given (issue 39's bar: within 10 % of its RMSE).
TEST_P(RealTracking, ChoosesTheLasersPresetWithoutAParameterFile) {
  const auto& r = GetParam();
  ASSERT_TRUE(std::filesystem::exists(SharedData(r.log))) << kMissing << SharedData(r.log);
  const testing::TempDir temp;
  const Evaluation e = Synthesise(temp, r, r.test_part, true);
  replay::ReplayOptions o;
  o.map_path = testing::SourcePath(std::string("maps/real/") + r.name + ".xml");
  o.log_path = e.log;
  o.truth_path = e.truth;
  o.initial_pose = testing::FirstTumPose(e.truth);
  o.out_tum = temp / "chosen.tum";
  const auto chosen = replay::RunReplay(o);
  std::cout << r.name << ": parameters " << chosen.parameters << std::endl;
  EXPECT_EQ(chosen.parameters.rfind("maps/params/sick_lms2xx.xml, chosen from the first scan", 0),
            0u)
      << chosen.parameters;
  o.params_path = testing::SourcePath("maps/params/sick_lms2xx.xml");
  o.out_tum = temp / "given.tum";
  const auto given = replay::RunReplay(o);
  ASSERT_TRUE(chosen.estimate_error && given.estimate_error);
  EXPECT_EQ(chosen.estimate_error->matched, given.estimate_error->matched);
  EXPECT_LE(chosen.estimate_error->position_rmse_m, 1.1 * given.estimate_error->position_rmse_m);
}

INSTANTIATE_TEST_SUITE_P(SharedData, RealTracking, ::testing::Values(kFreiburg, kIntel),
                         [](const ::testing::TestParamInfo<Recording>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace structloc
