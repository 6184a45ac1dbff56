// Odometry calibration over a sliding window (see header).
#include "structloc/calibration_core/online_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "structloc/calibration_core/calibration_problem.hpp"

namespace structloc::calibration_core {

void OnlineCalibrationOptions::Validate() const {
  if (!(window_s > 0 && std::isfinite(window_s))) {
    throw std::invalid_argument("online calibration: window_s must be a finite number > 0");
  }
  if (!(period_s > 0 && std::isfinite(period_s))) {
    throw std::invalid_argument("online calibration: period_s must be a finite number > 0");
  }
  if (!(change_sigmas > 0 && std::isfinite(change_sigmas))) {
    throw std::invalid_argument("online calibration: change_sigmas must be a finite number > 0");
  }
}

std::string Describe(const ParameterChange& c) {
  char text[200];
  const bool relative = IsScale(c.parameter) && std::abs(c.from) > 0;
  if (relative) {
    std::snprintf(text, sizeof text, "%s %.6g -> %.6g %s (%+.2f %%, %.1f sigma)",
                  ParameterName(c.parameter), c.from, c.to, ParameterUnit(c.parameter),
                  100.0 * (c.to / c.from - 1.0), c.sigmas);
  } else {
    std::snprintf(text, sizeof text, "%s %.6g -> %.6g %s (%+.3g, %.1f sigma)",
                  ParameterName(c.parameter), c.from, c.to, ParameterUnit(c.parameter),
                  c.to - c.from, c.sigmas);
  }
  return text;
}

OnlineCalibration::OnlineCalibration(const kinematics::RobotParameters& nominal,
                                     const CalibrationOptions& options,
                                     const OnlineCalibrationOptions& online)
    : nominal_(nominal),
      options_(options),
      online_(online),
      recorder_(RecorderOptions{0.0, options.max_encoder_gap_s, {}}) {
  nominal_.Validate();
  options_.Validate();
  online_.Validate();
}

bool OnlineCalibration::AddEncoders(const EncoderSample& sample) {
  const bool taken = recorder_.AddEncoders(sample);
  FollowRestarts();
  return taken;
}

bool OnlineCalibration::AddFix(const Fix& fix) {
  const bool taken = recorder_.AddFix(fix);
  FollowRestarts();
  return taken;
}

void OnlineCalibration::FollowRestarts() {
  const size_t restarts = recorder_.Stats().restarts;
  if (restarts == restarts_seen_) return;
  restarts_seen_ = restarts;
  last_end_s_.reset();
  history_.clear();
}

bool OnlineCalibration::Due() const {
  const auto& e = recorder_.Current().encoders;
  if (e.size() < 2 || e.back().t - e.front().t < online_.window_s) return false;
  return !last_end_s_ || e.back().t - *last_end_s_ >= online_.period_s;
}

namespace {

// Changes of the parameters both reports estimated, beyond `limit` sigmas.
std::vector<ParameterChange> Changes(const CalibrationReport& before,
                                     const CalibrationReport& after, double limit) {
  std::vector<ParameterChange> changes;
  const ParameterValues from = ValuesOf(before.parameters), to = ValuesOf(after.parameters);
  for (size_t k = 0; k < from.size(); ++k) {
    if (!before.estimated[k] || !after.estimated[k]) continue;
    const double sd = std::hypot(before.standard_deviation[k], after.standard_deviation[k]);
    const double sigmas = sd > 0 ? std::abs(to[k] - from[k]) / sd : INFINITY;
    if (sigmas > limit) changes.push_back({static_cast<Parameter>(k), from[k], to[k], sigmas});
  }
  return changes;
}

}  // namespace

OnlineCalibration::Window OnlineCalibration::NextWindow() {
  Window window;
  const auto& recording = recorder_.Current();
  if (recording.encoders.empty()) return window;
  window.end_s = recording.encoders.back().t;
  window.start_s = std::max(recording.encoders.front().t, window.end_s - online_.window_s);
  recorder_.ForgetBefore(window.start_s);
  last_end_s_ = window.end_s;
  window.recording = recorder_.Current();
  return window;
}

OnlineEstimate OnlineCalibration::Estimate(const Window& window) {
  OnlineEstimate out;
  out.window_start_s = window.start_s;
  out.window_end_s = window.end_s;
  if (window.recording.encoders.size() < 2) {
    out.report.success = false;
    out.report.parameters = nominal_;
    out.report.failure = "fewer than two encoder samples in the window";
    return out;
  }
  try {
    out.report = Calibrate(window.recording.encoders, window.recording.fixes, nominal_, options_);
  } catch (const std::exception& e) {
    out.report.success = false;
    out.report.parameters = nominal_;
    out.report.failure = e.what();
  }
  if (!out.report.success) return out;
  // The newest earlier estimate that used none of this window's data.
  for (auto it = history_.rbegin(); it != history_.rend(); ++it) {
    if (it->window_end_s <= out.window_start_s) {
      out.reference_end_s = it->window_end_s;
      out.changes = Changes(it->report, out.report, online_.change_sigmas);
      break;
    }
  }
  history_.push_back({out.window_end_s, out.report});
  // A later window starts at most window_s before its end, so the estimates
  // it may compare with are among the newest window_s / period_s + 2.
  const auto keep = static_cast<size_t>(std::ceil(online_.window_s / online_.period_s)) + 2;
  if (history_.size() > keep) {
    history_.erase(history_.begin(), history_.end() - static_cast<std::ptrdiff_t>(keep));
  }
  return out;
}

}  // namespace structloc::calibration_core
