// Algebraic circle fit (see header).
#include "structloc/fitting/circle_fit.hpp"

#include <Eigen/Core>
#include <cmath>

namespace structloc::fitting {

CircleFit FitCircle(const std::vector<double>& xs, const std::vector<double>& ys, size_t first,
                    size_t count) {
  const size_t n = xs.size();
  CircleFit fit;
  if (count < 3 || n == 0 || ys.size() != n || count > n) return fit;
  // Point j of the run, wrapping past the end (one compare, not a division).
  first %= n;
  auto at = [&](size_t j) {
    const size_t k = first + j;
    return k < n ? k : k - n;
  };
  double mx = 0, my = 0;
  for (size_t j = 0; j < count; ++j) {
    mx += xs[at(j)];
    my += ys[at(j)];
  }
  mx /= static_cast<double>(count);
  my /= static_cast<double>(count);
  // Rows [-2x, -2y, 1] (xc, yc, q) = -(x^2 + y^2) in centred coordinates (EQ 38).
  // About the centroid the sums of x and y vanish, so the normal equations
  // split: q = -mean(x^2 + y^2), and a 2 x 2 system for the centre.
  double sxx = 0, sxy = 0, syy = 0, sxr = 0, syr = 0, sr = 0;
  for (size_t j = 0; j < count; ++j) {
    const double x = xs[at(j)] - mx, y = ys[at(j)] - my;
    const double rho = x * x + y * y;
    sxx += x * x;
    sxy += x * y;
    syy += y * y;
    sxr += x * rho;
    syr += y * rho;
    sr += rho;
  }
  const double det = sxx * syy - sxy * sxy;
  const Eigen::Vector3d p(0.5 * (sxr * syy - syr * sxy) / det, 0.5 * (syr * sxx - sxr * sxy) / det,
                          -sr / static_cast<double>(count));
  const double r2 = p.x() * p.x() + p.y() * p.y() - p.z();
  if (!p.allFinite() || !(r2 > 0.0)) return fit;
  double sse = 0.0;  // EQ 39
  for (size_t j = 0; j < count; ++j) {
    const double x = xs[at(j)] - mx, y = ys[at(j)] - my;
    const double res = -2.0 * x * p.x() - 2.0 * y * p.y() + p.z() + (x * x + y * y);
    sse += res * res;
  }
  fit.xc = p.x() + mx;
  fit.yc = p.y() + my;
  fit.radius = std::sqrt(r2);
  fit.quality = sse > 0.0 ? 1.0 / sse : INFINITY;  // EQ 40
  fit.ok = true;
  return fit;
}

}  // namespace structloc::fitting
