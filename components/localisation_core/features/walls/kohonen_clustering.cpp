// Kohonen clustering (see header).
#include "structloc/localisation_core/features/walls/kohonen_clustering.hpp"

#include <cmath>

namespace structloc::localisation_core {

namespace {
struct Neuron {
  double r, alpha;  // oriented like the expected wall
};

// The window line expressed in the orientation of neuron `n` (r may be < 0).
void Oriented(const LineEstimate& l, const Neuron& n, double* r, double* alpha) {
  double a = l.Alpha(), rr = l.r;
  if (std::cos(a - n.alpha) < 0.0) {
    a += geometry::kPi;
    rr = -rr;
  }
  *r = rr;
  *alpha = n.alpha + geometry::WrapAngle(a - n.alpha);
}
}  // namespace

void AssignWindowsByKohonen(const std::vector<WindowLine>& windows, const ExpectedWalls& expected,
                            const WallClusterOptions& gates, const KohonenOptions& o,
                            std::mt19937& rng, std::vector<int>& assignment) {
  assignment.assign(windows.size(), -1);
  const size_t ne = expected.walls.size();
  if (ne == 0) return;
  std::vector<Neuron> neurons(ne);
  for (size_t e = 0; e < ne; ++e) {
    neurons[e] = {expected.walls[e].r, std::atan2(expected.walls[e].s, expected.walls[e].c)};
  }
  std::vector<size_t> valid;
  for (size_t i = 0; i < windows.size(); ++i) {
    if (windows[i].valid) valid.push_back(i);
  }
  if (valid.empty()) return;
  auto distance2 = [&](const LineEstimate& l, const Neuron& n) {
    double r, a;
    Oriented(l, n, &r, &a);
    const double dr = (r - n.r) / gates.gate_r_m, da = (a - n.alpha) / gates.gate_alpha_rad;
    return dr * dr + da * da;
  };
  std::uniform_int_distribution<size_t> pick(0, valid.size() - 1);
  for (int t = 0; t < o.iterations; ++t) {
    const double progress = static_cast<double>(t) / o.iterations;
    const double eta = o.initial_learning_rate * (1.0 - progress);  // EQ 22
    const double sigma = o.initial_neighbourhood * (1.0 - progress) + 1e-6;
    const auto& l = windows[valid[pick(rng)]].line;
    size_t winner = 0;
    double best = INFINITY;
    for (size_t e = 0; e < ne; ++e) {
      const double d = distance2(l, neurons[e]);
      if (d < best) {
        best = d;
        winner = e;
      }
    }
    if (best > 4.0) continue;          // far from every neuron: an unmodelled surface
    for (size_t e = 0; e < ne; ++e) {  // EQ 21
      const double k = static_cast<double>(e) - static_cast<double>(winner);
      const double lambda = std::exp(-k * k / (2.0 * sigma * sigma));
      if (lambda < 0.05) continue;  // tiny repeated pulls make neurons drift onto other walls
      double r, a;
      Oriented(l, neurons[e], &r, &a);
      neurons[e].r += eta * lambda * (r - neurons[e].r);
      neurons[e].alpha += eta * lambda * (a - neurons[e].alpha);
    }
  }
  for (size_t i : valid) {
    int best_e = -1;
    double best = INFINITY;
    for (size_t e = 0; e < ne; ++e) {
      double r, a;
      Oriented(windows[i].line, neurons[e], &r, &a);
      if (std::abs(r - neurons[e].r) > gates.gate_r_m ||
          std::abs(a - neurons[e].alpha) > gates.gate_alpha_rad) {
        continue;
      }
      const double d = distance2(windows[i].line, neurons[e]);
      if (d < best) {
        best = d;
        best_e = static_cast<int>(e);
      }
    }
    assignment[i] = best_e;
  }
}

}  // namespace structloc::localisation_core
