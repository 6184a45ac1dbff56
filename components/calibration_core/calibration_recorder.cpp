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

bool CalibrationRecorder::Admit(StampGuard CalibrationRecorder::*stream, double t,
                                size_t* refused) {
  const auto verdict = (this->*stream).Check(t);
  if (verdict == StampGuard::Verdict::kOutOfLine) {
    ++*refused;
    return false;
  }
  if (verdict == StampGuard::Verdict::kJumpedBack) {
    Restart();
    (this->*stream).Check(t);  // the first stamp of the new clock
  }
  return true;
}

bool CalibrationRecorder::AddEncoders(const EncoderSample& s) {
  if (finished_ ||
      !Admit(&CalibrationRecorder::encoder_stamps_, s.t, &stats_.encoders_out_of_order))
    return false;
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
  if (!Admit(&CalibrationRecorder::fix_stamps_, f.t, &stats_.fixes_rejected)) return false;
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
