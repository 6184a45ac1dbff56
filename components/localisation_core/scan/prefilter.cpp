// Prefilter steps (see header) and beam direction tables.
#include "structloc/localisation_core/scan/prefilter.hpp"

#include "structloc/localisation_core/scan/deskew.hpp"

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
  out.wraps = scan.WrapsAround();
  stats.beams = scan.count;
  const double lo = std::max(options.min_range_m, scan.range_min);
  const double hi =
      scan.range_max > 0.0 ? std::min(options.max_range_m, scan.range_max) : options.max_range_m;
  // Every beam is written to the next free slot, which advances only for a
  // usable one: no branch to mispredict on a scan full of drop-outs.
  out.Truncate(scan.count);
  size_t kept = 0, non_finite = 0, negative = 0;
  for (size_t i = 0; i < scan.count; ++i) {
    const double r = scan.ranges[i];
    const bool finite = std::isfinite(r);
    const bool usable = finite & (r >= 0.0) & (r >= lo) & (r <= hi);
    non_finite += !finite;
    negative += finite & (r < 0.0);
    out.x[kept] = r * directions.Cos(i);
    out.y[kept] = r * directions.Sin(i);
    out.beam[kept] = static_cast<int>(i);
    kept += usable;
  }
  out.Truncate(kept);
  stats.non_finite += non_finite;
  stats.negative += negative;
  stats.out_of_range += scan.count - kept - non_finite - negative;
}

void RejectUnsupportedAndThin(const PrefilterOptions& options, ScanPoints& points,
                              PrefilterStats& stats) {
  const size_t n = points.Size();
  stats.kept = 0;
  if (n == 0) return;
  const double far2 = options.max_neighbour_distance_m * options.max_neighbour_distance_m;
  const double near2 = options.min_neighbour_distance_m * options.min_neighbour_distance_m;
  auto far = [&](size_t a, size_t b) {
    const double dx = points.x[a] - points.x[b], dy = points.y[a] - points.y[b];
    return dx * dx + dy * dy > far2;
  };
  // Support needs two neighbours: fewer than three points are all kept.
  const bool check_support = n >= 3;
  // One pass, in place. Each gap to the next point is measured once, on the
  // points as they came (slot w <= i is written only after point i is read,
  // and the wrap-around gap is measured first). Each point is copied to the
  // next free slot, which advances only when the point is kept: no branch on
  // the data.
  const bool last_gap_far = !points.wraps || far(n - 1, 0);
  bool far_prev = last_gap_far;  // point 0 from its predecessor
  size_t w = 0, unsupported = 0;
  double last_x = 0.0, last_y = 0.0;  // the last point kept, for thinning
  for (size_t i = 0; i < n; ++i) {
    const double x = points.x[i], y = points.y[i];
    const bool far_next = i + 1 < n ? far(i, i + 1) : last_gap_far;
    const bool supported = !check_support | !(far_prev & far_next);
    const double dx = x - last_x, dy = y - last_y;
    const bool spaced = (w == 0) | !(dx * dx + dy * dy < near2);
    const bool keep = supported & spaced;
    MovePoint(points, i, w);
    unsupported += !supported;
    last_x = keep ? x : last_x;
    last_y = keep ? y : last_y;
    w += keep;
    far_prev = far_next;
  }
  stats.unsupported += unsupported;
  stats.thinned += n - w - unsupported;
  points.Truncate(w);
  stats.kept = w;
}

void Prefilter(const ScanView& scan, const BeamDirections& directions,
               const PrefilterOptions& options, const BeamMotion* motion, ScanPoints& out,
               PrefilterStats& stats) {
  RangeGate(scan, directions, options, out, stats);
  if (motion != nullptr) Deskew(*motion, out);
  RejectUnsupportedAndThin(options, out, stats);
}

}  // namespace structloc::localisation_core
