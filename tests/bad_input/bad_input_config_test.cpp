// Regression tests for the bad-input review of 12de806 (config defects): each
// test is named after the defect it keeps fixed (H = high, M = medium, L = low).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/types.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>

#include "cli_runner.hpp"
#include "shipped_copy.hpp"
#include "structloc/config/strict_xml.hpp"
#include "structloc/localisation_core/localiser/localiser_options.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/process/launch_file.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "structloc/world_model/visibility.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "temp_dir.hpp"
#include "test_domains.hpp"
#include "test_paths.hpp"
#include "wait_until.hpp"
#include "whole_params.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
using testing::SourcePath;
using testing::TempDir;

// A shipped file with `from` replaced by `to` (which must occur), written into
// `dir`; relative references of scenarios are made absolute.
std::string Mutated(const TempDir& dir, const std::string& relative, const std::string& from,
                    const std::string& to) {
  std::string text = testing::ShippedTextForCopy(relative);
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from << " not in " << relative;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  std::string name = relative;
  for (auto& c : name) c = c == '/' ? '_' : c;
  return dir.Write(name, text);
}

// The office's parameter file whole (every key, as `structloc params --expand`
// prints it: the shipped file states only what differs from the defaults),
// with `from` replaced by `to` (which must occur), written into `dir`.
std::string MutatedParams(const TempDir& dir, const std::string& from, const std::string& to) {
  return testing::EditedWholeParams(dir, SourcePath("maps/params/office_sick.xml"), from, to,
                                    "office_sick_whole.xml");
}

// Expects `read(path)` to throw a ConfigError whose message starts with
// "PATH:LINE:" and contains every one of `problems`.
void ExpectRejected(const std::string& path, const std::function<void(const std::string&)>& read,
                    const std::vector<std::string>& problems) {
  try {
    read(path);
    ADD_FAILURE() << "accepted: " << path;
  } catch (const config::ConfigError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path + ":", 0), 0u) << what;
    const char after = what.size() > path.size() + 1 ? what[path.size() + 1] : ' ';
    EXPECT_TRUE(after >= '1' && after <= '9') << "no line number: " << what;
    for (const auto& problem : problems) EXPECT_NE(what.find(problem), std::string::npos) << what;
  }
}

void LoadWorld(const std::string& path) {
  world_model::LoadWorldModel(path);
}
void LoadScenario(const std::string& path) {
  simulation_core::LoadScenario(path);
}
void LoadParams(const std::string& path) {
  localisation_core::LoadLocaliserOptions(path);
}
void LoadLaunch(const std::string& path) {
  process::ReadLaunchFile(path, {SourcePath(""), STRUCTLOC_BIN_DIR, {}});
}

size_t Count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t pos = 0; (pos = text.find(what, pos)) != std::string::npos; pos += what.size()) ++n;
  return n;
}

// A lattice of unit walls: `side` x `side` cells, 2 * side * (side + 1) walls,
// a corner wherever two of them meet at right angles.
std::string GridWorld(int side) {
  std::ostringstream xml;
  xml << "<world name=\"grid\">\n";
  for (int i = 0; i <= side; ++i) {
    for (int j = 0; j < side; ++j) {
      xml << "<wall x1=\"" << j << "\" y1=\"" << i << "\" x2=\"" << j + 1 << "\" y2=\"" << i
          << "\"/>\n";
      xml << "<wall x1=\"" << i << "\" y1=\"" << j << "\" x2=\"" << i << "\" y2=\"" << j + 1
          << "\"/>\n";
    }
  }
  xml << "</world>\n";
  return xml.str();
}

TEST(BadInputConfig, M4_WorldOf100000WallsLoadsWithoutBlowingUp) {
  TempDir dir;
  const std::string path = dir.Write("grid.xml", GridWorld(224));  // 100 800 walls
  const auto start = std::chrono::steady_clock::now();
  const auto world = world_model::LoadWorldModel(path);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(world.Walls().size(), 100800u);
  EXPECT_EQ(world.Corners().size(), 225u * 225u);  // every lattice point, each once
  // The time is printed; the bound only catches a blow-up (the quadratic
  // corner search took minutes), never a merely slow machine.
  std::printf("100 800 walls loaded in %.2f s\n", seconds);
  EXPECT_LT(seconds, testing::kGenerousTimeout.count());
}

TEST(BadInputConfig, M4_CornersFromTheIndexMatchTryingEveryPair) {
  // Walls meeting at right angles, at shallow angles, near misses and crossings.
  std::vector<world_model::Wall> walls;
  int id = 0;
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector2d base(0.37 * k, 0.11 * (k % 7));
    walls.push_back(world_model::MakeWall(id++, base, base + Eigen::Vector2d(1.0, 0.0)));
    walls.push_back(world_model::MakeWall(id++, base + Eigen::Vector2d(0.004 * (k % 4), 0.0),
                                          base + Eigen::Vector2d(0.0, 1.0 + 0.1 * (k % 3))));
    walls.push_back(world_model::MakeWall(id++, base + Eigen::Vector2d(1.0, 0.0),
                                          base + Eigen::Vector2d(1.5, 0.3 * (k % 5))));
  }
  const world_model::WorldModel world("pairs", walls, {{100, {0.0, 0.0}, false}}, {});
  // Reference: the original rule, every pair of walls in order (i, j > i).
  std::vector<world_model::Corner> expected = {{100, {0.0, 0.0}, false}};
  int next_id = 101;
  const double tolerance = world_model::CornerDerivation{}.join_tolerance_m;
  const double min_sin = std::cos(world_model::CornerDerivation{}.angle_tolerance_rad);
  for (size_t i = 0; i < walls.size(); ++i) {
    for (size_t j = i + 1; j < walls.size(); ++j) {
      const Eigen::Vector2d di = (walls[i].b - walls[i].a).normalized();
      const Eigen::Vector2d dj = (walls[j].b - walls[j].a).normalized();
      if (std::abs(di.x() * dj.y() - di.y() * dj.x()) < min_sin) continue;
      for (const auto& pi : {walls[i].a, walls[i].b}) {
        for (const auto& pj : {walls[j].a, walls[j].b}) {
          if ((pi - pj).norm() > tolerance) continue;
          const Eigen::Vector2d p = 0.5 * (pi + pj);
          bool known = false;
          for (const auto& c : expected) known = known || (c.position - p).norm() <= tolerance;
          if (!known) expected.push_back({next_id++, p, true});
        }
      }
    }
  }
  ASSERT_EQ(world.Corners().size(), expected.size());
  EXPECT_GE(expected.size(), 25u);
  for (size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(world.Corners()[k].id, expected[k].id);
    EXPECT_EQ(world.Corners()[k].position, expected[k].position);
  }
}

TEST(BadInputConfig, M4_WallsPerMapLimitIsVisibleAndChangeable) {
  TempDir dir;
  const std::string path = dir.Write("grid.xml", GridWorld(3));  // 24 walls
  world_model::WorldLimits limits;
  EXPECT_EQ(limits.max_walls, world_model::WorldLimits::kDefaultMaxWalls);
  limits.max_walls = 23;
  ExpectRejected(path, [&](const std::string& p) { world_model::LoadWorldModel(p, limits); },
                 {"more than 23 walls", "walls-per-map limit"});
  limits.max_walls = 24;
  EXPECT_EQ(world_model::LoadWorldModel(path, limits).Walls().size(), 24u);

  const auto help = testing::RunCli({"simulate", "--help"});
  EXPECT_EQ(help.exit_code, 0) << help.output;
  EXPECT_NE(help.output.find("--max-walls"), std::string::npos) << help.output;
  const auto refused =
      testing::RunCli({"simulate", "--scenario", SourcePath("maps/scenarios/robustness_room.xml"),
                       "--out", dir / "out", "--max-walls", "1"});
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("walls-per-map limit"), std::string::npos) << refused.output;
}

TEST(BadInputConfig, M5_OverLongAttributeIsRefusedBeforeItIsMatched) {
  TempDir dir;
  // std::regex would recurse once per character of this.
  const std::string path =
      dir.Write("long.launch.xml",
                "<launch>\n<node pkg=\"structloc\" exec=\"structloc_localisation\">"
                "<param name=\"x\" value=\"$(" +
                    std::string(200000, 'a') + "\"/></node>\n</launch>\n");
  ExpectRejected(path, LoadLaunch, {path + ":2:", "longer than 65536 bytes"});
}

TEST(BadInputConfig, M5_LaunchSubstitutionIsBoundedPerValue) {
  TempDir dir;
  std::ostringstream xml;
  xml << "<launch>\n<arg name=\"a0\" default=\"lol\"/>\n";
  for (int i = 1; i <= 40; ++i) {
    xml << "<arg name=\"a" << i << "\" default=\"$(var a" << i - 1 << ")$(var a" << i - 1
        << ")\"/>\n";
  }
  xml << "<node pkg=\"structloc\" exec=\"structloc_localisation\">"
         "<param name=\"x\" value=\"$(var a40)\"/></node>\n</launch>\n";
  const std::string path = dir.Write("laughs.launch.xml", xml.str());
  const auto start = std::chrono::steady_clock::now();
  // 3 * 2^15 bytes is the first value above 64 KiB: <arg name="a15"> on line 17.
  ExpectRejected(path, LoadLaunch, {path + ":17:", "longer than 65536 bytes"});
  // A guard against an exponential blow-up, not a speed test.
  EXPECT_LT(std::chrono::steady_clock::now() - start, testing::kGenerousTimeout);

  process::LaunchContext wider{SourcePath(""), STRUCTLOC_BIN_DIR, {}};
  wider.max_value_bytes = 1 << 20;
  wider.max_total_bytes = 1 << 20;
  ExpectRejected(path, [&](const std::string& p) { process::ReadLaunchFile(p, wider); },
                 {"exceed 1048576 bytes in total"});

  const auto help = testing::RunCli({"launch", "--help"});
  EXPECT_EQ(help.exit_code, 0) << help.output;
  EXPECT_NE(help.output.find("--max-value-bytes N"), std::string::npos) << help.output;
  EXPECT_NE(help.output.find("65536"), std::string::npos) << help.output;
}

TEST(BadInputConfig, M9_CoordinatesAndRadiiBeyondTheBoundAreRejected) {
  TempDir dir;
  const auto wall = Mutated(dir, "maps/robustness_room.xml", "x2=\"3.0\"", "x2=\"1e8\"");
  ExpectRejected(wall, LoadWorld, {"not \"1e8\"", "x2 must be from -100000 to 100000"});
  const auto corner =
      dir.Write("corner.xml", "<world name=\"c\">\n<corner x=\"0\" y=\"-1e308\"/>\n</world>\n");
  ExpectRejected(corner, LoadWorld, {corner + ":2:", "must be from -100000 to 100000"});
  const auto cylinder =
      dir.Write("cylinder.xml",
                "<world name=\"c\">\n<cylinder x=\"0\" y=\"0\" radius=\"1e300\"/>\n</world>\n");
  ExpectRejected(cylinder, LoadWorld, {cylinder + ":2:", "radius", "above the limit"});

  const auto waypoint = Mutated(dir, "maps/scenarios/robustness_room.xml", "<waypoint x=\"1.6\"",
                                "<waypoint x=\"1e300\"");
  ExpectRejected(waypoint, LoadScenario, {"waypoint", "must be from -100000 to 100000"});
  const auto box =
      Mutated(dir, "maps/scenarios/robustness_room.xml", "width_m=\"1.4\"", "width_m=\"1e300\"");
  ExpectRejected(box, LoadScenario, {"width_m", "must be from 0 to 100000"});

  // A library user may widen the bound; the world then still loads (linearly).
  world_model::WorldLimits wide;
  wide.max_abs_coordinate_m = 1e9;
  EXPECT_NO_THROW(world_model::LoadWorldModel(wall, wide));
}

TEST(BadInputConfig, M9_VisibilityOfAVeryLongWallHasNoIntegerOverflow) {
  // 2e8 m long: 4e9 samples at 0.05 m, beyond int (the old count overflowed
  // and the wall vanished); only the part within range is sampled now.
  world_model::WorldLimits wide;
  wide.max_abs_coordinate_m = 1e9;
  const world_model::WorldModel world(
      "long",
      {world_model::MakeWall(1, {-1e8, 0.0}, {1e8, 0.0}), world_model::MakeWall(2, {0, 0}, {0, 3})},
      {}, {}, {}, wide);
  const auto scene = world_model::Scene::FromWorld(world);
  world_model::Visibility seen;
  const auto start = std::chrono::steady_clock::now();
  world_model::ComputeVisibility(world, scene, {1.0, 1.5, 0.0}, world_model::VisibilityOptions{},
                                 seen);
  // A guard against sampling the whole wall (4e9 samples), not a speed test.
  EXPECT_LT(std::chrono::steady_clock::now() - start, testing::kGenerousTimeout);
  ASSERT_EQ(seen.walls.size(), 2u);
  EXPECT_EQ(seen.walls[0].index, 0);
  EXPECT_GT(seen.walls[0].visible_length_m, 2.0);
  EXPECT_LT(seen.walls[0].visible_length_m, 8.0);
}

TEST(BadInputConfig, L1_IntegersOutOfTheirTypesRangeAreRefusedNotTruncated) {
  TempDir dir;
  ExpectRejected(MutatedParams(dir, "window_points=\"7\"", "window_points=\"4294967303\""),
                 LoadParams, {"not \"4294967303\"", "window_points must be an integer from"});
  ExpectRejected(MutatedParams(dir, "seed=\"1\"", "seed=\"-1\""), LoadParams,
                 {"not \"-1\"", "seed must be an integer from 0 to 4294967295"});
  ExpectRejected(
      Mutated(dir, "maps/scenarios/robustness_room.xml", "beams=\"300\"", "beams=\"4294967596\""),
      LoadScenario, {"not \"4294967596\"", "beams must be an integer from 10 to 100000"});
  ExpectRejected(Mutated(dir, "maps/robustness_room.xml", "id=\"2\"", "id=\"4294967296\""),
                 LoadWorld, {"not \"4294967296\"", "id must be an integer from"});
  ExpectRejected(Mutated(dir, "maps/robustness_room.xml", "id=\"2\"", "id=\"2.0\""), LoadWorld,
                 {"id=\"2.0\"", "not an integer"});
}

TEST(BadInputConfig, L1b_ParamsCommandListsEveryKeyAndChecksAFile) {
  const auto listing = testing::RunCli({"params"});
  EXPECT_EQ(listing.exit_code, 0) << listing.output;
  for (const char* text :
       {"<corners>", "redundant_min_sin", "quality_chi2_per_dof", "max_beams", "in [1, 60]"}) {
    EXPECT_NE(listing.output.find(text), std::string::npos) << text << "\n" << listing.output;
  }
  TempDir dir;
  const auto good =
      testing::RunCli({"params", "--check", SourcePath("maps/params/office_sick.xml")});
  EXPECT_EQ(good.exit_code, 0) << good.output;
  const auto bad_path = MutatedParams(dir, "redundant_min_sin=\"0.5\"", "redundant_min_sin=\"2\"");
  const auto bad = testing::RunCli({"params", "--check", bad_path});
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find(bad_path + ":"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("corners: redundant_min_sin must be in [0, 1], not 2"),
            std::string::npos)
      << bad.output;
}

TEST(BadInputConfig, L2_AbsurdIterationCountsRatesAndDurationsAreRefused) {
  TempDir dir;
  ExpectRejected(
      MutatedParams(dir, "bisection_iterations=\"10\"", "bisection_iterations=\"2000000000\""),
      LoadParams, {"bisection_iterations", "from 1 to 60"});
  ExpectRejected(MutatedParams(dir, "iterations=\"2000\"", "iterations=\"2000000000\""), LoadParams,
                 {"<kohonen>", "from 1 to 100000"});
  const std::string room = "maps/scenarios/robustness_room.xml";
  ExpectRejected(Mutated(dir, room, "rate_hz=\"5\"", "rate_hz=\"1e9\""), LoadScenario,
                 {"laser: rate_hz must be in [0.1, 100]"});
  ExpectRejected(Mutated(dir, room, "step_s=\"0.01\"", "step_s=\"1e-9\""), LoadScenario,
                 {"scenario: step_s must be in [0.0001, 0.1]"});
  ExpectRejected(Mutated(dir, room, "duration_s=\"10\"", "duration_s=\"1e9\""), LoadScenario,
                 {"scenario: duration_s must be in (0, 3600]"});
  ExpectRejected(Mutated(dir, room, "traction_start_tick=\"0\"",
                         "traction_start_tick=\"9223372036854775807\""),
                 LoadScenario, {"traction_start_tick", "from 0 to 4294967295"});
  localisation_core::LocaliserOptions options;
  options.solver.bisection_iterations = 2000000000;
  EXPECT_THROW(options.Validate(), std::invalid_argument);
}

TEST(BadInputConfig, L3_DuplicatesSecondRootsWrappedSectorsAndHexAreErrors) {
  TempDir dir;
  const auto args = dir.Write("args.launch.xml",
                              "<launch>\n<arg name=\"a\" default=\"1\"/>\n"
                              "<arg name=\"a\" default=\"2\"/>\n"
                              "<node pkg=\"structloc\" exec=\"structloc_localisation\"/>\n"
                              "</launch>\n");
  ExpectRejected(args, LoadLaunch, {args + ":3:", "a second <arg name=\"a\">"});
  const std::string mount = "<sensor_mount x_m=\"0.2\" y_m=\"0\" theta_rad=\"0\"/>";
  ExpectRejected(MutatedParams(dir, mount,
                               mount + "\n  <sensor_mount x_m=\"0\" y_m=\"0.2\" theta_rad=\"0\"/>"),
                 LoadParams, {"a second <sensor_mount>"});
  ExpectRejected(
      Mutated(dir, "maps/robustness_room.xml", "</world>", "</world>\n<world name=\"other\"/>"),
      LoadWorld, {"a second root element"});
  ExpectRejected(
      Mutated(dir, "maps/scenarios/robustness_room.xml", "mixed_pixel_probability=\"0\"/>",
              "mixed_pixel_probability=\"0\">\n<blocked from_rad=\"3\" to_rad=\"-3\"/>"
              "\n</laser>"),
      LoadScenario, {"from_rad > to_rad", "two <blocked> elements"});
  ExpectRejected(Mutated(dir, "maps/robustness_room.xml", "x2=\"3.0\"", "x2=\"0x10\""), LoadWorld,
                 {"x2=\"0x10\"", "not a finite number"});
  ExpectRejected(Mutated(dir, "maps/robustness_room.xml", "x2=\"3.0\"", "x2=\" 3\""), LoadWorld,
                 {"not a finite number"});
}

TEST(BadInputConfig, L4_MissingExecutablesDurationsAndFoldersGetClearMessages) {
  TempDir dir;
  const auto missing = dir.Write("missing.launch.xml",
                                 "<launch>\n<node pkg=\"structloc\" exec=\"does_not_exist\"/>\n"
                                 "</launch>\n");
  ExpectRejected(missing, LoadLaunch, {missing + ":2:", "No such file or directory"});
  const auto dots =
      dir.Write("dots.launch.xml", "<launch>\n<node pkg=\"structloc\" exec=\"..\"/>\n</launch>\n");
  ExpectRejected(dots, LoadLaunch, {dots + ":2:", "plain executable name"});
  try {
    process::ChildProcess child(dir / "no_such_program", {});
    ADD_FAILURE() << "started a missing program";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("No such file or directory"), std::string::npos)
        << e.what();
  }

  const auto duration = testing::RunCli(
      {"launch", SourcePath("launch_xml/structloc.launch.xml"), "--duration", "abc"});
  EXPECT_EQ(duration.exit_code, 2) << duration.output;
  EXPECT_NE(duration.output.find("--duration 'abc'"), std::string::npos) << duration.output;

  std::filesystem::create_directory(dir / "folder.xml");
  try {
    world_model::LoadWorldModel(dir / "folder.xml");
    ADD_FAILURE() << "a folder loaded as a world";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("is a folder"), std::string::npos) << e.what();
  }
}

TEST(BadInputConfig, L5_SubcommandHelpPrintsUsageOnceAndExitsZero) {
  for (const char* subcommand :
       {"replay", "simulate", "calibrate", "render", "demo", "watch", "record", "slam"}) {
    const auto help = testing::RunCli({subcommand, "--help"});
    EXPECT_EQ(help.exit_code, 0) << subcommand << ": " << help.output;
    EXPECT_EQ(Count(help.output, "options:"), 1u) << subcommand << ": " << help.output;
    EXPECT_EQ(Count(help.output, std::string("usage: structloc ") + subcommand), 1u) << help.output;
    EXPECT_EQ(help.output.find("unknown option"), std::string::npos) << help.output;
  }
  const auto launch = testing::RunCli({"launch", "--help"});
  EXPECT_EQ(launch.exit_code, 0) << launch.output;
  EXPECT_EQ(launch.output.find("cannot open"), std::string::npos) << launch.output;
}

TEST(BadInputConfig, L5_MalformedDurationsAndInitialPosesAreRefused) {
  for (const char* duration : {"nan", "1e9x", "-1", "inf"}) {
    const auto run = testing::RunCli(
        {"launch", SourcePath("launch_xml/structloc.launch.xml"), "--duration", duration}, 20s);
    EXPECT_EQ(run.exit_code, 2) << duration << ": " << run.output;
    EXPECT_EQ(run.output.find("starting"), std::string::npos) << run.output;
  }
  for (const char* pose : {"1.5 1.5 0.3 99", "1.5 1.5 0.3junk", "1.5 1.5", "0x1 1 1"}) {
    const auto replay = testing::RunCli({"replay", "--map", SourcePath("maps/robustness_room.xml"),
                                         "--log", SourcePath("maps/robustness_room.xml"),
                                         "--initial-pose", pose, "--out", "/dev/null"});
    EXPECT_EQ(replay.exit_code, 2) << pose << ": " << replay.output;
    EXPECT_NE(replay.output.find("--initial-pose must be exactly three numbers"), std::string::npos)
        << replay.output;
    const auto component = testing::RunExecutable(
        "structloc_localisation",
        {"--domain", std::to_string(testing::domains::kBadInputConfig), "--initial-pose", pose},
        30s);
    EXPECT_EQ(component.exit_code, 2) << pose << ": " << component.output;
    EXPECT_NE(component.output.find("--initial-pose must be exactly three numbers"),
              std::string::npos)
        << component.output;
  }
}

// Bad-input review of 36dc199, M6 (issue 42): what a component writes over
// and over (the saved pose, the calibration's files) is refused at start-up
// when it names a file the component reads.
TEST(BadInputConfig, M6_TheComponentsNeverWriteTheirStateOverAFileTheyRead) {
  TempDir dir;
  const std::string map =
      dir.Write("map.xml", testing::ReadFile(SourcePath("maps/office_floor.xml")));
  const auto localisation =
      testing::RunExecutable("structloc_localisation",
                             {"--domain", std::to_string(testing::domains::kBadInputConfig),
                              "--map", map, "--state-file", map, "--initial-pose", "2 6.5 0"},
                             30s);
  EXPECT_EQ(localisation.exit_code, 2) << localisation.output;
  EXPECT_NE(localisation.output.find("refusing to write the output over the input"),
            std::string::npos)
      << localisation.output;
  EXPECT_EQ(testing::ReadFile(map), testing::ReadFile(SourcePath("maps/office_floor.xml")));

  const std::string robot =
      dir.Write("calibrated.xml", testing::ReadFile(SourcePath("maps/robots/tricycle.xml")));
  const auto calibration =
      testing::RunExecutable("structloc_calibration",
                             {"--domain", std::to_string(testing::domains::kBadInputConfig),
                              "--robot", robot, "--out-dir", dir.Path()},
                             30s);
  EXPECT_EQ(calibration.exit_code, 2) << calibration.output;
  EXPECT_NE(calibration.output.find("refusing to write the output over the input"),
            std::string::npos)
      << calibration.output;
  EXPECT_EQ(testing::ReadFile(robot), testing::ReadFile(SourcePath("maps/robots/tricycle.xml")));
}

TEST(BadInputConfig, L5_DemoValidatesItsOptionsBeforeStartingAnything) {
  const auto demo = testing::RunCli(
      {"demo", "--time-scale", "-1", "--domain", std::to_string(testing::domains::kBadInputConfig)},
      30s);
  EXPECT_EQ(demo.exit_code, 2) << demo.output;
  EXPECT_NE(demo.output.find("--time-scale"), std::string::npos) << demo.output;
  EXPECT_EQ(demo.output.find("components failed"), std::string::npos) << demo.output;
  EXPECT_EQ(demo.output.find("simulated driving"), std::string::npos) << demo.output;
}

TEST(BadInputConfig, L6_CheckQosAppliesTheComponentsRules) {
  TempDir dir;
  const std::string shipped = "qos/structloc_qos.xml";
  const std::string text = testing::ReadFile(SourcePath(shipped));
  const auto reader_from = text.find("<data_reader profile_name=\"sensor_data\">");
  ASSERT_NE(reader_from, std::string::npos);
  const auto reader_to =
      text.find("</data_reader>", reader_from) + std::string("</data_reader>").size();
  const auto no_reader =
      dir.Write("no_reader.xml", text.substr(0, reader_from) + text.substr(reader_to));
  const auto check = testing::RunExecutable("structloc_check_qos", {no_reader});
  EXPECT_EQ(check.exit_code, 2) << check.output;
  EXPECT_NE(check.output.find("no <data_reader profile_name=\"sensor_data\">"), std::string::npos)
      << check.output;

  TempDir lease_dir;
  const auto lease = Mutated(lease_dir, shipped, "<sec>3</sec>", "<sec>0</sec>");
  const auto zero = testing::RunExecutable("structloc_check_qos", {lease});
  EXPECT_EQ(zero.exit_code, 2) << zero.output;
  EXPECT_NE(zero.output.find("leaseDuration must be longer than 0"), std::string::npos)
      << zero.output;
  EXPECT_NE(zero.output.find(lease + ":"), std::string::npos) << zero.output;

  const auto second = testing::RunExecutable("structloc_check_qos", {SourcePath(shipped), lease});
  EXPECT_EQ(second.exit_code, 2) << second.output;
  const auto both_good =
      testing::RunExecutable("structloc_check_qos", {SourcePath(shipped), SourcePath(shipped)});
  EXPECT_EQ(both_good.exit_code, 0) << both_good.output;

  const auto component = testing::RunExecutable(
      "structloc_localisation",
      {"--domain", std::to_string(testing::domains::kBadInputConfig), "--qos", lease}, 30s);
  EXPECT_EQ(component.exit_code, 2) << component.output;
  const auto domain = testing::RunExecutable("structloc_localisation", {"--domain", "300"}, 30s);
  EXPECT_EQ(domain.exit_code, 2) << domain.output;
  EXPECT_NE(domain.output.find("--domain 300 must be from 0 to 232"), std::string::npos)
      << domain.output;
}

// True while `pid` exists and is not a zombie.
bool Running(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return false;
  const auto paren = line.rfind(')');
  return paren != std::string::npos && paren + 2 < line.size() && line[paren + 2] != 'Z';
}

TEST(BadInputConfig, L7_KillingTheLauncherStopsItsNodes) {
  TempDir dir;
  const auto path =
      dir.Write("one.launch.xml",
                "<launch>\n<node pkg=\"structloc\" exec=\"structloc_localisation\" "
                "name=\"loc\">\n<param name=\"domain\" value=\"" +
                    std::to_string(testing::domains::kBadInputConfig) +
                    "\"/>\n<param name=\"params\" value=\"" + testing::SimulatedRobotParams() +
                    "\"/>\n</node>\n"
                    "</launch>\n");
  process::ChildProcess launcher(std::string(STRUCTLOC_BIN_DIR) + "/structloc",
                                 {"launch", path, "--duration", "60"});
  pid_t node = -1;
  const std::string marker = "[launch] loc has pid ";
  // The node's pid, and the node up and running (its output is the launcher's).
  ASSERT_TRUE(testing::WaitUntil([&] {
    const auto out = launcher.CapturedOutput();
    const auto at = out.find(marker);
    if (at == std::string::npos || out.find('\n', at) == std::string::npos) return false;
    node = static_cast<pid_t>(std::stol(out.substr(at + marker.size())));
    return out.find(": running (SIGINT or SIGTERM stops)", at) != std::string::npos;
  })) << launcher.CapturedOutput();
  ASSERT_TRUE(Running(node));
  launcher.Signal(SIGKILL);
  launcher.WaitExit(testing::kGenerousTimeout);
  testing::WaitUntil([&] { return !Running(node); });
  const bool still_running = Running(node);
  if (still_running) kill(node, SIGKILL);
  EXPECT_FALSE(still_running) << "node " << node << " outlived its launcher";
}

}  // namespace
}  // namespace structloc
