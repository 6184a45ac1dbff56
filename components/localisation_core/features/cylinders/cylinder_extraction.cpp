// Cylinder extraction (see header).
#include "structloc/localisation_core/features/cylinders/cylinder_extraction.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cassert>
#include <cmath>

namespace structloc::localisation_core {

void CylinderWork::Reserve(size_t points, size_t expected) {
  sums.reserve(expected);
  ring.reserve(expected);
  point_label.reserve(points);
  members.reserve(points);
  labelled.reserve(expected);
  candidates.reserve(points);  // at most one window per point
}

namespace {
// Geometric fit of the centre with a known radius (Gauss-Newton), over the
// points `members` (indices in scan order); returns the covariance of the centre.
bool RefineCentre(const ScanPoints& points, const std::vector<int>& members, double radius,
                  double floor2, Eigen::Vector2d& centre, Eigen::Matrix2d& cov) {
  for (int iteration = 0; iteration < 10; ++iteration) {
    Eigen::Matrix2d jtj = Eigen::Matrix2d::Zero();
    Eigen::Vector2d jtr = Eigen::Vector2d::Zero();
    double sse = 0.0, n = 0.0;
    for (const int m : members) {
      const size_t k = static_cast<size_t>(m);
      const Eigen::Vector2d d(points.x[k] - centre.x(), points.y[k] - centre.y());
      const double dist = d.norm();
      if (dist < 1e-9) continue;
      const Eigen::Vector2d j = -d / dist;  // d(dist - R)/d(centre)
      const double res = dist - radius;
      jtj.noalias() += j * j.transpose();
      jtr += j * res;
      sse += res * res;
      n += 1.0;
    }
    if (n < 3 || std::abs(jtj.determinant()) < 1e-18) return false;
    const Eigen::Vector2d step = -jtj.inverse() * jtr;
    centre += step;
    if (step.norm() < 1e-10 || iteration == 9) {
      cov = std::max(sse / std::max(1.0, n - 2.0), floor2) * jtj.inverse();
      return true;
    }
  }
  return false;
}
}  // namespace

void CandidateWindows(const std::vector<WindowLine>& windows,
                      const std::vector<CandidateRing>& rings, std::vector<int>& candidates) {
  candidates.clear();
  constexpr size_t kBlock = 16;
  for (size_t block = 0; block < windows.size(); block += kBlock) {
    const size_t block_end = std::min(windows.size(), block + kBlock);
    double min_x = windows[block].line.xm, max_x = min_x;
    double min_y = windows[block].line.ym, max_y = min_y;
    for (size_t i = block + 1; i < block_end; ++i) {
      min_x = std::min(min_x, windows[i].line.xm);
      max_x = std::max(max_x, windows[i].line.xm);
      min_y = std::min(min_y, windows[i].line.ym);
      max_y = std::max(max_y, windows[i].line.ym);
    }
    bool any_ring = false;
    for (const auto& ring : rings) {
      const double dx = std::max({0.0, min_x - ring.x, ring.x - max_x});
      const double dy = std::max({0.0, min_y - ring.y, ring.y - max_y});
      any_ring |= dx * dx + dy * dy <= ring.hi2;
    }
    if (!any_ring) continue;
    for (size_t i = block; i < block_end; ++i) {
      const auto& l = windows[i].line;
      bool in_a_ring = false;
      for (const auto& ring : rings) {
        const double dx = l.xm - ring.x, dy = l.ym - ring.y;
        const double d2 = dx * dx + dy * dy;
        in_a_ring |= (d2 >= ring.lo2) & (d2 <= ring.hi2);
      }
      if (in_a_ring) candidates.push_back(static_cast<int>(i));
    }
  }
}

void CollectLabelled(const std::vector<int>& labels, const LabelSpan& span, int label,
                     std::vector<int>& members) {
  members.clear();
  const size_t n = labels.size();
  auto collect = [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      if (labels[k] == label) members.push_back(static_cast<int>(k));
    }
  };
  if (span.begin >= span.end) return;  // nothing labelled
  assert(span.begin < n);              // windows start at points
  if (span.end - span.begin >= n) {
    collect(0, n);
  } else if (span.end <= n) {
    collect(span.begin, span.end);
  } else {  // wraps: the first points first, to keep scan order
    collect(0, span.end - n);
    collect(span.begin, n);
  }
}

void ExtractCylinders(const std::vector<WindowLine>& windows, const ScanPoints& points,
                      const std::vector<ExpectedPoint>& expected, const CylinderOptions& o,
                      int window_points, CylinderWork& work, std::vector<PointCluster>& out) {
  out.clear();
  const size_t ne = expected.size();
  if (ne == 0) return;
  work.sums.assign(ne, PointSums{});
  work.point_label.assign(points.Size(), -1);
  work.labelled.assign(ne, LabelSpan{});
  const double gate2 = o.gate_m * o.gate_m;
  const size_t np = points.Size();
  // The ring around each expected surface a candidate's centroid lies in,
  // squared (no square root in the loop over windows).
  work.ring.clear();
  for (const auto& c : expected) {
    const double lo = std::max(0.0, c.radius - o.candidate_gate_m);
    const double hi = c.radius + o.candidate_gate_m;
    work.ring.push_back({c.sensor.x(), c.sensor.y(), lo * lo, hi * hi});
  }
  CandidateWindows(windows, work.ring, work.candidates);
  for (const int i : work.candidates) {
    const auto& w = windows[static_cast<size_t>(i)];
    const CircleFit fit =
        FitCircle(points, static_cast<size_t>(w.first), static_cast<size_t>(window_points));
    if (!fit.ok || fit.quality < o.min_quality) continue;
    const int e = NearestWithin(expected, fit.xc, fit.yc, gate2);
    if (e < 0) continue;
    if (std::abs(fit.radius - expected[static_cast<size_t>(e)].radius) > o.radius_tolerance_m) {
      continue;
    }
    work.sums[static_cast<size_t>(e)].Add(fit.xc, fit.yc);
    work.labelled[static_cast<size_t>(e)].Add(static_cast<size_t>(w.first),
                                              static_cast<size_t>(window_points));
    for (int j = 0; j < window_points; ++j) {
      int& label = work.point_label[(static_cast<size_t>(w.first) + static_cast<size_t>(j)) % np];
      label = (label == -1 || label == e) ? e : -2;
    }
  }
  const double floor2 = o.min_point_sigma_m * o.min_point_sigma_m;
  for (size_t e = 0; e < ne; ++e) {
    const auto& s = work.sums[e];
    if (s.n < o.min_cluster_size) continue;
    // The thesis' mean with its scatter; refined by a geometric fit with the
    // model radius over all member points when that converges nearby.
    PointCluster c = s.ToCluster(static_cast<int>(e), window_points, o.min_point_sigma_m);
    Eigen::Vector2d refined = c.mean;
    Eigen::Matrix2d cov;
    CollectLabelled(work.point_label, work.labelled[e], static_cast<int>(e), work.members);
    if (RefineCentre(points, work.members, expected[e].radius, floor2, refined, cov) &&
        (refined - c.mean).norm() < o.gate_m) {
      c.refined = refined;
      c.covariance = cov;
    }
    out.push_back(c);
  }
}

}  // namespace structloc::localisation_core
