// Launch files: every shipped one reads cleanly and names executables we
// build; broken ones are rejected with file:line; the real launch file starts
// the components, which exit cleanly when the launch ends.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "config_test_support.hpp"
#include "structloc/config/strict_xml.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/process/launch_file.hpp"
#include "temp_dir.hpp"
#include "test_domains.hpp"
#include "wait_until.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;

process::LaunchContext Context() {
  return {STRUCTLOC_SOURCE_DIR, STRUCTLOC_BIN_DIR, {}};
}

// Reads a launch file with no overrides (what ExpectRejected calls).
void ReadWithoutOverrides(const std::string& path) {
  process::ReadLaunchFile(path, Context());
}

TEST(LaunchFiles, EveryShippedLaunchFileReadsAndNamesBuiltExecutables) {
  int count = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(STRUCTLOC_SOURCE_DIR) + "/launch_xml")) {
    if (entry.path().extension() != ".xml") continue;
    ++count;
    const auto description = process::ReadLaunchFile(entry.path().string(), Context());
    for (const auto& node : description.nodes) {
      EXPECT_TRUE(std::filesystem::exists(node.executable)) << node.executable;
    }
  }
  EXPECT_GT(count, 0);
}

TEST(LaunchFiles, OverridesReplaceDefaultsAndUnknownOverridesAreErrors) {
  auto context = Context();
  context.overrides["domain"] = "42";
  const auto d = process::ReadLaunchFile(
      std::string(STRUCTLOC_SOURCE_DIR) + "/launch_xml/structloc.launch.xml", context);
  ASSERT_FALSE(d.nodes.empty());
  EXPECT_EQ(d.nodes[0].arguments[0], "--domain");
  EXPECT_EQ(d.nodes[0].arguments[1], "42");
  EXPECT_EQ(d.arguments.at("qos"), std::string(STRUCTLOC_SOURCE_DIR) + "/qos/structloc_qos.xml");
  context.overrides["no_such_arg"] = "1";
  EXPECT_THROW(process::ReadLaunchFile(
                   std::string(STRUCTLOC_SOURCE_DIR) + "/launch_xml/structloc.launch.xml", context),
               config::ConfigError);
}

TEST(LaunchFiles, GroupsScopeLetsAndNamespacesAndConditionsChooseNodes) {
  const testing::TempDir temp;
  const std::string path = temp.Write("groups.launch.xml", R"xml(<launch>
  <arg name="second" default="true"/>
  <let name="rate" value="5"/>
  <set_env name="A" value="1"/>
  <group>
    <push-ros-namespace namespace="fleet"/>
    <let name="rate" value="7"/>
    <set_env name="A" value="$(var rate)"/>
    <group>
      <push-ros-namespace namespace="robot1"/>
      <node pkg="structloc" exec="structloc_simulator" name="sim">
        <param name="time-scale" value="$(var rate)"/>
      </node>
    </group>
    <node pkg="structloc" exec="structloc_localisation" name="loc" namespace="robot2"
          if="$(var second)"><env name="B" value="2"/></node>
    <node pkg="structloc" exec="structloc_localisation" name="skipped" unless="$(var second)"/>
    <group if="false"><node pkg="structloc" exec="structloc_localisation" name="off"/></group>
  </group>
  <node pkg="structloc" exec="structloc_calibration" name="cal">
    <param name="x" value="$(var rate)"/>
  </node>
</launch>)xml");
  const auto d = process::ReadLaunchFile(path, Context());
  ASSERT_EQ(d.nodes.size(), 3u);
  EXPECT_EQ(d.nodes[0].name, "fleet/robot1/sim");
  EXPECT_EQ(d.nodes[0].arguments,
            (std::vector<std::string>{"--namespace", "fleet/robot1", "--time-scale", "7"}));
  EXPECT_EQ(d.nodes[1].name, "fleet/robot2/loc");
  EXPECT_EQ(d.nodes[1].arguments, (std::vector<std::string>{"--namespace", "fleet/robot2"}));
  EXPECT_EQ(d.nodes[2].name, "cal");  // the group's let and namespace stayed in the group
  EXPECT_EQ(d.nodes[2].arguments, (std::vector<std::string>{"--x", "5"}));
  using Environment = std::vector<std::pair<std::string, std::string>>;
  EXPECT_EQ(d.nodes[0].environment, (Environment{{"A", "7"}}));
  EXPECT_EQ(d.nodes[1].environment, (Environment{{"A", "7"}, {"B", "2"}}));
  EXPECT_EQ(d.nodes[2].environment, (Environment{{"A", "1"}}));
}

TEST(LaunchFiles, IncludesTakeArgumentsAndTheNamespaceAroundThem) {
  auto context = Context();
  context.overrides["domain"] = "7";
  const auto d = process::ReadLaunchFile(
      std::string(STRUCTLOC_SOURCE_DIR) + "/launch_xml/two_robots.launch.xml", context);
  ASSERT_EQ(d.nodes.size(), 4u);
  EXPECT_EQ(d.nodes[0].name, "robot1/simulator");
  EXPECT_EQ(d.nodes[3].name, "robot2/localisation");
  const auto& args = d.nodes[3].arguments;
  EXPECT_EQ(args[0], "--namespace");
  EXPECT_EQ(args[1], "robot2");
  EXPECT_EQ(args[2], "--domain");
  EXPECT_EQ(args[3], "7");
  EXPECT_EQ(args.back(), "19.0 6.5 0");
  const testing::TempDir temp;
  const std::string self = temp.Write("self.launch.xml", "");
  temp.Write("self.launch.xml", "<launch><include file='" + self + "'/></launch>");
  testing::ExpectRejected("<launch><include file='" + self + "'/></launch>", "includes itself",
                          ReadWithoutOverrides);
  const std::string robot = std::string(STRUCTLOC_SOURCE_DIR) + "/launch_xml/robot.launch.xml";
  testing::ExpectRejected(
      "<launch><include file='" + robot + "'><arg name='colour' value='red'/></include></launch>",
      "no <arg name=\"colour\">", ReadWithoutOverrides);
}

// ROS 2's <include> is not scoped: the included file sees the variables set
// so far (the command line's among them), its <arg>s keep a value already set,
// and what it sets stays set after it unless a <group> scopes it. An argument
// without a default must be passed by the <include> itself.
TEST(LaunchFiles, IncludesSeeAndSetVariablesAsInRos2) {
  const testing::TempDir temp;
  const std::string child = temp.Write("child.launch.xml", R"xml(<launch>
  <arg name="robot"/>
  <arg name="domain" default="0"/>
  <arg name="speed" default="1"/>
  <let name="from_child" value="child $(var rate)"/>
  <node pkg="structloc" exec="structloc_simulator" name="$(var robot)_sim">
    <param name="domain" value="$(var domain)"/>
    <param name="speed" value="$(var speed)"/>
  </node>
</launch>)xml");
  const std::string path = temp.Write("parent.launch.xml", R"xml(<launch>
  <arg name="domain" default="4"/>
  <let name="rate" value="5"/>
  <group>
    <include file=")xml" + child + R"xml("><arg name="robot" value="scoped"/></include>
  </group>
  <include file=")xml" + child + R"xml("><arg name="robot" value="open"/></include>
  <executable cmd="/bin/echo $(var from_child) $(var robot)" name="after"/>
</launch>)xml");
  auto context = Context();
  context.overrides["speed"] = "3";  // declared only in the included file
  const auto d = process::ReadLaunchFile(path, context);
  ASSERT_EQ(d.nodes.size(), 3u);
  EXPECT_EQ(d.nodes[0].name, "scoped_sim");
  EXPECT_EQ(d.nodes[0].arguments, (std::vector<std::string>{"--domain", "4", "--speed", "3"}));
  EXPECT_EQ(d.nodes[1].name, "open_sim");
  EXPECT_EQ(d.nodes[2].arguments, (std::vector<std::string>{"child 5", "open"}));
  EXPECT_EQ(d.arguments.count("speed"), 0u);  // the top file's own arguments

  // $(dirname): the folder of the file being read, the included one inside it.
  const std::string beside = temp.Write("beside.launch.xml", R"xml(<launch>
  <executable cmd="/bin/echo $(dirname)" name="where"/></launch>)xml");
  // A folder's spaces and "$(" are its name: the value stays one word.
  const std::filesystem::path odd = std::filesystem::path(temp / "my maps $(x)");
  std::filesystem::create_directory(odd);
  {
    std::ofstream((odd / "odd.launch.xml").string())
        << "<launch><executable cmd='/bin/echo $(dirname)/a.xml' name='odd'/></launch>";
  }
  const auto in_odd = process::ReadLaunchFile((odd / "odd.launch.xml").string(), Context());
  ASSERT_EQ(in_odd.nodes.size(), 1u);
  EXPECT_EQ(in_odd.nodes[0].arguments, std::vector<std::string>{(odd / "a.xml").string()});
  const auto where =
      process::ReadLaunchFile(temp.Write("where.launch.xml",
                                         "<launch><include file='$(dirname)/beside.launch.xml'/>"
                                         "</launch>"),
                              Context());
  ASSERT_EQ(where.nodes.size(), 1u);
  EXPECT_EQ(where.nodes[0].arguments,
            std::vector<std::string>{std::filesystem::path(beside).parent_path().string()});

  // An <include>'s values are set one after the other: a value sees those above it.
  const auto ordered = process::ReadLaunchFile(
      temp.Write("ordered.launch.xml", "<launch><let name='rate' value='1'/><include file='" +
                                           child +
                                           "'><arg name='robot' value='r7'/>"
                                           "<arg name='speed' value='$(var robot)'/></include>"
                                           "</launch>"),
      Context());
  ASSERT_EQ(ordered.nodes.size(), 1u);
  EXPECT_EQ(ordered.nodes[0].arguments,
            (std::vector<std::string>{"--domain", "0", "--speed", "r7"}));

  // NAME:=VALUE for an argument of a file an <include> or <group> leaves out
  // is no unknown argument (ROS 2 collects it as conditionally included).
  const std::string optional =
      temp.Write("optional.launch.xml",
                 "<launch><arg name='sim' default='false'/><group if='$(var sim)'>"
                 "<include file='" +
                     child +
                     "'><arg name='robot' value='r'/></include>"
                     "</group><executable cmd='/bin/true'/></launch>");
  auto left_out = Context();
  left_out.overrides["speed"] = "3";
  EXPECT_EQ(process::ReadLaunchFile(optional, left_out).nodes.size(), 1u);
  left_out.overrides["sped"] = "3";
  EXPECT_THROW(process::ReadLaunchFile(optional, left_out), config::ConfigError);

  const std::string needs = temp.Write("needs.launch.xml", R"xml(<launch>
  <arg name="robot"/><executable cmd="/bin/echo $(var robot)"/></launch>)xml");
  testing::ExpectRejected(
      "<launch><let name='robot' value='r1'/><include file='" + needs + "'/></launch>",
      "the <include> must pass it", ReadWithoutOverrides);
}

// A node or executable left out by its condition is not substituted further;
// if and unless together, or a name that is no ROS 2 node name, are errors.
TEST(LaunchFiles, ConditionsComeFirstAndNodeNamesAreChecked) {
  const testing::TempDir temp;
  const std::string path = temp.Write("off.launch.xml", R"xml(<launch>
  <node pkg="structloc" exec="structloc_simulator" name="$(var unset)" if="false">
    <param name="x" value="$(env STRUCTLOC_LAUNCH_TEST_NEVER_SET)"/>
  </node>
  <executable cmd="$(var unset)" unless="true" respawn="$(var unset)"/>
  <executable cmd="/bin/true" name="on"/>
</launch>)xml");
  const auto d = process::ReadLaunchFile(path, Context());
  ASSERT_EQ(d.nodes.size(), 1u);
  EXPECT_EQ(d.nodes[0].name, "on");
  testing::ExpectRejected("<launch><executable cmd='/bin/true' if='true' unless='false'/></launch>",
                          "has both if and unless", ReadWithoutOverrides);
  testing::ExpectRejected(
      "<launch><executable cmd='/bin/true' if='false'><param name='p' value='1'/></executable>"
      "</launch>",
      "unknown element", ReadWithoutOverrides);
  testing::ExpectRejected(
      "<launch><executable cmd='/bin/true' if='false'><env nme='X' value='1'/></executable>"
      "</launch>",
      "missing attribute name", ReadWithoutOverrides);
  testing::ExpectRejected("<launch><executable cmd='/bin/echo $(dirname x)'/></launch>",
                          "$(dirname) takes no argument", ReadWithoutOverrides);
  testing::ExpectRejected(
      "<launch><node pkg='structloc' exec='structloc_simulator' name='a b'/></launch>",
      "is not a node name", ReadWithoutOverrides);
  testing::ExpectRejected(
      "<launch><node pkg='structloc' exec='structloc_simulator' if='false' colour='red'/>"
      "</launch>",
      "colour", ReadWithoutOverrides);
}

// As ROS 2 launch reads them: $(env NAME) sees a <set_env> in scope, if and
// unless take true and false in any case, an <include> left out by its
// condition is not substituted (its file may name a variable only set where it
// is wanted), and an included file may launch nothing where its conditions say so.
TEST(LaunchFiles, SetEnvConditionsAndOptionalIncludesReadAsInRos2) {
  const testing::TempDir temp;
  const std::string optional = temp.Write("optional.launch.xml", R"xml(<launch>
  <arg name="enable" default="false"/>
  <group if="$(var enable)"><executable cmd="/bin/true" name="extra"/></group>
</launch>)xml");
  const std::string path = temp.Write("main.launch.xml", R"xml(<launch>
  <group>
    <set_env name="STRUCTLOC_LAUNCH_TEST_SET" value="from set_env"/>
    <executable cmd="/bin/echo $(env STRUCTLOC_LAUNCH_TEST_SET)" name="echo" if="TRUE"/>
  </group>
  <executable cmd="/bin/false" name="never" unless="True"/>
  <include file="$(env STRUCTLOC_LAUNCH_TEST_NEVER_SET)" if="False"/>
  <include file=")xml" + optional + R"xml("/>
</launch>)xml");
  const auto d = process::ReadLaunchFile(path, Context());
  ASSERT_EQ(d.nodes.size(), 1u);
  EXPECT_EQ(d.nodes[0].name, "echo");
  // A substituted value stays one word, as in ROS 2.
  EXPECT_EQ(d.nodes[0].arguments, (std::vector<std::string>{"from set_env"}));
  testing::ExpectRejected("<launch><executable cmd='/bin/true' if='yes'/></launch>",
                          "not true, false, 1 or 0", ReadWithoutOverrides);
}

TEST(LaunchFiles, ExecutablesRunProgramsFromPathWithTheirArgumentsAndEnvironment) {
  const testing::TempDir temp;
  const std::string path = temp.Write("executable.launch.xml", R"xml(<launch>
  <arg name="port" default="11811"/>
  <arg name="server" default="true"/>
  <set_env name="A" value="1"/>
  <executable cmd="sh -c  exit  $(var port)" name="server" respawn="true" if="$(var server)">
    <env name="B" value="2"/>
  </executable>
  <executable cmd="/bin/true" unless="$(var server)"/>
</launch>)xml");
  const auto d = process::ReadLaunchFile(path, Context());
  ASSERT_EQ(d.nodes.size(), 1u);
  EXPECT_EQ(d.nodes[0].name, "server");
  EXPECT_TRUE(d.nodes[0].executable == "/bin/sh" || d.nodes[0].executable == "/usr/bin/sh")
      << d.nodes[0].executable;
  EXPECT_EQ(d.nodes[0].arguments, (std::vector<std::string>{"-c", "exit", "11811"}));
  EXPECT_EQ(d.nodes[0].environment,
            (std::vector<std::pair<std::string, std::string>>{{"A", "1"}, {"B", "2"}}));
  EXPECT_TRUE(d.nodes[0].respawn);
  auto context = Context();
  context.overrides["server"] = "false";
  const auto other = process::ReadLaunchFile(path, context);
  ASSERT_EQ(other.nodes.size(), 1u);
  EXPECT_EQ(other.nodes[0].name, "true");
  EXPECT_EQ(other.nodes[0].executable, "/bin/true");
  testing::ExpectRejected("<launch><executable cmd='no_such_program_here --x'/></launch>",
                          "cmd 'no_such_program_here' is not an executable on PATH",
                          ReadWithoutOverrides);
  testing::ExpectRejected(
      "<launch><executable cmd='/bin/true'><param name='a' value='1'/></executable></launch>",
      "unknown element", ReadWithoutOverrides);
}

TEST(LaunchFiles, ParamFilesGiveEachNodeItsEntriesAndTheirOwnErrorsNameTheLine) {
  const testing::TempDir temp;
  const std::string params = temp.Write("params.yaml", R"yaml(/**:
  ros__parameters:
    domain: 3
    time-scale: 2
robot1/loc:
  ros__parameters:
    domain: 4
    initial-pose: "2.0 6.5 0"
other:
  ros__parameters:
    domain: 9
)yaml");
  const std::string path =
      temp.Write("from.launch.xml",
                 "<launch><group>"
                 "<push-ros-namespace namespace='robot1'/>"
                 "<node pkg='structloc' exec='structloc_localisation' name='loc'>"
                 "<param from='" +
                     params + "'/></node></group></launch>");
  const auto d = process::ReadLaunchFile(path, Context());
  ASSERT_EQ(d.nodes.size(), 1u);
  EXPECT_EQ(d.nodes[0].arguments,
            (std::vector<std::string>{"--namespace", "robot1", "--domain", "4", "--time-scale", "2",
                                      "--initial-pose", "2.0 6.5 0"}));
  const std::string broken = temp.Write("broken.yaml", "loc:\n  ros__parameters:\n    a: [1, 2]\n");
  testing::ExpectRejected(
      "<launch><node pkg='structloc' exec='structloc_localisation' name='loc'><param from='" +
          broken + "'/></node></launch>",
      broken + ":3: parameter 'a' must be a plain value", ReadWithoutOverrides);
}

struct BrokenLaunch {
  const char* tag;
  const char* text;
  const char* problem;
};

class BrokenLaunchFile : public ::testing::TestWithParam<BrokenLaunch> {};

TEST_P(BrokenLaunchFile, IsRejectedWithFileLineAndProblem) {
  testing::ExpectRejected(GetParam().text, GetParam().problem, [](const std::string& path) {
    process::ReadLaunchFile(path, Context());
  });
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BrokenLaunchFile,
    ::testing::Values(
        BrokenLaunch{"UnknownElement", "<launch><nod pkg='structloc' exec='x'/></launch>",
                     "unknown element"},
        BrokenLaunch{"UnknownAttribute",
                     "<launch><node pkg='structloc' exec='x' colour='red'/></launch>",
                     "unknown attribute(s): colour"},
        BrokenLaunch{"WrongPackage", "<launch><node pkg='other' exec='x'/></launch>",
                     "pkg must be"},
        BrokenLaunch{"UndeclaredVar",
                     "<launch><node pkg='structloc' exec='x'><param name='a' value='$(var b)'/>"
                     "</node></launch>",
                     "$(var b) names no <arg>"},
        BrokenLaunch{"ArgWithoutDefault",
                     "<launch><arg name='a'/><node pkg='structloc' exec='x'/></launch>",
                     "has no default"},
        BrokenLaunch{"Malformed", "<launch><node pkg='structloc' exec='x'></launch>",
                     "malformed XML"},
        BrokenLaunch{"NoNodes", "<launch/>", "launches no <node> or <executable>"},
        BrokenLaunch{"ConditionNotABoolean",
                     "<launch><node pkg='structloc' exec='structloc_simulator' if='maybe'/>"
                     "</launch>",
                     "not true, false, 1 or 0"},
        BrokenLaunch{"NamespaceOutsideAGroup",
                     "<launch><push-ros-namespace namespace='r1'/>"
                     "<node pkg='structloc' exec='structloc_simulator'/></launch>",
                     "unknown element"},
        BrokenLaunch{"BadVariableName",
                     "<launch><set_env name='1X' value='a'/>"
                     "<node pkg='structloc' exec='structloc_simulator'/></launch>",
                     "'1X' is not an environment variable name"},
        BrokenLaunch{"NamespaceTwice",
                     "<launch><group><push-ros-namespace namespace='r1'/>"
                     "<node pkg='structloc' exec='structloc_simulator'>"
                     "<param name='namespace' value='r2'/></node></group></launch>",
                     "a namespace param inside a pushed namespace"}),
    [](const auto& info) { return std::string(info.param.tag); });

TEST(LaunchFiles, RealLaunchFileRunsTheComponentsAndStopsThemCleanly) {
  process::ChildProcess launch(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc",
      {"launch", std::string(STRUCTLOC_SOURCE_DIR) + "/launch_xml/structloc.launch.xml",
       "domain:=" + std::to_string(testing::domains::kLaunch), "--duration", "2"});
  const auto code = launch.WaitExit(testing::kGenerousTimeout);
  const auto out = launch.CapturedOutput();
  ASSERT_TRUE(code.has_value()) << out;
  EXPECT_EQ(*code, 0) << out;
  for (const auto* name : {"simulator", "localisation", "calibration"}) {
    EXPECT_NE(out.find(std::string("[launch] ") + name + " exited with code 0"), std::string::npos)
        << out;
  }
  EXPECT_NE(out.find("on domain " + std::to_string(testing::domains::kLaunch)), std::string::npos)
      << out;
}

TEST(LaunchFiles, CalibrationLaunchFileEstimatesOnlineAndWritesTheCalibratedRobot) {
  const testing::TempDir dir;
  const std::string out = dir / "calibration";
  process::ChildProcess launch(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc",
      {"launch", std::string(STRUCTLOC_SOURCE_DIR) + "/launch_xml/calibration.launch.xml",
       "domain:=" + std::to_string(testing::domains::kLaunch), "time_scale:=8", "window_s:=30",
       "every_s:=10", "out_dir:=" + out, "--duration", "10"});
  const auto code = launch.WaitExit(testing::kGenerousTimeout);
  const auto output = launch.CapturedOutput();
  ASSERT_TRUE(code.has_value()) << output;
  EXPECT_EQ(*code, 0) << output;
  EXPECT_NE(output.find("calibration: estimated from"), std::string::npos) << output;
  EXPECT_NE(output.find("window "), std::string::npos) << output;
  EXPECT_TRUE(std::filesystem::exists(out + "/calibrated.xml")) << output;
}

}  // namespace
}  // namespace structloc
