// What a user of `structloc map build`, `map check` and `map grid` sees when
// the input is wrong: the message names the file or option, the options are
// listed only for a mistake in the options, exit codes say which (2: options or
// a file's content, 1: anything else), and nothing is written.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_runner.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using testing::RunCli;

bool Has(const testing::CliResult& r, const std::string& text) {
  return r.output.find(text) != std::string::npos;
}

class MapBuildCli : public ::testing::Test {
 protected:
  testing::TempDir dir;
  std::string no_scans = dir.Write("odometry.log", "ODOM 0 0 0 0 0 0 1.0 host 1.0\n");
  std::string map = testing::SourcePath("maps/office_floor.xml");
};

TEST_F(MapBuildCli, ALogWithoutScansNamesTheFileWithoutListingTheOptions) {
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"map", "build", "--log", no_scans, "--out", dir / "w.xml"},
           {"map", "check", "--map", map, "--log", no_scans},
           {"map", "grid", "--log", no_scans, "--out", dir / "g.yaml"}}) {
    const auto r = RunCli(args);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_TRUE(Has(r, no_scans + ": no laser scan with a pose")) << r.output;
    EXPECT_FALSE(Has(r, "options:")) << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "w.xml"));
  EXPECT_FALSE(std::filesystem::exists(dir / "g.yaml"));
}

TEST_F(MapBuildCli, MistakesInTheOptionsListThem) {
  auto r = RunCli({"map", "build", "--log", no_scans, "--out", dir / "w.xml", "--colour", "red"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(Has(r, "--colour")) << r.output;
  EXPECT_TRUE(Has(r, "options:")) << r.output;
  r = RunCli({"map", "check", "--map", map, "--log", no_scans, "--near", "0"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(Has(r, "--near 0 must be from 0.001 to 10")) << r.output;
  r = RunCli({"map", "teleport"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(Has(r, "unknown action 'teleport'")) << r.output;
}

TEST_F(MapBuildCli, AMissingLogOrMapAndAnOutputOverTheInputAreRefused) {
  auto r = RunCli({"map", "build", "--log", dir / "missing.log", "--out", dir / "w.xml"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(Has(r, dir / "missing.log")) << r.output;
  r = RunCli({"map", "check", "--map", dir / "missing.xml", "--log", no_scans});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(Has(r, dir / "missing.xml")) << r.output;
  const std::string before = testing::ReadFile(no_scans);
  r = RunCli({"map", "build", "--log", no_scans, "--out", no_scans});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(Has(r, "refusing to write the output over the input")) << r.output;
  EXPECT_EQ(testing::ReadFile(no_scans), before);
}

}  // namespace
}  // namespace structloc
