// The simulator core: tricycle kinematics against closed forms, dead reckoning
// against ground truth, encoders (quantisation and wrap-around), the skew of a
// scan taken while moving, a scan stamped late, determinism, scenario files and
// recordings.
#include <gtest/gtest.h>

#include "test_paths.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "structloc/config/strict_xml.hpp"
#include "structloc/kinematics/tricycle.hpp"
#include "structloc/simulation_core/recorder.hpp"
#include "structloc/simulation_core/simulation.hpp"
#include "temp_dir.hpp"

namespace structloc {
namespace {

using geometry::kPi;
using geometry::Pose2D;

TEST(Tricycle, StraightLineCircleAndTurnOnTheSpot) {
  const double r = 0.185, l = 0.62;
  // Straight: steering 0, the reference point moves wheel angle * radius.
  Pose2D p = kinematics::Advance({1, 2, 0.3}, 10.0, 0.0, r, l);
  EXPECT_NEAR(p.x, 1 + 10 * r * std::cos(0.3), 1e-12);
  EXPECT_NEAR(p.y, 2 + 10 * r * std::sin(0.3), 1e-12);
  EXPECT_NEAR(p.theta, 0.3, 1e-15);
  // Constant steering: a circle of radius l / tan(lambda) around the ICR.
  const double lambda = 0.4, radius = l / std::tan(lambda);
  p = {0, 0, 0};
  double max_dist_error = 0.0;
  for (int k = 0; k < 2000; ++k) {
    p = kinematics::Advance(p, 0.01, lambda, r, l);
    max_dist_error = std::max(
        max_dist_error, std::abs((p.Translation() - Eigen::Vector2d(0, radius)).norm() - radius));
  }
  EXPECT_LT(max_dist_error, 1e-9);
  // Steering at 90 degrees: the robot turns on the spot about the rear axle middle.
  p = kinematics::Advance({3, 4, 0}, 1.0, kPi / 2, r, l);
  EXPECT_NEAR(p.x, 3, 1e-12);
  EXPECT_NEAR(p.y, 4, 1e-12);
  EXPECT_NEAR(p.theta, r / l, 1e-12);
}

TEST(Encoders, TickDeltaAcrossTheCounterWrap) {
  kinematics::RobotParameters p;
  p.traction_counter_bits = 32;
  EXPECT_EQ(p.TickDelta(4294967290u, 5u), 11);
  EXPECT_EQ(p.TickDelta(5u, 4294967290u), -11);
  p.traction_counter_bits = 16;
  EXPECT_EQ(p.TickDelta(65530u, 10u), 16);
}

simulation_core::Scenario Office() {
  return simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/office_people.xml"));
}

TEST(Simulation, DeadReckoningWithTheTrueParametersReproducesTheGroundTruth) {
  auto scenario = Office();
  scenario.errors.wheel_slip_std = 0.0;
  scenario.duration_s = 20.0;
  // A very fine encoder makes quantisation negligible: then dead reckoning
  // with the true parameters must agree with the truth to numerical precision.
  scenario.nominal.traction_ticks_per_rev = 1e9;
  scenario.nominal.steering_rad_per_tick = 1e-9;
  simulation_core::Simulation sim(scenario);
  kinematics::DeadReckoning with_true(scenario.TrueParameters(), scenario.initial_pose);
  with_true.Add(sim.State().traction_ticks, static_cast<double>(sim.State().steering_ticks));
  while (!sim.Finished()) {
    const auto& s = sim.Step();
    with_true.Add(s.traction_ticks, static_cast<double>(s.steering_ticks));
  }
  const auto& truth = sim.State().truth;
  EXPECT_LT((with_true.Pose().Translation() - truth.Translation()).norm(), 1e-5);
  EXPECT_LT(std::abs(geometry::WrapAngle(with_true.Pose().theta - truth.theta)), 1e-6);
}

TEST(Simulation, OnePercentRadiusErrorDriftsAsPredictedOnAStraightRun) {
  auto scenario = Office();
  scenario.errors = {};
  scenario.errors.wheel_radius_scale = 1.01;
  scenario.path.waypoints = {{12.0, 6.5}};
  simulation_core::Simulation sim(scenario);
  while (!sim.Finished()) sim.Step();
  const auto& s = sim.State();
  const double travelled = s.truth.x - scenario.initial_pose.x;
  // Odometry believes the nominal radius: it reports 1/1.01 of the distance.
  EXPECT_GT(travelled, 9.0);
  EXPECT_NEAR(s.odometry.x, travelled / 1.01, 0.002);
  EXPECT_NEAR(travelled - s.odometry.x, travelled * 0.01 / 1.01, 0.002);
}

TEST(Simulation, EncodersAreQuantisedAndWrap) {
  auto scenario = Office();  // starts 7296 ticks below the 32-bit wrap
  scenario.duration_s = 5.0;
  simulation_core::Simulation sim(scenario);
  bool wrapped = false;
  uint64_t last = sim.State().traction_ticks;
  while (!sim.Finished()) {
    const auto& s = sim.Step();
    wrapped = wrapped || s.traction_ticks < last;
    last = s.traction_ticks;
    EXPECT_LT(s.traction_ticks, uint64_t{1} << 32);
  }
  EXPECT_TRUE(wrapped);
  EXPECT_GT(sim.State().odometry.x, 2.0);  // dead reckoning went straight through the wrap
}

TEST(Simulation, TheSkewOfAScanTakenAt1MetrePerSecondMatchesTheAnalyticDisplacement) {
  auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/dead_end_corridor.xml"));
  scenario.errors = {};
  scenario.laser.noise_std_m = 0;
  scenario.laser.spurious_probability = 0;
  scenario.laser.mixed_pixel_probability = 0;
  scenario.laser.blocked_sectors.clear();
  scenario.path.mode = simulation_core::PathSpec::Mode::kCmdVel;
  scenario.initial_pose = {5.0, 1.155, kPi};  // facing the end wall at x = 0.1, centred
  simulation_core::Simulation sim(scenario);
  sim.CommandVelocity(1.0, 0.0);
  std::optional<simulation_core::SimScan> scan;
  for (int i = 0; i < 300 && !scan; ++i) {
    sim.Step();
    scan = sim.TakeScan();
    if (scan && scan->stamp < 0.05) scan.reset();  // skip the first scan (accelerating)
  }
  ASSERT_TRUE(scan.has_value());
  // Beam i looks at bearing a_i and was taken at stamp + i dt, when the robot
  // had moved 1 m/s * i dt further towards the end wall (-x).
  const double x0 = scan->truth.x;
  int checked = 0;
  for (size_t i = 0; i < scan->ranges.size(); ++i) {
    const double a = scan->angle_min + static_cast<double>(i) * scan->angle_increment;
    const double heading = kPi + a;            // world direction of the beam
    if (std::cos(heading) > -0.985) continue;  // beams that hit the end wall head-on-ish
    const double x = x0 - 1.0 * static_cast<double>(i) * scan->time_increment;
    const double expected = (x - 0.1) / -std::cos(heading);
    EXPECT_NEAR(scan->ranges[i], expected, 1e-4) << i;
    ++checked;
  }
  EXPECT_GT(checked, 10);
  // And the skew itself is visible: the first and last of those beams differ
  // by the 1 m/s travel over the scan.
  EXPECT_GT(scan->time_increment * static_cast<double>(scan->ranges.size()), 0.1);
}

// A laser stamped when its readings arrive: the same readings and true pose
// as on time, the stamp later by the latency, given out no earlier than that,
// with the odometry of the later moment.
TEST(Simulation, AScanStampedLateKeepsItsReadingsAndCarriesTheOdometryOfItsStamp) {
  auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/dead_end_corridor.xml"));
  scenario.errors = {};
  scenario.path.mode = simulation_core::PathSpec::Mode::kCmdVel;
  scenario.initial_pose = {5.0, 1.155, kPi};
  const auto scans = [&](double latency_s) {
    auto s = scenario;
    s.laser.stamp_latency_s = latency_s;
    simulation_core::Simulation sim(s);
    sim.CommandVelocity(1.0, 0.0);
    std::vector<std::pair<double, simulation_core::SimScan>> out;  // (given out at, scan)
    for (int i = 0; i < 150; ++i) {
      sim.Step();
      if (auto scan = sim.TakeScan()) out.push_back({sim.State().time, *scan});
    }
    return out;
  };
  const auto on_time = scans(0.0);
  const auto late = scans(0.13);
  ASSERT_GE(on_time.size(), 5u);
  ASSERT_GE(late.size(), on_time.size() - 1);
  for (size_t i = 1; i + 1 < late.size(); ++i) {
    const auto& [given, scan] = late[i];
    const auto& reference = on_time[i].second;
    EXPECT_NEAR(scan.stamp, reference.stamp + 0.13, 1e-9) << i;
    // Given out at its stamp, or when complete if that is later (this
    // laser's 360 deg sweep takes 0.2 s).
    EXPECT_GE(given + 1e-9, scan.stamp) << i;
    EXPECT_LT(given, std::max(scan.stamp, on_time[i].first) + scenario.step_s + 1e-9) << i;
    EXPECT_EQ(scan.ranges, reference.ranges) << i;
    EXPECT_NEAR(scan.truth.x, reference.truth.x, 1e-12) << i;
    // At 1 m/s straight ahead in the odometry frame.
    EXPECT_NEAR(scan.odometry.x, reference.odometry.x + 0.13, 2e-3) << i;
  }
}

TEST(Simulation, SameScenarioAndSeedGiveBitForBitTheSameRecording) {
  auto scenario = Office();
  scenario.duration_s = 3.0;
  const testing::TempDir temp;
  const std::string a = temp / "a", b = temp / "b", c = temp / "c";
  simulation_core::RecordScenario(scenario, a);
  simulation_core::RecordScenario(scenario, b);
  scenario.seed += 1;
  simulation_core::RecordScenario(scenario, c);
  auto read = [](const std::string& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  for (const auto* f : {"/run.clf", "/truth.tum", "/encoders.csv", "/initial_pose"}) {
    EXPECT_EQ(read(a + f), read(b + f)) << f;
    EXPECT_FALSE(read(a + f).empty()) << f;
  }
  EXPECT_NE(read(a + "/run.clf"), read(c + "/run.clf"));
}

TEST(Simulation, RecordingHasTheDocumentedFormats) {
  auto scenario = Office();
  scenario.duration_s = 2.0;
  const testing::TempDir temp;
  const std::string dir = temp / "office";
  const auto summary = simulation_core::RecordScenario(scenario, dir);
  EXPECT_EQ(summary.scans, 20);  // 10 Hz
  std::ifstream clf(dir + "/run.clf");
  std::string line;
  int odom = 0, laser = 0;
  while (std::getline(clf, line)) {
    std::istringstream ss(line);
    std::string tag;
    ss >> tag;
    if (tag == "ODOM") ++odom;
    if (tag == "ROBOTLASER1") {
      ++laser;
      int type, n;
      double start, fov, res, max_range, accuracy, remission_mode;
      ss >> type >> start >> fov >> res >> max_range >> accuracy >> remission_mode >> n;
      EXPECT_EQ(n, 1081);
      EXPECT_NEAR(start, -0.75 * kPi, 1e-5);
    }
  }
  EXPECT_EQ(laser, 20);
  EXPECT_EQ(odom, 101);  // t = 0, then 50 Hz
  std::ifstream enc(dir + "/encoders.csv");
  std::getline(enc, line);
  EXPECT_EQ(line, "t,traction_ticks,steering_ticks");
  std::ifstream tum(dir + "/truth.tum");
  int tum_lines = 0;
  while (std::getline(tum, line)) tum_lines += line.empty() || line[0] == '#' ? 0 : 1;
  EXPECT_EQ(tum_lines, 20);
  std::ifstream initial(dir + "/initial_pose");
  double x, y, th;
  ASSERT_TRUE(initial >> x >> y >> th);
  EXPECT_NEAR(x, 2.0, 0.01);
}

TEST(Scenarios, EveryShippedScenarioAndRobotFileLoads) {
  int count = 0;
  for (const auto& e : std::filesystem::directory_iterator(testing::SourcePath("maps/scenarios"))) {
    if (e.path().extension() != ".xml") continue;
    const auto s = simulation_core::LoadScenario(e.path().string());
    EXPECT_FALSE(s.name.empty());
    ++count;
  }
  EXPECT_GE(count, 3);
  for (const auto& e : std::filesystem::directory_iterator(testing::SourcePath("maps/robots"))) {
    EXPECT_NO_THROW(kinematics::LoadRobotParameters(e.path().string())) << e.path();
  }
}

TEST(Scenarios, BrokenScenarioNamesFileLineAndProblem) {
  const testing::TempDir temp;
  const std::string path = temp / "broken.xml";
  std::ifstream in(testing::SourcePath("maps/scenarios/office_people.xml"));
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  text.replace(text.find("beams=\"1081\""), 12, "beams=\"-5\"");
  for (size_t pos; (pos = text.find("file=\"../")) != std::string::npos;) {
    text.replace(pos, 9, "file=\"" + testing::SourcePath("maps/"));
  }
  std::ofstream(path) << text;
  try {
    simulation_core::LoadScenario(path);
    ADD_FAILURE() << "accepted beams=-5";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("beams must be"), std::string::npos) << e.what();
  }
}

// A kidnapping in a scenario (issue 38): the true pose jumps, odometry sees
// nothing; a teleport naming no waypoint of the path, or out of time order,
// is refused naming the file.
TEST(Scenarios, ATeleportMovesTheRobotAndNotItsOdometry) {
  const auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/office_kidnap.xml"));
  ASSERT_EQ(scenario.teleports.size(), 1u);
  const auto& teleport = scenario.teleports.front();
  simulation_core::Simulation sim(scenario);
  geometry::Pose2D truth_before, odometry_before;
  while (sim.State().time < teleport.at_s - 1e-9) {
    truth_before = sim.State().truth;
    odometry_before = sim.State().odometry;
    sim.Step();
  }
  const auto& after = sim.Step();
  const auto& t = teleport.pose;
  EXPECT_LT(std::hypot(after.truth.x - t.x, after.truth.y - t.y), 0.05);
  EXPECT_GT(std::hypot(after.truth.x - truth_before.x, after.truth.y - truth_before.y), 10.0);
  EXPECT_LT(std::hypot(after.odometry.x - odometry_before.x, after.odometry.y - odometry_before.y),
            0.05);

  const testing::TempDir temp;
  std::ifstream in(testing::SourcePath("maps/scenarios/office_kidnap.xml"));
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  for (size_t pos; (pos = text.find("file=\"../")) != std::string::npos;) {
    text.replace(pos, 9, "file=\"" + testing::SourcePath("maps/"));
  }
  auto refused = [&](const std::string& from, const std::string& to, const std::string& why) {
    std::string broken = text;
    broken.replace(broken.find(from), from.size(), to);
    const std::string path = temp / "broken.xml";
    std::ofstream(path) << broken;
    try {
      simulation_core::LoadScenario(path);
      ADD_FAILURE() << "accepted " << to;
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(path + ":"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  refused("next_waypoint=\"0\"", "next_waypoint=\"11\"", "next_waypoint must be the index");
  refused("<teleport at_s=\"20\"",
          "<teleport at_s=\"30\" x=\"1\" y=\"6.5\" theta=\"0\" next_waypoint=\"0\"/>\n"
          "  <teleport at_s=\"20\"",
          "time order");
}

}  // namespace
}  // namespace structloc
