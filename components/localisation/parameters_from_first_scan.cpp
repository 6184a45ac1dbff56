// Parameters from the first scan (see header).
#include "structloc/localisation/parameters_from_first_scan.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <mutex>

#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "structloc/config/install_layout.hpp"
#include "structloc/dds_common/diagnostics.hpp"
#include "structloc/dds_common/ros_conversions.hpp"
#include "structloc/dds_common/static_transforms.hpp"
#include "structloc/dds_common/topics.hpp"
#include "structloc/geometry/pose2d.hpp"
#include "structloc/localisation_core/scan/laser_preset.hpp"
#include "structloc/localisation_core/tracking/tracking_session_options.hpp"
#include "tf2_msgs/msg/TFMessagePubSubTypes.h"

namespace structloc::localisation {
namespace {

using namespace std::chrono_literals;

// What the probe's listeners heard, for the waiting thread.
struct Heard {
  std::mutex mutex;
  std::optional<localisation_core::ScanShape> shape;
  std::string laser_frame;
  dds_common::StaticTransforms statics;                                       // rt/tf_static
  std::optional<geometry_msgs::msg::PoseWithCovarianceStamped> initial_pose;  // the newest
  bool refused_scan = false;
};

// While it waits, the component is not made yet; the wait itself is what
// rt/diagnostics says, at the component's rhythm (every 0.5 s), a warning
// that becomes an error as the component's would (the <tracking> block's
// default silent_error_after_s: no parameter file is read yet).
dds_common::HealthReport WaitingReport(double waited_s, bool refused_scan) {
  dds_common::HealthReport report;
  report.level = waited_s > localisation_core::SessionOptions{}.silent_error_after_s
                     ? dds_common::HealthLevel::kError
                     : dds_common::HealthLevel::kWarn;
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.1f", waited_s);
  report.message = std::string(refused_scan ? "no scan that names a laser" : "no scans") + " on " +
                   dds_common::topics::kScan.name + " yet for " + seconds +
                   " s: waiting for the first to choose the laser's preset (no --params)";
  report.values.emplace_back("start_up", "waiting for the first scan");
  return report;
}

bool Usable(const sensor_msgs::msg::LaserScan& m) {
  return m.ranges().size() >= 2 && std::isfinite(m.angle_increment()) && m.angle_increment() != 0;
}

// What the probe has heard, once it may choose: the first usable scan's shape
// and frame, and the mounting if its chain of transforms came.
struct Choosable {
  localisation_core::ScanShape shape;
  std::string laser_frame;
  std::string base_frame;
  std::optional<geometry::Pose2D> mount;
  std::string mount_path;  // "base_link -> ... -> laser"
};

ParametersFromFirstScan Choose(const Choosable& heard) {
  const auto preset = localisation_core::ChooseLaserPreset(heard.shape);
  ParametersFromFirstScan out;
  out.file = preset.file.empty() ? "" : config::SharePath(preset.file);
  out.choice = localisation_core::DescribeChoice(preset);
  out.mount = heard.mount;
  if (!out.mount) {
    out.mount_source = "laser mounting from the preset: no usable transforms from '" +
                       heard.base_frame + "' to the scan's frame '" + heard.laser_frame + "' on " +
                       dds_common::topics::kTfStatic.name + " (publish them, or give --params)";
    return out;
  }
  char values[96];
  std::snprintf(values, sizeof values, "x %.3f m, y %.3f m, yaw %.2f deg", out.mount->x,
                out.mount->y, out.mount->theta * 180.0 / geometry::kPi);
  out.mount_source = "laser mounting " + std::string(values) + " from " +
                     dds_common::topics::kTfStatic.name + " (" + heard.mount_path + ")";
  return out;
}

}  // namespace

std::optional<ParametersFromFirstScan> WaitForFirstScan(dds_common::Node& node,
                                                        const dds_common::StopWait& stop,
                                                        const std::string& base_frame,
                                                        std::chrono::milliseconds tf_wait) {
  auto heard = std::make_shared<Heard>();
  std::optional<Choosable> choosable;
  {  // the probe's subscriptions live only while it waits
    const auto scans = node.Subscribe<sensor_msgs::msg::LaserScanPubSubType>(
        dds_common::topics::kScan, [heard](const sensor_msgs::msg::LaserScan& m) {
          std::lock_guard<std::mutex> lock(heard->mutex);
          if (heard->shape) return;
          if (!Usable(m)) {
            heard->refused_scan = true;
            return;
          }
          heard->shape = localisation_core::ScanShape{
              m.ranges().size(), static_cast<double>(m.angle_increment()),
              std::isfinite(m.range_max()) ? static_cast<double>(m.range_max()) : 0.0};
          heard->laser_frame = m.header().frame_id();
        });
    const auto statics = node.Subscribe<tf2_msgs::msg::TFMessagePubSubType>(
        dds_common::topics::kTfStatic, [heard](const tf2_msgs::msg::TFMessage& m) {
          std::lock_guard<std::mutex> lock(heard->mutex);
          heard->statics.Add(m);
        });
    // An operator may give the pose before the laser runs; the component
    // subscribes only once it is made, so the probe keeps the newest.
    const auto poses = node.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
        dds_common::topics::kInitialPose,
        [heard](const geometry_msgs::msg::PoseWithCovarianceStamped& m) {
          std::lock_guard<std::mutex> lock(heard->mutex);
          heard->initial_pose = m;
        });
    auto diagnostics = node.CreateWriter<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
        dds_common::topics::kDiagnostics);
    node.ReleaseCallbacks();
    std::cout << "localisation: no --params: waiting for the first scan on "
              << dds_common::topics::kScan.name << " to choose the laser's preset from"
              << std::endl;
    bool said_refused = false;
    using Clock = std::chrono::steady_clock;
    std::optional<Clock::time_point> scan_heard, reported;
    const auto started = Clock::now();
    while (!choosable && !stop(50ms)) {
      const auto now = Clock::now();
      std::unique_lock<std::mutex> lock(heard->mutex);
      if (!heard->shape && (!reported || now - *reported >= 500ms)) {
        reported = now;
        const auto report = WaitingReport(std::chrono::duration<double>(now - started).count(),
                                          heard->refused_scan);
        lock.unlock();  // the write never holds up the listeners
        diagnostics.Write(
            dds_common::ToDiagnosticArray("localisation", report, dds_common::WallClockSeconds()));
        lock.lock();
      }
      if (heard->refused_scan && !said_refused) {
        said_refused = true;
        std::cout << "localisation: a scan with fewer than two beams or no finite angle increment "
                     "cannot name a laser; waiting for another"
                  << std::endl;
      }
      if (!heard->shape) continue;
      if (!scan_heard) scan_heard = Clock::now();
      std::string path;
      const auto mount = heard->statics.Chain(base_frame, heard->laser_frame, path);
      if (mount || Clock::now() - *scan_heard >= tf_wait) {
        choosable = Choosable{*heard->shape, heard->laser_frame, base_frame, mount, path};
      }
    }
  }
  // The component's subscriptions are made with callbacks held, as the
  // factory found them.
  node.HoldCallbacks();
  if (!choosable) return std::nullopt;
  auto chosen = Choose(*choosable);
  std::lock_guard<std::mutex> lock(heard->mutex);  // the listeners are gone; for the reads' order
  chosen.initial_pose = heard->initial_pose;
  if (const size_t dropped = heard->statics.Dropped()) {
    std::cout << "localisation: WARNING: " << dropped << " transforms on "
              << dds_common::topics::kTfStatic.name << " to frames beyond the first "
              << dds_common::StaticTransforms::kMaxFrames << " were ignored" << std::endl;
  }
  return chosen;
}

}  // namespace structloc::localisation
