// A map's error does not change from one scan to the next. A wall drawn 2 cm
// off is 2 cm off in every scan that sees it while the robot drives past, so
// fusing twenty such scans must not make the filter twenty times surer that the
// wall is where the map says (beyond the thesis, whose map is exact, 3.6). On
// the real recordings this piling-up of one map error was the largest error
// left with perfect odometry. This memory counts, per map feature, how often it
// was fused recently (the count fading with the distance driven); the map's
// share of the feature's next pairing covariance is multiplied by 1 + that
// count, so that all the scans of one stretch together carry the map's error
// once, while the scan's own measurement noise still averages out. DDS-free;
// sized once, it never allocates afterwards.
#pragma once

#include <cstddef>
#include <vector>

namespace structloc::localisation_core {

class MapErrorMemory {
 public:
  // `features`: how many map features there are (one slot each); `travel_m`:
  // the distance over which a feature's error counts as the same (0: the
  // memory is off and every scan's map error independent).
  void Reset(size_t features, double travel_m);
  bool Enabled() const { return travel_m_ > 0.0; }
  // The robot moved `metres`: earlier uses fade by exp(-metres / travel_m).
  void Travel(double metres);
  // The factor on the map's covariance of feature `slot`: 1 + its faded uses.
  double MapErrorScale(int slot) const;
  // Feature `slot` was fused into the pose.
  void RememberFused(int slot);

 private:
  double travel_m_ = 0.0;
  std::vector<double> uses_;
};

}  // namespace structloc::localisation_core
