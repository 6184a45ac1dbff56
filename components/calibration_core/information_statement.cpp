// The calibration information in words (see header).
#include "structloc/calibration_core/information_statement.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>

namespace structloc::calibration_core {
namespace {

std::string Format(const char* format, double a, double b = 0.0, double c = 0.0) {
  char text[160];
  std::snprintf(text, sizeof text, format, a, b, c);
  return text;
}

// "+0.71 axle_distance -0.70 steering_rad_per_tick" (components above 0.1).
std::string Mix(const Eigen::VectorXd& v, const std::vector<size_t>& index) {
  std::string text;
  for (Eigen::Index k = 0; k < v.size(); ++k) {
    if (std::abs(v(k)) < 0.1) continue;
    text += (text.empty() ? "" : " ") + Format("%+.2f ", v(k)) +
            ParameterName(static_cast<Parameter>(index[static_cast<size_t>(k)]));
  }
  return text;
}

// The combination of a strongly correlated pair that the data determine.
std::string DeterminedPair(size_t a, size_t b, double sa, double sb, double rho,
                           const ParameterValues& values) {
  const std::string na = ParameterName(static_cast<Parameter>(a));
  const std::string nb = ParameterName(static_cast<Parameter>(b));
  if (IsScale(static_cast<Parameter>(a)) && IsScale(static_cast<Parameter>(b))) {
    // Relative deviations: log a - beta log b is determined.
    const double ra = sa / std::abs(values[a]), rb = sb / std::abs(values[b]);
    const double beta = rho * ra / rb;
    const double sigma = ra * std::sqrt(std::max(0.0, 1.0 - rho * rho));
    return na + " and " + nb + " are correlated " + Format("%+.3f", rho) +
           ": alone they are known to " + Format("%.2g %% and %.2g %%", 100 * ra, 100 * rb) +
           ", but " + na + " / " + nb +
           Format("^%.2f is determined to %.2g %%", beta, 100 * sigma) +
           (std::abs(beta - 1) < 0.1 ? " (in effect their ratio)" : "");
  }
  const double beta = rho * sa / sb;
  const double sigma = sa * std::sqrt(std::max(0.0, 1.0 - rho * rho));
  return na + " and " + nb + " are correlated " + Format("%+.3f", rho) + ": " + na +
         Format(" %+.4g * ", -beta) + nb + Format(" is determined to %.3g (", sigma) + na +
         Format(" alone to %.3g)", sa);
}

}  // namespace

std::vector<std::string> DescribeInformation(const Eigen::MatrixXd& information,
                                             const std::vector<size_t>& index,
                                             const ParameterValues& values,
                                             const ParameterValues& max_std) {
  std::vector<std::string> lines;
  const Eigen::Index n = information.rows();
  if (n == 0) return lines;
  // Information in units of each parameter's deviation limit.
  Eigen::VectorXd limit(n);
  for (Eigen::Index k = 0; k < n; ++k) limit(k) = max_std[index[static_cast<size_t>(k)]];
  const Eigen::MatrixXd scaled = limit.asDiagonal() * information * limit.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(scaled);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double lambda = eig.eigenvalues()(k);
    const double sigma = lambda > 0 ? 1.0 / std::sqrt(lambda) : INFINITY;
    lines.push_back(
        Format("information direction %.0f of ", static_cast<double>(k + 1)) + std::to_string(n) +
        ": " + Mix(eig.eigenvectors().col(k), index) +
        Format(" (in units of each deviation limit) is known to %.3g of the limit", sigma) +
        (sigma > 1 ? ": NOT determined by this trajectory" : ""));
  }
  // Pairs the trajectory mixes up: what it determines of them.
  const Eigen::MatrixXd covariance = information.completeOrthogonalDecomposition().pseudoInverse();
  for (Eigen::Index a = 0; a < n; ++a) {
    for (Eigen::Index b = a + 1; b < n; ++b) {
      const double sa = std::sqrt(std::max(0.0, covariance(a, a)));
      const double sb = std::sqrt(std::max(0.0, covariance(b, b)));
      if (!(sa > 0 && sb > 0)) continue;
      const double rho = covariance(a, b) / (sa * sb);
      // Steering gain and axle distance both scale the turn rate of small
      // steering angles (EQ 46): what the data determine of them is always said.
      const size_t pa = index[static_cast<size_t>(a)], pb = index[static_cast<size_t>(b)];
      const bool gain_and_axle = (pa == kAxleDistance && pb == kSteeringGain) ||
                                 (pa == kSteeringGain && pb == kAxleDistance);
      if (std::abs(rho) < 0.95 && !gain_and_axle) continue;
      lines.push_back(DeterminedPair(index[static_cast<size_t>(a)], index[static_cast<size_t>(b)],
                                     sa, sb, rho, values));
    }
  }
  return lines;
}

}  // namespace structloc::calibration_core
