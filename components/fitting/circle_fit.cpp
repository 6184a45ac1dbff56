// Algebraic circle fit (see header).
#include "structloc/fitting/circle_fit.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace structloc::fitting {

CircleFit FitCircle(const std::vector<double>& xs, const std::vector<double>& ys, size_t first,
                    size_t count) {
  const size_t n = xs.size();
  CircleFit fit;
  if (count < 3 || n == 0 || ys.size() != n) return fit;
  double mx = 0, my = 0;
  for (size_t j = 0; j < count; ++j) {
    mx += xs[(first + j) % n];
    my += ys[(first + j) % n];
  }
  mx /= static_cast<double>(count);
  my /= static_cast<double>(count);
  // Rows [-2x, -2y, 1] (xc, yc, q) = -(x^2 + y^2) in centred coordinates (EQ 38).
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Vector3d atb = Eigen::Vector3d::Zero();
  for (size_t j = 0; j < count; ++j) {
    const double x = xs[(first + j) % n] - mx, y = ys[(first + j) % n] - my;
    const Eigen::Vector3d a(-2.0 * x, -2.0 * y, 1.0);
    ata.noalias() += a * a.transpose();
    atb += a * (-(x * x + y * y));
  }
  const Eigen::Vector3d p = ata.ldlt().solve(atb);
  const double r2 = p.x() * p.x() + p.y() * p.y() - p.z();
  if (!p.allFinite() || !(r2 > 0.0)) return fit;
  double sse = 0.0;  // EQ 39
  for (size_t j = 0; j < count; ++j) {
    const double x = xs[(first + j) % n] - mx, y = ys[(first + j) % n] - my;
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
