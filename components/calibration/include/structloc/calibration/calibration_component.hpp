// The odometry-calibration component: records the wheel-encoder stream and
// position fixes (rt/pose from the localisation, or any PoseWithCovarianceStamped
// topic) for a given time, or until it is stopped, then estimates the
// parameters with the DDS-free calibration core, publishes the result latched
// (RELIABLE + TRANSIENT_LOCAL: late subscribers still get it) and writes the
// recording and the calibrated robot file; a restarted component publishes
// the last result kept in its --out-dir again (last_result_file.hpp). What is
// recorded and when to estimate is the DDS-free
// calibration_core::CalibrationRecorder's policy (gaps in the encoder
// stream are detected and reported, never silently bridged); this component
// converts and moves messages around it. A failed estimate of a
// complete recording, or a result that cannot be written, makes the process
// exit non-zero. Online (--window-s): the DDS-free
// calibration_core::OnlineCalibration re-estimates over a sliding window every
// period and each estimate is published with its covariance and the
// parameters flagged as changed (also a WARN on rt/diagnostics).
#pragma once

#include <atomic>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "structloc/calibration_core/calibration_data.hpp"
#include "structloc/calibration_core/calibration_recorder.hpp"
#include "structloc/calibration_core/odometry_calibration.hpp"
#include "structloc/calibration_core/online_calibration.hpp"
#include "structloc/dds_common/component_runtime.hpp"
#include "structloc_msgs/msg/CalibrationResultPubSubTypes.h"
#include "structloc_msgs/msg/WheelEncodersPubSubTypes.h"

namespace structloc::calibration {

struct CalibrationComponentOptions {
  kinematics::RobotParameters nominal;
  std::string robot_path;  // the nominal robot file: never overwritten
  calibration_core::CalibrationOptions calibration;
  double record_s = 60.0;  // recording length in stamp time; 0 = until stopped
  // Online re-estimation over a sliding window (window_s > 0; record_s is then unused).
  bool online = false;
  calibration_core::OnlineCalibrationOptions online_options;
  std::string fix_topic = dds_common::topics::kPose.name;
  std::string out_dir;  // encoders.csv, fixes.csv, calibrated.xml ("" = none)
  bool exit_when_done = false;

  // Throws config::ConfigError (exit code 2) for options that cannot work: an
  // empty --fix-topic or one of structloc's topics of another message type,
  // nothing to estimate, an --out-dir that is not (and cannot become) a
  // writable folder. Creates --out-dir when it is missing.
  void Validate() const;
};

class CalibrationComponent : public dds_common::Component {
 public:
  CalibrationComponent(dds_common::Node& node, const CalibrationComponentOptions& options);
  void Step() override;
  // Estimates with what was recorded if that has not happened yet; throws
  // std::runtime_error (exit code 1) when the result could not be written, or
  // when the calibration failed after a complete recording (--record-s
  // reached, or 0 = until stopped).
  void Stop() override;
  bool Done() const override { return options_.exit_when_done && estimated_; }

 private:
  // Takes an encoder sample of the robot file's drive kind and counter width;
  // counts and refuses any other.
  void AddEncoders(const structloc_msgs::msg::WheelEncoders& m);
  void EstimateOnline();
  // `stopped_early`: the recording was cut short by a stop before --record-s.
  void Estimate(bool stopped_early);
  // Writes the recording and, for a successful estimate, calibrated.xml into
  // out_dir; returns what went wrong, or "" when everything was written.
  std::string WriteResults(const std::vector<calibration_core::EncoderSample>& encoders,
                           const std::vector<calibration_core::Fix>& fixes,
                           const calibration_core::CalibrationReport& report) const;
  void PublishDiagnostics(double now);
  // Publishes `msg` and, with an --out-dir, keeps it there for a restart;
  // returns what could not be saved ("" when all went well).
  std::string PublishResult(const structloc_msgs::msg::CalibrationResult& msg);
  // At start: publishes the result a previous run kept in --out-dir, if any
  // (a file that cannot be read is reported and left alone).
  void RepublishLastResult();

  CalibrationComponentOptions options_;
  dds_common::TopicWriter<structloc_msgs::msg::CalibrationResultPubSubType> result_;
  dds_common::TopicWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType> diagnostics_;
  std::mutex mutex_;  // guards the members up to failure_
  calibration_core::CalibrationRecorder recorder_;
  // Online mode only; its samples and NextWindow under mutex_, its Estimate
  // (the worker's alone) outside it.
  std::optional<calibration_core::OnlineCalibration> online_;
  size_t encoders_wrong_kind_ = 0;    // of another drive kind or counter width than the robot file
  std::vector<std::string> changed_;  // the newest online estimate's flagged changes
  std::string outcome_;
  std::string failure_;  // why the run produced no usable result ("" = it did)
  std::atomic<bool> estimated_{false};
  double last_diagnostics_s_ = 0.0;
  // Last: destroyed first, so no sample reaches the members above then.
  dds_common::Subscription encoders_subscription_;
  dds_common::Subscription fixes_subscription_;
};

}  // namespace structloc::calibration
