// Message conversions of the localisation component (see header).
#include "structloc/localisation/localisation_conversions.hpp"

#include <algorithm>
#include <cmath>

#include "structloc/dds_common/ros_conversions.hpp"

namespace structloc::localisation {

localisation_core::ScanInput FromLaserScan(const sensor_msgs::msg::LaserScan& msg) {
  localisation_core::ScanInput s;
  s.stamp = dds_common::FromRosTime(msg.header().stamp());
  s.angle_min = msg.angle_min();
  s.angle_max = msg.angle_max();
  s.angle_increment = msg.angle_increment();
  s.time_increment = msg.time_increment();
  s.range_min = msg.range_min();
  s.range_max = msg.range_max();
  s.ranges = msg.ranges().data();
  s.count = msg.ranges().size();
  return s;
}

localisation_core::SessionScan ToSessionScan(const sensor_msgs::msg::LaserScan& msg) {
  localisation_core::SessionScan s;
  s.geometry = FromLaserScan(msg);
  s.geometry.ranges = nullptr;
  s.geometry.count = 0;
  s.ranges = msg.ranges();
  return s;
}

StampedPose2D FromOdometry(const nav_msgs::msg::Odometry& msg) {
  const auto& p = msg.pose().pose();
  return {dds_common::FromRosTime(msg.header().stamp()),
          {p.position().x(), p.position().y(), dds_common::YawFromQuaternion(p.orientation())}};
}

StampedPose2D FromPoseWithCovariance(const geometry_msgs::msg::PoseWithCovarianceStamped& msg,
                                     Eigen::Matrix3d* covariance) {
  const auto& p = msg.pose().pose();
  const auto& c = msg.pose().covariance();
  // 6x6 row-major (x y z rotX rotY rotZ): take x, y, rotZ.
  const int idx[3] = {0, 1, 5};
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) (*covariance)(r, k) = c[static_cast<size_t>(idx[r] * 6 + idx[k])];
  }
  return {dds_common::FromRosTime(msg.header().stamp()),
          {p.position().x(), p.position().y(), dds_common::YawFromQuaternion(p.orientation())}};
}

geometry_msgs::msg::PoseWithCovarianceStamped ToPoseWithCovarianceStamped(
    const localisation_core::TrackedPose& t, const dds_common::FrameIds& frames) {
  geometry_msgs::msg::PoseWithCovarianceStamped msg;
  msg.header().stamp(dds_common::ToRosTime(t.stamp));
  msg.header().frame_id(frames.map);
  msg.pose().pose().position().x(t.pose.x);
  msg.pose().pose().position().y(t.pose.y);
  msg.pose().pose().orientation(dds_common::ToQuaternion(t.pose.theta));
  auto& c = msg.pose().covariance();
  const int idx[3] = {0, 1, 5};
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      // Exactly symmetric on the wire, as clients (and Cholesky) expect: the
      // filter's product of Jacobians leaves last-bit differences.
      c[static_cast<size_t>(idx[r] * 6 + idx[k])] = 0.5 * (t.covariance(r, k) + t.covariance(k, r));
    }
  }
  c[14] = c[21] = c[28] = 1e6;  // z, roll, pitch: not estimated
  return msg;
}

tf2_msgs::msg::TFMessage ToMapToOdomTf(const geometry::Pose2D& m, double stamp,
                                       const dds_common::FrameIds& frames) {
  tf2_msgs::msg::TFMessage msg;
  msg.transforms().push_back(
      dds_common::ToPlanarTransform(m.x, m.y, m.theta, stamp, frames.map, frames.odom));
  return msg;
}

structloc_msgs::msg::ScanFeatures ToScanFeatures(const localisation_core::LocalisationResult& r,
                                                 double stamp, const dds_common::FrameIds& frames) {
  structloc_msgs::msg::ScanFeatures msg;
  msg.header().stamp(dds_common::ToRosTime(stamp));
  msg.header().frame_id(frames.laser);
  for (const auto& kind : r.features) {
    structloc_msgs::msg::FeatureSet set;
    set.kind(kind.kind);
    for (const auto& m : kind.matches) {
      if (kind.shape == localisation_core::FeatureShape::kLine) {
        structloc_msgs::msg::WallFeature f;
        f.r_m(m.r_m);
        f.alpha_rad(m.alpha_rad);
        f.member_count(static_cast<uint32_t>(m.members));
        f.model_id(m.model_id);
        f.residual_m(m.residual_m);
        set.lines().push_back(f);
      } else {
        structloc_msgs::msg::PointFeature f;
        f.x_m(m.x_m);
        f.y_m(m.y_m);
        f.radius_m(m.radius_m);
        f.member_count(static_cast<uint32_t>(m.members));
        f.model_id(m.model_id);
        f.residual_m(m.residual_m);
        set.points().push_back(f);
      }
    }
    msg.kinds().push_back(std::move(set));
  }
  return msg;
}

structloc_msgs::msg::LocalisationStatus ToStatus(const localisation_core::LocalisationResult& r,
                                                 const char* lost_reason,
                                                 const localisation_core::TrackerStats& stats,
                                                 uint64_t dropped, double stamp,
                                                 const dds_common::FrameIds& frames) {
  structloc_msgs::msg::LocalisationStatus s;
  s.header().stamp(dds_common::ToRosTime(stamp));
  s.header().frame_id(frames.map);
  s.quality(r.quality);
  s.phase("tracking");
  const bool lost = lost_reason != nullptr && lost_reason[0] != '\0';
  s.lost(lost);
  s.lost_reason(lost ? lost_reason : "");
  for (const auto& kind : r.features) {
    structloc_msgs::msg::FeatureCount c;
    c.kind(kind.kind);
    c.matched(static_cast<uint32_t>(kind.Matched()));
    c.expected(static_cast<uint32_t>(kind.expected));
    s.features().push_back(c);
  }
  s.scans_processed(stats.scans_processed);
  s.scans_dropped(dropped);
  s.scans_rejected(stats.Rejected());
  auto& t = s.timings();
  t.prefilter_us(r.times.prefilter_us);
  t.line_fit_us(r.times.line_fit_us);
  for (const auto& kind : r.features) {
    structloc_msgs::msg::FeatureTiming k;
    k.kind(kind.kind);
    k.extract_us(kind.extract_us);
    t.features().push_back(k);
  }
  t.solve_us(r.times.solve_us);
  t.total_us(r.times.total_us);
  return s;
}

geometry_msgs::msg::PoseArray ToPoseArray(
    const std::vector<localisation_core::Hypothesis>& hypotheses, double stamp,
    const dds_common::FrameIds& frames) {
  geometry_msgs::msg::PoseArray msg;
  msg.header().stamp(dds_common::ToRosTime(stamp));
  msg.header().frame_id(frames.map);
  for (const auto& h : hypotheses) {
    geometry_msgs::msg::Pose p;
    p.position().x(h.pose.x);
    p.position().y(h.pose.y);
    p.orientation(dds_common::ToQuaternion(h.pose.theta));
    msg.poses().push_back(p);
  }
  return msg;
}

structloc_msgs::msg::LocalisationStatus ToStartUpStatus(
    const std::vector<localisation_core::Hypothesis>& hypotheses, double stamp,
    const dds_common::FrameIds& frames) {
  structloc_msgs::msg::LocalisationStatus s;
  s.header().stamp(dds_common::ToRosTime(stamp));
  s.header().frame_id(frames.map);
  s.lost(true);
  s.phase(hypotheses.empty() ? "searching" : "holding");
  s.lost_reason(hypotheses.empty()
                    ? "no pose yet: searching the map"
                    : "no pose yet: weighing " + std::to_string(hypotheses.size()) + " hypotheses");
  double best = -INFINITY, sum = 0.0;
  for (const auto& h : hypotheses) best = std::max(best, h.log_likelihood);
  for (const auto& h : hypotheses) sum += std::exp(h.log_likelihood - best);
  for (const auto& h : hypotheses)
    s.hypothesis_weights().push_back(std::exp(h.log_likelihood - best) / sum);
  return s;
}

dds_common::HealthReport ToHealthReport(const localisation_core::SessionHealth& health) {
  dds_common::HealthReport report;
  switch (health.level) {
    case localisation_core::HealthLevel::kOk:
      report.level = dds_common::HealthLevel::kOk;
      break;
    case localisation_core::HealthLevel::kWarn:
      report.level = dds_common::HealthLevel::kWarn;
      break;
    case localisation_core::HealthLevel::kError:
      report.level = dds_common::HealthLevel::kError;
      break;
  }
  report.message = health.message;
  report.values = health.values;
  return report;
}

}  // namespace structloc::localisation
