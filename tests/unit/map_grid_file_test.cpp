// map_server grid files: what SaveGridMap writes LoadGridMap reads back cell
// for cell, map_server's value rules (negate, thresholds, modes, colour), and
// every bad YAML or image refused with a message naming the file and the
// problem.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "structloc/config/strict_xml.hpp"
#include "structloc/map_formats/grid_map_file.hpp"
#include "temp_dir.hpp"

namespace structloc {
namespace {

using map_building::OccupancyGrid;
using map_formats::GridMapReadOptions;
using map_formats::LoadGridMap;
using map_formats::SaveGridMap;
using testing::TempDir;

// A 3 x 2 image: top row 0 (black), 254, 205; bottom row 255, 100, 30.
std::string WriteSmallImage(const TempDir& dir, const std::string& name) {
  cv::Mat image = (cv::Mat_<uint8_t>(2, 3) << 0, 254, 205, 255, 100, 30);
  const std::string path = dir / name;
  EXPECT_TRUE(cv::imwrite(path, image));
  return path;
}

std::string Yaml(const std::string& extra) {
  return "image: small.pgm\nresolution: 0.05\norigin: [1.0, -2.0, 0.0]\n" + extra;
}

// Expects LoadGridMap to throw a ConfigError naming the YAML and containing `what`.
void ExpectRefused(const std::string& path, const std::string& what,
                   const GridMapReadOptions& options = {}) {
  try {
    LoadGridMap(path, options);
    ADD_FAILURE() << "no error for " << path << " (expected '" << what << "')";
  } catch (const config::ConfigError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  }
}

TEST(GridMapFile, SavedGridLoadsBackCellForCell) {
  TempDir dir;
  OccupancyGrid grid(7, 4, 0.1, {-1.25, 3.5, 0.3});
  for (size_t i = 0; i < grid.cells.size(); ++i)
    grid.cells[i] = i % 3 == 0 ? OccupancyGrid::kOccupied
                               : (i % 3 == 1 ? OccupancyGrid::kFree : OccupancyGrid::kUnknown);
  grid.At(6, 3) = 70;  // >= 65: occupied
  grid.At(5, 3) = 10;  // <= 19: free
  grid.At(4, 3) = 40;  // in between: unknown
  const std::string yaml = dir / "map.yaml";
  SaveGridMap(grid, yaml);
  const std::string text = testing::ReadFile(yaml);
  EXPECT_NE(text.find("image: map.pgm"), std::string::npos) << text;
  EXPECT_NE(text.find("occupied_thresh: 0.65"), std::string::npos) << text;
  EXPECT_NE(text.find("free_thresh: 0.196"), std::string::npos) << text;
  EXPECT_NE(text.find("negate: 0"), std::string::npos) << text;
  EXPECT_NE(text.find("mode: trinary"), std::string::npos) << text;
  const OccupancyGrid back = LoadGridMap(yaml);
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.height, 4);
  EXPECT_DOUBLE_EQ(back.resolution_m, 0.1);
  EXPECT_DOUBLE_EQ(back.origin.x(), -1.25);
  EXPECT_DOUBLE_EQ(back.origin.y(), 3.5);
  EXPECT_DOUBLE_EQ(back.origin.z(), 0.3);
  grid.At(6, 3) = OccupancyGrid::kOccupied;
  grid.At(5, 3) = OccupancyGrid::kFree;
  grid.At(4, 3) = OccupancyGrid::kUnknown;
  EXPECT_EQ(back.cells, grid.cells);
  // Row 0 is the bottom: the PGM's last line.
  const cv::Mat image = cv::imread(dir / "map.pgm", cv::IMREAD_UNCHANGED);
  EXPECT_EQ(image.at<uint8_t>(3, 0), grid.At(0, 0) == OccupancyGrid::kOccupied ? 0 : 254);
}

TEST(GridMapFile, ValuesFollowMapServer) {
  TempDir dir;
  WriteSmallImage(dir, "small.pgm");
  const OccupancyGrid trinary = LoadGridMap(dir.Write("t.yaml", Yaml("")));
  // Bottom row (image row 1): 255 free, 100 (p 0.61) unknown, 30 (p 0.88) occupied.
  EXPECT_EQ(trinary.At(0, 0), OccupancyGrid::kFree);
  EXPECT_EQ(trinary.At(1, 0), OccupancyGrid::kUnknown);
  EXPECT_EQ(trinary.At(2, 0), OccupancyGrid::kOccupied);
  EXPECT_EQ(trinary.At(0, 1), OccupancyGrid::kOccupied);
  EXPECT_EQ(trinary.At(1, 1), OccupancyGrid::kFree);
  EXPECT_EQ(trinary.At(2, 1), OccupancyGrid::kUnknown);  // 205: p 0.196 is not below 0.196
  const OccupancyGrid negated = LoadGridMap(dir.Write("n.yaml", Yaml("negate: 1\n")));
  EXPECT_EQ(negated.At(0, 1), OccupancyGrid::kFree);
  EXPECT_EQ(negated.At(0, 0), OccupancyGrid::kOccupied);
  const OccupancyGrid scale = LoadGridMap(dir.Write("s.yaml", Yaml("mode: scale\n")));
  EXPECT_EQ(scale.At(1, 0), 90);  // 99 * (0.608 - 0.196) / (0.65 - 0.196) = 89.8
  // Raw: the cell values themselves, 255 for unknown (as map_saver writes raw maps).
  const cv::Mat raw_image = (cv::Mat_<uint8_t>(1, 4) << 0, 100, 30, 255);
  ASSERT_TRUE(cv::imwrite(dir / "raw.pgm", raw_image));
  const OccupancyGrid raw = LoadGridMap(
      dir.Write("r.yaml", "image: raw.pgm\nresolution: 1\norigin: [0, 0, 0]\nmode: raw\n"));
  EXPECT_EQ(raw.At(0, 0), 0);
  EXPECT_EQ(raw.At(1, 0), 100);
  EXPECT_EQ(raw.At(2, 0), 30);
  EXPECT_EQ(raw.At(3, 0), OccupancyGrid::kUnknown);
  const OccupancyGrid thresholds =
      LoadGridMap(dir.Write("h.yaml", Yaml("occupied_thresh: 0.5\nfree_thresh: 0.1\n")));
  EXPECT_EQ(thresholds.At(1, 0), OccupancyGrid::kOccupied);
}

// A binary PGM's white is its maxval, as map_server reads it (OpenCV hands
// binary PGMs over unscaled): a maxval of 100 or of 1023 is not 255 or 65535.
TEST(GridMapFile, APgmsMaxvalIsItsWhite) {
  TempDir dir;
  const std::string eight = std::string("P5\n3 1\n100\n") + '\x00' + '\x32' + '\x64';
  dir.Write("m100.pgm", eight);
  std::string sixteen = "P5\n3 1\n1023\n";
  for (const int v : {0, 512, 1019}) {
    sixteen += static_cast<char>(v >> 8);
    sixteen += static_cast<char>(v & 0xff);
  }
  dir.Write("m1023.pgm", sixteen);
  for (const std::string image : {"m100.pgm", "m1023.pgm"}) {
    map_formats::GridMapSource source;
    source.mode = map_formats::GridMapMode::kRaw;
    const OccupancyGrid grid = LoadGridMap(
        dir.Write(image + ".yaml", "image: " + image + "\nresolution: 1\norigin: [0, 0, 0]\n"), {},
        &source);
    EXPECT_EQ(source.mode, map_formats::GridMapMode::kTrinary);
    EXPECT_EQ(source.image_path, dir / image);
    EXPECT_EQ(grid.At(0, 0), OccupancyGrid::kOccupied) << image;
    EXPECT_EQ(grid.At(1, 0), OccupancyGrid::kUnknown) << image;  // half grey: p 0.5
    EXPECT_EQ(grid.At(2, 0), OccupancyGrid::kFree) << image;
  }
}

TEST(GridMapFile, ColourImagesAreAveragedAndImagePathsAreRelativeToTheYaml) {
  TempDir dir;
  std::filesystem::create_directory(dir / "maps");
  cv::Mat colour(1, 2, CV_8UC3);
  colour.at<cv::Vec3b>(0, 0) = {0, 30, 60};      // mean 30: occupied
  colour.at<cv::Vec3b>(0, 1) = {255, 250, 254};  // mean 253: free
  ASSERT_TRUE(cv::imwrite(dir / "maps/colour.png", colour));
  const OccupancyGrid grid = LoadGridMap(dir.Write(
      "maps/c.yaml", "image: colour.png\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\n"));
  EXPECT_EQ(grid.At(0, 0), OccupancyGrid::kOccupied);
  EXPECT_EQ(grid.At(1, 0), OccupancyGrid::kFree);
}

TEST(GridMapFile, BadYamlsAreRefusedNamingFileAndProblem) {
  TempDir dir;
  WriteSmallImage(dir, "small.pgm");
  ExpectRefused(dir / "none.yaml", "no such grid map file");
  ExpectRefused(
      dir.Write("missing_image.yaml", "image: gone.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n"),
      "gone.pgm, does not exist");
  ExpectRefused(dir.Write("zero.yaml", "image: small.pgm\nresolution: 0\norigin: [0, 0, 0]\n"),
                "'resolution' (metres per cell) must be positive");
  ExpectRefused(
      dir.Write("negative.yaml", "image: small.pgm\nresolution: -0.05\norigin: [0, 0, 0]\n"),
      "must be positive");
  ExpectRefused(dir.Write("text.yaml", "image: small.pgm\nresolution: fine\norigin: [0, 0, 0]\n"),
                "'resolution' is not a number: 'fine'");
  ExpectRefused(dir.Write("mode.yaml", Yaml("mode: ternary\n")), "unknown 'mode' 'ternary'");
  ExpectRefused(dir.Write("no_image.yaml", "resolution: 0.05\norigin: [0, 0, 0]\n"),
                "missing key 'image'");
  ExpectRefused(dir.Write("no_resolution.yaml", "image: small.pgm\norigin: [0, 0, 0]\n"),
                "missing key 'resolution'");
  ExpectRefused(dir.Write("no_origin.yaml", "image: small.pgm\nresolution: 0.05\n"),
                "missing key 'origin'");
  ExpectRefused(dir.Write("short_origin.yaml", "image: small.pgm\nresolution: 1\norigin: [0, 0]\n"),
                "'origin' must be [x, y, yaw]");
  ExpectRefused(dir.Write("typo.yaml", Yaml("ocupied_thresh: 0.7\n")),
                "unknown key 'ocupied_thresh'");
  ExpectRefused(dir.Write("order.yaml", Yaml("occupied_thresh: 0.3\nfree_thresh: 0.3\n")),
                "free_thresh (0.3) must be below occupied_thresh (0.3)");
  ExpectRefused(dir.Write("negative_thresh.yaml", Yaml("free_thresh: -0.1\n")),
                "'free_thresh' must lie in [0, 1]");
  ExpectRefused(dir.Write("negate.yaml", Yaml("negate: 2\n")), "'negate' must be 0 or 1");
  ExpectRefused(dir.Write("twice.yaml", Yaml("resolution: 0.1\n")), "given twice");
  ExpectRefused(dir.Write("list.yaml", "- image\n- resolution\n"), "not a map_server YAML");
  ExpectRefused(dir.Write("broken.yaml", "image: [small.pgm\n"), "not a readable YAML file");
  dir.Write("empty.pgm", "");
  ExpectRefused(
      dir.Write("empty_image.yaml", "image: empty.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n"),
      "empty.pgm is neither a PNG nor a PGM");
  dir.Write("garbage.png", "this is no picture");
  ExpectRefused(
      dir.Write("garbage.yaml", "image: garbage.png\nresolution: 0.05\norigin: [0, 0, 0]\n"),
      "garbage.png is neither a PNG nor a PGM");
  // A PNG whose data is cut short passes the header and fails in decoding.
  cv::Mat white(40, 40, CV_8UC1, cv::Scalar(254));
  ASSERT_TRUE(cv::imwrite(dir / "cut.png", white));
  const std::string png = testing::ReadFile(dir / "cut.png");
  dir.Write("cut.png", png.substr(0, png.size() / 2));
  ExpectRefused(dir.Write("cut.yaml", "image: cut.png\nresolution: 0.05\norigin: [0, 0, 0]\n"),
                "cannot read the image");
  cv::Mat grey(2, 1, CV_8UC1, cv::Scalar(180));
  ASSERT_TRUE(cv::imwrite(dir / "grey.pgm", grey));
  ExpectRefused(dir.Write("raw.yaml",
                          "image: grey.pgm\nresolution: 1\norigin: [0, 0, 0]\n"
                          "mode: raw\n"),
                "grey level 180");
}

TEST(GridMapFile, UnknownKeysCanBeIgnoredAsRosDoes) {
  TempDir dir;
  WriteSmallImage(dir, "small.pgm");
  const std::string path = dir.Write("extra.yaml", Yaml("elevation_image: e.pgm\n"));
  ExpectRefused(path, "unknown key 'elevation_image'");
  GridMapReadOptions lenient;
  lenient.ignore_unknown_keys = true;
  EXPECT_EQ(LoadGridMap(path, lenient).width, 3);
}

TEST(GridMapFile, TooLargeImagesAreRefusedBeforeDecoding) {
  TempDir dir;
  WriteSmallImage(dir, "small.pgm");
  GridMapReadOptions small;
  small.max_cells = 5;
  ExpectRefused(dir.Write("large.yaml", Yaml("")), "too large: 3 x 2 cells (the limit is 5)",
                small);
  // Formats whose size is known only by decoding them (TIFF, a 6 kB file of
  // which decoded to 1 GB) are refused before OpenCV sees them.
  ASSERT_TRUE(cv::imwrite(dir / "small.tiff", cv::Mat(2, 3, CV_8UC1, cv::Scalar(0))));
  ExpectRefused(dir.Write("tiff.yaml", "image: small.tiff\nresolution: 0.05\norigin: [0, 0, 0]\n"),
                "small.tiff is neither a PNG nor a PGM");
  // A PGM header whose sides multiply past 2^64 (to a small number) is refused.
  dir.Write("wrap.pgm", "P5\n8589934592 2147483648\n255\n");
  ExpectRefused(dir.Write("wrap.yaml", "image: wrap.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n"),
                "too large: 8589934592 x 2147483648 cells");
  // A PGM header claiming 100000 x 100000 cells is refused without reading its pixels.
  dir.Write("huge.pgm", "P5\n# a comment\n100000 100000\n255\n");
  ExpectRefused(dir.Write("huge.yaml", "image: huge.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n"),
                "too large: 100000 x 100000 cells");
  cv::Mat png(3, 4, CV_8UC1, cv::Scalar(255));
  ASSERT_TRUE(cv::imwrite(dir / "p.png", png));
  ExpectRefused(dir.Write("png.yaml", "image: p.png\nresolution: 0.05\norigin: [0, 0, 0]\n"),
                "too large: 4 x 3 cells", small);
}

TEST(GridMapFile, SavingNeverOverwritesAnInput) {
  TempDir dir;
  OccupancyGrid grid(2, 2, 0.05, {0, 0, 0}, OccupancyGrid::kFree);
  const std::string input = dir.Write("map.pgm", "precious");
  EXPECT_THROW(SaveGridMap(grid, dir / "map.yaml", {input}), config::ConfigError);
  EXPECT_EQ(testing::ReadFile(input), "precious");
  EXPECT_THROW(SaveGridMap(OccupancyGrid(), dir / "empty.yaml"), std::invalid_argument);
}

}  // namespace
}  // namespace structloc
