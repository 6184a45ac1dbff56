// Regression tests for the bad-input review of 36dc199 (issue 42) on the map
// tools, their outputs and the saved pose: each test is named after the
// finding it keeps fixed (H = high, M = medium, L = low). Recordings are
// simulated from the repository's robustness room; every hostile file is made
// in a per-test folder and every command runs as the user would run it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "room_recording.hpp"
#include "structloc/localisation/pose_state_file.hpp"
#include "structloc/log_formats/carmen_reader.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using testing::CliResult;
using testing::ReadFile;
using testing::RunCli;
using testing::TempDir;

using testing::RoomLog;

std::string Describe(const CliResult& r) {
  return "exit " + std::to_string(r.exit_code) + ":\n" + r.output;
}

bool Contains(const CliResult& r, const std::string& text) {
  return r.output.find(text) != std::string::npos;
}

// A copy of `path` in `dir`, to be put at risk.
std::string CopyInto(const TempDir& dir, const std::string& path, const std::string& name) {
  return dir.Write(name, ReadFile(path));
}

// The room's log with every other ROBOTLASER line cut in half.
std::string HalfBadLog(const TempDir& dir) {
  std::ifstream in(RoomLog());
  std::string text, line;
  int lasers = 0;
  while (std::getline(in, line)) {
    if (line.rfind("ROBOTLASER", 0) == 0 && lasers++ % 2 == 1)
      line = line.substr(0, line.size() / 2);
    text += line + "\n";
  }
  return dir.Write("half_bad.clf", text);
}

TEST(BadInputMaps, H3_ABeamAngleOverflowingToInfinityIsAMalformedLine) {
  const TempDir dir;
  const std::string log =
      dir.Write("nan_angles.clf", testing::FiveBeamLaserLine("0.785398", "1.0") +
                                      testing::FiveBeamLaserLine("1e308", "2.0"));
  log_formats::CarmenReader reader(log);
  log_formats::CarmenRecord record;
  size_t scans = 0;
  while (reader.Next(record)) scans += record.kind == log_formats::CarmenRecord::Kind::kScan;
  EXPECT_EQ(scans, 1u);
  ASSERT_EQ(reader.Stats().malformed_lines.size(), 1u);
  EXPECT_EQ(reader.Stats().malformed_lines[0].line, 2u);
  EXPECT_NE(reader.Stats().malformed_lines[0].reason.find("do not lie within one turn"),
            std::string::npos);
  // map grid (which wrote outside its grid) makes the grid of the good line
  // and says which line it left out.
  const auto grid = RunCli({"map", "grid", "--log", log, "--out", dir / "g.yaml"});
  EXPECT_EQ(grid.exit_code, 0) << Describe(grid);
  EXPECT_TRUE(Contains(grid, "1 malformed line of " + log + " left out")) << grid.output;
  EXPECT_TRUE(Contains(grid, "line 2: ")) << grid.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "g.pgm"));
}

TEST(BadInputMaps, H4_PoseFitsNeverReplaceTheMapOrTheLog) {
  const TempDir dir;
  const std::string map = CopyInto(dir, testing::SourcePath("maps/robustness_room.xml"), "map.xml");
  const std::string log = CopyInto(dir, RoomLog(), "run.clf");
  const std::string map_text = ReadFile(map), log_text = ReadFile(log);
  for (const auto& victim : {map, log}) {
    const auto r = RunCli({"map", "check", "--map", map, "--log", log, "--fit-poses-out", victim});
    EXPECT_EQ(r.exit_code, 2) << Describe(r);
    EXPECT_TRUE(Contains(r, "refusing to write the output over the input")) << r.output;
  }
  EXPECT_EQ(ReadFile(map), map_text);
  EXPECT_EQ(ReadFile(log), log_text);
  // Through another name of the same file (a hard link) too.
  std::filesystem::create_hard_link(map, dir / "alias.xml");
  const auto alias =
      RunCli({"map", "check", "--map", map, "--log", log, "--fit-poses-out", dir / "alias.xml"});
  EXPECT_EQ(alias.exit_code, 2) << Describe(alias);
  EXPECT_EQ(ReadFile(map), map_text);
  // And a CSV of its own is written whole (the control).
  const auto fits =
      RunCli({"map", "check", "--map", map, "--log", log, "--fit-poses-out", dir / "fits.csv"});
  EXPECT_EQ(fits.exit_code, 0) << Describe(fits);
  EXPECT_EQ(ReadFile(dir / "fits.csv").rfind("scan,fitted,converged", 0), 0u);
}

TEST(BadInputMaps, M1_AGridImportNeverReplacesTheGridsImage) {
  const TempDir dir;
  const auto exported =
      RunCli({"map", "export", "--map", testing::SourcePath("maps/office_floor.xml"), "--grid",
              dir / "g.yaml"});
  ASSERT_EQ(exported.exit_code, 0) << Describe(exported);
  const std::string image = ReadFile(dir / "g.pgm");
  // The world written over the image the YAML names.
  const auto out = RunCli({"map", "import", "--grid", dir / "g.yaml", "--out", dir / "g.pgm"});
  EXPECT_EQ(out.exit_code, 2) << Describe(out);
  EXPECT_TRUE(Contains(out, "refusing to write the output over the input " + dir / "g.pgm"))
      << out.output;
  EXPECT_EQ(ReadFile(dir / "g.pgm"), image);
  // The picture written over a PNG image the YAML names.
  std::filesystem::copy_file(dir / "g.pgm", dir / "room.png");
  const std::string png =
      dir.Write("room.yaml", "image: room.png\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n");
  const auto plot =
      RunCli({"map", "import", "--grid", png, "--out", dir / "w.xml", "--plot", dir / "room.png"});
  EXPECT_EQ(plot.exit_code, 2) << Describe(plot);
  EXPECT_TRUE(Contains(plot, "refusing to write the output over the input " + dir / "room.png"))
      << plot.output;
  EXPECT_EQ(ReadFile(dir / "room.png"), image);
  EXPECT_FALSE(std::filesystem::exists(dir / "w.xml"));
}

TEST(BadInputMaps, M6_OutputsAreNotWrittenThroughSymbolicLinks) {
  const TempDir dir;
  const std::string victim = dir.Write("victim.txt", "precious");
  std::filesystem::create_symlink(victim, dir / "link.yaml");
  const auto r = RunCli({"map", "export", "--map", testing::SourcePath("maps/office_floor.xml"),
                         "--grid", dir / "link.yaml"});
  EXPECT_EQ(r.exit_code, 2) << Describe(r);
  EXPECT_TRUE(Contains(r, dir / "link.yaml" + ": is a symbolic link")) << r.output;
  EXPECT_EQ(ReadFile(victim), "precious");
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "link.yaml"));
  // A link to a device is written through, in place (as /dev/stdout is).
  std::filesystem::create_symlink("/dev/null", dir / "null.png");
  const auto to_device =
      RunCli({"render", "--scenario", testing::SourcePath("maps/scenarios/robustness_room.xml"),
              "--out", dir / "null.png"});
  EXPECT_EQ(to_device.exit_code, 0) << Describe(to_device);
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "null.png"));
  // The demo's saved pose is no fixed name in /tmp any more.
  const std::string demo = ReadFile(testing::SourcePath("launch_xml/demo.launch.xml"));
  EXPECT_EQ(demo.find("/tmp"), std::string::npos);
}

TEST(BadInputMaps, L1_ADxfCutShortIsRefused) {
  const TempDir dir;
  std::ifstream in(testing::SourcePath("tests/data/maps/office_floor_mm.dxf"));
  std::string text, line;
  for (int n = 0; n < 300 && std::getline(in, line); ++n) text += line + "\n";
  const std::string cut = dir.Write("trunc.dxf", text);
  const auto r =
      RunCli({"map", "import", "--dxf", cut, "--layers", "WALLS", "--out", dir / "o.xml"});
  EXPECT_EQ(r.exit_code, 2) << Describe(r);
  EXPECT_TRUE(Contains(r, "ends before the ENTITIES section's ENDSEC")) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "o.xml"));
  // Without its EOF only.
  std::string whole = ReadFile(testing::SourcePath("tests/data/maps/office_floor_mm.dxf"));
  whole = whole.substr(0, whole.rfind("EOF"));
  const std::string no_eof = dir.Write("no_eof.dxf", whole.substr(0, whole.rfind("0\n")));
  const auto e =
      RunCli({"map", "import", "--dxf", no_eof, "--layers", "WALLS", "--out", dir / "o.xml"});
  EXPECT_EQ(e.exit_code, 2) << Describe(e);
  EXPECT_TRUE(Contains(e, "ends before its EOF")) << e.output;
}

TEST(BadInputMaps, L2_EveryMapToolSaysWhichLinesItLeftOut) {
  const TempDir dir;
  const std::string log = HalfBadLog(dir);
  const auto grid = RunCli({"map", "grid", "--log", log, "--out", dir / "g.yaml"});
  const auto check = RunCli(
      {"map", "check", "--map", testing::SourcePath("maps/robustness_room.xml"), "--log", log});
  const auto synthesised = RunCli(
      {"synthesise-odometry", "--log", log, "--out", dir / "e.clf", "--truth", dir / "e.tum"});
  for (const auto* r : {&grid, &check, &synthesised}) {
    EXPECT_EQ(r->exit_code, 0) << Describe(*r);
    EXPECT_TRUE(Contains(*r, "malformed lines of " + log + " left out")) << r->output;
    EXPECT_TRUE(Contains(*r, "  line ")) << r->output;
  }
}

TEST(BadInputMaps, L3_SynthesisedOdometryIsReadBackWhole) {
  const TempDir dir;
  // The room's log with a scan of no beams and one whose angles overflow (the
  // output's field of view was written as inf, a line its reader drops).
  const std::string log = dir.Write(
      "zero.clf", ReadFile(RoomLog()) +
                      "ROBOTLASER1 0 -1.5707963 3.14159 0.0174533 20 0.01 0 0 0 0 0 0 0 0 0 0 0 0 "
                      "0 0 999.0 host 999.0\n" +
                      testing::FiveBeamLaserLine("1e308", "1000.0"));
  const auto r = RunCli(
      {"synthesise-odometry", "--log", log, "--out", dir / "e.clf", "--truth", dir / "e.tum"});
  ASSERT_EQ(r.exit_code, 0) << Describe(r);
  size_t in_scans = 0, out_scans = 0;
  log_formats::CarmenRecord record;
  log_formats::CarmenReader original(log);
  while (original.Next(record)) in_scans += record.kind == log_formats::CarmenRecord::Kind::kScan;
  log_formats::CarmenReader written(dir / "e.clf");
  while (written.Next(record)) out_scans += record.kind == log_formats::CarmenRecord::Kind::kScan;
  EXPECT_EQ(written.Stats().malformed, 0u) << ReadFile(dir / "e.clf").substr(0, 2000);
  EXPECT_EQ(out_scans, in_scans);
}

TEST(BadInputMaps, L6_AFailingPictureLeavesTheWorldAsItWas) {
  const TempDir dir;
  const std::string world = dir.Write("b.xml", "precious");
  const auto missing =
      RunCli({"map", "build", "--log", RoomLog(), "--out", world, "--plot", dir / "no/p.png"});
  EXPECT_EQ(missing.exit_code, 2) << Describe(missing);
  EXPECT_TRUE(Contains(missing, "cannot create an output file there")) << missing.output;
  EXPECT_EQ(ReadFile(world), "precious");
  // A grey-only picture format is refused before the import, not after it.
  const auto exported =
      RunCli({"map", "export", "--map", testing::SourcePath("maps/office_floor.xml"), "--grid",
              dir / "g.yaml"});
  ASSERT_EQ(exported.exit_code, 0) << Describe(exported);
  const auto pgm =
      RunCli({"map", "import", "--grid", dir / "g.yaml", "--out", world, "--plot", dir / "p.pgm"});
  EXPECT_EQ(pgm.exit_code, 2) << Describe(pgm);
  EXPECT_TRUE(Contains(pgm, "not a name for a colour picture")) << pgm.output;
  EXPECT_FALSE(Contains(pgm, "structloc map import: " + dir / "g.yaml" + ": ")) << pgm.output;
  EXPECT_EQ(ReadFile(world), "precious");
}

TEST(BadInputMaps, L7_ASavedPoseBeyondTheMapsBoundsIsRefused) {
  const TempDir dir;
  for (const std::string text :
       {"map_to_odom 1e300 0 0 0.01 0.01 0.01\n", "map_to_odom 0 -2e5 0 0.01 0.01 0.01\n",
        "map_to_odom 0 0 0 1e300 0.01 0.01\n", "map_to_odom 0 0 1e9 0.01 0.01 0.01\n"}) {
    const std::string path = dir.Write("pose.txt", text);
    EXPECT_THROW(localisation::LoadSavedPose(path), std::runtime_error) << text;
  }
  const auto fine = localisation::LoadSavedPose(
      dir.Write("pose.txt", "map_to_odom 1234.5 -99999 3.1 0.01 0.02 0.03\n"));
  ASSERT_TRUE(fine.has_value());
  EXPECT_DOUBLE_EQ(fine->map_to_odom.y, -99999.0);
  dir.Write("big.txt", std::string(10000, ' ') + "map_to_odom 0 0 0 1 1 1\n");
  EXPECT_THROW(localisation::LoadSavedPose(dir / "big.txt"), std::runtime_error);
}

}  // namespace
}  // namespace structloc
