// Free conversions from the simulation core's outputs to ROS 2 / structloc
// messages (tested without a participant).
#pragma once

#include "nav_msgs/msg/Odometry.h"
#include "sensor_msgs/msg/LaserScan.h"
#include "structloc/dds_common/topics.hpp"
#include "structloc/simulation_core/simulation.hpp"
#include "structloc_msgs/msg/WheelEncoders.h"

namespace structloc::simulator {

// `clock_offset_s` maps simulation time to message stamps; headers carry the
// frame ids of `frames`.
sensor_msgs::msg::LaserScan ToLaserScan(const simulation_core::SimScan& scan, double clock_offset_s,
                                        const dds_common::FrameIds& frames = {});
// Odometry in the odom frame with a covariance growing with the distance driven.
nav_msgs::msg::Odometry ToOdometry(const simulation_core::SimState& state, double distance_m,
                                   double clock_offset_s, const dds_common::FrameIds& frames = {});
// Ground truth: the true pose in the map frame, zero covariance.
nav_msgs::msg::Odometry ToGroundTruth(const simulation_core::SimState& state, double clock_offset_s,
                                      const dds_common::FrameIds& frames = {});
structloc_msgs::msg::WheelEncoders ToWheelEncoders(const simulation_core::SimState& state,
                                                   const kinematics::RobotParameters& nominal,
                                                   uint64_t previous_ticks, double clock_offset_s,
                                                   const dds_common::FrameIds& frames = {});

}  // namespace structloc::simulator
