// Scan data as the pipeline sees it: a non-owning view of one laser scan's
// ranges (LaserScan conventions) and the Cartesian points that survive the
// prefilter, stored in preallocated buffers so the steady-state update never
// allocates.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::localisation_core {

// One scan, as sensor_msgs/LaserScan describes it; beam i points at
// angle_min + i * angle_increment (laser frame) and was taken at
// stamp + i * time_increment.
struct ScanView {
  const float* ranges = nullptr;
  size_t count = 0;
  double angle_min = 0.0;
  double angle_increment = 0.0;
  double time_increment = 0.0;
  double range_min = 0.0;  // the sensor's own limits
  double range_max = 0.0;

  // A full circle: beam n-1 neighbours beam 0 (thesis 3.4).
  bool WrapsAround() const {
    return count > 2 && std::abs(static_cast<double>(count) * angle_increment) >=
                            2.0 * geometry::kPi - 0.5 * std::abs(angle_increment);
  }
};

// Prefiltered points in the laser frame (structure of arrays).
struct ScanPoints {
  std::vector<double> x;
  std::vector<double> y;
  std::vector<int> beam;  // index of the beam each point came from
  bool wraps = false;

  void Reserve(size_t n) {
    x.reserve(n);
    y.reserve(n);
    beam.reserve(n);
  }
  void Clear() {
    x.clear();
    y.clear();
    beam.clear();
  }
  void Push(double px, double py, int b) {
    x.push_back(px);
    y.push_back(py);
    beam.push_back(b);
  }
  size_t Size() const { return x.size(); }
  void Truncate(size_t n) {
    x.resize(n);
    y.resize(n);
    beam.resize(n);
  }
};

// cos/sin of every beam angle, recomputed only when the scan geometry changes.
class BeamDirections {
 public:
  void Reserve(size_t n) {
    cos_.reserve(n);
    sin_.reserve(n);
  }
  void Update(const ScanView& scan);
  double Cos(size_t i) const { return cos_[i]; }
  double Sin(size_t i) const { return sin_[i]; }

 private:
  size_t count_ = 0;
  double angle_min_ = NAN;
  double angle_increment_ = NAN;
  std::vector<double> cos_;
  std::vector<double> sin_;
};

}  // namespace structloc::localisation_core
