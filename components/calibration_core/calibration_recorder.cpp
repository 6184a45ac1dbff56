// Calibration recorder (see header).
#include "structloc/calibration_core/calibration_recorder.hpp"

#include <algorithm>
#include <stdexcept>

namespace structloc::calibration_core {

CalibrationRecorder::CalibrationRecorder(const RecorderOptions& options)
    : options_(options), encoder_stamps_(options.stamps), fix_stamps_(options.stamps) {
  if (!(options_.record_s >= 0)) throw std::invalid_argument("record_s must be >= 0");
  if (!(options_.max_encoder_gap_s > 0)) {
    throw std::invalid_argument("max_encoder_gap_s must be > 0");
  }
}

void CalibrationRecorder::Restart() {
  recording_ = {};
  ++stats_.restarts;
  // Both streams start again on the new clock.
  encoder_stamps_ = StampGuard(options_.stamps);
  fix_stamps_ = StampGuard(options_.stamps);
}

bool CalibrationRecorder::AddEncoders(const EncoderSample& s) {
  if (finished_) return false;
  const auto verdict = encoder_stamps_.Check(s.t);
  if (verdict == StampGuard::Verdict::kOutOfLine) {
    ++stats_.encoders_out_of_order;
    return false;
  }
  if (verdict == StampGuard::Verdict::kJumpedBack) {
    Restart();
    encoder_stamps_.Check(s.t);
  }
  auto& encoders = recording_.encoders;
  if (!encoders.empty()) {
    const double dt = s.t - encoders.back().t;
    stats_.largest_gap_s = std::max(stats_.largest_gap_s, dt);
    if (dt > options_.max_encoder_gap_s) ++stats_.gaps;
  }
  encoders.push_back(s);
  return true;
}

bool CalibrationRecorder::AddFix(const Fix& f) {
  if (finished_) return false;
  if (!geometry::IsFinite(f.pose)) {
    ++stats_.fixes_rejected;
    return false;
  }
  const auto verdict = fix_stamps_.Check(f.t);
  if (verdict == StampGuard::Verdict::kOutOfLine) {
    ++stats_.fixes_rejected;
    return false;
  }
  if (verdict == StampGuard::Verdict::kJumpedBack) {
    Restart();
    fix_stamps_.Check(f.t);
  }
  recording_.fixes.push_back(f);
  return true;
}

bool CalibrationRecorder::Due() const {
  const auto& e = recording_.encoders;
  return !finished_ && options_.record_s > 0 && e.size() > 1 &&
         e.back().t - e.front().t >= options_.record_s;
}

bool CalibrationRecorder::WorthEstimating() const {
  return !finished_ && recording_.encoders.size() > 1 && recording_.fixes.size() > 2;
}

Recording CalibrationRecorder::Finish() {
  finished_ = true;  // recording ends here
  return recording_;
}

void CalibrationRecorder::ForgetBefore(double t) {
  auto& e = recording_.encoders;
  e.erase(e.begin(), std::lower_bound(e.begin(), e.end(), t,
                                      [](const EncoderSample& s, double v) { return s.t < v; }));
  auto& f = recording_.fixes;
  f.erase(f.begin(),
          std::lower_bound(f.begin(), f.end(), t, [](const Fix& x, double v) { return x.t < v; }));
}

RecorderStats CalibrationRecorder::Stats() const {
  RecorderStats s = stats_;
  s.encoders = recording_.encoders.size();
  s.fixes = recording_.fixes.size();
  return s;
}

}  // namespace structloc::calibration_core
