// The robot and scenario files read through their one declaration of keys
// (RobotParameterTable, scenario_options.hpp): every shipped file loads and
// every attribute lands in the member its key names, an out-of-range value
// names file:line, section and key, the calibration's writer writes every key,
// and `structloc params` lists and checks both kinds of file.
#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <sstream>

#include "cli_runner.hpp"
#include "structloc/config/strict_number.hpp"
#include "structloc/kinematics/robot_parameters.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "structloc/simulation_core/scenario_options.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using testing::SourcePath;
using testing::TempDir;

std::vector<std::string> ShippedFiles(const std::string& folder) {
  std::vector<std::string> paths;
  for (const auto& e : std::filesystem::directory_iterator(SourcePath(folder))) {
    if (e.path().extension() == ".xml") paths.push_back(e.path().string());
  }
  EXPECT_FALSE(paths.empty()) << folder;
  return paths;
}

// Expects `element`'s attributes to be exactly the table's keys, each with the
// value loaded into `loaded` (numbers to the 10 digits Values() writes).
template <class S>
void ExpectAttributesLoaded(const config::OptionTable<S>& table, const S& loaded,
                            const tinyxml2::XMLElement& element, const std::string& where) {
  size_t attributes = 0;
  for (const auto* a = element.FirstAttribute(); a != nullptr; a = a->Next()) ++attributes;
  size_t found = 0;
  for (const auto& [key, value] : table.Values(loaded)) {
    const char* text = element.Attribute(key.c_str());
    if (text == nullptr) continue;  // an optional key left out
    ++found;
    const auto in_file = config::ParseFiniteDouble(text);
    const auto as_loaded = config::ParseFiniteDouble(value);
    if (in_file && as_loaded) {
      EXPECT_NEAR(*as_loaded, *in_file, 1e-9 * std::max(1.0, std::abs(*in_file)))
          << where << " " << table.Section() << " " << key;
    } else {
      EXPECT_EQ(value, text) << where << " " << table.Section() << " " << key;
    }
  }
  EXPECT_EQ(found, attributes) << where << " <" << element.Name() << ">";
}

std::unique_ptr<tinyxml2::XMLDocument> Parse(const std::string& path) {
  auto doc = std::make_unique<tinyxml2::XMLDocument>();
  EXPECT_EQ(doc->LoadFile(path.c_str()), tinyxml2::XML_SUCCESS) << path;
  return doc;
}

TEST(RobotFile, EveryShippedFileLoadsEveryKeyIntoItsMember) {
  for (const auto& path : ShippedFiles("maps/robots")) {
    const auto p = kinematics::LoadRobotParameters(path);
    const auto doc = Parse(path);
    ExpectAttributesLoaded(kinematics::RobotParameterTable(p.kind), p, *doc->RootElement(), path);
  }
}

// The shipped tricycle with `key` set to `value` (or removed when empty).
std::string RobotWith(const TempDir& dir, const std::string& key, const std::string& value) {
  const auto doc = Parse(SourcePath("maps/robots/tricycle.xml"));
  if (value.empty()) {
    doc->RootElement()->DeleteAttribute(key.c_str());
  } else {
    doc->RootElement()->SetAttribute(key.c_str(), value.c_str());
  }
  tinyxml2::XMLPrinter printer;
  doc->Print(&printer);
  return dir.Write("robot.xml", printer.CStr());
}

std::string Problem(const std::function<void()>& load) {
  try {
    load();
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(RobotFile, AnImplausibleValueOfAnyKeyNamesFileLineSectionAndKey) {
  const TempDir dir;
  for (const auto& [key, value] :
       kinematics::RobotParameterTable().Values(kinematics::RobotParameters{})) {
    if (key == "kind") continue;  // a choice, not a number: see DriveKind tests
    const std::string bad = key == "traction_counter_bits" ? "4294967328" : "1e300";
    const std::string path = RobotWith(dir, key, bad);
    const auto what = Problem([&] { kinematics::LoadRobotParameters(path); });
    EXPECT_EQ(what.rfind(path + ":", 0), 0u) << what;
    EXPECT_NE(what.find("robot: " + key + " = " + (bad == "1e300" ? "1e+300" : bad) +
                        " is implausible; it must be "),
              std::string::npos)
        << what;
  }
  auto what = Problem(
      [&] { kinematics::LoadRobotParameters(RobotWith(dir, "steering_rad_per_tick", "0")); });
  EXPECT_NE(what.find("steering_rad_per_tick = 0 is implausible; it must be magnitude in [1e-09, "
                      "1] rad"),
            std::string::npos)
      << what;
  what = Problem([&] { kinematics::LoadRobotParameters(RobotWith(dir, "wheel_radius", "")); });
  EXPECT_NE(what.find("missing attribute wheel_radius"), std::string::npos) << what;
  what = Problem([&] { kinematics::LoadRobotParameters(RobotWith(dir, "wheel_radius_m", "1")); });
  EXPECT_NE(what.find("unknown attribute(s): wheel_radius_m"), std::string::npos) << what;
}

TEST(RobotFile, NegativeSteeringScaleAndOptionalSensorKeysAreAccepted) {
  const TempDir dir;
  const auto p =
      kinematics::LoadRobotParameters(RobotWith(dir, "steering_rad_per_tick", "-0.000767"));
  EXPECT_DOUBLE_EQ(p.steering_rad_per_tick, -0.000767);
  EXPECT_DOUBLE_EQ(p.sensor.x, 0.0);  // left out of the shipped file: the default
  EXPECT_DOUBLE_EQ(
      kinematics::LoadRobotParameters(RobotWith(dir, "sensor_theta", "0.5")).sensor.theta, 0.5);
}

TEST(RobotFile, ValidateNamesTheImplausibleKeyOfParametersBuiltInCode) {
  kinematics::RobotParameters p;
  EXPECT_NO_THROW(p.Validate());
  p.wheel_radius = 185;
  try {
    p.Validate();
    ADD_FAILURE() << "wheel_radius = 185 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "robot: wheel_radius = 185 is implausible; it must be in [0.001, 100] m");
  }
}

TEST(RobotFile, WrittenFileHoldsEveryKeyAndLoadsBackExactly) {
  kinematics::RobotParameters p;
  p.wheel_radius = 0.1869123456;
  p.steering_offset = -0.0087;
  p.traction_counter_bits = 24;
  p.sensor = {0.3, -0.1, 0.05};
  std::ostringstream out;
  kinematics::WriteRobotParameters(p, out, "calibrated -- test");
  const TempDir dir;
  const std::string path = dir.Write("written.xml", out.str());
  const auto back = kinematics::LoadRobotParameters(path);
  EXPECT_EQ(kinematics::RobotParameterTable().Values(back),
            kinematics::RobotParameterTable().Values(p));
  const auto doc = Parse(path);
  ExpectAttributesLoaded(kinematics::RobotParameterTable(), back, *doc->RootElement(), path);
  EXPECT_NE(doc->RootElement()->Attribute("sensor_theta"), nullptr);  // optional, still written
}

TEST(RobotFile, DifferentialDriveFileHasItsOwnKeysAndRoundTrips) {
  const auto p = kinematics::LoadRobotParameters(SourcePath("maps/robots/differential.xml"));
  EXPECT_EQ(p.kind, kinematics::DriveKind::kDifferential);
  EXPECT_DOUBLE_EQ(p.left_wheel_radius, 0.1);
  EXPECT_DOUBLE_EQ(p.wheel_separation, 0.5);
  EXPECT_EQ(p.traction_counter_bits, 32);
  std::ostringstream out;
  kinematics::WriteRobotParameters(p, out, "written");
  const TempDir dir;
  const std::string path = dir.Write("written.xml", out.str());
  const auto doc = Parse(path);
  EXPECT_STREQ(doc->RootElement()->Attribute("kind"), "differential");
  EXPECT_NE(doc->RootElement()->Attribute("ticks_per_rev"), nullptr);
  EXPECT_EQ(doc->RootElement()->Attribute("wheel_radius"), nullptr);  // a tricycle key
  const auto back = kinematics::LoadRobotParameters(path);
  EXPECT_EQ(kinematics::RobotParameterTable(back.kind).Values(back),
            kinematics::RobotParameterTable(p.kind).Values(p));
  // A tricycle key in a differential file, and an unknown kind, are errors naming them.
  const std::string mixed =
      dir.Write("mixed.xml",
                "<robot kind=\"differential\" left_wheel_radius=\"0.1\" right_wheel_radius=\"0.1\" "
                "wheel_separation=\"0.5\" ticks_per_rev=\"4096\" counter_bits=\"32\" "
                "axle_distance=\"0.6\"/>");
  EXPECT_NE(Problem([&] { kinematics::LoadRobotParameters(mixed); }).find("axle_distance"),
            std::string::npos);
  const std::string bicycle = RobotWith(dir, "kind", "bicycle");
  const auto what = Problem([&] { kinematics::LoadRobotParameters(bicycle); });
  EXPECT_NE(what.find("tricycle or differential"), std::string::npos) << what;
}

TEST(ScenarioFile, EveryShippedFileLoadsEveryAttributeIntoItsMember) {
  const simulation_core::ScenarioLimits limits;
  for (const auto& path : ShippedFiles("maps/scenarios")) {
    const auto s = simulation_core::LoadScenario(path);
    const auto doc = Parse(path);
    const auto& root = *doc->RootElement();
    ExpectAttributesLoaded(simulation_core::ScenarioAttributes(limits), s, root, path);
    ExpectAttributesLoaded(simulation_core::TrueRobotAttributes(s.nominal.traction_counter_bits),
                           s.errors, *root.FirstChildElement("true_robot"), path);
    ExpectAttributesLoaded(simulation_core::InitialPoseAttributes(limits.world), s.initial_pose,
                           *root.FirstChildElement("initial_pose"), path);
    ExpectAttributesLoaded(simulation_core::LaserAttributes(limits), s.laser,
                           *root.FirstChildElement("laser"), path);
    ExpectAttributesLoaded(simulation_core::PathAttributes(), s.path,
                           *root.FirstChildElement("path"), path);
    size_t person = 0;
    if (const auto* obstacles = root.FirstChildElement("obstacles")) {
      for (const auto* p = obstacles->FirstChildElement("person"); p != nullptr;
           p = p->NextSiblingElement("person")) {
        ASSERT_LT(person, s.people.size()) << path;
        ExpectAttributesLoaded(simulation_core::PersonAttributes(limits.world), s.people[person++],
                               *p, path);
      }
    }
    EXPECT_EQ(person, s.people.size()) << path;
  }
}

// The shipped office scenario with one attribute of the element at `where`
// ("laser", "obstacles/person") set to `value`; file references made absolute.
std::string ScenarioWith(const TempDir& dir, const std::string& where, const std::string& key,
                         const std::string& value) {
  const auto doc = Parse(SourcePath("maps/scenarios/office_people.xml"));
  auto* root = doc->RootElement();
  for (const char* name : {"world", "robot"}) {
    auto* e = root->FirstChildElement(name);
    e->SetAttribute("file", (SourcePath("maps/scenarios/") + e->Attribute("file")).c_str());
  }
  tinyxml2::XMLElement* e = root;
  std::stringstream path(where);
  for (std::string name; std::getline(path, name, '/');) {
    if (name != "scenario") e = e->FirstChildElement(name.c_str());
  }
  e->SetAttribute(key.c_str(), value.c_str());
  tinyxml2::XMLPrinter printer;
  doc->Print(&printer);
  return dir.Write("scenario.xml", printer.CStr());
}

TEST(ScenarioFile, AnOutOfRangeValueNamesFileLineSectionAndKey) {
  const TempDir dir;
  struct Case {
    const char* where;
    const char* key;
    const char* value;
    const char* problem;
  };
  for (const auto& c : std::vector<Case>{
           {"scenario", "duration_s", "0", "scenario: duration_s must be in (0, 3600], not 0"},
           {"scenario", "odom_rate_hz", "1e4", "scenario: odom_rate_hz must be in [0.1, 1000]"},
           {"true_robot", "wheel_slip_std", "-0.1", "true_robot: wheel_slip_std must be >= 0"},
           {"true_robot", "axle_distance_scale", "0", "true_robot: axle_distance_scale must be"},
           {"initial_pose", "x", "1e9", "initial_pose: x must be in [-100000, 100000]"},
           {"laser", "y", "-1e9", "laser: y must be in [-100000, 100000]"},
           {"laser", "field_of_view_rad", "7", "laser: field_of_view_rad must be in (0, 6.28"},
           {"laser", "spurious_probability", "2", "laser: spurious_probability must be in [0, 1]"},
           {"laser", "mixed_pixel_probability", "-1", "laser: mixed_pixel_probability must be"},
           {"laser", "noise_std_m", "-0.01", "laser: noise_std_m must be >= 0, not -0.01"},
           {"laser", "no_return", "zero", "no_return must be inf or max, not 'zero'"},
           {"laser", "max_range_m", "0.01", "laser: max_range_m must be > min_range_m"},
           {"path", "speed_m_s", "0", "path: speed_m_s must be > 0, not 0"},
           {"path", "mode", "fly", "mode must be waypoints, stop_look_move or cmd_vel, not 'fly'"},
           {"path", "loop", "yes", "loop=\"yes\" must be true or false"},
           {"obstacles/person", "radius_m", "0", "person: radius_m must be in (0, 1000], not 0"},
           {"obstacles/person", "speed_m_s", "-1", "person: speed_m_s must be > 0"},
       }) {
    const std::string path = ScenarioWith(dir, c.where, c.key, c.value);
    const auto what = Problem([&] { simulation_core::LoadScenario(path); });
    EXPECT_EQ(what.rfind(path + ":", 0), 0u) << what;
    EXPECT_NE(what.find(c.problem), std::string::npos) << c.key << "=" << c.value << ": " << what;
  }
}

TEST(ScenarioFile, TractionStartTickIsBoundedByTheRobotsCounter) {
  EXPECT_NO_THROW(simulation_core::TrueRobotAttributes(8).Validate({1.0, 1.0, 0.0, 0.0, 255}));
  try {
    simulation_core::TrueRobotAttributes(8).Validate({1.0, 1.0, 0.0, 0.0, 256});
    ADD_FAILURE() << "256 accepted for an 8-bit counter";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "true_robot: traction_start_tick must be in [0, 255], not 256");
  }
}

TEST(ParamsCommand, ListsRobotAndScenarioKeysAndChecksEitherKindOfFile) {
  const auto robot = testing::RunCli({"params", "--robot"});
  EXPECT_EQ(robot.exit_code, 0) << robot.output;
  for (const auto& [key, value] :
       kinematics::RobotParameterTable().Values(kinematics::RobotParameters{})) {
    EXPECT_NE(robot.output.find("  " + key + " "), std::string::npos) << key << robot.output;
  }
  EXPECT_NE(robot.output.find("magnitude in [1e-09, 1]"), std::string::npos) << robot.output;
  EXPECT_EQ(robot.output.find("<prefilter>"), std::string::npos) << robot.output;

  const auto scenario = testing::RunCli({"params", "--scenario"});
  EXPECT_EQ(scenario.exit_code, 0) << scenario.output;
  for (const char* text :
       {"<scenario>", "<true_robot>", "<initial_pose>", "<laser>", "<path>", "<person>",
        "mixed_pixel_probability", "stop_look_move", "in [10, 100000]", "traction_start_tick"}) {
    EXPECT_NE(scenario.output.find(text), std::string::npos) << text << "\n" << scenario.output;
  }
  EXPECT_EQ(scenario.output.find("wheel_radius "), std::string::npos) << scenario.output;

  const auto all = testing::RunCli({"params"});
  EXPECT_EQ(all.exit_code, 0) << all.output;
  for (const char* text : {"<prefilter>", "<robot>", "<laser>"}) {
    EXPECT_NE(all.output.find(text), std::string::npos) << text;
  }

  for (const auto& path : ShippedFiles("maps/robots")) {
    const auto run = testing::RunCli({"params", "--check", path});
    EXPECT_EQ(run.exit_code, 0) << run.output;
  }
  for (const auto& path : ShippedFiles("maps/scenarios")) {
    const auto run = testing::RunCli({"params", "--check", path});
    EXPECT_EQ(run.exit_code, 0) << run.output;
  }
  const TempDir dir;
  auto bad = testing::RunCli({"params", "--check", RobotWith(dir, "axle_distance", "620")});
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("robot: axle_distance = 620 is implausible"), std::string::npos)
      << bad.output;
  bad = testing::RunCli({"params", "--check", ScenarioWith(dir, "laser", "beams", "5")});
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("beams must be an integer from 10 to 100000"), std::string::npos)
      << bad.output;
  bad = testing::RunCli({"params", "--check", SourcePath("qos/structloc_qos.xml")});
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("expected <localisation_params>, <robot>, <scenario>, "
                            "<map_build_params>, <slam_params> or <world>"),
            std::string::npos)
      << bad.output;
}

// Every XML file shipped under maps/ (worlds, localiser, robot, scenario,
// map-build and SLAM files, in any subfolder) loads with the code that reads
// its kind.
TEST(ShippedFiles, EveryXmlFileUnderMapsLoads) {
  size_t checked = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(SourcePath("maps"))) {
    if (e.path().extension() != ".xml") continue;
    const auto run = testing::RunCli({"params", "--check", e.path().string()});
    EXPECT_EQ(run.exit_code, 0) << e.path() << ": " << run.output;
    ++checked;
  }
  EXPECT_GE(checked, 12u);
}

}  // namespace
}  // namespace structloc
