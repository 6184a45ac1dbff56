// Prefilter steps (see header) and beam direction tables.
#include "structloc/localisation_core/scan/prefilter.hpp"

namespace structloc::localisation_core {

void BeamDirections::Update(const ScanView& scan) {
  if (scan.count == count_ && scan.angle_min == angle_min_ &&
      scan.angle_increment == angle_increment_) {
    return;
  }
  count_ = scan.count;
  angle_min_ = scan.angle_min;
  angle_increment_ = scan.angle_increment;
  cos_.resize(count_);
  sin_.resize(count_);
  for (size_t i = 0; i < count_; ++i) {
    const double a = angle_min_ + static_cast<double>(i) * angle_increment_;
    cos_[i] = std::cos(a);
    sin_[i] = std::sin(a);
  }
}

namespace {
// Moves point i to slot w (compaction in place).
inline void MovePoint(ScanPoints& points, size_t i, size_t w) {
  points.x[w] = points.x[i];
  points.y[w] = points.y[i];
  points.beam[w] = points.beam[i];
}
}  // namespace

void RangeGate(const ScanView& scan, const BeamDirections& directions,
               const PrefilterOptions& options, ScanPoints& out, PrefilterStats& stats) {
  out.Clear();
  out.wraps = scan.WrapsAround();
  stats.beams = scan.count;
  const double lo = std::max(options.min_range_m, scan.range_min);
  const double hi =
      scan.range_max > 0.0 ? std::min(options.max_range_m, scan.range_max) : options.max_range_m;
  for (size_t i = 0; i < scan.count; ++i) {
    const double r = scan.ranges[i];
    if (!std::isfinite(r)) {
      ++stats.non_finite;
    } else if (r < 0.0) {
      ++stats.negative;
    } else if (r < lo || r > hi) {
      ++stats.out_of_range;
    } else {
      out.Push(r * directions.Cos(i), r * directions.Sin(i), static_cast<int>(i));
    }
  }
}

void RejectUnsupported(const PrefilterOptions& options, ScanPoints& points,
                       std::vector<unsigned char>& keep, PrefilterStats& stats) {
  const size_t n = points.Size();
  if (n < 3) return;
  const double d2 = options.max_neighbour_distance_m * options.max_neighbour_distance_m;
  auto far = [&](size_t a, size_t b) {
    const double dx = points.x[a] - points.x[b], dy = points.y[a] - points.y[b];
    return dx * dx + dy * dy > d2;
  };
  keep.assign(n, 1);
  for (size_t i = 0; i < n; ++i) {
    const bool has_prev = i > 0 || points.wraps;
    const bool has_next = i + 1 < n || points.wraps;
    const size_t prev = i > 0 ? i - 1 : n - 1;
    const size_t next = i + 1 < n ? i + 1 : 0;
    const bool far_prev = !has_prev || far(i, prev);
    const bool far_next = !has_next || far(i, next);
    if (far_prev && far_next) keep[i] = 0;
  }
  size_t w = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!keep[i]) {
      ++stats.unsupported;
      continue;
    }
    MovePoint(points, i, w++);
  }
  points.Truncate(w);
}

void Thin(const PrefilterOptions& options, ScanPoints& points, PrefilterStats& stats) {
  const size_t n = points.Size();
  const double d2 = options.min_neighbour_distance_m * options.min_neighbour_distance_m;
  size_t w = 0;
  for (size_t i = 0; i < n; ++i) {
    if (w > 0) {
      const double dx = points.x[i] - points.x[w - 1], dy = points.y[i] - points.y[w - 1];
      if (dx * dx + dy * dy < d2) {
        ++stats.thinned;
        continue;
      }
    }
    MovePoint(points, i, w++);
  }
  points.Truncate(w);
  stats.kept = w;
}

}  // namespace structloc::localisation_core
