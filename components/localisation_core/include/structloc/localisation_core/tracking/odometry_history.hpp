// A bounded, time-ordered history of odometric poses with interpolation, used
// to de-skew scans (the pose at every beam's time) and to carry the pose
// forward between scans. Fixed capacity: no allocation after construction.
#pragma once

#include <optional>
#include <vector>

#include "structloc/geometry/pose2d.hpp"

namespace structloc::localisation_core {

class OdometryHistory {
 public:
  explicit OdometryHistory(size_t capacity = 2048);

  enum class AddResult { kAdded, kOutOfOrder, kNonFinite };
  // Samples must arrive with strictly increasing stamps; others are refused.
  AddResult Add(double stamp, const geometry::Pose2D& pose);

  // Pose at `stamp`, linearly interpolated (theta the short way); nullopt
  // outside [Oldest(), Newest()].
  std::optional<geometry::Pose2D> At(double stamp) const;

  // Like At(), and beyond the newest sample by up to `max_extrapolation_s`
  // at the velocity of the last two samples.
  std::optional<geometry::Pose2D> AtOrExtrapolated(double stamp, double max_extrapolation_s) const;

  bool Empty() const { return size_ == 0; }
  size_t Size() const { return size_; }
  double Oldest() const;
  double Newest() const;
  void Clear() { size_ = 0; }

 private:
  struct Sample {
    double stamp;
    geometry::Pose2D pose;
  };
  const Sample& Get(size_t i) const { return samples_[(head_ + i) % samples_.size()]; }
  std::vector<Sample> samples_;
  size_t head_ = 0;  // index of the oldest sample
  size_t size_ = 0;
};

}  // namespace structloc::localisation_core
