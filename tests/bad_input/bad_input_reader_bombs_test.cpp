// No reader takes more than 2 s of CPU or 500 MB on any input under 1 MB
// (issue 42): the bombs of the bad-input review of 36dc199 (and the worst
// cases within the limits that fixed them), each run through the structloc
// CLI as a user would, must end with a clear refusal (exit 2) or a result
// (exit 0) within those bounds, the child's CPU time and peak memory read
// from the kernel's accounting of it. A reader that crashes, hangs (a 60 s
// timeout) or runs over fails.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <zlib.h>

#include <cstdio>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "room_recording.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using testing::TempDir;

constexpr double kMaxCpuSeconds = 2.0;
constexpr long kMaxResidentKb = 500L * 1024;
constexpr uintmax_t kMaxInputBytes = 1 << 20;

struct Usage {
  double cpu_s = 0.0;
  long max_resident_kb = 0;
};

Usage ChildrenUsage() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  const auto seconds = [](const timeval& t) { return t.tv_sec + 1e-6 * t.tv_usec; };
  return {seconds(usage.ru_utime) + seconds(usage.ru_stime), usage.ru_maxrss};
}

// One bomb: the files it is made of (each under 1 MB) and the command that reads it.
struct Bomb {
  std::vector<std::string> files;
  std::vector<std::string> args;
  int exit_code = 2;
  std::string says;  // in the output
};

void Explode(const Bomb& bomb) {
  for (const auto& file : bomb.files) {
    ASSERT_LT(std::filesystem::file_size(file), kMaxInputBytes) << file;
  }
  const Usage before = ChildrenUsage();
  const auto run = testing::RunCli(bomb.args, std::chrono::seconds(60));
  const Usage after = ChildrenUsage();
  const double cpu_s = after.cpu_s - before.cpu_s;
  std::printf("%.2f s CPU, %ld MB at most (exit %d)\n", cpu_s, after.max_resident_kb / 1024,
              run.exit_code);
  EXPECT_EQ(run.exit_code, bomb.exit_code) << run.output;
  EXPECT_NE(run.output.find(bomb.says), std::string::npos) << run.output;
  EXPECT_LE(cpu_s, kMaxCpuSeconds) << run.output;
  // The largest child so far: each test runs in a process of its own under ctest.
  EXPECT_LE(after.max_resident_kb, kMaxResidentKb) << run.output;
}

std::string Launch(const std::string& body) {
  return "<launch>" + body + "</launch>";
}

void WritePng(const std::string& path, const cv::Mat& image) {
  ASSERT_TRUE(cv::imwrite(path, image, {cv::IMWRITE_PNG_COMPRESSION, 9})) << path;
}

std::string GridYaml(const TempDir& dir, const std::string& name, const cv::Mat& image) {
  WritePng(dir / (name + ".png"), image);
  return dir.Write(name + ".yaml", "image: " + name +
                                       ".png\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n"
                                       "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
}

// A 64 x 64 tile of random black and white cells, repeated over `size`
// (compresses to little: the review's noise PNGs).
cv::Mat Noise(int rows, int cols) {
  std::mt19937 random(1);
  cv::Mat tile(64, 64, CV_8UC1);
  for (int r = 0; r < 64; ++r)
    for (int c = 0; c < 64; ++c) tile.at<uint8_t>(r, c) = random() % 2 ? 0 : 254;
  cv::Mat out;
  cv::repeat(tile, rows / 64 + 1, cols / 64 + 1, out);
  return out(cv::Rect(0, 0, cols, rows)).clone();
}

// Free space crossed by a wall every `spacing` cells.
cv::Mat Building(int size, int spacing = 200) {
  cv::Mat image(size, size, CV_8UC1, cv::Scalar(254));
  for (int k = 0; k < size; k += spacing) {
    image.row(k).setTo(0);
    image.col(k).setTo(0);
  }
  return image;
}

// A drawing `text` given to `structloc map import --dxf`: refused, saying `says`.
void ExplodeDxf(const std::string& text, const std::string& says) {
  const TempDir dir;
  const std::string path = dir.Write("bomb.dxf", text);
  Explode({{path},
           {"map", "import", "--dxf", path, "--layers", "WALLS", "--out", dir / "o.xml"},
           2,
           says});
}

// A grid `image` (a PNG and its YAML) given to `structloc map import --grid`:
// it ends with `exit_code`, saying `says`.
void ImportGrid(const cv::Mat& image, int exit_code, const std::string& says) {
  const TempDir dir;
  const std::string yaml = GridYaml(dir, "grid", image);
  Explode({{yaml, dir / "grid.png"},
           {"map", "import", "--grid", yaml, "--out", dir / "o.xml"},
           exit_code,
           says});
}

TEST(ReaderBombs, LaunchFileWithAnAttributeOf60000Characters) {
  const TempDir dir;
  const std::string path =
      dir.Write("regex.launch.xml", Launch("<let name='x' value='$(" + std::string(60000, 'a') +
                                           "'/><executable cmd='true' name='t'/>"));
  Explode({{path}, {"launch", path}, 2, "malformed substitution"});
}

TEST(ReaderBombs, LaunchParameterFileWithAnEntryRepeatedThroughAliases) {
  const TempDir dir;
  std::string yaml = "base: &p {ros__parameters: {";
  for (int k = 0; k < 2000; ++k) yaml += (k ? ", k" : "k") + std::to_string(k) + ": 1";
  yaml += "}}\n";
  for (int n = 0; n < 2000; ++n) yaml += "localisation: *p\n";
  const std::string params = dir.Write("alias.yaml", yaml);
  const std::string path =
      dir.Write("alias.launch.xml",
                Launch("<node pkg='structloc' exec='structloc_localisation' name='localisation'>"
                       "<param from='" +
                       params + "'/></node>"));
  Explode({{path, params}, {"launch", path}, 2, "appears a second time"});
}

TEST(ReaderBombs, LaunchFilesThatIncludeEachOtherFortyTimesSixDeep) {
  const TempDir dir;
  const std::string names = "bcdefg";
  std::vector<std::string> files;
  for (size_t i = 0; i < names.size(); ++i) {
    std::string body;
    for (int k = 0; k < 40 && i + 1 < names.size(); ++k)
      body += "<include file='" + dir / std::string(1, names[i + 1]) + "'/>";
    files.push_back(dir.Write(std::string(1, names[i]), Launch(body)));
  }
  std::string top;
  for (int k = 0; k < 40; ++k) top += "<include file='" + dir / "b" + "'/>";
  files.push_back(dir.Write("fan.launch.xml", Launch(top + "<executable cmd='true' name='t'/>")));
  Explode({files, {"launch", files.back()}, 2, "--max-files"});
}

TEST(ReaderBombs, LaunchedNodeThatNeverStopsWriting) {
  const TempDir dir;
  const std::string path =
      dir.Write("yes.launch.xml", Launch("<executable cmd='yes' name='chatty' output='log'/>"));
  // The launcher relays it for the second asked, then stops it: exit 0.
  Explode({{path}, {"launch", path, "--duration", "1"}, 0, "chatty"});
}

TEST(ReaderBombs, LogLineWhoseBeamAnglesOverflow) {
  const TempDir dir;
  // Five beams of 1 m, each field finite; the second line's resolution puts
  // its later beams' angles at infinity (they wrote outside the grid).
  const std::string log =
      dir.Write("nan_angles.clf", testing::FiveBeamLaserLine("0.785398", "1.0") +
                                      testing::FiveBeamLaserLine("1e308", "2.0"));
  Explode({{log},
           {"map", "grid", "--log", log, "--out", dir / "g.yaml"},
           0,
           "do not lie within one turn"});
}

// 200 MB of one scan line repeated, gzipped to a few hundred kB: the map
// tools hold every scan (readings, points) in memory, 700 MB for this one.
TEST(ReaderBombs, GzippedLogThatInflatesAThousandfold) {
  const TempDir dir;
  std::string line = "ROBOTLASER1 0 -1.5707963 3.14159 0.0087266 20 0.01 0 361";
  for (int k = 0; k < 361; ++k) line += " 2.000";
  line += " 0 0 0 0 0 0 0 0 0 0 0 0 1.0 host 1.0\n";
  std::string block;
  while (block.size() < (1u << 20)) block += line;
  const std::string path = dir / "bomb.log.gz";
  gzFile file = gzopen(path.c_str(), "wb9");
  ASSERT_NE(file, nullptr);
  for (int k = 0; k < 200; ++k) {
    ASSERT_EQ(gzwrite(file, block.data(), static_cast<unsigned>(block.size())),
              static_cast<int>(block.size()));
  }
  ASSERT_EQ(gzclose(file), Z_OK);
  Explode({{path}, {"map", "build", "--log", path, "--out", dir / "w.xml"}, 2, "a gzip bomb?"});
}

TEST(ReaderBombs, DxfWhoseLongLineShiftsTheVertexCountPastTheGuard) {
  ExplodeDxf("999\n" + std::string(1023, 'x') +
                 "999\nshifted\n0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n8\nWALLS\n90\n"
                 "20000000\n70\n0\n10\n0\n20\n0\n0\nENDSEC\n0\nEOF\n",
             "DXF readers take at most");
}

// dxflib reads a group code that is no number, even an empty line, as 0:
// the LWPOLYLINE after it starts an entity (found by the fuzzer: 12.8 GB
// asked for 400 million vertices).
TEST(ReaderBombs, DxfWhosePolylineFollowsAnEmptyGroupCode) {
  ExplodeDxf("0\nSECTION\n2\nENTITIES\n\nLWPOLYLINE\n8\nWALLS\n90\n400000101\n\n\377",
             "announces 400000101 items");
}

// dxflib reads a line up to its first NUL: "LWPOLYLINE" and then bytes it never sees.
TEST(ReaderBombs, DxfWhosePolylineNameHidesANul) {
  ExplodeDxf("0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE" + std::string(1, '\0') +
                 "hidden\n8\nWALLS\n90\n400000101\n0\nENDSEC\n0\nEOF\n",
             "announces 400000101 items");
}

// dxflib starts an object at a group 9 as at a group 0 (found by the fuzzer:
// the count passed the guard, dxflib's allocation for it overflowed, threw,
// and its vertex buffer was freed twice).
TEST(ReaderBombs, DxfWhosePolylineIsStartedByAVariableGroup) {
  ExplodeDxf(
      "0\nSECTION\n2\nENTITIES\n9\nLWPOLYLINE\n8\nWALLS\n90\n2\n10\n0\n20\n0\n90\n"
      "400000101007\n0\nENDSEC\n0\nEOF\n",
      "announces 400000101007 items");
}

// dxflib cuts a group code to an int: 4294967296 is a group 0.
TEST(ReaderBombs, DxfWhosePolylineIsStartedByAGroupCodeThatWrapsToZero) {
  ExplodeDxf(
      "0\nSECTION\n2\nENTITIES\n4294967296\nLWPOLYLINE\n8\nWALLS\n90\n2\n10\n0\n20\n0\n90\n"
      "400000101007\n0\nENDSEC\n0\nEOF\n",
      "announces 400000101007 items");
}

// A last group code with no value line: dxflib pairs it with the value
// before it, here a count no check saw (a double free inside dxflib). dxflib
// reads a copy of what was checked, which ends with the last whole pair.
TEST(ReaderBombs, DxfWhoseLastGroupCodeHasNoValue) {
  ExplodeDxf(
      "0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n8\nWALLS\n90\n2\n10\n0\n20\n0\n8\n"
      "400000101007\n90\n",
      "cut short");
}

TEST(ReaderBombs, DxfOfAThousandPolylinesAnnouncingAMillionVerticesEach) {
  std::string text = "0\nSECTION\n2\nENTITIES\n";
  for (int k = 0; k < 1000; ++k) {
    text += "0\nLWPOLYLINE\n8\nWALLS\n90\n1000000\n70\n0\n10\n0\n20\n0\n10\n1\n20\n0\n";
  }
  ExplodeDxf(text + "0\nENDSEC\n0\nEOF\n", "vertices, knots or points in all");
}

TEST(ReaderBombs, GridImageInAFormatWhoseSizeIsOnlyKnownByDecodingIt) {
  const TempDir dir;
  ASSERT_TRUE(cv::imwrite(dir / "map.tiff", Building(64)));
  const std::string yaml =
      dir.Write("tiff.yaml", "image: map.tiff\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n");
  Explode({{yaml, dir / "map.tiff"},
           {"map", "import", "--grid", yaml, "--out", dir / "o.xml"},
           2,
           "neither a PNG nor a PGM"});
}

// A PNG says its size in its header: 40000 x 40000 cells (a uniform image
// that large compresses to about 1.6 MB; its header is all that is read).
TEST(ReaderBombs, GridPngOfAGigaCell) {
  const TempDir dir;
  const std::string yaml = GridYaml(dir, "giga", Building(64));
  std::string png = testing::ReadFile(dir / "giga.png");
  for (const size_t at : {16u, 20u}) {  // IHDR's width and height, big-endian
    const uint32_t side = 40000;
    for (int k = 0; k < 4; ++k)
      png[at + static_cast<size_t>(k)] = static_cast<char>(side >> (24 - 8 * k));
  }
  dir.Write("giga.png", png);
  Explode({{yaml, dir / "giga.png"},
           {"map", "import", "--grid", yaml, "--out", dir / "o.xml"},
           2,
           "is too large: 40000 x 40000 cells"});
}

// Refused by the face-cell limit before Hough's proposals.
TEST(ReaderBombs, GridOfNoise800) {
  ImportGrid(Noise(800, 800), 2, "max_face_cells");
}

// About the largest square of noise the face-cell limit lets through
// (97 447 face cells): refused by the refits' bound.
TEST(ReaderBombs, GridOfNoise460) {
  ImportGrid(Noise(460, 460), 2, "max_refit_work");
}

TEST(ReaderBombs, GridOfNoise2000) {
  ImportGrid(Noise(2000, 2000), 2, "max_face_cells");
}

// The slowest grid the limits let through to the wall refits: the largest
// grid, walls across it every 1000 cells, and a patch of noise just small
// enough to pass the face-cell limit (97 843 of 100 000), refused by the refits' bound.
TEST(ReaderBombs, LargestGridWithAPatchOfNoise) {
  cv::Mat image = Building(4000, 1000);
  Noise(380, 380).copyTo(image(cv::Rect(0, 0, 380, 380)));
  ImportGrid(image, 2, "max_refit_work");
}

// The largest grid, with walls across it every 400 cells (20 m; 79 800 face
// cells of the 100 000 allowed), imports in full.
TEST(ReaderBombs, LargestCleanGridImports) {
  ImportGrid(Building(4000, 400), 0, "wrote");
}

}  // namespace
}  // namespace structloc
