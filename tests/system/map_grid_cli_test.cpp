// `structloc map export` and `structloc map import --grid` as a user runs
// them: the round trip through files, the summary they print, and bad input
// refused with the file named and existing outputs left untouched.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_runner.hpp"
#include "structloc/map_formats/grid_map_file.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using testing::RunCli;
using testing::TempDir;

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(MapGridCli, ExportThenImportGivesTheOfficeFloorBack) {
  TempDir dir;
  const std::string map = testing::SourcePath("maps/office_floor.xml");
  const auto exported = RunCli({"map", "export", "--map", map, "--grid", dir / "office.yaml"});
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  EXPECT_TRUE(Contains(exported.output, "500 x 300 cells of 0.05 m")) << exported.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "office.pgm"));
  const auto imported = RunCli({"map", "import", "--grid", dir / "office.yaml", "--out",
                                dir / "world.xml", "--plot", dir / "world.png"});
  ASSERT_EQ(imported.exit_code, 0) << imported.output;
  std::cout << imported.output;
  EXPECT_TRUE(Contains(imported.output, "150000 cells read")) << imported.output;
  EXPECT_TRUE(Contains(imported.output, "16 walls, 6 corners")) << imported.output;
  EXPECT_TRUE(Contains(imported.output, "3 pillars")) << imported.output;
  const auto world = world_model::LoadWorldModel(dir / "world.xml");
  EXPECT_EQ(world.Name(), "office");
  EXPECT_EQ(world.Walls().size(), 16u);
  EXPECT_EQ(world.Cylinders().size(), 3u);
  EXPECT_GT(std::filesystem::file_size(dir / "world.png"), 1000u);
  EXPECT_TRUE(Contains(testing::ReadFile(dir / "world.xml"), "made by structloc map import"));
}

TEST(MapGridCli, BadGridsAreRefusedNamingTheFileAndLeaveTheOutputAlone) {
  TempDir dir;
  const std::string out = dir.Write("world.xml", "precious");
  const std::string missing =
      dir.Write("missing.yaml", "image: nowhere.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
  auto result = RunCli({"map", "import", "--grid", missing, "--out", out});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_TRUE(Contains(result.output, missing)) << result.output;
  EXPECT_TRUE(Contains(result.output, "nowhere.pgm, does not exist")) << result.output;

  map_building::OccupancyGrid empty(20, 20, 0.05, {0, 0, 0}, map_building::OccupancyGrid::kFree);
  map_formats::SaveGridMap(empty, dir / "empty.yaml");
  result = RunCli({"map", "import", "--grid", dir / "empty.yaml", "--out", out});
  EXPECT_EQ(result.exit_code, 2) << result.output;  // bad input, as any grid refused
  EXPECT_TRUE(Contains(result.output, "empty.yaml: the grid has no occupied cell"))
      << result.output;
  EXPECT_TRUE(Contains(result.output, "nothing to import")) << result.output;
  EXPECT_EQ(testing::ReadFile(out), "precious");

  result = RunCli({"map", "import", "--grid", dir / "empty.yaml", "--out", out, "--max-gap", "0"});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_TRUE(Contains(result.output, "max-gap")) << result.output;
  for (const char* gap : {"-0.1", "1.5", "nan"}) {
    result =
        RunCli({"map", "import", "--grid", dir / "empty.yaml", "--out", out, "--join-gap", gap});
    EXPECT_EQ(result.exit_code, 2) << gap << ": " << result.output;
    EXPECT_TRUE(Contains(result.output, "join-gap")) << result.output;
  }
  EXPECT_EQ(testing::ReadFile(out), "precious");
}

// In a "scale" grid the cells between the thresholds are graded 0..99; none
// of them is occupied (that takes p above occupied_thresh). A room drawn in
// grey 128 (p 0.498, under the default 0.65) holds no wall in either mode.
TEST(MapGridCli, GreyBelowTheOccupiedThresholdIsNoWallInScaleModeEither) {
  TempDir dir;
  cv::Mat image(60, 80, CV_8U, cv::Scalar(254));
  cv::rectangle(image, {5, 5}, {74, 54}, cv::Scalar(128), 2);
  ASSERT_TRUE(cv::imwrite(dir / "grey.pgm", image));
  for (const std::string mode : {"trinary", "scale"}) {
    const std::string yaml =
        dir.Write(mode + ".yaml",
                  "image: grey.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nmode: " + mode + "\n");
    const auto result = RunCli({"map", "import", "--grid", yaml, "--out", dir / "w.xml"});
    EXPECT_NE(result.exit_code, 0) << mode << ": " << result.output;
    EXPECT_TRUE(Contains(result.output, "no occupied cell")) << mode << ": " << result.output;
  }
  // Drawn in black, scale mode finds the room's walls (both faces of each side).
  cv::rectangle(image, {5, 5}, {74, 54}, cv::Scalar(0), 2);
  ASSERT_TRUE(cv::imwrite(dir / "grey.pgm", image));
  const auto result =
      RunCli({"map", "import", "--grid", dir / "scale.yaml", "--out", dir / "w.xml"});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(Contains(result.output, "8 walls")) << result.output;
}

TEST(MapGridCli, ExportRefusesBadResolutionsAndOverwritingItsInput) {
  TempDir dir;
  const std::string map = testing::SourcePath("maps/office_floor.xml");
  auto result =
      RunCli({"map", "export", "--map", map, "--grid", dir / "g.yaml", "--resolution", "0"});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_TRUE(Contains(result.output, "resolution")) << result.output;
  result =
      RunCli({"map", "export", "--map", map, "--grid", dir / "g.yaml", "--resolution", "0.001"});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_TRUE(Contains(result.output, "choose a coarser resolution")) << result.output;
  result = RunCli({"map", "export", "--map", map, "--grid", dir / "g.yaml", "--margin", "-1"});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_TRUE(Contains(result.output, "margin")) << result.output;
  // The grid named like the map itself: refused, the map untouched.
  std::filesystem::copy_file(map, dir / "map.yaml");
  const std::string original = testing::ReadFile(dir / "map.yaml");
  result = RunCli({"map", "export", "--map", dir / "map.yaml", "--grid", dir / "map.yaml"});
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_EQ(testing::ReadFile(dir / "map.yaml"), original);
  EXPECT_FALSE(std::filesystem::exists(dir / "g.pgm"));
}

}  // namespace
}  // namespace structloc
