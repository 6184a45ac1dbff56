// A CARMEN log from live streams (see header).
#include "structloc/log_formats/carmen_recording.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace structloc::log_formats {
namespace {

template <class Line>
void InsertInOrder(std::deque<Line>& lines, Line line) {
  auto it = std::upper_bound(lines.begin(), lines.end(), line.stamp,
                             [](double t, const Line& l) { return t < l.stamp; });
  lines.insert(it, std::move(line));
}

}  // namespace

CarmenRecording::CarmenRecording(CarmenWriter& writer, std::optional<geometry::Pose2D> mount,
                                 const CarmenRecordingOptions& options)
    : writer_(writer), mount_(mount), options_(options) {}

void CarmenRecording::SetMount(const geometry::Pose2D& mount) {
  if (geometry::IsFinite(mount)) mount_ = mount;
}

void CarmenRecording::AddOdometry(double stamp, const geometry::Pose2D& pose, double tv,
                                  double rv) {
  if (!std::isfinite(stamp) || !geometry::IsFinite(pose)) {
    ++stats_.rejected;
    return;
  }
  if (!std::isfinite(tv)) tv = 0.0;
  if (!std::isfinite(rv)) rv = 0.0;
  const Odometry odometry{stamp, pose, tv, rv};
  InsertInOrder(history_, odometry);
  newest_odometry_ = std::max(newest_odometry_.value_or(stamp), stamp);
  while (!history_.empty() &&
         history_.front().stamp < *newest_odometry_ - options_.odometry_history_s &&
         history_.size() > 2) {
    history_.pop_front();
  }
  if (stamp <= written_until_) {  // younger lines are out already
    ++stats_.odometry;
    writer_.Odometry(stamp, pose, tv, rv);
    return;
  }
  InsertInOrder(held_odometry_, odometry);
}

void CarmenRecording::AddScan(double stamp, const CarmenLaser& laser, std::vector<float> ranges) {
  if (!std::isfinite(stamp)) {
    ++stats_.rejected;
    return;
  }
  Scan scan{stamp, laser, std::move(ranges)};
  if (stamp <= written_until_ && mount_) {
    ++stats_.scans_late;
    WriteScan(scan);
    return;
  }
  InsertInOrder(held_scans_, std::move(scan));
}

void CarmenRecording::WriteReady() {
  if (newest_odometry_) WriteUntil(*newest_odometry_ - options_.hold_s);
  // Too many held (odometry stopped): the oldest go out with what there is.
  if (mount_ && held_scans_.size() > options_.max_held_scans)
    WriteUntil(held_scans_[held_scans_.size() - options_.max_held_scans - 1].stamp);
}

bool CarmenRecording::Finish() {
  const bool had_mount = mount_.has_value() || held_scans_.empty();
  if (!mount_) mount_ = geometry::Pose2D{};
  WriteUntil(std::numeric_limits<double>::infinity());
  return had_mount;
}

void CarmenRecording::WriteUntil(double until) {
  while (true) {
    const bool odometry = !held_odometry_.empty() && held_odometry_.front().stamp <= until;
    const bool scan = !held_scans_.empty() && held_scans_.front().stamp <= until;
    if (!odometry && !scan) return;
    // Of the two, the older first (odometry first at equal stamps).
    if (odometry && (!scan || held_odometry_.front().stamp <= held_scans_.front().stamp)) {
      const Odometry o = held_odometry_.front();
      held_odometry_.pop_front();
      ++stats_.odometry;
      writer_.Odometry(o.stamp, o.pose, o.tv, o.rv);
      written_until_ = std::max(written_until_, o.stamp);
      continue;
    }
    if (!mount_) return;  // scans wait for the mounting
    WriteScan(held_scans_.front());
    written_until_ = std::max(written_until_, held_scans_.front().stamp);
    held_scans_.pop_front();
  }
}

void CarmenRecording::WriteScan(const Scan& scan) {
  bool nearest = false;
  const auto odometry = OdometryAt(scan.stamp, &nearest);
  if (!odometry || nearest) ++stats_.scans_nearest_odometry;
  const geometry::Pose2D robot = odometry ? odometry->pose : geometry::Pose2D{};
  const double tv = odometry ? odometry->tv : 0.0;
  const double rv = odometry ? odometry->rv : 0.0;
  writer_.RobotLaser(scan.stamp, scan.laser, scan.ranges, geometry::Compose(robot, *mount_), robot,
                     tv, rv);
  ++stats_.scans;
}

std::optional<CarmenRecording::Odometry> CarmenRecording::OdometryAt(double t,
                                                                     bool* nearest) const {
  if (history_.empty()) return std::nullopt;
  auto it = std::lower_bound(history_.begin(), history_.end(), t,
                             [](const Odometry& o, double s) { return o.stamp < s; });
  if (it == history_.end()) {
    *nearest = true;
    return history_.back();
  }
  if (it->stamp == t) return *it;
  if (it == history_.begin()) {
    *nearest = true;
    return *it;
  }
  const Odometry& a = *(it - 1);
  const Odometry& b = *it;
  const double f = (t - a.stamp) / (b.stamp - a.stamp);
  const Odometry& near = f < 0.5 ? a : b;
  return Odometry{t, geometry::Interpolate(a.pose, b.pose, f), near.tv, near.rv};
}

}  // namespace structloc::log_formats
