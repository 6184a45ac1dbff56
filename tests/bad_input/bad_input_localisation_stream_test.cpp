// Bad input through real DataWriters: the localisation component receives a
// good simulated stream interleaved with every kind of bad scan and odometry
// sample (REP-117 specials, NaN, inf, zero or mismatched beam counts, an
// angle_increment of 0, stamps out of order or far in the future, odometry
// jumps and NaNs). It must stay up, report what it rejected and why, never
// publish a NaN, and keep localising on the good data.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "localisation_feed.hpp"
#include "pose_argument.hpp"
#include "structloc/process/child_process.hpp"
#include "test_domains.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
constexpr int kDomain = testing::domains::kLocalisationBadInput;
constexpr double kOffset = testing::LocalisationFeed::kClockOffset;

TEST(LocalisationBadInput, StaysUpReportsRejectionsAndKeepsLocalising) {
  auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/office_people.xml"));
  scenario.duration_s = 8.0;
  testing::LocalisationFeed feed("bad_input_feeder", kDomain);
  const auto& p0 = scenario.initial_pose;
  process::ChildProcess localisation(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_localisation",
      {"--domain", std::to_string(kDomain), "--qos", testing::ShippedQos(), "--params",
       testing::SimulatedRobotParams(), "--initial-pose", testing::PoseArgument(p0)});
  ASSERT_TRUE(feed.WaitForLocalisation(testing::kGenerousTimeout)) << localisation.CapturedOutput();
  int bad_sent = 0;
  size_t good_sent = 0;
  feed.Play(
      scenario, [&](int k, const simulation_core::SimState& s, sensor_msgs::msg::LaserScan& scan) {
        if (k % 3 != 0) {
          ++good_sent;
          return true;
        }
        // One bad input of each kind, in turn, instead of every third good scan.
        ++bad_sent;
        const double stamp = dds_common::FromRosTime(scan.header().stamp());
        switch ((k / 3) % 9) {
          case 0:
            for (auto& r : scan.ranges()) r = std::nanf("");
            return true;  // processed: every beam counted as non-finite, robot reported lost
          case 1:
            scan.ranges().clear();
            return true;
          case 2:
            scan.ranges().resize(scan.ranges().size() / 2);
            return true;
          case 3:
            scan.angle_increment(0.0f);
            return true;
          case 4:
            scan.header().stamp(dds_common::ToRosTime(stamp - 5.0));
            return true;
          case 5:
            scan.header().stamp(dds_common::ToRosTime(stamp + 3600.0));
            return true;
          case 6:
            for (size_t i = 0; i < scan.ranges().size(); i += 2) {
              scan.ranges()[i] = std::numeric_limits<float>::infinity();  // REP-117: no return
            }
            return true;
          case 7: {
            auto jump = simulator::ToOdometry(s, 0.0, kOffset);
            jump.header().stamp(dds_common::ToRosTime(kOffset + s.time + 0.001));
            jump.pose().pose().position().x(1e6);
            feed.OdometryWriter().Write(jump);
            return false;
          }
          default: {
            auto nan = simulator::ToOdometry(s, 0.0, kOffset);
            nan.header().stamp(dds_common::ToRosTime(kOffset + s.time + 0.002));
            nan.pose().pose().position().y(std::nan(""));
            feed.OdometryWriter().Write(nan);
            return false;
          }
        }
      });
  // Rejections are reported with their reasons (in the diagnostics, which
  // the component publishes about once a second: wait for them).
  const std::vector<std::string> reasons = {
      "rejected: empty scan",
      "rejected: beam count does not match the scan angles",
      "rejected: angle_increment zero or non-finite, or bad limits",
      "rejected: scan stamp not after the previous scan",
      "rejected: scan stamp too far ahead of the odometry",
      "rejected: odometry jump faster than max_odometry_speed_m_s or "
      "max_odometry_turn_rate_rad_s",
      "rejected: odometry pose or stamp not finite, or its orientation not a unit quaternion"};
  const auto counted = [&](const std::string& reason) {
    const auto count = feed.Value(reason);
    return !count.empty() && std::stol(count) > 0;
  };
  EXPECT_TRUE(testing::WaitUntil([&] {
    return std::all_of(reasons.begin(), reasons.end(), counted) && feed.Poses() > good_sent / 2;
  })) << localisation.CapturedOutput();
  EXPECT_FALSE(localisation.Poll().has_value()) << "the component died:\n"
                                                << localisation.CapturedOutput();
  EXPECT_FALSE(feed.NonFinitePoseSeen());
  EXPECT_GT(bad_sent, 20);
  for (const auto& reason : reasons) EXPECT_TRUE(counted(reason)) << reason;
  // And it kept localising on the good scans.
  EXPECT_GT(feed.Poses(), good_sent / 2);
  EXPECT_LT(feed.WorstError(), 0.03);
}

}  // namespace
}  // namespace structloc
