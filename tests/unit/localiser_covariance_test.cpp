// Is the reported covariance honest? Random rectangular rooms (corners derived
// from the walls) with pillars, 20 % of the beams hitting unmodelled clutter,
// a noisy odometric prior drawn from its own stated covariance: the pose
// error must lie within 3 sigma (Mahalanobis distance, 3 dof) of the reported
// covariance in at least 95 % of the cases.
#include <gtest/gtest.h>

#include <cstdio>

#include "structloc/localisation_core/features/corners/corner_extractor.hpp"
#include "structloc/localisation_core/features/cylinders/cylinder_extractor.hpp"
#include "structloc/localisation_core/features/walls/wall_extractor.hpp"
#include "structloc/localisation_core/localiser/localiser.hpp"
#include "synthetic_scans.hpp"

namespace structloc::localisation_core {
namespace {

using geometry::kPi;

TEST(CovarianceHonesty, ErrorsLieWithinThreeSigmaOfTheReportedCovariance) {
  std::mt19937 rng(20261122);
  const testing::ScanSpec spec{720, 2 * kPi, 15.0, 0.01};
  LocaliserOptions options;
  options.prefilter.max_range_m = 15.0;
  options.prefilter.min_range_m = 0.2;
  options.prefilter.min_neighbour_distance_m = 0.03;
  options.kinds.Get<WallKindOptions>().clusters.min_cluster_size = 3;
  options.kinds.Get<CornerKindOptions>().extraction.min_cluster_size = 3;
  options.kinds.Get<CylinderKindOptions>().extraction.min_cluster_size = 2;
  const double prior_sigma_xy = 0.05, prior_sigma_theta = 0.03;
  std::normal_distribution<double> n01(0.0, 1.0);
  const int cases = 200;
  int within = 0, lost = 0;
  double sum_d2 = 0.0, worst_d2 = 0.0, sum_err = 0.0;
  for (int c = 0; c < cases; ++c) {
    const auto room = testing::MakeRandomRoom(rng, spec, 0.2);
    Localiser localiser(room.world, options);
    const auto scan = testing::CastScan(room.scene, room.truth, spec, rng);
    UpdateInput in;
    in.scan = scan.View();
    in.odometry_pose = {room.truth.x + prior_sigma_xy * n01(rng),
                        room.truth.y + prior_sigma_xy * n01(rng),
                        geometry::WrapAngle(room.truth.theta + prior_sigma_theta * n01(rng))};
    in.odometry_covariance =
        Eigen::Vector3d(prior_sigma_xy * prior_sigma_xy, prior_sigma_xy * prior_sigma_xy,
                        prior_sigma_theta * prior_sigma_theta)
            .asDiagonal();
    const auto& r = localiser.Update(in);
    ASSERT_TRUE(geometry::IsFinite(r.pose));
    if (r.lost) ++lost;
    const Eigen::Vector3d e(r.pose.x - room.truth.x, r.pose.y - room.truth.y,
                            geometry::WrapAngle(r.pose.theta - room.truth.theta));
    const double d2 = e.dot(r.covariance.inverse() * e);
    sum_d2 += d2;
    sum_err += e.head<2>().norm();
    worst_d2 = std::max(worst_d2, d2);
    if (d2 <= 14.16) ++within;  // chi-square, 3 dof, 99.73 % (3 sigma)
  }
  std::printf(
      "within 3 sigma: %d / %d; mean Mahalanobis^2 %.2f (3 if exact), worst %.1f; "
      "mean position error %.2f mm; lost %d\n",
      within, cases, sum_d2 / cases, worst_d2, 1e3 * sum_err / cases, lost);
  EXPECT_GE(within, static_cast<int>(0.95 * cases));
  EXPECT_LT(sum_err / cases, 0.01);
}

}  // namespace
}  // namespace structloc::localisation_core
