// Each scan fitted alone to the map from its recorded pose (see header).
#include "structloc/map_building/scan_pose_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "structloc/map_building/nearest_wall.hpp"
#include "structloc/map_building/option_check.hpp"
#include "structloc/map_building/quantile.hpp"

namespace structloc::map_building {
namespace {

// Bad options are refused as "scan pose fit option ...".
constexpr const char* kOptions = "scan pose fit";

// |p - centre|, and its gradient with respect to p (the unit vector away).
double DistanceFrom(const Eigen::Vector2d& centre, const Eigen::Vector2d& p,
                    Eigen::Vector2d* gradient) {
  const Eigen::Vector2d out = p - centre;
  const double n = out.norm();
  *gradient = n > 1e-12 ? Eigen::Vector2d(out / n) : Eigen::Vector2d::Zero();
  return n;
}

// The signed distance of `p` from the surface `s` it was paired with, as the
// pairing measured it (a wall segment: its line between the ends, the nearer
// end beyond them; a pillar: its circle), and the gradient with respect to p.
double SurfaceResidual(const world_model::WorldModel& world, const NearestSurface& s,
                       const Eigen::Vector2d& p, Eigen::Vector2d* gradient) {
  if (s.kind == NearestSurface::Kind::kPillar) {
    const auto& pillar = world.Cylinders()[s.index];
    return DistanceFrom(pillar.centre, p, gradient) - pillar.radius;
  }
  const auto& wall = world.Walls()[s.index];
  const double t = (wall.b - wall.a).dot(p - wall.a) / (wall.b - wall.a).squaredNorm();
  if (t < 0.0 || t > 1.0) return DistanceFrom(t < 0.0 ? wall.a : wall.b, p, gradient);
  *gradient = Eigen::Vector2d(std::cos(wall.line.alpha), std::sin(wall.line.alpha));
  return gradient->dot(p) - wall.line.r;
}

// The fitted pose minus the recorded one: x, y in the map frame, theta wrapped.
geometry::Pose2D OffsetFrom(const geometry::Pose2D& recorded, const geometry::Pose2D& pose) {
  return {pose.x - recorded.x, pose.y - recorded.y,
          geometry::WrapAngle(pose.theta - recorded.theta)};
}

// Readings of `scan` near the map at `pose`.
size_t ReadingsNear(const NearestWallIndex& index, const PosedScan& scan,
                    const geometry::Pose2D& pose) {
  size_t near = 0;
  for (const auto& q : scan.points)
    near += index.Nearest(pose.Apply(q)).kind != NearestSurface::Kind::kNone;
  return near;
}

// One scan fitted from its recorded pose; `prior_information` is the inverse
// variance of the pull towards that pose (x, y, theta).
ScanPoseFit FitOneScan(const world_model::WorldModel& world, const NearestWallIndex& index,
                       const PosedScan& scan, const Eigen::Vector3d& prior_information,
                       const ScanPoseFitOptions& options) {
  ScanPoseFit fit;
  fit.index = scan.index;
  geometry::Pose2D pose = scan.laser_pose;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    Eigen::Matrix3d h = prior_information.asDiagonal();
    const geometry::Pose2D offset = OffsetFrom(scan.laser_pose, pose);
    Eigen::Vector3d g =
        prior_information.cwiseProduct(Eigen::Vector3d(offset.x, offset.y, offset.theta));
    size_t paired = 0;
    for (const auto& q : scan.points) {
      const Eigen::Vector2d p = pose.Apply(q);
      const NearestSurface surface = index.Nearest(p);
      if (surface.kind == NearestSurface::Kind::kNone) continue;
      Eigen::Vector2d n;
      const double r = SurfaceResidual(world, surface, p, &n);
      // d p / d (x, y, theta) = [1 0 -(p - t).y; 0 1 (p - t).x]
      const Eigen::Vector2d lever = p - pose.Translation();
      const Eigen::Vector3d j(n.x(), n.y(), n.x() * -lever.y() + n.y() * lever.x());
      h += j * j.transpose();
      g += j * r;
      ++paired;
    }
    if (paired < options.min_readings) break;
    const Eigen::Vector3d step = -h.ldlt().solve(g);
    if (!step.allFinite()) break;
    pose.x += step.x();
    pose.y += step.y();
    pose.theta = geometry::WrapAngle(pose.theta + step.z());
    fit.iterations = iteration + 1;
    if (step.head<2>().norm() < 1e-5 && std::abs(step.z()) < 1e-5) {
      fit.converged = true;
      break;
    }
  }
  fit.readings = ReadingsNear(index, scan, pose);
  fit.fitted = fit.iterations > 0 && fit.readings >= options.min_readings;
  fit.converged = fit.converged && fit.fitted;
  if (fit.fitted) fit.offset = OffsetFrom(scan.laser_pose, pose);
  return fit;
}

}  // namespace

std::vector<ScanPoseFit> FitScanPoses(const world_model::WorldModel& world,
                                      const std::vector<PosedScan>& scans,
                                      const ScanPoseFitOptions& options) {
  RequireOption(options.near_m > 0.0, kOptions, "near_m must be positive");
  RequireOption(options.max_iterations > 0, kOptions, "max_iterations must be positive");
  RequireOption(options.min_readings >= 3, kOptions, "min_readings must be at least 3");
  RequireOption(options.prior_sigma_m > 0.0, kOptions, "prior_sigma_m must be positive");
  RequireOption(options.prior_sigma_rad > 0.0, kOptions, "prior_sigma_rad must be positive");
  const NearestWallIndex index(world, options.near_m);
  const double xy = 1.0 / (options.prior_sigma_m * options.prior_sigma_m);
  const Eigen::Vector3d prior_information(
      xy, xy, 1.0 / (options.prior_sigma_rad * options.prior_sigma_rad));
  std::vector<ScanPoseFit> fits;
  fits.reserve(scans.size());
  for (const auto& scan : scans)
    fits.push_back(FitOneScan(world, index, scan, prior_information, options));
  return fits;
}

ScanPoseFitSummary SummarisePoseFits(const std::vector<ScanPoseFit>& fits, size_t farthest) {
  ScanPoseFitSummary summary;
  summary.scans = fits.size();
  std::vector<double> shifts_m, turns_rad;
  std::vector<size_t> converged;
  for (size_t i = 0; i < fits.size(); ++i) {
    summary.fitted += fits[i].fitted;
    if (!fits[i].converged) continue;
    converged.push_back(i);
    shifts_m.push_back(fits[i].offset.Translation().norm());
    turns_rad.push_back(std::abs(fits[i].offset.theta));
  }
  summary.converged = converged.size();
  if (converged.empty()) return summary;
  summary.median_shift_m = Quantile(shifts_m, 0.5);
  summary.p90_shift_m = Quantile(shifts_m, 0.9);
  summary.max_shift_m = *std::max_element(shifts_m.begin(), shifts_m.end());
  summary.median_turn_rad = Quantile(turns_rad, 0.5);
  summary.p90_turn_rad = Quantile(turns_rad, 0.9);
  summary.max_turn_rad = *std::max_element(turns_rad.begin(), turns_rad.end());
  std::vector<size_t> order(converged.size());
  std::iota(order.begin(), order.end(), 0);
  const size_t shown = std::min(farthest, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<long>(shown), order.end(),
                    [&](size_t a, size_t b) { return shifts_m[a] > shifts_m[b]; });
  for (size_t k = 0; k < shown; ++k) summary.farthest.push_back(converged[order[k]]);
  return summary;
}

}  // namespace structloc::map_building
