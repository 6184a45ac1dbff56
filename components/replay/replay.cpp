// Offline replay (see header).
#include "replay.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <sstream>

#include "localiser_options.hpp"
#include "map_canvas.hpp"
#include "output_file.hpp"
#include "pose_tracker.hpp"
#include "prefilter.hpp"
#include "recording_writers.hpp"
#include "strict_xml.hpp"
#include "world_model_xml.hpp"

namespace structloc::replay {
namespace {

using localisation::PoseTracker;

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

// A scan read from the log, waiting until odometry covers it.
struct PendingScan {
  logs::CarmenRecord record;
};

class Replayer {
 public:
  // Reads and checks every input, then opens the outputs (temporary files).
  explicit Replayer(const ReplayOptions& o) : o_(o) {
    if (!o.initial_pose) throw config::ConfigError("replay needs --initial-pose \"X Y THETA\"");
    const double bound = o.world_limits.max_abs_coordinate_m;
    if (!geometry::IsFinite(*o.initial_pose) || std::abs(o.initial_pose->x) > bound ||
        std::abs(o.initial_pose->y) > bound) {
      throw config::ConfigError("--initial-pose must lie within " +
                                std::to_string(static_cast<long long>(bound)) +
                                " m of the map origin");
    }
    if (!o.plot_path.empty()) rendering::MapCanvas::CheckPictureName(o.plot_path);
    RefuseSameOutputs();
    if (!o.no_map)
      world_ =
          std::make_unique<world::WorldModel>(world::LoadWorldModel(o.map_path, o.world_limits));
    if (!o.params_path.empty()) params_ = localisation::LoadLocaliserOptions(o.params_path);
    if (!o.truth_path.empty()) {
      truth_ = logs::ReadTum(o.truth_path);
      if (truth_.empty()) {
        throw std::runtime_error(o.truth_path +
                                 ": no poses in it (TUM lines \"t x y z qx qy qz qw\")");
      }
    }
    reader_ = std::make_unique<logs::CarmenReader>(o.log_path, o.limits);
    const std::vector<std::string> inputs = {o.log_path, o.map_path, o.params_path, o.truth_path};
    out_ = std::make_unique<logs::TumWriter>(o.out_tum, inputs);
    if (!o.fixes_path.empty()) {
      fixes_ = std::make_unique<logs::FixesCsvWriter>(o.fixes_path, true, inputs);
    }
    if (!o.plot_path.empty()) plot_ = std::make_unique<config::OutputFile>(o.plot_path, inputs);
  }

  ReplayReport Run() {
    report_.no_map = o_.no_map;
    logs::CarmenRecord r;
    size_t records = 0;
    while (reader_->Next(r)) {
      ++records;
      time_increment_ = reader_->LaserTimeIncrement();
      if (r.kind == logs::CarmenRecord::Kind::kOdometry) {
        AddOdometry(r.stamp, *r.robot_pose);
      } else {
        if (r.robot_pose) AddOdometry(r.stamp, *r.robot_pose);
        pending_.push_back({r});
      }
      Drain(false);
      if (o_.progress && records % 2000 == 0) o_.progress(report_.scans_used, -1.0);
    }
    Drain(true);
    report_.log = reader_->Stats();
    if (report_.scans_used == 0) {
      throw std::runtime_error(o_.log_path + ": no scan could be localised, nothing written\n" +
                               FormatInputSummary(report_));
    }
    if (!o_.no_map && report_.scans_lost == report_.scans_used) {
      throw std::runtime_error(
          o_.log_path + ": all " + std::to_string(report_.scans_used) +
          " scans were lost, the map explains none of them; check --initial-pose, that the map "
          "is in metres and in the log's frame; nothing written\n" +
          FormatInputSummary(report_));
    }
    Finish();
    // Every output reaches the disk before any replaces an existing file.
    out_->Flush();
    if (fixes_) fixes_->Flush();
    if (plot_) plot_->Flush();
    out_->Close();
    if (fixes_) fixes_->Close();
    if (plot_) plot_->Commit();
    return report_;
  }

 private:
  void AddOdometry(double stamp, const geometry::Pose2D& pose) {
    if (odometry_.empty() || stamp > odometry_.back().stamp) odometry_.push_back({stamp, pose});
    if (tracker_) tracker_->AddOdometry(stamp, pose);
  }

  // Processes waiting scans once odometry covers them (or at the end of the
  // log). A log whose odometry never comes (RAWLASER lines without ODOM)
  // must not keep every scan in memory: beyond kMaxPendingScans the oldest is
  // processed with what there is (and rejected if no odometry covers it).
  void Drain(bool end) {
    constexpr size_t kMaxPendingScans = 1000;
    while (!pending_.empty()) {
      const auto& rec = pending_.front().record;
      const double last_beam =
          rec.stamp +
          time_increment_ * static_cast<double>(rec.ranges.size() ? rec.ranges.size() - 1 : 0);
      const bool overdue = pending_.size() > kMaxPendingScans;
      if (!end && !overdue && (odometry_.empty() || odometry_.back().stamp < last_beam)) return;
      Process(rec);
      pending_.pop_front();
    }
  }

  // Odometry pose at `t` from what has been read (interpolated).
  std::optional<geometry::Pose2D> OdometryAt(double t) const {
    if (odometry_.empty() || t < odometry_.front().stamp) return std::nullopt;
    auto it = std::lower_bound(odometry_.begin(), odometry_.end(), t,
                               [](const logs::StampedPose& p, double s) { return p.stamp < s; });
    if (it == odometry_.end()) return odometry_.back().pose;
    if (it == odometry_.begin() || it->stamp == t) return it->pose;
    const auto& a = *(it - 1);
    return geometry::Interpolate(a.pose, it->pose, (t - a.stamp) / (it->stamp - a.stamp));
  }

  void Start(const logs::CarmenRecord& first, const geometry::Pose2D& odom) {
    if (first.laser_pose && first.robot_pose) {
      report_.sensor_mount = geometry::Between(*first.robot_pose, *first.laser_pose);
      params_.sensor_mount = report_.sensor_mount;
    } else {
      report_.sensor_mount = params_.sensor_mount;
    }
    params_.max_beams = std::max(params_.max_beams, 4096);
    first_odometry_ = odom;
    if (!o_.no_map) {
      tracker_ = std::make_unique<PoseTracker>(*world_, params_, localisation::TrackerOptions{});
      for (const auto& p : odometry_) tracker_->AddOdometry(p.stamp, p.pose);
      tracker_->SetInitialPose(first.stamp, *o_.initial_pose,
                               localisation::TrackerOptions{}.InitialCovariance());
    }
    started_ = true;
  }

  void Process(const logs::CarmenRecord& rec) {
    const auto odom = rec.robot_pose ? rec.robot_pose : OdometryAt(rec.stamp);
    if (!odom) {
      ++report_.scans_rejected["no odometry before the first laser line"];
      return;
    }
    if (!started_) Start(rec, *odom);
    // Odometry alone, carried from the initial pose.
    const geometry::Pose2D dead_reckoned =
        geometry::Compose(*o_.initial_pose, geometry::Between(first_odometry_, *odom));
    odometry_only_.push_back({rec.stamp, dead_reckoned});
    if (o_.no_map) {
      PassThrough(rec, dead_reckoned);
      return;
    }
    localisation::ScanInput in;
    in.stamp = rec.stamp;
    in.angle_min = rec.start_angle;
    in.angle_increment = rec.angular_resolution;
    in.angle_max = NAN;
    in.time_increment = time_increment_;
    in.range_min = 0.0;
    in.range_max = rec.max_range;
    in.ranges = rec.ranges.data();
    in.count = rec.ranges.size();
    const auto t0 = std::chrono::steady_clock::now();
    const auto outcome = tracker_->ProcessScan(in, 1e9);
    times_us_.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
    if (outcome.verdict != PoseTracker::ScanVerdict::kProcessed) {
      ++report_.scans_rejected[localisation::ToString(outcome.rejection)];
      return;
    }
    const auto& r = *outcome.result;
    ++report_.scans_used;
    features_ += r.Matched();
    if (r.lost) {
      ++report_.scans_lost;
      if (!lost_) ++report_.lost_periods;
      if (lost_) report_.lost_duration_s += rec.stamp - last_stamp_;
    }
    lost_ = r.lost;
    last_stamp_ = rec.stamp;
    Emit(rec, outcome.pose.pose);
    if (fixes_ && !r.lost) {
      const auto& c = outcome.pose.covariance;
      fixes_->Fix(rec.stamp, outcome.pose.pose, c(0, 0), c(1, 1), c(2, 2));
    }
  }

  void PassThrough(const logs::CarmenRecord& rec, const geometry::Pose2D& pose) {
    // Still exercise parsing, filtering and timing on every scan.
    localisation::ScanView view;
    view.ranges = rec.ranges.data();
    view.count = rec.ranges.size();
    view.angle_min = rec.start_angle;
    view.angle_increment = rec.angular_resolution;
    view.range_max = rec.max_range;
    const auto t0 = std::chrono::steady_clock::now();
    if (view.count > 0 && view.angle_increment != 0.0) {
      directions_.Update(view);
      localisation::PrefilterStats stats;
      RangeGate(view, directions_, params_.prefilter, points_, stats);
      RejectUnsupported(params_.prefilter, points_, keep_, stats);
      Thin(params_.prefilter, points_, stats);
      FitWindowLines(points_, params_.line_fit, windows_);
    }
    times_us_.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
    if (view.count == 0 || view.angle_increment == 0.0) {
      ++report_.scans_rejected["empty scan"];
      return;
    }
    if (!(rec.stamp > last_stamp_)) {
      ++report_.scans_rejected["scan stamp not after the previous scan"];
      return;
    }
    last_stamp_ = rec.stamp;
    ++report_.scans_used;
    Emit(rec, pose);
  }

  void Emit(const logs::CarmenRecord& rec, const geometry::Pose2D& pose) {
    out_->Pose(rec.stamp, pose);
    report_.estimate.push_back({rec.stamp, pose});
    if (!o_.plot_path.empty() && report_.scans_used % 10 == 1) {
      const geometry::Pose2D laser = geometry::Compose(pose, report_.sensor_mount);
      for (size_t i = 0; i < rec.ranges.size(); i += 2) {
        const double range = rec.ranges[i];
        if (!(range > 0.1 && range < std::min(rec.max_range, 30.0))) continue;
        const double a = rec.start_angle + static_cast<double>(i) * rec.angular_resolution;
        scan_points_.push_back(laser.Apply({range * std::cos(a), range * std::sin(a)}));
      }
    }
  }

  void Finish() {
    report_.mean_features =
        report_.scans_used > 0 ? static_cast<double>(features_) / report_.scans_used : 0.0;
    report_.median_update_us = Percentile(times_us_, 0.5);
    report_.p99_update_us = Percentile(times_us_, 0.99);
    if (!o_.truth_path.empty()) {
      report_.estimate_error = CompareTrajectories(report_.estimate, truth_);
      report_.odometry_error = CompareTrajectories(odometry_only_, truth_);
    }
    if (plot_) Plot(truth_);
  }

  // Two outputs of one run must not be the same file.
  void RefuseSameOutputs() const {
    const std::vector<std::pair<std::string, std::string>> outputs = {
        {"--out", o_.out_tum}, {"--fixes-out", o_.fixes_path}, {"--plot", o_.plot_path}};
    for (size_t i = 0; i < outputs.size(); ++i) {
      for (size_t j = i + 1; j < outputs.size(); ++j) {
        const auto& [a, path_a] = outputs[i];
        const auto& [b, path_b] = outputs[j];
        std::error_code error;
        if (!path_a.empty() && !path_b.empty() &&
            (path_a == path_b || std::filesystem::equivalent(path_a, path_b, error))) {
          throw config::ConfigError(path_a + ": given as both " + a + " and " + b);
        }
      }
    }
  }

  void Plot(const std::vector<logs::StampedPose>& truth) {
    Eigen::Vector4d bounds(INFINITY, INFINITY, -INFINITY, -INFINITY);
    auto grow = [&bounds](const Eigen::Vector2d& p) {
      bounds[0] = std::min(bounds[0], p.x());
      bounds[1] = std::min(bounds[1], p.y());
      bounds[2] = std::max(bounds[2], p.x());
      bounds[3] = std::max(bounds[3], p.y());
    };
    if (world_) {
      const auto b = world_->Bounds();
      grow({b[0], b[1]});
      grow({b[2], b[3]});
    }
    auto path = [&grow](const std::vector<logs::StampedPose>& poses) {
      std::vector<Eigen::Vector2d> out;
      for (const auto& p : poses) {
        out.push_back(p.pose.Translation());
        grow(out.back());
      }
      return out;
    };
    const auto truth_path = path(truth), odom_path = path(odometry_only_),
               est_path = path(report_.estimate);
    const double span = std::max(bounds[2] - bounds[0], bounds[3] - bounds[1]);
    if (!std::isfinite(span)) {
      throw std::runtime_error(o_.plot_path +
                               ": cannot draw the plot: the map or the poses "
                               "reach beyond any finite extent");
    }
    rendering::MapCanvas canvas(bounds, std::clamp(1200.0 / std::max(span, 1.0), 2.0, 60.0));
    if (world_) canvas.DrawWorld(*world_);
    canvas.DrawPoints(scan_points_, cv::Scalar(230, 200, 160), 1);
    canvas.DrawPath(odom_path, rendering::colours::kOdometry, 2);
    canvas.DrawPath(truth_path, rendering::colours::kTruth, 5);
    canvas.DrawPath(est_path, rendering::colours::kEstimate, 2);
    std::vector<std::pair<cv::Scalar, std::string>> legend = {
        {rendering::colours::kOdometry, "odometry only"},
        {rendering::colours::kEstimate, "localised estimate"},
        {cv::Scalar(230, 200, 160), "scans at the estimate"}};
    if (!truth.empty()) legend.insert(legend.begin(), {rendering::colours::kTruth, "ground truth"});
    canvas.DrawLegend(legend);
    canvas.DrawTitle("replay of " + o_.log_path);
    canvas.WriteTo(*plot_);
  }

  ReplayOptions o_;
  std::unique_ptr<world::WorldModel> world_;
  std::vector<logs::StampedPose> truth_;
  std::unique_ptr<logs::CarmenReader> reader_;
  std::unique_ptr<logs::TumWriter> out_;
  std::unique_ptr<logs::FixesCsvWriter> fixes_;
  std::unique_ptr<config::OutputFile> plot_;
  localisation::LocaliserOptions params_;
  std::unique_ptr<PoseTracker> tracker_;
  std::vector<logs::StampedPose> odometry_;
  std::vector<logs::StampedPose> odometry_only_;
  std::deque<PendingScan> pending_;
  geometry::Pose2D first_odometry_;
  bool started_ = false;
  double time_increment_ = 0.0;
  ReplayReport report_;
  std::vector<double> times_us_;
  size_t features_ = 0;
  bool lost_ = false;
  double last_stamp_ = -1e300;
  std::vector<Eigen::Vector2d> scan_points_;
  localisation::BeamDirections directions_;
  localisation::ScanPoints points_;
  std::vector<unsigned char> keep_;
  std::vector<localisation::WindowLine> windows_;
};

}  // namespace

ReplayReport RunReplay(const ReplayOptions& options) {
  return Replayer(options).Run();
}

std::string FormatInputSummary(const ReplayReport& r) {
  std::ostringstream out;
  out << "log: " << r.log.lines << " lines, " << r.log.scans << " scans, " << r.log.odometry
      << " odometry lines, " << r.log.malformed << " malformed\n";
  for (const auto& m : r.log.malformed_lines) {
    out << "  malformed line " << m.line << ": " << m.reason << "\n";
  }
  if (r.log.malformed > r.log.malformed_lines.size()) {
    out << "  (" << r.log.malformed - r.log.malformed_lines.size() << " more malformed lines)\n";
  }
  for (const auto& [type, n] : r.log.skipped) out << "  skipped " << n << " " << type << " lines\n";
  out << "scans used: " << r.scans_used << "\n";
  for (const auto& [why, n] : r.scans_rejected) out << "  rejected " << n << ": " << why << "\n";
  return out.str();
}

std::string FormatReport(const ReplayReport& r) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(1);
  out << FormatInputSummary(r);
  if (r.no_map) {
    out << "features matched per scan: n/a (--no-map: odometry passed through; prefilter and "
           "line fits timed)\n";
  } else {
    out << "features matched per scan: " << r.mean_features << "\n";
  }
  out << "lost: " << r.scans_lost << " scans in " << r.lost_periods << " periods ("
      << r.lost_duration_s << " s)\n";
  out.precision(1);
  out << "time per update: median " << r.median_update_us << " us, p99 " << r.p99_update_us
      << " us\n";
  out.precision(2);
  out << "sensor mounting used: x " << r.sensor_mount.x << " m, y " << r.sensor_mount.y
      << " m, theta " << r.sensor_mount.theta << " rad\n";
  auto error = [&out](const char* what, const TrajectoryError& e) {
    if (e.matched == 0) {
      out << what << ": n/a (no estimated pose matches a ground-truth stamp)\n";
      return;
    }
    out.precision(1);
    out << what << ": position RMSE " << 1e3 * e.position_rmse_m << " mm, max "
        << 1e3 * e.position_max_m << " mm, heading RMSE " << std::setprecision(3)
        << e.heading_rmse_rad * 180.0 / geometry::kPi << " deg (" << e.matched << " poses)\n";
  };
  if (r.estimate_error) error("estimate vs truth", *r.estimate_error);
  if (r.odometry_error) error("odometry only vs truth", *r.odometry_error);
  return out.str();
}

}  // namespace structloc::replay
