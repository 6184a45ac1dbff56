// Test helper: synthetic laser scans ray-cast from a scene (the world model's
// surfaces plus unmodelled clutter) with seeded Gaussian range noise, and
// random rooms with corners, pillars and clutter for statistical tests.
#pragma once

#include <Eigen/Geometry>
#include <random>
#include <vector>

#include "structloc/localisation_core/localiser/localiser.hpp"
#include "structloc/localisation_core/scan/session_scan.hpp"
#include "structloc/localisation_core/tracking/pose_tracker.hpp"
#include "structloc/world_model/ray_cast.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::testing {

struct ScanSpec {
  int beams = 300;
  double field_of_view_rad = 2.0 * geometry::kPi;
  double max_range_m = 30.0;
  double noise_sigma_m = 0.0;
};

struct SyntheticScan {
  std::vector<float> ranges;
  double angle_min = 0.0;
  double angle_increment = 0.0;
  double max_range_m = 30.0;
  localisation_core::ScanView View() const {
    localisation_core::ScanView v;
    v.ranges = ranges.data();
    v.count = ranges.size();
    v.angle_min = angle_min;
    v.angle_increment = angle_increment;
    v.range_min = 0.0;
    v.range_max = max_range_m;
    return v;
  }
};

// The scan as the pose tracker takes it, stamped `stamp` (its ranges stay in `scan`).
inline localisation_core::ScanInput TrackerInput(const SyntheticScan& scan, double stamp) {
  localisation_core::ScanInput in;
  in.stamp = stamp;
  in.angle_min = scan.angle_min;
  in.angle_increment = scan.angle_increment;
  in.angle_max =
      scan.angle_min + scan.angle_increment * static_cast<double>(scan.ranges.size() - 1);
  in.range_max = scan.max_range_m;
  in.ranges = scan.ranges.data();
  in.count = scan.ranges.size();
  return in;
}

// The scan as the tracking session and the global start take it, stamped `stamp`.
inline localisation_core::SessionScan SessionScanOf(const SyntheticScan& synthetic, double stamp) {
  localisation_core::SessionScan scan;
  scan.geometry.stamp = stamp;
  scan.geometry.angle_min = synthetic.angle_min;
  scan.geometry.angle_increment = synthetic.angle_increment;
  scan.geometry.range_max = synthetic.max_range_m;
  scan.ranges = synthetic.ranges;
  return scan;
}

inline SyntheticScan CastScan(const world_model::Scene& scene, const geometry::Pose2D& sensor,
                              const ScanSpec& spec, std::mt19937& rng) {
  SyntheticScan scan;
  const bool full = spec.field_of_view_rad >= 2.0 * geometry::kPi - 1e-9;
  scan.angle_increment =
      full ? spec.field_of_view_rad / spec.beams : spec.field_of_view_rad / (spec.beams - 1);
  scan.angle_min = full ? -geometry::kPi : -0.5 * spec.field_of_view_rad;
  scan.max_range_m = spec.max_range_m;
  std::normal_distribution<double> noise(0.0, spec.noise_sigma_m);
  for (int i = 0; i < spec.beams; ++i) {
    const double a = sensor.theta + scan.angle_min + i * scan.angle_increment;
    const double range =
        scene.Cast(sensor.Translation(), {std::cos(a), std::sin(a)}, spec.max_range_m);
    const double noisy =
        std::isfinite(range) && spec.noise_sigma_m > 0 ? range + noise(rng) : range;
    scan.ranges.push_back(static_cast<float>(noisy));
  }
  return scan;
}

// Fraction of beams whose nearest surface is in `clutter` rather than `world`.
inline double ClutterFraction(const world_model::Scene& world, const world_model::Scene& clutter,
                              const geometry::Pose2D& sensor, const ScanSpec& spec) {
  int hits = 0;
  const bool full = spec.field_of_view_rad >= 2.0 * geometry::kPi - 1e-9;
  const double inc =
      full ? spec.field_of_view_rad / spec.beams : spec.field_of_view_rad / (spec.beams - 1);
  const double a0 = full ? -geometry::kPi : -0.5 * spec.field_of_view_rad;
  for (int i = 0; i < spec.beams; ++i) {
    const double a = sensor.theta + a0 + i * inc;
    const Eigen::Vector2d d(std::cos(a), std::sin(a));
    if (clutter.Cast(sensor.Translation(), d, spec.max_range_m) <
        world.Cast(sensor.Translation(), d, spec.max_range_m)) {
      ++hits;
    }
  }
  return static_cast<double>(hits) / spec.beams;
}

// An axis-aligned box as four segments.
inline world_model::Scene Box(const Eigen::Vector2d& centre, double w, double h, double angle) {
  world_model::Scene s;
  const Eigen::Rotation2Dd rot(angle);
  const Eigen::Vector2d c[4] = {{-w / 2, -h / 2}, {w / 2, -h / 2}, {w / 2, h / 2}, {-w / 2, h / 2}};
  for (int i = 0; i < 4; ++i) {
    s.segments.push_back({centre + rot * c[i], centre + rot * c[(i + 1) % 4]});
  }
  return s;
}

// A random rectangular room (rotated, placed anywhere) with pillars and
// unmodelled clutter covering about `clutter_fraction` of the beams seen
// from the returned true sensor pose.
struct RandomRoom {
  world_model::WorldModel world;
  world_model::Scene scene;  // world + clutter
  geometry::Pose2D truth;
};

inline RandomRoom MakeRandomRoom(std::mt19937& rng, const ScanSpec& spec, double clutter_fraction) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double w = 4.0 + 5.0 * u(rng), h = 3.0 + 4.0 * u(rng);
  const double yaw = geometry::kPi * (2.0 * u(rng) - 1.0);
  const Eigen::Vector2d origin(20.0 * u(rng) - 10.0, 20.0 * u(rng) - 10.0);
  const Eigen::Rotation2Dd rot(yaw);
  auto at = [&](double x, double y) {
    return Eigen::Vector2d(origin + rot * Eigen::Vector2d(x, y));
  };
  std::vector<world_model::Wall> walls = {
      world_model::MakeWall(0, at(0, 0), at(w, 0)), world_model::MakeWall(1, at(w, 0), at(w, h)),
      world_model::MakeWall(2, at(w, h), at(0, h)), world_model::MakeWall(3, at(0, h), at(0, 0))};
  std::vector<world_model::Cylinder> pillars;
  const int n_pillars = 1 + static_cast<int>(2.0 * u(rng));
  for (int i = 0; i < n_pillars; ++i) {
    pillars.push_back(
        {i, at(1.0 + (w - 2.0) * u(rng), 1.0 + (h - 2.0) * u(rng)), 0.15 + 0.2 * u(rng)});
  }
  world_model::WorldModel model("random_room", walls, {}, pillars);
  world_model::Scene scene = world_model::Scene::FromWorld(model);
  // The robot: inside, at least 0.8 m from walls and pillars.
  geometry::Pose2D truth;
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const Eigen::Vector2d p = at(0.8 + (w - 1.6) * u(rng), 0.8 + (h - 1.6) * u(rng));
    bool clear = true;
    for (const auto& c : pillars) clear = clear && (p - c.centre).norm() > c.radius + 0.8;
    if (!clear) continue;
    truth = {p.x(), p.y(), geometry::kPi * (2.0 * u(rng) - 1.0)};
    break;
  }
  world_model::Scene clutter;
  for (int attempt = 0;
       attempt < 200 && ClutterFraction(scene, clutter, truth, spec) < clutter_fraction;
       ++attempt) {
    const Eigen::Vector2d c = at(0.3 + (w - 0.6) * u(rng), 0.3 + (h - 0.6) * u(rng));
    if ((c - truth.Translation()).norm() < 0.9) continue;
    clutter.Add(Box(c, 0.2 + 0.5 * u(rng), 0.2 + 0.5 * u(rng), geometry::kPi * u(rng)));
  }
  scene.Add(clutter);
  return {model, scene, truth};
}

}  // namespace structloc::testing
