// Calibration component (see header).
#include "structloc/calibration/calibration_component.hpp"

#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "structloc/calibration/calibration_conversions.hpp"
#include "structloc/calibration_core/calibration_problem.hpp"
#include "structloc/config/output_file.hpp"
#include "structloc/dds_common/diagnostics.hpp"
#include "structloc/log_formats/recording_writers.hpp"

namespace structloc::calibration {
namespace {

void CheckFixTopic(const std::string& topic) {
  const std::string hint =
      "; give a topic of geometry_msgs/PoseWithCovarianceStamped fixes (default rt/pose)";
  if (topic.empty()) throw config::ConfigError("--fix-topic is empty" + hint);
  for (const char c : topic) {
    if (!std::isgraph(static_cast<unsigned char>(c))) {
      throw config::ConfigError("--fix-topic '" + topic +
                                "' contains a space or control character" + hint);
    }
  }
  namespace t = dds_common::topics;
  for (const auto* other :
       {&t::kScan, &t::kOdom, &t::kWheelEncoders, &t::kGroundTruth, &t::kCmdVel, &t::kTf,
        &t::kFeatures, &t::kStatus, &t::kCalibration, &t::kDiagnostics}) {
    if (topic == other->name) {
      throw config::ConfigError("--fix-topic " + topic +
                                " is a structloc topic of another message type (no fix would "
                                "ever arrive)" +
                                hint);
    }
  }
}

void PrepareOutputFolder(const std::string& folder) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (!std::filesystem::is_directory(folder)) {
    throw config::ConfigError("--out-dir " + folder +
                              (std::filesystem::exists(folder)
                                   ? std::string(" exists and is not a folder")
                                   : " cannot be created (" + error.message() + ")") +
                              "; give a folder for encoders.csv, fixes.csv and calibrated.xml");
  }
  if (::access(folder.c_str(), W_OK | X_OK) != 0) {
    throw config::ConfigError("--out-dir " + folder + " is not writable");
  }
}

}  // namespace

void CalibrationComponentOptions::Validate() const {
  CheckFixTopic(fix_topic);
  if (!(record_s >= 0)) throw config::ConfigError("--record-s must be >= 0");
  try {
    calibration.Validate();
  } catch (const std::invalid_argument& e) {
    throw config::ConfigError(e.what());
  }
  if (!out_dir.empty()) PrepareOutputFolder(out_dir);
}

CalibrationComponent::CalibrationComponent(dds_common::Node& node,
                                           const CalibrationComponentOptions& options)
    : options_(options),
      result_(node.CreateWriter<structloc_msgs::msg::CalibrationResultPubSubType>(
          dds_common::topics::kCalibration)),
      diagnostics_(node.CreateWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
          dds_common::topics::kDiagnostics)),
      recorder_(calibration_core::RecorderOptions{options.record_s,
                                                  options.calibration.max_encoder_gap_s}) {
  encoders_subscription_ = node.Subscribe<structloc_msgs::msg::WheelEncodersPubSubType>(
      dds_common::topics::kWheelEncoders, [this](const structloc_msgs::msg::WheelEncoders& m) {
        const auto sample = FromWheelEncoders(m);
        std::lock_guard<std::mutex> lock(mutex_);
        recorder_.AddEncoders(sample);
      });
  // Fixes RELIABLE (the reliable_state profile): none may be lost.
  fixes_subscription_ = node.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
      {options_.fix_topic, dds_common::qos_profiles::kReliableState},
      [this](const geometry_msgs::msg::PoseWithCovarianceStamped& m) {
        const auto fix = FromPoseFix(m);
        std::lock_guard<std::mutex> lock(mutex_);
        recorder_.AddFix(fix);
      });
  std::ostringstream length;
  if (options_.record_s > 0) {
    length << options_.record_s << " s";
  } else {
    length << "until stopped";
  }
  std::cout << "calibration: recording " << dds_common::topics::kWheelEncoders.name << " and "
            << options_.fix_topic << " for " << length.str() << std::endl;
}

void CalibrationComponent::Step() {
  const double now = dds_common::WallClockSeconds();
  bool due = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    due = recorder_.Due();
  }
  if (due) Estimate(false);
  if (now - last_diagnostics_s_ >= 1.0) PublishDiagnostics(now);
}

void CalibrationComponent::Stop() {
  bool pending = false;
  bool early = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending = recorder_.WorthEstimating();
    early = recorder_.StopIsEarly();
  }
  if (pending) Estimate(early);
  std::lock_guard<std::mutex> lock(mutex_);
  if (!failure_.empty()) throw std::runtime_error(failure_);
}

void CalibrationComponent::Estimate(bool stopped_early) {
  calibration_core::Recording recording;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    recording = recorder_.Finish();
    estimated_ = true;
  }
  const auto& encoders = recording.encoders;
  const auto& fixes = recording.fixes;
  calibration_core::CalibrationReport report;
  try {
    report = calibration_core::Calibrate(encoders, fixes, options_.nominal, options_.calibration);
  } catch (const std::exception& e) {
    report.success = false;
    report.failure = e.what();
  }
  std::ostringstream text;
  text << "calibration: " << (report.success ? "estimated" : "FAILED") << " from "
       << encoders.size() << " encoder samples and " << fixes.size() << " fixes";
  for (int k = 0; k < calibration_core::kParameterCount; ++k) {
    if (!report.estimated[static_cast<size_t>(k)]) continue;
    text << "\n  " << calibration_core::ParameterName(static_cast<calibration_core::Parameter>(k))
         << " " << calibration_core::ValuesOf(report.parameters)[static_cast<size_t>(k)] << " +- "
         << report.standard_deviation[static_cast<size_t>(k)];
  }
  for (const auto& w : report.warnings) text << "\n  WARNING: " << w;
  if (!report.success && !report.failure.empty()) text << "\n  FAILED: " << report.failure;
  for (const auto& cause : report.likely_causes) text << "\n  likely cause: " << cause;
  std::cout << text.str() << std::endl;
  const std::string write_error = WriteResults(encoders, fixes, report);
  if (!write_error.empty()) std::cerr << "calibration: " << write_error << std::endl;
  auto msg = ToCalibrationResult(report, encoders.empty() ? 0.0 : encoders.back().t);
  result_.Write(msg);
  std::lock_guard<std::mutex> lock(mutex_);
  const std::string why = !report.failure.empty()   ? report.failure
                          : report.warnings.empty() ? std::string("?")
                                                    : report.warnings.back();
  outcome_ = report.success ? "calibrated" : "calibration failed: " + why;
  if (!write_error.empty()) {
    failure_ = "the result could not be written: " + write_error;
  } else if (!report.success && !stopped_early) {
    failure_ = "calibration failed: " + why;
  }
}

std::string CalibrationComponent::WriteResults(
    const std::vector<calibration_core::EncoderSample>& encoders,
    const std::vector<calibration_core::Fix>& fixes,
    const calibration_core::CalibrationReport& report) const {
  if (options_.out_dir.empty()) return "";
  try {
    log_formats::EncodersCsvWriter enc(options_.out_dir + "/encoders.csv");
    for (const auto& s : encoders)
      enc.Sample(s.t, s.traction_ticks, static_cast<int64_t>(s.steering_ticks));
    log_formats::FixesCsvWriter fix(options_.out_dir + "/fixes.csv", true);
    for (const auto& f : fixes)
      fix.Fix(f.t, f.pose, f.variance.x(), f.variance.y(), f.variance.z());
    std::optional<config::OutputFile> robot;
    if (report.success) {
      robot.emplace(options_.out_dir + "/calibrated.xml",
                    std::vector<std::string>{options_.robot_path});
      kinematics::WriteRobotParameters(report.parameters, robot->Stream(),
                                       "calibrated live by structloc_calibration");
    }
    // Every file reaches the disk before any replaces an earlier one.
    enc.Flush();
    fix.Flush();
    if (robot) robot->Flush();
    enc.Close();
    fix.Close();
    if (robot) robot->Commit();
  } catch (const std::exception& e) {
    return e.what();
  }
  std::cout << "calibration: wrote " << options_.out_dir << std::endl;
  return "";
}

void CalibrationComponent::PublishDiagnostics(double now) {
  last_diagnostics_s_ = now;
  dds_common::HealthReport report;
  calibration_core::RecorderStats stats;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stats = recorder_.Stats();
    report.message = recorder_.Finished() ? outcome_ : "recording";
  }
  if (stats.gaps > 0 || stats.encoders_out_of_order > 0)
    report.level = dds_common::HealthLevel::kWarn;
  if (stats.gaps > 0) {
    report.message += "; " + std::to_string(stats.gaps) + " gaps in the encoder stream";
  }
  report.values = {{"encoder_samples", std::to_string(stats.encoders)},
                   {"fixes", std::to_string(stats.fixes)},
                   {"encoder_gaps", std::to_string(stats.gaps)},
                   {"largest_encoder_gap_s", std::to_string(stats.largest_gap_s)},
                   {"encoders_out_of_order", std::to_string(stats.encoders_out_of_order)},
                   {"fixes_rejected", std::to_string(stats.fixes_rejected)}};
  diagnostics_.Write(dds_common::ToDiagnosticArray("calibration", report, now));
}

}  // namespace structloc::calibration
