// "structloc record": a robot's laser and odometry, heard on a DDS domain like
// any client hears them, written to a CARMEN log that replay, map building
// and calibration read (log_formats::CarmenRecording puts the lines in time
// order with each scan's odometric pose), with the laser's mounting from
// --sensor-mount or the transforms from base_link down to the laser's frame on
// rt/tf_static (dds_common::StaticTransforms); the
// wheel encoders to an encoders.csv and the simulator's ground truth to a TUM
// file when asked. It stops on Ctrl-C (or SIGTERM), after --duration-s, or
// once the scans have been silent --quiet-s after the first, and writes
// everything received before it stops: outputs reach their names only then.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>

#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "structloc/config/command_line.hpp"
#include "structloc/config/strict_number.hpp"
#include "structloc/dds_common/component_runtime.hpp"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/dds_common/static_transforms.hpp"
#include "structloc/log_formats/carmen_recording.hpp"
#include "structloc/process/shutdown_signal.hpp"
#include "structloc_msgs/msg/WheelEncodersPubSubTypes.h"
#include "subcommands.hpp"
#include "tf2_msgs/msg/TFMessagePubSubTypes.h"

namespace structloc::cli {
namespace {

using Clock = std::chrono::steady_clock;

std::vector<config::OptionSpec> RecordOptions() {
  std::vector<config::OptionSpec> specs = dds_common::StandardOptions();
  for (auto& spec : dds_common::FrameIdOptions(dds_common::BaseFrame::kNamed))
    specs.push_back(spec);
  specs.push_back({"out", true, "the CARMEN log to write (required; .log or .clf)"});
  specs.push_back({"sensor-mount", true,
                   "\"X Y THETA\": the laser on the robot, metres and radians (default: the "
                   "transforms from the base frame down to the laser frame on rt/tf_static)"});
  specs.push_back({"encoders-out", true, "also write the wheel encoders to this encoders.csv"});
  specs.push_back({"truth-out", true, "also write the simulator's ground truth to this TUM file"});
  specs.push_back({"duration-s", true, "stop after this long, 0.1..1e6 s (default: Ctrl-C)"});
  specs.push_back({"quiet-s", true,
                   "stop once the scans have been silent this long after the first, 0.1..1e6 s "
                   "(default: Ctrl-C)"});
  return specs;
}

// The outputs and what writes them; every call under `mutex`.
struct Recorder {
  std::mutex mutex;
  std::unique_ptr<log_formats::CarmenWriter> log;
  std::unique_ptr<log_formats::CarmenRecording> recording;
  std::unique_ptr<log_formats::TumWriter> truth;
  std::string encoders_path;
  std::vector<std::string> outputs;  // written before: the encoders file must not replace one
  std::unique_ptr<log_formats::EncodersCsvWriter> encoders;  // at the first sample
  bool time_increment_written = false;
  size_t encoder_samples = 0, truth_poses = 0;
  std::optional<Clock::time_point> last_scan;
  dds_common::StaticTransforms statics;  // rt/tf_static, until the mounting is known
};

void OnScan(Recorder& r, const sensor_msgs::msg::LaserScan& m) {
  log_formats::CarmenLaser laser;
  laser.start_angle = m.angle_min();
  laser.angular_resolution = m.angle_increment();
  laser.field_of_view =
      m.angle_increment() * static_cast<double>(m.ranges().empty() ? 0 : m.ranges().size() - 1);
  laser.max_range = m.range_max();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (!r.time_increment_written && m.time_increment() > 0.0 && std::isfinite(m.time_increment())) {
    r.log->Param("structloc_laser_time_increment", m.time_increment());
    r.time_increment_written = true;
  }
  r.recording->AddScan(dds_common::FromRosTime(m.header().stamp()), laser, m.ranges());
  r.last_scan = Clock::now();
}

void OnOdometry(Recorder& r, const nav_msgs::msg::Odometry& m) {
  const auto& p = m.pose().pose();
  const geometry::Pose2D pose{p.position().x(), p.position().y(),
                              dds_common::YawFromQuaternion(p.orientation())};
  std::lock_guard<std::mutex> lock(r.mutex);
  r.recording->AddOdometry(dds_common::FromRosTime(m.header().stamp()), pose,
                           m.twist().twist().linear().x(), m.twist().twist().angular().z());
}

void OnEncoders(Recorder& r, const structloc_msgs::msg::WheelEncoders& m) {
  const double t = dds_common::FromRosTime(m.header().stamp());
  std::lock_guard<std::mutex> lock(r.mutex);
  if (!r.encoders)
    r.encoders = std::make_unique<log_formats::EncodersCsvWriter>(r.encoders_path, r.outputs,
                                                                  m.differential());
  if (m.differential()) {
    r.encoders->SampleWheels(t, m.left_ticks(), m.right_ticks());
  } else {
    r.encoders->Sample(t, m.traction_ticks(), m.steering_ticks());
  }
  ++r.encoder_samples;
}

void OnTruth(Recorder& r, const nav_msgs::msg::Odometry& m) {
  const auto& p = m.pose().pose();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.truth->Pose(
      dds_common::FromRosTime(m.header().stamp()),
      {p.position().x(), p.position().y(), dds_common::YawFromQuaternion(p.orientation())});
  ++r.truth_poses;
}

void OnTfStatic(Recorder& r, const tf2_msgs::msg::TFMessage& m, const dds_common::FrameIds& f) {
  std::lock_guard<std::mutex> lock(r.mutex);
  if (r.recording->HasMount()) return;
  r.statics.Add(m);
  std::string path;
  const auto mount = r.statics.Chain(f.base_link, f.laser, path);
  if (!mount) return;
  r.recording->SetMount(*mount);
  std::printf("  the laser's mounting from %s (%s): (%.3f, %.3f, %.3f)\n",
              dds_common::topics::kTfStatic.name.c_str(), path.c_str(), mount->x, mount->y,
              mount->theta);
  std::fflush(stdout);
}

}  // namespace

int RecordCommand(const Invocation& inv) {
  const auto specs = RecordOptions();
  try {
    const config::CommandLine cli(inv.argc, inv.argv, 2, specs);
    // First, before DDS starts the threads that would inherit the signals.
    process::ShutdownSignal shutdown;
    const std::string out = cli.Required("out");
    std::optional<geometry::Pose2D> mount;
    if (cli.Has("sensor-mount")) {
      const std::string text = cli.Required("sensor-mount");
      const auto m = config::ParseNumberList(text, 3);
      if (!m) {
        throw config::ConfigError(
            "--sensor-mount must be exactly three numbers \"X Y THETA\", got '" + text + "'");
      }
      mount = geometry::Pose2D{(*m)[0], (*m)[1], (*m)[2]};
    }
    std::optional<double> duration_s, quiet_s;
    if (cli.Has("duration-s")) duration_s = cli.NumberIn("duration-s", 0, 0.1, 1e6);
    if (cli.Has("quiet-s")) quiet_s = cli.NumberIn("quiet-s", 0, 0.1, 1e6);
    const dds_common::FrameIds frames = dds_common::FrameIdsFrom(cli);
    const auto node_options = dds_common::NodeOptionsFrom(cli, "record", "operator");

    Recorder r;
    r.outputs.push_back(out);
    r.log = std::make_unique<log_formats::CarmenWriter>(out);
    r.log->Comment("recorded by structloc record from DDS domain " +
                   std::to_string(node_options.domain_id));
    r.recording = std::make_unique<log_formats::CarmenRecording>(*r.log, mount);
    if (cli.Has("truth-out")) {
      r.truth = std::make_unique<log_formats::TumWriter>(cli.Required("truth-out"), r.outputs);
      r.outputs.push_back(cli.Required("truth-out"));
    }
    if (cli.Has("encoders-out")) r.encoders_path = cli.Required("encoders-out");

    dds_common::Node node(node_options);
    std::vector<dds_common::Subscription> subscriptions;
    namespace t = dds_common::topics;
    subscriptions.push_back(node.Subscribe<sensor_msgs::msg::LaserScanPubSubType>(
        t::kScan, [&r](const sensor_msgs::msg::LaserScan& m) { OnScan(r, m); }));
    subscriptions.push_back(node.Subscribe<nav_msgs::msg::OdometryPubSubType>(
        t::kOdom, [&r](const nav_msgs::msg::Odometry& m) { OnOdometry(r, m); }));
    if (!mount) {
      subscriptions.push_back(node.Subscribe<tf2_msgs::msg::TFMessagePubSubType>(
          t::kTfStatic,
          [&r, &frames](const tf2_msgs::msg::TFMessage& m) { OnTfStatic(r, m, frames); }));
    }
    if (!r.encoders_path.empty()) {
      subscriptions.push_back(node.Subscribe<structloc_msgs::msg::WheelEncodersPubSubType>(
          t::kWheelEncoders,
          [&r](const structloc_msgs::msg::WheelEncoders& m) { OnEncoders(r, m); }));
    }
    if (r.truth) {
      subscriptions.push_back(node.Subscribe<nav_msgs::msg::OdometryPubSubType>(
          t::kGroundTruth, [&r](const nav_msgs::msg::Odometry& m) { OnTruth(r, m); }));
    }
    std::printf("structloc record: DDS domain %d, %s and %s to %s; Ctrl-C stops\n",
                node_options.domain_id, t::kScan.name.c_str(), t::kOdom.name.c_str(), out.c_str());
    std::fflush(stdout);

    const auto start = Clock::now();
    std::string why = "Ctrl-C or SIGTERM";
    while (!shutdown.WaitFor(std::chrono::milliseconds(100))) {
      std::lock_guard<std::mutex> lock(r.mutex);
      r.recording->WriteReady();
      const auto now = Clock::now();
      if (duration_s && now - start >= std::chrono::duration<double>(*duration_s)) {
        why = "--duration-s reached";
        break;
      }
      if (quiet_s && r.last_scan && now - *r.last_scan >= std::chrono::duration<double>(*quiet_s)) {
        why = "the scans fell silent";
        break;
      }
    }
    subscriptions.clear();  // no sample arrives after this
    const bool mounted = r.recording->Finish();
    const auto& s = r.recording->Stats();
    std::printf("structloc record: stopped (%s): %zu scans and %zu odometry samples in %s\n",
                why.c_str(), s.scans, s.odometry, out.c_str());
    if (s.scans_nearest_odometry > 0)
      std::printf("  %zu scans without odometry on both sides took the nearest sample\n",
                  s.scans_nearest_odometry);
    if (s.scans_late > 0) std::printf("  %zu scans came out of order\n", s.scans_late);
    if (s.rejected > 0) std::printf("  %zu samples with non-finite values left out\n", s.rejected);
    if (r.statics.Dropped() > 0)
      std::printf("  WARNING: %zu transforms on %s to frames beyond the first %zu were ignored\n",
                  r.statics.Dropped(), t::kTfStatic.name.c_str(),
                  dds_common::StaticTransforms::kMaxFrames);
    if (!mounted)
      std::printf(
          "  WARNING: no laser mounting was heard (no transforms on %s from %s to %s): the scans "
          "are written with the laser at the robot's origin; give --sensor-mount\n",
          t::kTfStatic.name.c_str(), frames.base_link.c_str(), frames.laser.c_str());
    r.log->Close();
    if (r.truth) {
      r.truth->Close();
      std::printf("  %zu ground-truth poses in %s\n", r.truth_poses,
                  cli.Required("truth-out").c_str());
    }
    if (r.encoders) {
      r.encoders->Close();
      std::printf("  %zu encoder samples in %s\n", r.encoder_samples, r.encoders_path.c_str());
    } else if (!r.encoders_path.empty()) {
      std::printf("  WARNING: no wheel encoders were heard on %s: %s not written\n",
                  t::kWheelEncoders.name.c_str(), r.encoders_path.c_str());
    }
    if (s.scans == 0) {
      std::printf(
          "  FAILED: no scan was heard on %s (is the robot or the simulator on domain %d?)\n",
          t::kScan.name.c_str(), node_options.domain_id);
      return 1;
    }
    return 0;
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc record: " << e.what() << "\n" << config::CommandLine::Usage(specs);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "structloc record: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::cli
