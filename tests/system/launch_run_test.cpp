// Launch files run for real: a node with respawn="true" killed with SIGKILL
// is started again after its delay and the pose stream resumes within 5 s; a
// node without it stops the launch with a non-zero exit and a message naming
// the node and the signal; a group's <set_env name="ROS_DOMAIN_ID"> puts its
// nodes on that domain.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <regex>

#include "dds_test_support.hpp"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "structloc/process/child_process.hpp"
#include "temp_dir.hpp"
#include "test_domains.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
constexpr int kDomain = testing::domains::kLaunchRun;

// Simulator and localisation; the localisation respawns when `respawn`.
std::string LaunchFile(bool respawn) {
  const std::string qos = testing::ShippedQos();
  const std::string common = "<param name='domain' value='" + std::to_string(kDomain) +
                             "'/><param name='qos' value='" + qos + "'/>";
  return std::string("<launch>") +
         "<node pkg='structloc' exec='structloc_simulator' name='simulator'>" + common +
         "<param name='scenario' value='$(find-pkg-share structloc)/maps/scenarios/"
         "office_people.xml'/></node>"
         "<node pkg='structloc' exec='structloc_localisation' name='localisation'" +
         (respawn ? " respawn='true' respawn_delay='0.5'" : "") + ">" + common +
         "<param name='initial-pose' value='2.0 6.5 0'/><param name='params' value='" +
         testing::SimulatedRobotParams() + "'/></node></launch>";
}

// The pid the launch reports for `node` the `nth` time it starts it (0 = none yet).
pid_t StartedPid(const std::string& output, const std::string& node, size_t nth) {
  const std::regex started("\\[launch\\] " + node + " has pid ([0-9]+)");
  size_t n = 0;
  for (auto it = std::sregex_iterator(output.begin(), output.end(), started);
       it != std::sregex_iterator(); ++it) {
    if (++n == nth) return static_cast<pid_t>(std::stol((*it)[1]));
  }
  return 0;
}

// Counts the poses published on the test's domain.
struct PoseCounter {
  explicit PoseCounter(const std::string& name)
      : node(testing::TestNodeOptions(name, kDomain)),
        subscription(node.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
            dds_common::topics::kPose,
            [this](const geometry_msgs::msg::PoseWithCovarianceStamped&) { ++count; })) {}
  std::atomic<int> count{0};
  dds_common::Node node;
  dds_common::Subscription subscription;  // last: gone before the count
};

TEST(LaunchRespawn, AKilledNodeWithRespawnComesBackAndPosesResume) {
  const testing::TempDir dir;
  const std::string file = dir.Write("respawn.launch.xml", LaunchFile(true));
  PoseCounter poses("respawn_observer");
  process::ChildProcess launch(std::string(STRUCTLOC_BIN_DIR) + "/structloc",
                               {"launch", file, "--duration", "20"});
  ASSERT_TRUE(testing::WaitUntil([&] { return poses.count > 5; })) << launch.CapturedOutput();
  const pid_t first = StartedPid(launch.CapturedOutput(), "localisation", 1);
  ASSERT_GT(first, 0) << launch.CapturedOutput();
  ASSERT_EQ(::kill(first, SIGKILL), 0);
  const auto killed = std::chrono::steady_clock::now();
  ASSERT_TRUE(testing::WaitUntil(
      [&] { return StartedPid(launch.CapturedOutput(), "localisation", 2) > 0; }, 5s))
      << launch.CapturedOutput();
  std::this_thread::sleep_for(200ms);  // poses already on their way from the dead process
  const int before = poses.count.load();
  ASSERT_TRUE(testing::WaitUntil([&] { return poses.count.load() > before + 3; }, 5s))
      << launch.CapturedOutput();
  const double resumed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - killed).count();
  std::printf("localisation killed with SIGKILL; respawned, poses again after %.1f s\n", resumed_s);
  EXPECT_LT(resumed_s, 5.0);
  EXPECT_NE(launch.CapturedOutput().find("localisation ended with signal 9"), std::string::npos)
      << launch.CapturedOutput();
  launch.Stop(10s);
}

TEST(LaunchRespawn, AKilledNodeWithoutRespawnStopsTheLaunchNamingIt) {
  const testing::TempDir dir;
  const std::string file = dir.Write("no_respawn.launch.xml", LaunchFile(false));
  process::ChildProcess launch(std::string(STRUCTLOC_BIN_DIR) + "/structloc",
                               {"launch", file, "--duration", "30"});
  ASSERT_TRUE(testing::WaitUntil([&] {
    return StartedPid(launch.CapturedOutput(), "localisation", 1) > 0 &&
           launch.CapturedOutput().find("localisation: running") != std::string::npos;
  })) << launch.CapturedOutput();
  ASSERT_EQ(::kill(StartedPid(launch.CapturedOutput(), "localisation", 1), SIGKILL), 0);
  const auto code = launch.WaitExit(15s);
  ASSERT_TRUE(code.has_value()) << launch.CapturedOutput();
  EXPECT_EQ(*code, 1) << launch.CapturedOutput();
  EXPECT_NE(launch.CapturedOutput().find(
                "localisation died with signal 9 (Killed) and has no respawn=\"true\""),
            std::string::npos)
      << launch.CapturedOutput();
}

TEST(LaunchEnvironment, ASetEnvGroupPutsItsNodesOnTheDomainItNames) {
  const testing::TempDir dir;
  const std::string qos = "<param name='qos' value='" + testing::ShippedQos() + "'/>";
  const std::string file = dir.Write(
      "domain.launch.xml",
      "<launch><group><set_env name='ROS_DOMAIN_ID' value='" + std::to_string(kDomain) + "'/>" +
          "<node pkg='structloc' exec='structloc_simulator' name='simulator'>" + qos +
          "<param name='scenario' value='$(find-pkg-share structloc)/maps/scenarios/"
          "office_people.xml'/></node>"
          "<node pkg='structloc' exec='structloc_localisation' name='localisation'>" +
          qos + "<param name='initial-pose' value='2.0 6.5 0'/><param name='params' value='" +
          testing::SimulatedRobotParams() + "'/></node></group></launch>");
  PoseCounter poses("domain_observer");
  process::ChildProcess launch(std::string(STRUCTLOC_BIN_DIR) + "/structloc",
                               {"launch", file, "--duration", "20"});
  EXPECT_TRUE(testing::WaitUntil([&] { return poses.count > 5; })) << launch.CapturedOutput();
  // Each node's output comes line by line behind its name, as ros2 launch prints it.
  EXPECT_NE(launch.CapturedOutput().find("[localisation] localisation on domain " +
                                         std::to_string(kDomain)),
            std::string::npos)
      << launch.CapturedOutput();
  launch.Stop(10s);
}

// The stop reaches what a node started (a wrapper script's program is no
// orphan), a program without a SIGINT handler ended by the stop's SIGINT has
// stopped as asked (exit 0), and nodes deaf to SIGINT and SIGTERM are stopped
// together: SIGTERM after the grace, SIGKILL 2 s later, for all of them at once.
TEST(LaunchStop, EveryNodeAndWhatItStartedStopsTogether) {
  const testing::TempDir dir;
  // The wrapper's program, told apart from every other by its duration.
  const std::string marker = "sleep 9" + std::to_string(getpid());
  const std::string wrapper = dir.Write("wrapper.sh", "#!/bin/sh\n/bin/" + marker + "\n");
  const std::string deaf = dir.Write("deaf.sh", "#!/bin/sh\ntrap '' INT TERM\n/bin/sleep 300\n");
  ASSERT_EQ(chmod(wrapper.c_str(), 0755), 0);
  ASSERT_EQ(chmod(deaf.c_str(), 0755), 0);
  auto orphans = [&] {
    return std::system(("pgrep -f '^/bin/" + marker + "$' > /dev/null").c_str()) == 0;
  };
  const std::string plain = dir.Write(
      "plain.launch.xml", "<launch><executable cmd='" + wrapper + "' name='wrapper'/>" +
                              "<executable cmd='/bin/sleep 300' name='sleeper'/></launch>");
  process::ChildProcess first(std::string(STRUCTLOC_BIN_DIR) + "/structloc",
                              {"launch", plain, "--duration", "1"});
  EXPECT_TRUE(testing::WaitUntil([&] { return orphans(); })) << first.CapturedOutput();
  const auto code = first.WaitExit(20s);
  ASSERT_TRUE(code.has_value()) << first.CapturedOutput();
  EXPECT_EQ(*code, 0) << first.CapturedOutput();
  EXPECT_NE(first.CapturedOutput().find("sleeper exited with code 130 (stopped by the launch's"),
            std::string::npos)
      << first.CapturedOutput();
  EXPECT_TRUE(testing::WaitUntil([&] { return !orphans(); }, 5s)) << "the wrapper's sleep lives on";
  if (orphans()) std::system(("pkill -f '^/bin/" + marker + "$'").c_str());

  const std::string deaf_file =
      dir.Write("deaf.launch.xml",
                "<launch><executable cmd='" + deaf + "' name='a'/><executable cmd='" + deaf +
                    "' name='b'/><executable cmd='" + deaf + "' name='c'/></launch>");
  process::ChildProcess second(std::string(STRUCTLOC_BIN_DIR) + "/structloc",
                               {"launch", deaf_file, "--duration", "1"});
  const auto started = std::chrono::steady_clock::now();
  const auto deaf_code = second.WaitExit(60s);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  ASSERT_TRUE(deaf_code.has_value()) << second.CapturedOutput();
  EXPECT_EQ(*deaf_code, 1) << second.CapturedOutput();  // they had to be killed
  for (const char* node : {"a", "b", "c"})
    EXPECT_NE(
        second.CapturedOutput().find(std::string("[launch] ") + node + " exited with code 137"),
        std::string::npos)
        << second.CapturedOutput();
  // 1 s + 5 s grace + 2 s: one after the other it took 12 s.
  EXPECT_LT(seconds, 11.0) << second.CapturedOutput();
}

// A node that exits with code 137 by itself is not reported as killed by
// signal 9; nodes read an empty stdin (a node of its own process group reading
// the terminal would be stopped); a node that cannot be respawned stops the
// launch as a node that dies does, its other nodes stopped by the launch's signal.
TEST(LaunchStop, ExitCodesStdinAndARespawnThatCannotStartAreReportedAndStopTheLaunch) {
  const testing::TempDir dir;
  const std::string exits = dir.Write("exits.sh", "#!/bin/sh\nexit 137\n");
  const std::string reader =
      dir.Write("reader.sh",
                "#!/bin/sh\nif read line; then echo got a line; else echo stdin "
                "empty; fi\nexec /bin/sleep 300\n");
  const std::string once = dir.Write("once.sh", "#!/bin/sh\nrm -f \"$0\"\nexit 3\n");
  for (const auto& script : {exits, reader, once}) ASSERT_EQ(chmod(script.c_str(), 0755), 0);

  const std::string exit_file = dir.Write(
      "exit.launch.xml", "<launch><executable cmd='" + exits + "' name='exits'/>" +
                             "<executable cmd='/bin/sleep 300' name='sleeper'/></launch>");
  process::ChildProcess first(std::string(STRUCTLOC_BIN_DIR) + "/structloc", {"launch", exit_file});
  const auto code = first.WaitExit(20s);
  ASSERT_TRUE(code.has_value()) << first.CapturedOutput();
  EXPECT_EQ(*code, 1) << first.CapturedOutput();
  EXPECT_NE(first.CapturedOutput().find("exits died with exit code 137"), std::string::npos)
      << first.CapturedOutput();

  const std::string respawn_file =
      dir.Write("respawn.launch.xml",
                "<launch><executable cmd='" + reader + "' name='reader'/>" + "<executable cmd='" +
                    once + "' name='once' respawn='true' respawn_delay='0.2'/></launch>");
  process::ChildProcess second(std::string(STRUCTLOC_BIN_DIR) + "/structloc",
                               {"launch", respawn_file});
  const auto respawn_code = second.WaitExit(20s);
  ASSERT_TRUE(respawn_code.has_value()) << second.CapturedOutput();
  const std::string output = second.CapturedOutput();
  EXPECT_EQ(*respawn_code, 1) << output;
  EXPECT_NE(output.find("[reader] stdin empty"), std::string::npos) << output;
  EXPECT_NE(output.find("[launch] ERROR: once: cannot start " + once), std::string::npos) << output;
  EXPECT_NE(output.find("stopping all nodes (once could not be respawned)"), std::string::npos)
      << output;
  EXPECT_NE(output.find("reader exited with code 130 (stopped by the launch's signal)"),
            std::string::npos)
      << output;
}

// A child's stdin is /dev/null, set after its output: a parent without a
// stdin gets its capture file as fd 0, which must still receive the output.
TEST(ChildProcessOutput, IsCapturedWhenTheParentHasNoStdin) {
  const int saved = dup(STDIN_FILENO);
  ASSERT_GE(saved, 0);
  close(STDIN_FILENO);
  std::string output;
  {
    process::ChildProcess echo("/bin/echo", {"hello"});
    echo.WaitExit(5s);
    output = echo.CapturedOutput();
  }
  dup2(saved, STDIN_FILENO);
  close(saved);
  EXPECT_EQ(output, "hello\n");
}

}  // namespace
}  // namespace structloc
