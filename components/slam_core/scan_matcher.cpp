// Point-to-line ICP (see header).
#include "structloc/slam_core/scan_matcher.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <utility>

namespace structloc::slam_core {
namespace {

// A position direction counts as pinned when the pairs' normal matrix holds
// at least this share of their number along it.
constexpr double kPinnedShare = 0.05;

// The cell of `p` in a grid of squares `cell_m` wide: (column, row).
std::pair<long long, long long> CellOf(const Eigen::Vector2d& p, double cell_m) {
  return {static_cast<long long>(std::floor(p.x() / cell_m)),
          static_cast<long long>(std::floor(p.y() / cell_m))};
}

long long Key(long long cx, long long cy) {
  return cx * 2000003LL + cy;
}

// Every point of `points` within `radius` of `centre`, through the cells.
template <class Visit>
void ForEachNear(const std::unordered_map<long long, std::vector<int>>& cells, double cell_m,
                 const Eigen::Vector2d& centre, double radius, Visit visit) {
  const auto [cx, cy] = CellOf(centre, cell_m);
  const long long reach = static_cast<long long>(std::ceil(radius / cell_m));
  for (long long dx = -reach; dx <= reach; ++dx) {
    for (long long dy = -reach; dy <= reach; ++dy) {
      const auto it = cells.find(Key(cx + dx, cy + dy));
      if (it == cells.end()) continue;
      for (int i : it->second) visit(i);
    }
  }
}

// Point `p` of the scan at `pose` paired with the nearest reference point
// within `reach`: its distance along that point's normal and the derivative
// of that distance by (x, y, theta); false when it has no partner.
bool Pair(const ReferencePoints& reference, const geometry::Pose2D& pose, double c, double s,
          const Eigen::Vector2d& p, double reach, double* e, Eigen::Vector3d* j) {
  const Eigen::Vector2d q(c * p.x() - s * p.y() + pose.x, s * p.x() + c * p.y() + pose.y);
  const int i = reference.Nearest(q, reach);
  if (i < 0) return false;
  const Eigen::Vector2d& n = reference.Normal(i);
  *e = n.dot(q - reference.Point(i));
  *j = {n.x(), n.y(), n.dot(Eigen::Vector2d(-s * p.x() - c * p.y(), c * p.x() - s * p.y()))};
  return true;
}

// The Gauss-Newton step for normal matrix `h` and gradient `g` over pairs of
// total weight `weight`; with `hold_unpinned`, where the pairs pin one
// direction of the position only, solved in the pinned directions (that one
// and the heading) alone.
Eigen::Vector3d Step(const Eigen::Matrix3d& h, const Eigen::Vector3d& g, double weight,
                     bool hold_unpinned) {
  if (!hold_unpinned) return -h.ldlt().solve(g);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> xy(h.topLeftCorner<2, 2>());
  if (xy.eigenvalues()(0) > kPinnedShare * weight) return -h.ldlt().solve(g);
  Eigen::Matrix<double, 3, 2> pinned = Eigen::Matrix<double, 3, 2>::Zero();
  pinned.block<2, 1>(0, 0) = xy.eigenvectors().col(1);
  pinned(2, 1) = 1.0;
  const Eigen::Matrix2d reduced = pinned.transpose() * h * pinned;
  return -pinned * reduced.ldlt().solve(pinned.transpose() * g);
}

}  // namespace

ReferencePoints::ReferencePoints(const std::vector<Eigen::Vector2d>& points,
                                 const ScanMatchOptions& options)
    : points_(points),
      normal_radius_m_(options.normal_radius_m),
      tree_(points),
      surface_(points.size(), Surface::kUnknown),
      normals_(points.size(), Eigen::Vector2d::Zero()) {
  for (size_t i = 0; i < points.size(); ++i) {
    const auto [cx, cy] = CellOf(points[i], normal_radius_m_);
    cells_[Key(cx, cy)].push_back(static_cast<int>(i));
  }
}

bool ReferencePoints::OnSurface(int i) const {
  if (surface_[i] != Surface::kUnknown) return surface_[i] == Surface::kLine;
  surface_[i] = Surface::kNone;
  const Eigen::Vector2d& c = points_[i];
  const double r2 = normal_radius_m_ * normal_radius_m_;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  int n = 0;
  ForEachNear(cells_, normal_radius_m_, c, normal_radius_m_, [&](int j) {
    const Eigen::Vector2d d = points_[j] - c;
    if (d.squaredNorm() > r2) return;
    mean += points_[j];
    scatter += points_[j] * points_[j].transpose();
    ++n;
  });
  if (n < 4) return false;  // too few neighbours for a line
  mean /= n;
  const Eigen::Matrix2d covariance = scatter / n - mean * mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance);
  // A surface: spread along one direction, thin across it.
  if (!(eigen.eigenvalues()(0) < 0.1 * eigen.eigenvalues()(1))) return false;
  normals_[i] = eigen.eigenvectors().col(0).normalized();
  surface_[i] = Surface::kLine;
  return true;
}

int ReferencePoints::Nearest(const Eigen::Vector2d& p, double max_distance_m) const {
  // Of points equally near, the one a search through the cells (x, then y,
  // then the points of a cell in order), keeping the last of equals, ends
  // with: the matches this gives are those such a search gave.
  const auto last_in_cells = [this](int a, int b) {
    return std::pair(CellOf(points_[a], normal_radius_m_), a) >
           std::pair(CellOf(points_[b], normal_radius_m_), b);
  };
  return tree_.Nearest(
      p, max_distance_m, [this](int i) { return OnSurface(i); }, last_in_cells);
}

ScanMatch MatchScan(const ReferencePoints& reference, const std::vector<Eigen::Vector2d>& points,
                    const geometry::Pose2D& guess, const ScanMatchOptions& options) {
  ScanMatch match;
  geometry::Pose2D pose = guess;
  const double huber = 2.0 * options.point_sigma_m;
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    // The pairing distance shrinks over the first half, then holds.
    const double f = std::min(1.0, 2.0 * iteration / std::max(1, options.iterations - 1));
    const double reach = options.first_pair_distance_m +
                         f * (options.last_pair_distance_m - options.first_pair_distance_m);
    const double c = std::cos(pose.theta), s = std::sin(pose.theta);
    Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    double weight = 0.0;
    for (const auto& p : points) {
      double e = 0.0;
      Eigen::Vector3d j;
      if (!Pair(reference, pose, c, s, p, reach, &e, &j)) continue;
      const double w = std::abs(e) <= huber ? 1.0 : huber / std::abs(e);
      h += w * j * j.transpose();
      g += w * j * e;
      weight += w;
    }
    if (h.determinant() <= 1e-12) break;
    const Eigen::Vector3d step = Step(h, g, weight, options.hold_unpinned);
    pose = {pose.x + step(0), pose.y + step(1), geometry::WrapAngle(pose.theta + step(2))};
    if (f >= 1.0 && step.head<2>().norm() < 1e-5 && std::abs(step(2)) < 1e-6) break;
  }
  // The final pairing: what the match explains, and its covariance.
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  double sum_e2 = 0.0;
  for (const auto& p : points) {
    double e = 0.0;
    Eigen::Vector3d j;
    if (!Pair(reference, pose, c, s, p, options.last_pair_distance_m, &e, &j)) continue;
    hessian += j * j.transpose();
    sum_e2 += e * e;
    ++match.pairs;
  }
  match.pose = pose;
  match.inlier_share = points.empty() ? 0.0 : static_cast<double>(match.pairs) / points.size();
  match.rms_m = match.pairs > 0 ? std::sqrt(sum_e2 / match.pairs) : 0.0;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> xy(hessian.topLeftCorner<2, 2>());
  // Pinned in every direction: walls of more than one direction, each seen
  // by a good share of the pairs.
  match.constrained = match.pairs > 10 && xy.eigenvalues()(0) > kPinnedShare * match.pairs &&
                      hessian(2, 2) > 0.0 && std::abs(hessian.determinant()) > 1e-9;
  if (match.pairs > 10) {
    // Along a corridor the walls pin nothing: the covariance there grows as
    // large as the regularisation lets it, and a graph takes the match only
    // for what it pins.
    const double sigma2 =
        std::max(options.point_sigma_m * options.point_sigma_m, match.rms_m * match.rms_m);
    const Eigen::Matrix3d regularised = hessian + 1e-4 * Eigen::Matrix3d::Identity();
    match.covariance = options.correlated_points * sigma2 * regularised.inverse();
    match.covariance(0, 0) = std::max(match.covariance(0, 0), std::pow(options.min_sigma_xy_m, 2));
    match.covariance(1, 1) = std::max(match.covariance(1, 1), std::pow(options.min_sigma_xy_m, 2));
    match.covariance(2, 2) =
        std::max(match.covariance(2, 2), std::pow(options.min_sigma_theta_rad, 2));
  }
  return match;
}

}  // namespace structloc::slam_core
