// Odometry calibration while the robot works (thesis 6.5.4, re-run
// continuously): the encoder stream and the position fixes are kept over a
// sliding window of stamp time; every period the parameters are estimated from
// that window with the batch calibration, and each estimate is compared with
// the previous estimate from a window that shares no data with it. A parameter
// that moved by more than `change_sigmas` combined standard deviations is
// flagged: a tyre worn or changed, a load added. What a fleet operator then
// sees drifting is the robot's parameters, not only its pose. DDS-free; the
// live calibration component holds one and publishes what it returns.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "structloc/calibration_core/calibration_data.hpp"
#include "structloc/calibration_core/calibration_recorder.hpp"
#include "structloc/calibration_core/odometry_calibration.hpp"
#include "structloc/kinematics/robot_parameters.hpp"

namespace structloc::calibration_core {

struct OnlineCalibrationOptions {
  double window_s = 120.0;     // stamp seconds of encoders and fixes each estimate uses
  double period_s = 30.0;      // a new estimate after this much more stamp time
  double change_sigmas = 3.0;  // a larger change between independent windows is flagged
  // Throws std::invalid_argument naming the broken option.
  void Validate() const;
};

// A parameter that moved between two estimates from windows sharing no data.
struct ParameterChange {
  Parameter parameter = kWheelRadius;
  double from = 0.0, to = 0.0;
  double sigmas = 0.0;  // |to - from| / sqrt(sd_from^2 + sd_to^2)
};

struct OnlineEstimate {
  CalibrationReport report;
  double window_start_s = 0.0, window_end_s = 0.0;  // encoder stamps the estimate used
  // Flagged changes against `reference_end_s`'s estimate (none when there is
  // no earlier independent estimate or the estimate failed).
  std::vector<ParameterChange> changes;
  std::optional<double> reference_end_s;
};

// "wheel_radius 0.1870 -> 0.1885 m (+0.80 %, 5.2 sigma)".
std::string Describe(const ParameterChange& change);

class OnlineCalibration {
 public:
  // Throws std::invalid_argument for invalid options or nominal parameters.
  OnlineCalibration(const kinematics::RobotParameters& nominal, const CalibrationOptions& options,
                    const OnlineCalibrationOptions& online);

  // Return false when the sample was refused (out of order or out of line,
  // not finite). A jump back of the stamps (a clock stepped back) restarts the
  // windows and the estimates compared with (CalibrationRecorder).
  bool AddEncoders(const EncoderSample& sample);
  bool AddFix(const Fix& fix);

  // A full window is recorded and a period has passed since the last estimate.
  bool Due() const;

  // The newest window_s of encoders and fixes, which the next estimate uses;
  // older samples are forgotten. Cheap: a live component takes it under the
  // lock its sample callbacks share and estimates outside it.
  struct Window {
    Recording recording;
    double start_s = 0.0, end_s = 0.0;
  };
  Window NextWindow();
  // Estimates from `window` and compares with the newest earlier estimate
  // whose window ended before this one starts. Touches nothing the Add
  // functions or NextWindow touch. Never throws for bad data: a failed
  // estimate is reported with success == false.
  OnlineEstimate Estimate(const Window& window);
  // Both in one (single-threaded use).
  OnlineEstimate Estimate() { return Estimate(NextWindow()); }

  // Encoder samples and fixes in the window, and the samples refused so far.
  RecorderStats Stats() const { return recorder_.Stats(); }

 private:
  struct Past {
    double window_end_s;
    CalibrationReport report;
  };

  kinematics::RobotParameters nominal_;
  CalibrationOptions options_;
  OnlineCalibrationOptions online_;
  // After the recorder restarted: the window and the history are on the old clock.
  void FollowRestarts();

  CalibrationRecorder recorder_;
  size_t restarts_seen_ = 0;
  std::optional<double> last_end_s_;
  std::vector<Past> history_;  // successful estimates, oldest first
};

}  // namespace structloc::calibration_core
