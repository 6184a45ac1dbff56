// Live evaluation over DDS (see header).
#include "structloc/evaluation/live_evaluator.hpp"

#include <chrono>

#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/rendering/map_canvas.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "structloc_msgs/msg/LocalisationStatusPubSubTypes.h"

namespace structloc::evaluation {
namespace {
log_formats::StampedPose Stamped(const builtin_interfaces::msg::Time& t,
                                 const geometry_msgs::msg::Pose& p) {
  return {dds_common::FromRosTime(t),
          {p.position().x(), p.position().y(), dds_common::YawFromQuaternion(p.orientation())}};
}
}  // namespace

LiveEvaluator::LiveEvaluator(dds_common::Node& node, const geometry::Pose2D& initial_pose)
    : node_(node), initial_pose_(initial_pose) {
  subscriptions_.push_back(node.Subscribe<nav_msgs::msg::OdometryPubSubType>(
      dds_common::topics::kGroundTruth, [this](const nav_msgs::msg::Odometry& m) {
        std::lock_guard<std::mutex> lock(mutex_);
        truth_.push_back(Stamped(m.header().stamp(), m.pose().pose()));
        snapshot_.sim_time_s = truth_.back().stamp - truth_.front().stamp;
      }));
  subscriptions_.push_back(node.Subscribe<nav_msgs::msg::OdometryPubSubType>(
      dds_common::topics::kOdom, [this](const nav_msgs::msg::Odometry& m) {
        std::lock_guard<std::mutex> lock(mutex_);
        auto s = Stamped(m.header().stamp(), m.pose().pose());
        s.pose = geometry::Compose(initial_pose_, s.pose);
        odometry_.push_back(s);
      }));
  subscriptions_.push_back(node.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
      dds_common::topics::kPose, [this](const geometry_msgs::msg::PoseWithCovarianceStamped& m) {
        const double arrived =
            std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
                .count();
        std::lock_guard<std::mutex> lock(mutex_);
        pose_arrivals_s_.push_back(arrived);
        estimate_.push_back(Stamped(m.header().stamp(), m.pose().pose()));
        ++snapshot_.poses;
        // Truth at the pose's stamp, interpolated between the samples around it.
        const auto& e = estimate_.back();
        for (size_t i = truth_.size(); i-- > 1;) {
          if (truth_[i - 1].stamp <= e.stamp && e.stamp <= truth_[i].stamp) {
            const double f = (e.stamp - truth_[i - 1].stamp) /
                             std::max(1e-9, truth_[i].stamp - truth_[i - 1].stamp);
            const auto t = geometry::Interpolate(truth_[i - 1].pose, truth_[i].pose, f);
            snapshot_.position_error_m = (t.Translation() - e.pose.Translation()).norm();
            snapshot_.heading_error_rad = geometry::WrapAngle(e.pose.theta - t.theta);
            break;
          }
          if (truth_[i].stamp < e.stamp) break;
        }
      }));
  subscriptions_.push_back(node.Subscribe<structloc_msgs::msg::LocalisationStatusPubSubType>(
      dds_common::topics::kStatus, [this](const structloc_msgs::msg::LocalisationStatus& s) {
        if (s.phase() != "tracking") return;  // no pose yet: searching or weighing hypotheses
        std::lock_guard<std::mutex> lock(mutex_);
        snapshot_.matched_features = 0;
        snapshot_.expected_features = 0;
        for (const auto& kind : s.features()) {
          snapshot_.matched_features += static_cast<int>(kind.matched());
          snapshot_.expected_features += static_cast<int>(kind.expected());
        }
        snapshot_.quality = s.quality();
        snapshot_.lost = s.lost();
        if (s.lost()) ++lost_;
      }));
}

LiveSnapshot LiveEvaluator::Snapshot() {
  std::lock_guard<std::mutex> lock(mutex_);
  return snapshot_;
}
std::vector<log_formats::StampedPose> LiveEvaluator::Truth() {
  std::lock_guard<std::mutex> lock(mutex_);
  return truth_;
}
std::vector<double> LiveEvaluator::PoseArrivals() {
  std::lock_guard<std::mutex> lock(mutex_);
  return pose_arrivals_s_;
}
std::vector<log_formats::StampedPose> LiveEvaluator::Estimate() {
  std::lock_guard<std::mutex> lock(mutex_);
  return estimate_;
}
std::vector<log_formats::StampedPose> LiveEvaluator::OdometryInMap() {
  std::lock_guard<std::mutex> lock(mutex_);
  return odometry_;
}
uint64_t LiveEvaluator::LostCount() {
  std::lock_guard<std::mutex> lock(mutex_);
  return lost_;
}

replay::TrajectoryError LiveEvaluator::EstimateError() {
  return replay::CompareTrajectories(Estimate(), Truth(), 0.011);
}
replay::TrajectoryError LiveEvaluator::OdometryError() {
  return replay::CompareTrajectories(OdometryInMap(), Truth(), 0.011);
}

void LiveEvaluator::RenderFigure(const std::string& map_path, const std::string& png_path,
                                 const std::string& title) {
  const auto world = world_model::LoadWorldModel(map_path);
  rendering::MapCanvas canvas(world.Bounds(), 40.0);
  canvas.DrawWorld(world);
  auto points = [](const std::vector<log_formats::StampedPose>& poses) {
    std::vector<Eigen::Vector2d> out;
    for (const auto& p : poses) out.push_back(p.pose.Translation());
    return out;
  };
  canvas.DrawPath(points(OdometryInMap()), rendering::colours::kOdometry, 2);
  canvas.DrawPath(points(Truth()), rendering::colours::kTruth, 5);
  canvas.DrawPath(points(Estimate()), rendering::colours::kEstimate, 2);
  canvas.DrawLegend({{rendering::colours::kTruth, "true path"},
                     {rendering::colours::kOdometry, "odometry only"},
                     {rendering::colours::kEstimate, "localised estimate (structloc)"}});
  canvas.DrawTitle(title);
  canvas.Save(png_path);
}

}  // namespace structloc::evaluation
