// Doubt about a tracked pose, and the kidnapping it may hide (see header).
#include "structloc/localisation_core/global/kidnap_watch.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace structloc::localisation_core {

void CheckKidnapOptions(const KidnapOptions& o) {
  auto require = [](bool ok, const char* name, const char* range) {
    if (!ok)
      throw std::invalid_argument(std::string("kidnap options: ") + name + " must be " + range);
  };
  require(o.unexplained_share >= 0.0 && o.unexplained_share <= 1.0, "unexplained_share",
          "in [0, 1]");
  require(o.after_s >= 0.0 && o.after_s <= 3600.0, "after_s", "in [0, 3600]");
  require(o.check_period_s >= 0.0 && o.check_period_s <= 60.0, "check_period_s", "in [0, 60]");
  require(o.search_period_s >= 0.0 && o.search_period_s <= 600.0, "search_period_s", "in [0, 600]");
  require(o.max_search_period_s >= o.search_period_s && o.max_search_period_s <= 3600.0,
          "max_search_period_s", "in [search_period_s, 3600]");
  require(o.min_jump_m >= 0.0 && o.min_jump_rad >= 0.0, "min_jump_m / min_jump_rad", "at least 0");
  require(o.max_share_drop >= 0.0 && o.max_share_drop <= 1.0, "max_share_drop", "in [0, 1]");
  require(o.min_share_gain >= 0.0 && o.min_share_gain <= 1.0, "min_share_gain", "in [0, 1]");
  require(o.max_share_below_normal >= 0.0 && o.max_share_below_normal <= 1.0,
          "max_share_below_normal", "in [0, 1]");
  require(o.search_work_per_scan >= 0.0 && o.search_work_per_scan <= 1e12, "search_work_per_scan",
          "in [0, 1e12]");
  require(o.search_work_banked >= o.search_work_per_scan && o.search_work_banked <= 1e15,
          "search_work_banked", "in [search_work_per_scan, 1e15]");
  require(o.fit_points >= 10 && o.fit_points <= 5000, "fit_points", "in [10, 5000]");
}

KidnapWatch::KidnapWatch(const GlobalLocaliser& localiser, const geometry::Pose2D& sensor_mount,
                         const KidnapOptions& options)
    : localiser_(localiser),
      mount_(sensor_mount),
      options_(options),
      search_period_s_(options.search_period_s),
      budget_(options.search_work_banked) {
  CheckKidnapOptions(options_);
}

void KidnapWatch::Clear() {
  last_check_s_.reset();
  last_search_s_.reset();
  doubt_since_.reset();
  last_share_.reset();
  doubt_s_ = 0.0;
  search_period_s_ = options_.search_period_s;
  told_until_.reset();
}

void KidnapWatch::Doubt(double stamp) {
  told_until_ = stamp + options_.max_search_period_s;
  doubt_since_ = std::min(doubt_since_.value_or(stamp), stamp - options_.after_s);
  doubt_s_ = std::max(doubt_s_, options_.after_s);
}

bool KidnapWatch::Observe(const std::vector<Eigen::Vector2d>& laser_points, double stamp,
                          const geometry::Pose2D& tracked, bool lost) {
  budget_ = std::min(budget_ + options_.search_work_per_scan, options_.search_work_banked);
  const bool checked = CheckDue(stamp, lost);
  if (checked) {
    last_check_s_ = stamp;
    const auto points = localiser_.FitPoints(laser_points, options_.fit_points);
    last_share_ = localiser_.FitAt(points, geometry::Compose(tracked, mount_), 0.1).share;
  }
  const double floor = std::max(options_.unexplained_share,
                                normal_share_ ? *normal_share_ - options_.max_share_drop : 0.0);
  if (told_until_ && stamp > *told_until_) told_until_.reset();
  const bool unexplained = lost || told_until_ || (last_share_ && *last_share_ < floor);
  // Only shares near the normal update it: a pose that explains a little
  // more than the floor (a robot carried to a place like the one it was in,
  // tracked a metre off) would otherwise pull it down to its own share, and
  // then nothing would be doubted.
  const double near_normal = normal_share_ ? *normal_share_ - 0.5 * options_.max_share_drop : 0.0;
  if (!unexplained && checked && *last_share_ >= near_normal) {
    normal_share_ = normal_share_ ? 0.9 * *normal_share_ + 0.1 * *last_share_ : *last_share_;
  }
  if (!unexplained) {
    doubt_since_.reset();
    doubt_s_ = 0.0;
    last_search_s_.reset();
    search_period_s_ = options_.search_period_s;
    return false;
  }
  if (!doubt_since_) doubt_since_ = stamp;
  doubt_s_ = stamp - *doubt_since_;
  if (doubt_s_ < options_.after_s || !CanAfford()) return false;
  return !last_search_s_ || stamp - *last_search_s_ >= search_period_s_;
}

KidnapWatch::Comparison KidnapWatch::Compare(const std::vector<Eigen::Vector2d>& laser_points,
                                             const geometry::Pose2D& found,
                                             const geometry::Pose2D& tracked) const {
  const auto points = localiser_.FitPoints(laser_points, options_.fit_points);
  auto share = [&](const geometry::Pose2D& robot) {
    return localiser_.FitAt(points, geometry::Compose(robot, mount_), 0.1).share;
  };
  const double at_found = share(found);
  Comparison c;
  c.far = std::hypot(found.x - tracked.x, found.y - tracked.y) > options_.min_jump_m ||
          std::abs(geometry::WrapAngle(found.theta - tracked.theta)) > options_.min_jump_rad;
  c.better = at_found >= share(tracked) + options_.min_share_gain;
  c.as_well_as_normal =
      !normal_share_ || at_found >= *normal_share_ - options_.max_share_below_normal;
  return c;
}

void KidnapWatch::Searched(double stamp) {
  if (last_search_s_)
    search_period_s_ = std::min(2.0 * search_period_s_, options_.max_search_period_s);
  last_search_s_ = stamp;
}

void KidnapWatch::Spent(uint64_t work) {
  last_work_ = std::min(static_cast<double>(work), options_.search_work_banked);
  budget_ -= static_cast<double>(work);
}

std::optional<Kidnapping> KidnapWatch::Jumped(double stamp,
                                              const std::vector<Eigen::Vector2d>& laser_points,
                                              const geometry::Pose2D& found,
                                              const geometry::Pose2D& tracked,
                                              Comparison* comparison) {
  // Not a kidnapping: the doubt goes on (and its searches keep backing off)
  // for as long as the scans stay unexplained.
  const Comparison c = Compare(laser_points, found, tracked);
  if (comparison) *comparison = c;
  if (!c.far) {
    told_until_.reset();  // found where it is tracked
    return std::nullopt;
  }
  if (!c.better || !c.as_well_as_normal) return std::nullopt;
  const Kidnapping kidnapping{stamp, tracked, found, doubt_s_};
  Clear();
  return kidnapping;
}

}  // namespace structloc::localisation_core
