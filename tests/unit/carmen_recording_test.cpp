// CarmenRecording (carmen_recording.hpp): odometry and scans that arrive out
// of step come out of the log in time order, each scan with the odometric
// pose interpolated at its stamp and the laser's pose through the mounting;
// scans wait for a mounting heard late; Finish writes everything held, and
// scans the odometry does not reach on both sides are counted.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "structloc/log_formats/carmen_reader.hpp"
#include "structloc/log_formats/carmen_recording.hpp"
#include "temp_dir.hpp"

namespace structloc::log_formats {
namespace {

CarmenLaser Laser() {
  CarmenLaser laser;
  laser.start_angle = -1.0;
  laser.angular_resolution = 0.5;
  laser.field_of_view = 2.0;
  laser.max_range = 10.0;
  return laser;
}

std::vector<CarmenRecord> ReadBack(const std::string& path) {
  CarmenReader reader(path);
  std::vector<CarmenRecord> records;
  for (CarmenRecord r; reader.Next(r);) records.push_back(r);
  EXPECT_EQ(reader.Stats().malformed, 0u);
  return records;
}

TEST(CarmenRecording, LinesComeOutInTimeOrderWithTheOdometryAtEachScan) {
  const testing::TempDir temp;
  const std::string path = temp / "run.log";
  CarmenWriter writer(path);
  CarmenRecording recording(writer, geometry::Pose2D{0.2, 0.0, 0.0});
  // The robot drives along x at 1 m/s; odometry every 0.1 s, scans between
  // samples, one of them delivered after younger odometry.
  for (int k = 0; k <= 10; ++k) {
    recording.AddOdometry(0.1 * k, {0.1 * k, 0.0, 0.0}, 1.0, 0.0);
    if (k == 3) recording.AddScan(0.25, Laser(), {1.0f, 2.0f, 3.0f, 4.0f, 5.0f});
    if (k == 6) recording.AddScan(0.15, Laser(), {1.0f, 2.0f, 3.0f, 4.0f, 5.0f});  // late
    recording.WriteReady();
  }
  EXPECT_TRUE(recording.Finish());
  writer.Close();
  const auto records = ReadBack(path);
  ASSERT_EQ(records.size(), 13u);
  for (size_t i = 1; i < records.size(); ++i) EXPECT_LE(records[i - 1].stamp, records[i].stamp);
  std::vector<double> scan_x;
  for (const auto& r : records) {
    if (r.kind == CarmenRecord::Kind::kOdometry) continue;
    ASSERT_TRUE(r.robot_pose && r.laser_pose);
    EXPECT_NEAR(r.robot_pose->x, r.stamp, 1e-6) << "interpolated at the scan's stamp";
    EXPECT_NEAR(r.laser_pose->x, r.robot_pose->x + 0.2, 1e-6);
    scan_x.push_back(r.robot_pose->x);
  }
  ASSERT_EQ(scan_x.size(), 2u);
  EXPECT_NEAR(scan_x[0], 0.15, 1e-6);
  EXPECT_NEAR(scan_x[1], 0.25, 1e-6);
  EXPECT_EQ(recording.Stats().scans_nearest_odometry, 0u);
}

TEST(CarmenRecording, ScansWaitForAMountingHeardLate) {
  const testing::TempDir temp;
  const std::string path = temp / "run.log";
  CarmenWriter writer(path);
  CarmenRecording recording(writer, std::nullopt);
  for (int k = 0; k <= 20; ++k) {
    recording.AddOdometry(0.1 * k, {0.0, 0.1 * k, 1.5707963267948966}, 1.0, 0.0);
    if (k % 2 == 1) recording.AddScan(0.1 * k + 0.05, Laser(), {1.0f, 2.0f, 3.0f, 4.0f, 5.0f});
    recording.WriteReady();
  }
  EXPECT_EQ(recording.Stats().scans, 0u) << "no mounting yet";
  recording.SetMount({0.3, 0.0, 0.0});
  recording.WriteReady();
  EXPECT_GT(recording.Stats().scans, 0u);
  EXPECT_TRUE(recording.Finish());
  writer.Close();
  for (const auto& r : ReadBack(path)) {
    if (r.kind == CarmenRecord::Kind::kOdometry) continue;
    // Facing +y: the laser 0.3 m ahead of the robot is 0.3 m further along y.
    EXPECT_NEAR(r.laser_pose->y, r.robot_pose->y + 0.3, 1e-6);
  }
}

TEST(CarmenRecording, FinishWritesEverythingHeldAndCountsScansBeyondTheOdometry) {
  const testing::TempDir temp;
  const std::string path = temp / "run.log";
  CarmenWriter writer(path);
  CarmenRecording recording(writer, std::nullopt);
  recording.AddScan(0.5, Laser(), {1.0f, 2.0f, 3.0f, 4.0f, 5.0f});  // before any odometry
  recording.AddOdometry(1.0, {1.0, 0.0, 0.0}, 0.0, 0.0);
  recording.AddOdometry(1.1, {1.1, 0.0, 0.0}, 0.0, 0.0);
  recording.AddScan(1.05, Laser(), {1.0f, 2.0f, 3.0f, 4.0f, 5.0f});
  recording.AddScan(1.3, Laser(), {1.0f, 2.0f, 3.0f, 4.0f, 5.0f});  // beyond the last sample
  recording.AddOdometry(NAN, {1.2, 0.0, 0.0}, 0.0, 0.0);
  recording.WriteReady();
  EXPECT_FALSE(recording.Finish()) << "no mounting was ever heard";
  writer.Close();
  EXPECT_EQ(ReadBack(path).size(), 5u);
  EXPECT_EQ(recording.Stats().scans, 3u);
  EXPECT_EQ(recording.Stats().scans_nearest_odometry, 2u);
  EXPECT_EQ(recording.Stats().rejected, 1u);
}

}  // namespace
}  // namespace structloc::log_formats
