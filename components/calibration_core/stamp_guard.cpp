// StampGuard (see header).
#include "structloc/calibration_core/stamp_guard.hpp"

#include <cmath>
#include <stdexcept>

namespace structloc::calibration_core {

StampGuard::StampGuard(const StampGuardOptions& options) : options_(options) {
  if (!(options_.max_jump_s > 0.0)) throw std::invalid_argument("max_jump_s must be > 0");
  if (options_.confirm_samples < 1) throw std::invalid_argument("confirm_samples must be >= 1");
}

StampGuard::Verdict StampGuard::Check(double t) {
  if (!std::isfinite(t)) return Verdict::kOutOfLine;
  const auto follows = [&](double before) {
    return t > before && t - before <= options_.max_jump_s;
  };
  if (!last_ || follows(*last_)) {
    last_ = t;
    held_.reset();
    held_count_ = 0;
    return Verdict::kNext;
  }
  held_count_ = held_ && follows(*held_) ? held_count_ + 1 : 1;
  held_ = t;
  if (held_count_ < options_.confirm_samples) return Verdict::kOutOfLine;
  const bool forward = t > *last_;
  last_ = t;
  held_.reset();
  held_count_ = 0;
  return forward ? Verdict::kJumpedForward : Verdict::kJumpedBack;
}

}  // namespace structloc::calibration_core
