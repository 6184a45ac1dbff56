// The <slam_params> file (slam_options.cpp): the shipped file holds exactly
// the built-in defaults, a file based on the defaults changes only what it
// states, and a bad file is refused naming its path, line, section and key,
// by the library and by `structloc slam` before it reads the log.
#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>
#include <string>

#include "cli_runner.hpp"
#include "structloc/config/strict_xml.hpp"
#include "structloc/slam_core/slam.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc::slam_core {
namespace {

using testing::SourcePath;

const char* const kShipped = "maps/slam/sick_180deg.xml";

std::string Expanded(const std::string& path) {
  std::ostringstream out;
  WriteExpandedSlamOptions(path, out);
  return out.str();
}

// The message loading `path` fails with ("" when it loads).
std::string LoadError(const std::string& path) {
  try {
    LoadSlamOptions(path);
    return "";
  } catch (const config::ConfigError& e) {
    return e.what();
  }
}

TEST(SlamOptions, TheShippedFileHoldsTheDefaults) {
  const testing::TempDir dir;
  const auto defaults = dir.Write("defaults.xml", "<slam_params base=\"defaults\"/>\n");
  EXPECT_EQ(Expanded(SourcePath(kShipped)), Expanded(defaults));
  const SlamOptions loaded = LoadSlamOptions(SourcePath(kShipped));
  const SlamOptions built_in;
  EXPECT_DOUBLE_EQ(loaded.loop_match.first_pair_distance_m,
                   built_in.loop_match.first_pair_distance_m);
  EXPECT_EQ(loaded.loop_min_separation, built_in.loop_min_separation);
}

TEST(SlamOptions, AFileBasedOnTheDefaultsChangesOnlyWhatItStates) {
  const testing::TempDir dir;
  const auto path = dir.Write("loops.xml",
                              "<slam_params base=\"defaults\">\n"
                              "  <loops min_share=\"0.6\"/>\n"
                              "  <loop_match correlated_points=\"40\"/>\n"
                              "</slam_params>\n");
  const SlamOptions loaded = LoadSlamOptions(path);
  const SlamOptions built_in;
  EXPECT_DOUBLE_EQ(loaded.loop_min_share, 0.6);
  EXPECT_DOUBLE_EQ(loaded.loop_match.correlated_points, 40.0);
  EXPECT_DOUBLE_EQ(loaded.match.correlated_points, built_in.match.correlated_points);
  EXPECT_DOUBLE_EQ(loaded.loop_max_rms_m, built_in.loop_max_rms_m);
}

TEST(SlamOptions, ABadFileIsRefusedNamingItsLineSectionAndKey) {
  const testing::TempDir dir;
  const std::string text = testing::ReadFile(SourcePath(kShipped));
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string changed = text;
    const auto at = changed.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) changed.replace(at, from.size(), to);
    return dir.Write("slam.xml", changed);
  };
  struct Case {
    std::string from, to, words;
  };
  for (const Case& c : std::vector<Case>{
           {"min_share=\"0.7\"", "min_share=\"1.5\"",
            "loops: min_share must be in [0, 1], not 1.5"},
           {"candidates=\"3\"", "candidates=\"3\" colour=\"red\"", "colour"},
           {" max_rms_m=\"0.05\"", "", "max_rms_m"},
           {"<loop_match iterations=\"30\" first_pair_distance_m=\"2\"",
            "<loop_match iterations=\"30\" first_pair_distance_m=\"0.1\"",
            "loop_match: first_pair_distance_m must be >= last_pair_distance_m"},
           {"max_radius_m=\"8\"", "max_radius_m=\"1\"", "loops: max_radius_m must be >= radius_m"},
           {"<step_match iterations=\"30\" first_pair_distance_m=\"1\" "
            "last_pair_distance_m=\"0.2\"\n"
            "              normal_radius_m=\"0.25\"",
            "<step_match iterations=\"30\" first_pair_distance_m=\"1\" "
            "last_pair_distance_m=\"0.2\"\n"
            "              normal_radius_m=\"1e-9\"",
            "step_match: normal_radius_m must be in [0.02, 5]"},
           {"latency_s=\"0\"", "latency_s=\"0.13\"",
            "scan_latency: latency_s is 0.13 but estimate is true"},
           {"confidence=\"0.95\"", "confidence=\"1\"",
            "scan_latency: confidence must be in (0, 1), not 1"},
       }) {
    const auto path = with(c.from, c.to);
    const std::string error = LoadError(path);
    EXPECT_NE(error.find(path + ":"), std::string::npos) << c.words << ": " << error;
    EXPECT_NE(error.find(c.words), std::string::npos) << error;
  }
}

TEST(SlamOptions, ASlamBuiltWithOptionsOutOfRangeIsRefusedByName) {
  SlamOptions options;
  options.loop_match.normal_radius_m = 0.0;
  try {
    Slam slam(options);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("loop_match: normal_radius_m"), std::string::npos)
        << e.what();
  }
}

TEST(SlamOptions, TheSlamCommandRefusesABadFileBeforeReadingTheLog) {
  const testing::TempDir dir;
  const auto bad = dir.Write("slam.xml",
                             "<slam_params base=\"defaults\">\n"
                             "  <keyframes distance_m=\"-1\"/>\n"
                             "</slam_params>\n");
  const auto run = testing::RunCli({"slam", "--log", (dir / "missing.log"), "--poses-out",
                                    (dir / "poses.tum"), "--slam-params", bad});
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find(bad + ":2"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("keyframes: distance_m must be > 0"), std::string::npos) << run.output;
  const auto listing = testing::RunCli({"params", "--slam"});
  EXPECT_EQ(listing.exit_code, 0) << listing.output;
  EXPECT_NE(listing.output.find("<loop_match>"), std::string::npos) << listing.output;
}

}  // namespace
}  // namespace structloc::slam_core
