// Calibration component (see header).
#include "structloc/calibration/calibration_component.hpp"

#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "structloc/calibration/calibration_conversions.hpp"
#include "structloc/calibration/last_result_file.hpp"
#include "structloc/calibration_core/calibration_problem.hpp"
#include "structloc/config/output_file.hpp"
#include "structloc/dds_common/diagnostics.hpp"
#include "structloc/log_formats/recording_writers.hpp"

namespace structloc::calibration {
namespace {

// The estimate in a few lines for the log.
std::string Summary(const calibration_core::CalibrationReport& report, size_t encoders,
                    size_t fixes, const calibration_core::RecorderStats& stream, double max_gap_s) {
  std::ostringstream text;
  text << "calibration: " << (report.success ? "estimated" : "FAILED") << " from " << encoders
       << " encoder samples and " << fixes << " fixes";
  text << "\n  encoder stream: largest gap " << stream.largest_gap_s << " s, " << stream.gaps
       << " gaps over " << max_gap_s << " s, " << stream.encoders_out_of_order
       << " samples out of order or out of line; fixes refused: " << stream.fixes_rejected
       << "; restarts after the stamps jumped back: " << stream.restarts;
  for (int k = 0; k < calibration_core::kParameterCount; ++k) {
    if (!report.estimated[static_cast<size_t>(k)]) continue;
    text << "\n  " << calibration_core::ParameterName(static_cast<calibration_core::Parameter>(k))
         << " " << calibration_core::ValuesOf(report.parameters)[static_cast<size_t>(k)] << " +- "
         << report.standard_deviation[static_cast<size_t>(k)];
  }
  for (const auto& w : report.warnings) text << "\n  WARNING: " << w;
  if (!report.success && !report.failure.empty()) text << "\n  FAILED: " << report.failure;
  for (const auto& cause : report.likely_causes) text << "\n  likely cause: " << cause;
  return text.str();
}

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
    if (online) online_options.Validate();
  } catch (const std::invalid_argument& e) {
    throw config::ConfigError(e.what());
  }
  if (!out_dir.empty()) {
    PrepareOutputFolder(out_dir);
    // Outputs written over and over: never over the robot file read.
    for (const char* name : {"encoders.csv", "fixes.csv", "calibrated.xml", kLastResultFileName}) {
      config::RefuseOverwritingInput(out_dir + "/" + name, {robot_path});
    }
  }
}

CalibrationComponent::CalibrationComponent(dds_common::Node& node,
                                           const CalibrationComponentOptions& options)
    : options_(options),
      result_(node.CreateWriter<structloc_msgs::msg::CalibrationResultPubSubType>(
          dds_common::topics::kCalibration)),
      diagnostics_(node.CreateWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
          dds_common::topics::kDiagnostics)),
      recorder_(calibration_core::RecorderOptions{
          options.record_s, options.calibration.max_encoder_gap_s, {}}) {
  if (options_.online) {
    online_.emplace(options_.nominal, options_.calibration, options_.online_options);
  }
  encoders_subscription_ = node.Subscribe<structloc_msgs::msg::WheelEncodersPubSubType>(
      dds_common::topics::kWheelEncoders,
      [this](const structloc_msgs::msg::WheelEncoders& m) { AddEncoders(m); });
  // Fixes RELIABLE (the reliable_state profile): none may be lost.
  fixes_subscription_ = node.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
      {options_.fix_topic, dds_common::qos_profiles::kReliableState},
      [this](const geometry_msgs::msg::PoseWithCovarianceStamped& m) {
        const auto fix = FromPoseFix(m);
        std::lock_guard<std::mutex> lock(mutex_);
        if (online_) {
          online_->AddFix(fix);
        } else {
          recorder_.AddFix(fix);
        }
      });
  std::ostringstream length;
  if (online_) {
    length << "ever (estimating over the last " << options_.online_options.window_s << " s every "
           << options_.online_options.period_s << " s)";
  } else if (options_.record_s > 0) {
    length << options_.record_s << " s";
  } else {
    length << "until stopped";
  }
  RepublishLastResult();
  std::cout << "calibration: recording " << dds_common::topics::kWheelEncoders.name << " and "
            << options_.fix_topic << " for " << length.str() << std::endl;
}

void CalibrationComponent::AddEncoders(const structloc_msgs::msg::WheelEncoders& m) {
  const bool differential = options_.nominal.kind == kinematics::DriveKind::kDifferential;
  // A counter width of 0 is a publisher that does not say: the robot file decides.
  const bool fits = m.differential() == differential &&
                    (m.traction_counter_bits() == 0 ||
                     m.traction_counter_bits() == options_.nominal.traction_counter_bits);
  const auto sample = FromWheelEncoders(m);
  std::lock_guard<std::mutex> lock(mutex_);
  if (!fits) {
    if (encoders_wrong_kind_++ == 0) {
      std::cerr << "calibration: refusing wheel encoders of a "
                << (m.differential() ? "differential drive" : "tricycle") << " with "
                << static_cast<int>(m.traction_counter_bits()) << "-bit counters: the robot file "
                << options_.robot_path << " describes a "
                << (differential ? "differential drive" : "tricycle") << " with "
                << options_.nominal.traction_counter_bits << "-bit counters" << std::endl;
    }
    return;
  }
  if (online_) {
    online_->AddEncoders(sample);
  } else {
    recorder_.AddEncoders(sample);
  }
}

void CalibrationComponent::Step() {
  const double now = dds_common::WallClockSeconds();
  bool due = false, due_online = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    due = !online_ && recorder_.Due();
    due_online = online_ && online_->Due();
  }
  if (due) Estimate(false);
  if (due_online) EstimateOnline();
  if (now - last_diagnostics_s_ >= 1.0) PublishDiagnostics(now);
}

void CalibrationComponent::Stop() {
  bool pending = false;
  bool early = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (online_) return;  // every window was estimated as it came
    pending = recorder_.WorthEstimating();
    early = recorder_.StopIsEarly();
  }
  if (pending) Estimate(early);
  std::lock_guard<std::mutex> lock(mutex_);
  if (!failure_.empty()) throw std::runtime_error(failure_);
}

void CalibrationComponent::Estimate(bool stopped_early) {
  calibration_core::Recording recording;
  calibration_core::RecorderStats stream;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    recording = recorder_.Finish();
    stream = recorder_.Stats();
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
  std::cout << Summary(report, encoders.size(), fixes.size(), stream,
                       options_.calibration.max_encoder_gap_s)
            << std::endl;
  std::string write_error = WriteResults(encoders, fixes, report);
  const auto msg = ToCalibrationResult(report, encoders.empty() ? 0.0 : encoders.front().t,
                                       encoders.empty() ? 0.0 : encoders.back().t);
  const std::string save_error = PublishResult(msg);
  if (write_error.empty()) write_error = save_error;
  if (!write_error.empty()) std::cerr << "calibration: " << write_error << std::endl;
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

void CalibrationComponent::EstimateOnline() {
  calibration_core::OnlineCalibration::Window window;
  calibration_core::RecorderStats stream;
  {
    // Only the copy under the lock: samples keep arriving while it estimates.
    std::lock_guard<std::mutex> lock(mutex_);
    window = online_->NextWindow();
    stream = online_->Stats();
  }
  const calibration_core::OnlineEstimate estimate = online_->Estimate(window);
  const auto& encoders = window.recording.encoders;
  const auto& fixes = window.recording.fixes;
  const auto message = ToCalibrationResult(estimate);
  std::ostringstream text;
  text << Summary(estimate.report, encoders.size(), fixes.size(), stream,
                  options_.calibration.max_encoder_gap_s)
       << "\n  window " << estimate.window_start_s << " .. " << estimate.window_end_s << " s";
  for (const auto& change : message.changed()) text << "\n  CHANGED: " << change;
  std::cout << text.str() << std::endl;
  std::string write_error = WriteResults(encoders, fixes, estimate.report);
  const std::string save_error = PublishResult(message);
  if (write_error.empty()) write_error = save_error;
  if (!write_error.empty()) std::cerr << "calibration: " << write_error << std::endl;
  estimated_ = true;
  std::lock_guard<std::mutex> lock(mutex_);
  changed_ = message.changed();
  outcome_ =
      estimate.report.success
          ? "calibrated over the window ending at " + std::to_string(estimate.window_end_s) + " s"
          : "calibration of the window failed: " + estimate.report.failure;
  if (!write_error.empty()) failure_ = "the result could not be written: " + write_error;
}

std::string CalibrationComponent::PublishResult(const structloc_msgs::msg::CalibrationResult& msg) {
  result_.Write(msg);
  if (options_.out_dir.empty()) return "";
  return SaveLastResult(options_.out_dir + "/" + kLastResultFileName, msg);
}

void CalibrationComponent::RepublishLastResult() {
  if (options_.out_dir.empty()) return;
  const std::string path = options_.out_dir + "/" + kLastResultFileName;
  if (!std::filesystem::exists(path)) return;
  std::string why;
  if (const auto last = LoadLastResult(path, why)) {
    result_.Write(*last);
    std::cout << "calibration: published the last result again, from " << path << " ("
              << (last->success() ? "a calibration" : "a failed calibration") << " of "
              << last->window_end().sec() << " s)" << std::endl;
  } else {
    std::cerr << "calibration: WARNING: not publishing the last result again: " << why << std::endl;
  }
}

std::string CalibrationComponent::WriteResults(
    const std::vector<calibration_core::EncoderSample>& encoders,
    const std::vector<calibration_core::Fix>& fixes,
    const calibration_core::CalibrationReport& report) const {
  if (options_.out_dir.empty()) return "";
  try {
    const bool differential = options_.nominal.kind == kinematics::DriveKind::kDifferential;
    log_formats::EncodersCsvWriter enc(options_.out_dir + "/encoders.csv", {}, differential);
    for (const auto& s : encoders) {
      if (differential) {
        enc.SampleWheels(s.t, s.left_ticks, s.right_ticks);
      } else {
        enc.Sample(s.t, s.traction_ticks, static_cast<int64_t>(s.steering_ticks));
      }
    }
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
  size_t wrong_kind = 0;
  std::vector<std::string> changed;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stats = online_ ? online_->Stats() : recorder_.Stats();
    report.message =
        recorder_.Finished() || (online_ && !outcome_.empty()) ? outcome_ : "recording";
    wrong_kind = encoders_wrong_kind_;
    changed = changed_;
  }
  if (stats.gaps > 0 || stats.encoders_out_of_order > 0 || wrong_kind > 0 || stats.restarts > 0 ||
      !changed.empty())
    report.level = dds_common::HealthLevel::kWarn;
  for (const auto& change : changed) report.message += "; CHANGED: " + change;
  if (stats.gaps > 0) {
    report.message += "; " + std::to_string(stats.gaps) + " gaps in the encoder stream";
  }
  if (stats.restarts > 0) {
    report.message += "; recording restarted " + std::to_string(stats.restarts) +
                      " times after the stamps jumped back";
  }
  if (wrong_kind > 0) {
    report.message += "; " + std::to_string(wrong_kind) +
                      " encoder samples of another drive kind or counter width than the robot "
                      "file refused";
  }
  report.values = {{"encoder_samples", std::to_string(stats.encoders)},
                   {"fixes", std::to_string(stats.fixes)},
                   {"encoder_gaps", std::to_string(stats.gaps)},
                   {"largest_encoder_gap_s", std::to_string(stats.largest_gap_s)},
                   {"encoders_out_of_order", std::to_string(stats.encoders_out_of_order)},
                   {"fixes_rejected", std::to_string(stats.fixes_rejected)},
                   {"stamp_restarts", std::to_string(stats.restarts)},
                   {"encoders_wrong_kind", std::to_string(wrong_kind)}};
  diagnostics_.Write(dds_common::ToDiagnosticArray("calibration", report, now));
}

}  // namespace structloc::calibration
