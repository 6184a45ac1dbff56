// Each scan fitted alone to the map from its recorded pose (see header).
#include "structloc/map_building/scan_pose_fit.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>

#include "structloc/map_building/nearest_wall.hpp"

namespace structloc::map_building {
namespace {

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("scan pose fit option " + what);
}

// The signed distance of `p` from the surface `s` is nearest to (the wall's
// infinite line, or the pillar's circle) and its gradient with respect to p.
double SurfaceResidual(const world_model::WorldModel& world, const NearestSurface& s,
                       const Eigen::Vector2d& p, Eigen::Vector2d* gradient) {
  if (s.kind == NearestSurface::Kind::kWall) {
    const auto& wall = world.Walls()[s.index];
    const Eigen::Vector2d along = (wall.b - wall.a).normalized();
    *gradient = Eigen::Vector2d(-along.y(), along.x());
    return gradient->dot(p - wall.a);
  }
  const auto& pillar = world.Cylinders()[s.index];
  const Eigen::Vector2d out = p - pillar.centre;
  const double n = out.norm();
  *gradient = n > 1e-9 ? Eigen::Vector2d(out / n) : Eigen::Vector2d(1.0, 0.0);
  return n - pillar.radius;
}

}  // namespace

std::vector<ScanPoseFit> FitScanPoses(const world_model::WorldModel& world,
                                      const std::vector<PosedScan>& scans,
                                      const ScanPoseFitOptions& o) {
  Require(o.near_m > 0.0, "near_m must be positive");
  Require(o.max_iterations > 0, "max_iterations must be positive");
  Require(o.min_readings >= 3, "min_readings must be at least 3");
  Require(o.prior_sigma_m > 0.0 && o.prior_sigma_rad > 0.0,
          "prior_sigma_m and prior_sigma_rad must be positive");
  const NearestWallIndex index(world, o.near_m);
  const Eigen::Vector3d prior_information(1.0 / (o.prior_sigma_m * o.prior_sigma_m),
                                          1.0 / (o.prior_sigma_m * o.prior_sigma_m),
                                          1.0 / (o.prior_sigma_rad * o.prior_sigma_rad));
  std::vector<ScanPoseFit> fits;
  fits.reserve(scans.size());
  for (const auto& scan : scans) {
    ScanPoseFit fit;
    fit.index = scan.index;
    geometry::Pose2D pose = scan.laser_pose;
    for (int iteration = 0; iteration < o.max_iterations; ++iteration) {
      Eigen::Matrix3d h = prior_information.asDiagonal();
      const Eigen::Vector3d offset(pose.x - scan.laser_pose.x, pose.y - scan.laser_pose.y,
                                   geometry::WrapAngle(pose.theta - scan.laser_pose.theta));
      Eigen::Vector3d g = prior_information.cwiseProduct(offset);
      size_t used = 0;
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
        ++used;
      }
      fit.readings = used;
      if (used < o.min_readings) break;
      const Eigen::Vector3d step = -h.ldlt().solve(g);
      if (!step.allFinite()) break;
      pose.x += step.x();
      pose.y += step.y();
      pose.theta = geometry::WrapAngle(pose.theta + step.z());
      fit.fitted = true;
      if (step.head<2>().norm() < 1e-5 && std::abs(step.z()) < 1e-5) break;
    }
    fit.fitted = fit.fitted && fit.readings >= o.min_readings;
    if (fit.fitted) {
      fit.offset = {pose.x - scan.laser_pose.x, pose.y - scan.laser_pose.y,
                    geometry::WrapAngle(pose.theta - scan.laser_pose.theta)};
    }
    fits.push_back(fit);
  }
  return fits;
}

}  // namespace structloc::map_building
