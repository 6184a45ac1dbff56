// Offline replay (see header).
#include "structloc/replay/replay.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <optional>
#include <sstream>

#include "structloc/config/install_layout.hpp"
#include "structloc/config/output_file.hpp"
#include "structloc/config/strict_xml.hpp"
#include "structloc/localisation_core/localiser/localiser_options.hpp"
#include "structloc/localisation_core/scan/laser_preset.hpp"
#include "structloc/localisation_core/scan/prefilter.hpp"
#include "structloc/localisation_core/start_up/start_up_policy.hpp"
#include "structloc/localisation_core/tracking/tracking_session.hpp"
#include "structloc/log_formats/recording_writers.hpp"
#include "structloc/rendering/map_canvas.hpp"
#include "structloc/replay/trajectory_alignment.hpp"
#include "structloc/world_model/world_model_xml.hpp"

namespace structloc::replay {
namespace {

using localisation_core::ScanReport;
using localisation_core::TrackingSession;

// Why a scan was not used, with the session's detail when it gives one.
std::string RejectionReason(const ScanReport& report) {
  return report.reason.empty() ? localisation_core::ToString(report.rejection) : report.reason;
}

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

class Replayer {
 public:
  // Reads and checks every input, then opens the outputs (temporary files).
  explicit Replayer(const ReplayOptions& o) : o_(o) {
    if (!o.initial_pose && o.no_map)
      throw config::ConfigError(
          "--no-map needs --initial-pose \"X Y THETA\" (without a map the "
          "robot cannot be located globally)");
    const double bound = o.world_limits.max_abs_coordinate_m;
    if (o.initial_pose &&
        (!geometry::IsFinite(*o.initial_pose) || std::abs(o.initial_pose->x) > bound ||
         std::abs(o.initial_pose->y) > bound)) {
      throw config::ConfigError("--initial-pose must lie within " +
                                std::to_string(static_cast<long long>(bound)) +
                                " m of the map origin");
    }
    if (!o.plot_path.empty()) rendering::MapCanvas::CheckPictureName(o.plot_path);
    RefuseSameOutputs();
    if (!o.no_map)
      world_ = std::make_unique<world_model::WorldModel>(
          world_model::LoadWorldModel(o.map_path, o.world_limits));
    if (!o.params_path.empty()) {
      params_ = localisation_core::LoadLocaliserOptions(o.params_path);
      session_options_ = localisation_core::LoadSessionOptions(o.params_path);
      report_.parameters = o.params_path + " (given)";
    }
    initial_pose_ = o.initial_pose;
    // Checked now, built at the first laser line (whose poses give the mount).
    localisation_core::CheckHypothesisOptions(o.hypotheses);
    localisation_core::CheckKidnapOptions(o.kidnap);
    if (!o.truth_path.empty()) {
      truth_ = log_formats::ReadTum(o.truth_path);
      if (truth_.empty()) {
        throw std::runtime_error(o.truth_path +
                                 ": no poses in it (TUM lines \"t x y z qx qy qz qw\")");
      }
    }
    reader_ = std::make_unique<log_formats::CarmenReader>(o.log_path, o.limits);
    // Each output is refused when it would replace an input or an output
    // named before it.
    std::vector<std::string> inputs = {o.log_path, o.map_path, o.params_path, o.truth_path};
    out_ = std::make_unique<log_formats::TumWriter>(o.out_tum, inputs);
    inputs.push_back(o.out_tum);
    if (!o.fixes_path.empty()) {
      fixes_ = std::make_unique<log_formats::FixesCsvWriter>(o.fixes_path, true, inputs);
      inputs.push_back(o.fixes_path);
    }
    if (!o.plot_path.empty()) plot_ = std::make_unique<config::OutputFile>(o.plot_path, inputs);
  }

  ReplayReport Run() {
    report_.no_map = o_.no_map;
    log_formats::CarmenRecord r;
    size_t records = 0;
    while (reader_->Next(r)) {
      ++records;
      if (r.kind == log_formats::CarmenRecord::Kind::kOdometry) {
        AddOdometry(r.stamp, *r.robot_pose);
      } else {
        AddScan(r);
      }
      Drain(false);
      if (o_.progress && records % 2000 == 0) o_.progress(report_.scans_used, -1.0);
    }
    if (!initial_pose_) {
      report_.log = reader_->Stats();
      throw std::runtime_error(o_.log_path + ": the log ended before any scan was located " +
                               "globally; give --initial-pose \"X Y THETA\"; nothing written\n" +
                               FormatGlobalAttempts(report_.global_attempts));
    }
    if (!session_) StartSession(nullptr);
    Drain(true);
    report_.lost_periods = session_->LostPeriods();
    report_.lost_duration_s = session_->LostSeconds();
    report_.longest_lost_s = session_->LongestLostSeconds();
    const auto stats = session_->Stats();
    report_.corrections_refused = stats.corrections_refused;
    report_.visibility_computations = stats.visibility_computations;
    report_.stale_visibility_updates = stats.stale_visibility_updates;
    report_.log = reader_->Stats();
    if (report_.scans_used == 0) {
      throw std::runtime_error(o_.log_path + ": no scan could be localised, nothing written\n" +
                               FormatInputSummary(report_));
    }
    if (!o_.no_map && report_.scans_matched == 0) {
      throw std::runtime_error(o_.log_path + ": none of the " + std::to_string(report_.scans_used) +
                               " scans matched the map, the map explains none of them; check "
                               "--initial-pose, that the map "
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
  // Odometry before the first laser line waits for the session that line
  // starts; the tracker keeps no more than this much odometry history anyway.
  static constexpr size_t kMaxEarlyOdometry = 4096;

  void AddOdometry(double stamp, const geometry::Pose2D& pose) {
    if (session_) {
      session_->AddOdometry(stamp, pose, stamp);
      return;
    }
    early_odometry_.push_back({stamp, pose});
    if (early_odometry_.size() > kMaxEarlyOdometry) early_odometry_.pop_front();
  }

  // A laser line: the start-up's until a pose is given or found, then the
  // session's (odometry before the first laser line waits for the session
  // that line starts, see AddOdometry).
  void AddScan(const log_formats::CarmenRecord& r) {
    if (report_.parameters.empty()) ChoosePreset(r);  // given or chosen once
    if (!session_) StartSession(&r);
    if (r.robot_pose) AddOdometry(r.stamp, *r.robot_pose);
    if (!initial_pose_ && !LocateGlobally(r)) return;
    session_->AddScan(ToSessionScan(r), r.stamp);
  }

  // Without a parameter file: the preset the first scan's geometry names,
  // loaded from structloc's data folder (the built-in defaults when none does).
  void ChoosePreset(const log_formats::CarmenRecord& first_scan) {
    const auto choice = localisation_core::ChooseLaserPreset(
        {first_scan.ranges.size(), first_scan.angular_resolution, first_scan.max_range});
    report_.parameters = localisation_core::DescribeChoice(choice);
    if (choice.file.empty()) return;
    const std::string path = config::SharePath(choice.file);
    params_ = localisation_core::LoadLocaliserOptions(path);
    session_options_ = localisation_core::LoadSessionOptions(path);
  }

  // The laser's mounting on the robot: from the scan's laser and robot poses
  // when it has both, else the parameters'.
  geometry::Pose2D SensorMount(const log_formats::CarmenRecord* scan) const {
    if (scan != nullptr && scan->laser_pose && scan->robot_pose)
      return geometry::Between(*scan->robot_pose, *scan->laser_pose);
    return params_.sensor_mount;
  }

  // Without a pose: the scan goes to the start-up policy (the global
  // search, or the hypotheses held weighed), as the component starts a
  // robot; true when it found or committed a pose, which the session then
  // tracks from. Throws when the last allowed scan gave none.
  bool LocateGlobally(const log_formats::CarmenRecord& r) {
    ++global_scans_;
    if (start_up_->HeldHypotheses() > 0) ++held_scans_;
    if (auto search = start_up_->SearchAt(*session_, ToSessionScan(r))) {
      start_up_->Run(*search);
      const auto outcome = start_up_->Apply(*session_, *search, r.stamp);
      auto& attempt = *search->global;
      if (attempt.searched) {
        report_.global_attempts.push_back(
            {global_scans_, r.line, r.stamp, std::move(attempt.result), search->seconds});
      }
      if (outcome.pose_set) {
        initial_pose_ = attempt.found->pose;
        report_.initial_pose = *initial_pose_;
        if (attempt.travel_m) {
          report_.commit = ReplayReport::Commit{global_scans_,     r.line,         r.stamp,
                                                *attempt.travel_m, attempt.seeded, held_scans_};
        }
        return true;
      }
    }
    ++report_.scans_rejected["before the global localisation found the robot"];
    if (o_.global_attempts > 0 && global_scans_ >= o_.global_attempts) {
      report_.log = reader_->Stats();
      throw std::runtime_error(
          o_.log_path + ": none of the first " + std::to_string(global_scans_) +
          " scans could be located on the map without a doubt; give --initial-pose \"X Y "
          "THETA\" or check that the map is of this building; nothing written\n" +
          FormatGlobalAttempts(report_.global_attempts));
    }
    return false;
  }

  // Starts the session and the start-up policy at the first laser line
  // (nullptr: the log has none), whose laser and robot poses give the sensor
  // mounting (else the parameters'), so that both start with their final
  // options. The log's initial pose is that of its first laser line: a fact,
  // not a hint to confirm. Throws std::invalid_argument when the robot must
  // be located globally on a map too large for the search's grid.
  void StartSession(const log_formats::CarmenRecord* first_scan) {
    report_.sensor_mount = SensorMount(first_scan);
    params_.sensor_mount = report_.sensor_mount;
    params_.max_beams = std::max(params_.max_beams, 4096);
    session_ = std::make_unique<TrackingSession>(world_.get(), params_, session_options_,
                                                 localisation_core::Scheduling::kInOrder);
    localisation_core::StartUpOptions start;
    start.global = o_.global;
    start.hypotheses = o_.hypotheses;
    start.kidnap = o_.kidnap;
    start.confirm_given_poses = false;
    start_up_ = std::make_unique<localisation_core::StartUpPolicy>(
        world_.get(), report_.sensor_mount, session_options_, start);
    if (world_ && !start_up_->CanSearch()) {
      if (!initial_pose_) throw std::invalid_argument(start_up_->NoSearchReason());
      report_.kidnap_watch_off = start_up_->NoSearchReason();
    }
    if (initial_pose_) {
      report_.initial_pose = *initial_pose_;
      start_up_->GivenAtStart(*session_, *initial_pose_,
                              TrackingSession::InitialPoseWhen::kAtFirstScan, "--initial-pose");
    }
    for (const auto& odometry : early_odometry_) AddOdometry(odometry.stamp, odometry.pose);
    early_odometry_.clear();
  }

  localisation_core::SessionScan ToSessionScan(const log_formats::CarmenRecord& rec) const {
    localisation_core::SessionScan scan;
    scan.geometry.stamp = rec.stamp;
    scan.geometry.angle_min = rec.start_angle;
    scan.geometry.angle_increment = rec.angular_resolution;
    scan.geometry.angle_max = NAN;
    scan.geometry.time_increment = reader_->LaserTimeIncrement();
    scan.geometry.range_min = 0.0;
    scan.geometry.range_max = rec.max_range;
    scan.ranges = rec.ranges;
    scan.odometry = rec.robot_pose;
    scan.TakenEarlier(session_options_.scan_latency_s);
    return scan;
  }

  // Handles the scans the session has ready (all of them at the end of the log).
  void Drain(bool end) {
    if (!session_) return;
    while (auto report = session_->Next(0.0, end)) {
      Handle(*report);
      session_->Anticipate();  // as the component does after publishing
      if (report->kind == ScanReport::Kind::kTracked && !stage_times_.empty()) {
        between_us_.push_back({session_->LastAnticipateUs(), session_->LastAnticipateCpuUs()});
      }
    }
  }

  void Handle(const ScanReport& report) {
    const auto& scan = report.scan;
    if (!report.odometry) {
      ++report_.scans_rejected[RejectionReason(report)];
      return;
    }
    if (!first_odometry_) first_odometry_ = *report.odometry;
    // Odometry alone, carried from the initial pose.
    const geometry::Pose2D dead_reckoned =
        geometry::Compose(*initial_pose_, geometry::Between(*first_odometry_, *report.odometry));
    odometry_only_.push_back({LogStamp(report.stamp), dead_reckoned});
    if (o_.no_map) {
      PassThrough(scan, report, dead_reckoned);
      return;
    }
    times_us_.push_back(report.update_us);
    if (report.kind != ScanReport::Kind::kTracked) {
      ++report_.scans_rejected[RejectionReason(report)];
      return;
    }
    stage_times_.push_back(report.timings);
    const auto& r = *report.result;
    ++report_.scans_used;
    features_ += r.Matched();
    if (report.lost) ++report_.scans_lost;
    if (r.Matched() > 0) ++report_.scans_matched;
    if (report.reacquired) {
      report_.reacquisitions.push_back({LogStamp(report.stamp), report.pose.pose, report.jump});
    }
    Emit(scan, report.pose.pose);
    WatchForKidnapping(report);
    // A fix for calibration only where the scan alone pinned every direction.
    if (fixes_ && !report.lost && !r.lost) {
      const auto& c = report.pose.covariance;
      fixes_->Fix(report.stamp, report.pose.pose, c(0, 0), c(1, 1), c(2, 2));
    }
  }

  // After a tracked scan: the start-up policy's kidnap watch, and its search
  // when one is due, run at once (the component runs it on a thread of its
  // own); a robot found far away moves the tracking there.
  void WatchForKidnapping(const ScanReport& report) {
    if (!report.odometry || !start_up_->CanSearch()) return;
    std::vector<std::string> sentences;
    auto search = start_up_->Watch(*session_, report, sentences);
    if (!search) return;
    start_up_->Run(*search);
    report_.kidnap_searches += search->global && search->global->searched ? 1 : 0;
    report_.twin_checks += search->twin_check ? 1 : 0;
    const auto outcome = start_up_->Apply(*session_, *search, report.stamp);
    if (outcome.kidnapping) report_.kidnappings.push_back(*outcome.kidnapping);
  }

  void PassThrough(const localisation_core::SessionScan& scan, const ScanReport& report,
                   const geometry::Pose2D& pose) {
    // Still exercise parsing, filtering and timing on every scan.
    localisation_core::ScanView view;
    view.ranges = scan.ranges.data();
    view.count = scan.ranges.size();
    view.angle_min = scan.geometry.angle_min;
    view.angle_increment = scan.geometry.angle_increment;
    view.range_max = scan.geometry.range_max;
    const auto t0 = std::chrono::steady_clock::now();
    if (view.count > 0 && view.angle_increment != 0.0) {
      directions_.Update(view);
      localisation_core::PrefilterStats stats;
      Prefilter(view, directions_, params_.prefilter, nullptr, points_, stats);
      FitWindowLines(points_, params_.line_fit, windows_);
    }
    times_us_.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
    if (report.kind == ScanReport::Kind::kRejected) {
      ++report_.scans_rejected[RejectionReason(report)];
      return;
    }
    ++report_.scans_used;
    Emit(scan, pose);
  }

  // A scan tracked at the moment it was taken (its stamp less the laser's
  // latency) is written, and judged, at its stamp in the log, as slam's path
  // is: the truth of a recording is stamped as its scans are.
  double LogStamp(double taken) const { return taken + session_options_.scan_latency_s; }

  void Emit(const localisation_core::SessionScan& scan, const geometry::Pose2D& pose) {
    const double stamp = LogStamp(scan.geometry.stamp);
    out_->Pose(stamp, pose);
    report_.estimate.push_back({stamp, pose});
    if (!o_.plot_path.empty() && report_.scans_used % 10 == 1) {
      const geometry::Pose2D laser = geometry::Compose(pose, report_.sensor_mount);
      for (size_t i = 0; i < scan.ranges.size(); i += 2) {
        const double range = scan.ranges[i];
        if (!(range > 0.1 && range < std::min(scan.geometry.range_max, 30.0))) continue;
        const double a =
            scan.geometry.angle_min + static_cast<double>(i) * scan.geometry.angle_increment;
        scan_points_.push_back(laser.Apply({range * std::cos(a), range * std::sin(a)}));
      }
    }
  }

  void Finish() {
    report_.mean_features =
        report_.scans_used > 0 ? static_cast<double>(features_) / report_.scans_used : 0.0;
    report_.median_update_us = Percentile(times_us_, 0.5);
    report_.p99_update_us = Percentile(times_us_, 0.99);
    SummariseStageTimes();
    if (!o_.truth_path.empty()) {
      report_.estimate_error = CompareTrajectories(report_.estimate, truth_);
      report_.aligned_estimate_error = CompareAligned(report_.estimate, truth_);
      report_.scaled_estimate_error = CompareAlignedWithScale(report_.estimate, truth_);
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

  void Plot(const std::vector<log_formats::StampedPose>& truth) {
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
    auto path = [&grow](const std::vector<log_formats::StampedPose>& poses) {
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
  std::unique_ptr<world_model::WorldModel> world_;
  std::vector<log_formats::StampedPose> truth_;
  std::unique_ptr<log_formats::CarmenReader> reader_;
  std::unique_ptr<log_formats::TumWriter> out_;
  std::unique_ptr<log_formats::FixesCsvWriter> fixes_;
  std::unique_ptr<config::OutputFile> plot_;
  localisation_core::LocaliserOptions params_;
  localisation_core::SessionOptions session_options_;
  std::unique_ptr<TrackingSession> session_;                    // from the first laser line on
  std::unique_ptr<localisation_core::StartUpPolicy> start_up_;  // with the session
  std::optional<geometry::Pose2D> initial_pose_;                // given, or found by start_up_
  size_t global_scans_ = 0;  // scans it has tried (searched or weighed hypotheses with)
  size_t held_scans_ = 0;    // of them, with hypotheses held
  std::deque<log_formats::StampedPose> early_odometry_;
  std::vector<log_formats::StampedPose> odometry_only_;
  std::optional<geometry::Pose2D> first_odometry_;  // of the first scan handled
  ReplayReport report_;
  std::vector<double> times_us_;
  std::vector<localisation_core::StageTimings> stage_times_;
  // After each tracked scan: the work between scans (Anticipate), wall and CPU.
  std::vector<std::pair<double, double>> between_us_;

  void SummariseStageTimes() {
    if (stage_times_.empty()) return;
    const auto summary = [this](const std::string& what, auto of) {
      std::vector<double> v;
      v.reserve(stage_times_.size());
      for (const auto& t : stage_times_) v.push_back(of(t));
      double sum = 0.0;
      for (const double x : v) sum += x;
      report_.stage_times.push_back({what, Percentile(v, 0.5), Percentile(v, 0.99),
                                     *std::max_element(v.begin(), v.end()),
                                     sum / static_cast<double>(v.size())});
    };
    for (size_t k = 0; k < localisation_core::kStageNames.size(); ++k) {
      summary(localisation_core::kStageNames[k], [k](const auto& t) { return t.us[k]; });
    }
    summary("update (wall)", [](const auto& t) { return t.total_us; });
    summary("update (thread CPU)", [](const auto& t) { return t.total_cpu_us; });
    if (between_us_.size() != stage_times_.size()) return;
    // What the tracking costs in all, the searches and visibility between
    // scans included (the lost-mode budget is on its mean).
    std::vector<double> between, all;
    for (size_t i = 0; i < between_us_.size(); ++i) {
      between.push_back(between_us_[i].second);
      all.push_back(stage_times_[i].total_cpu_us + between_us_[i].second);
    }
    const auto add = [this](const std::string& what, std::vector<double> v) {
      double sum = 0.0;
      for (const double x : v) sum += x;
      const double max = *std::max_element(v.begin(), v.end());
      report_.stage_times.push_back({what, Percentile(v, 0.5), Percentile(v, 0.99), max,
                                     sum / static_cast<double>(v.size())});
    };
    add("between scans (CPU)", between);
    add("scan + between (CPU)", all);
  }
  size_t features_ = 0;
  std::vector<Eigen::Vector2d> scan_points_;
  localisation_core::BeamDirections directions_;
  localisation_core::ScanPoints points_;
  std::vector<localisation_core::WindowLine> windows_;
};

}  // namespace

ReplayReport RunReplay(const ReplayOptions& options) {
  return Replayer(options).Run();
}

std::string FormatGlobalAttempts(const std::vector<GlobalAttempt>& attempts) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  auto pose = [&out](const localisation_core::GlobalCandidate& c) {
    out << std::setprecision(2) << "(" << c.pose.x << " m, " << c.pose.y << " m, "
        << std::setprecision(1) << c.pose.theta * 180.0 / geometry::kPi << " deg) explaining "
        << std::setprecision(0) << 100.0 * c.score << " %";
    if (c.newest_score) out << " (" << 100.0 * *c.newest_score << " % of the newest scan alone)";
  };
  for (const auto& a : attempts) {
    out << "global localisation, scan " << a.scan << " (line " << a.line << ")";
    if (a.result.scans > 1) out << " with " << a.result.scans - 1 << " before it";
    out << ": " << localisation_core::ToString(a.result.decision);
    if (a.result.best) {
      out << ", laser at ";
      pose(*a.result.best);
    }
    if (a.result.runner_up) {
      out << "; runner-up ";
      pose(*a.result.runner_up);
    }
    if (!a.result.reason.empty()) out << "; " << a.result.reason;
    out << std::setprecision(2) << " (" << a.seconds << " s)\n";
  }
  return out.str();
}

std::string FormatStageTimes(const ReplayReport& r) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(1);
  out << "time per tracked scan, us (" << r.scans_used << " scans; " << r.visibility_computations
      << " visibilities computed, " << r.stale_visibility_updates
      << " updates with the one of the place before):\n";
  out << "  " << std::left << std::setw(22) << "stage" << std::right << std::setw(10) << "median"
      << std::setw(10) << "p99" << std::setw(10) << "max" << std::setw(10) << "mean"
      << "\n";
  for (const auto& t : r.stage_times) {
    out << "  " << std::left << std::setw(22) << t.what << std::right << std::setw(10)
        << t.median_us << std::setw(10) << t.p99_us << std::setw(10) << t.max_us << std::setw(10)
        << t.mean_us << "\n";
  }
  return out.str();
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
  out << FormatGlobalAttempts(r.global_attempts);
  if (r.commit) {
    out << std::setprecision(1) << "committed to one of " << r.commit->hypotheses
        << " hypotheses at scan " << r.commit->scan << " (line " << r.commit->line
        << ", t = " << std::setprecision(2) << r.commit->stamp << " s) after "
        << std::setprecision(1) << r.commit->travel_m << " m of travel and " << r.commit->held_scans
        << " scans weighing them; the scans before it are not tracked and not scored\n";
  }
  if (!r.global_attempts.empty()) {
    out << std::setprecision(2) << "tracking started from robot pose (" << r.initial_pose.x
        << " m, " << r.initial_pose.y << " m, " << r.initial_pose.theta << " rad)\n"
        << std::setprecision(1);
  }
  out << FormatInputSummary(r);
  if (r.no_map) {
    out << "features matched per scan: n/a (--no-map: odometry passed through; prefilter and "
           "line fits timed)\n";
  } else {
    out << "features matched per scan: " << r.mean_features << "\n";
  }
  out << "lost: " << r.scans_lost << " scans in " << r.lost_periods << " periods ("
      << r.lost_duration_s << " s, the longest " << r.longest_lost_s << " s)\n";
  if (r.corrections_refused > 0) {
    out << "corrections refused by the whole-scan check: " << r.corrections_refused << "\n";
  }
  out << "re-acquired: " << r.reacquisitions.size() << " times\n";
  if (!r.kidnap_watch_off.empty()) {
    out << "no watch for a kidnapped robot: " << r.kidnap_watch_off << "\n";
  }
  if (r.kidnap_searches > 0) {
    out << "searched the whole map at " << r.kidnap_searches
        << " scans the tracked pose did not explain (in case the robot was carried away)\n";
  }
  if (r.twin_checks > 0) {
    out << "searched the whole map " << r.twin_checks
        << " times for a robot tracked at the twin of its place (the map is the same turned)\n";
  }
  for (const auto& k : r.kidnappings) {
    out << std::setprecision(2) << "kidnapped: at t = " << k.stamp << " s, after " << k.doubt_s
        << " s of doubt, the robot was found at (" << k.to.x << " m, " << k.to.y << " m, "
        << k.to.theta << " rad), not at (" << k.from.x << " m, " << k.from.y << " m, "
        << k.from.theta << " rad)\n"
        << std::setprecision(1);
  }
  out.precision(3);
  const size_t shown = std::min<size_t>(r.reacquisitions.size(), 10);
  for (size_t i = 0; i < shown; ++i) {
    const auto& a = r.reacquisitions[i];
    out << "  at " << a.stamp << " s: locked on at (" << a.pose.x << " m, " << a.pose.y << " m, "
        << a.pose.theta << " rad), a jump of (" << a.jump.x << " m, " << a.jump.y << " m, "
        << a.jump.theta << " rad)\n";
  }
  if (shown < r.reacquisitions.size()) {
    out << "  (" << r.reacquisitions.size() - shown << " more)\n";
  }
  out.precision(1);
  out.precision(1);
  out << "time per update: median " << r.median_update_us << " us, p99 " << r.p99_update_us
      << " us\n";
  out.precision(2);
  if (!r.parameters.empty()) out << "parameters: " << r.parameters << "\n";
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
  if (r.aligned_estimate_error) {
    error("estimate vs truth after one rigid alignment", *r.aligned_estimate_error);
  }
  if (r.scaled_estimate_error) {
    std::ostringstream what;
    what << "estimate vs truth after one alignment with scale (" << std::fixed
         << std::setprecision(5) << r.scaled_estimate_error->scale << ")";
    error(what.str().c_str(), r.scaled_estimate_error->error);
  }
  if (r.odometry_error) error("odometry only vs truth", *r.odometry_error);
  return out.str();
}

}  // namespace structloc::replay
