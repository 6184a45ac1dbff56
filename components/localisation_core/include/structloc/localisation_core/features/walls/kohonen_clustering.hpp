// The clustering the thesis tried and rejected (thesis 3.5.3, EQ 21-22): a
// self-organising map with one neuron per expected wall, initialised at the
// expected (r, alpha) and trained on randomly drawn window lines with a
// decreasing learning rate and shrinking neighbourhood. Kept as a selectable
// strategy so that its cost and results can be compared with the expectation
// gates. Deterministic for a given generator state.
#pragma once

#include <random>
#include <vector>

#include "structloc/localisation_core/expectation/expected_walls.hpp"
#include "structloc/localisation_core/features/walls/wall_clustering.hpp"
#include "structloc/localisation_core/scan/line_fit.hpp"

namespace structloc::localisation_core {

struct KohonenOptions {
  int iterations = 2000;               // training steps per scan
  double initial_learning_rate = 0.3;  // eta(0), decreasing linearly to 0
  // sigma(0) in neuron-index units, shrinking to 0; wider neighbourhoods drag
  // the neurons of different walls onto one wall.
  double initial_neighbourhood = 0.3;
};

// Window i -> expected wall index, or -1: nearest trained neuron within the
// gates of `cluster_options`. Neurons keep the expected walls' order.
void AssignWindowsByKohonen(const std::vector<WindowLine>& windows, const ExpectedWalls& expected,
                            const WallClusterOptions& cluster_options,
                            const KohonenOptions& options, std::mt19937& rng,
                            std::vector<int>& assignment);

}  // namespace structloc::localisation_core
