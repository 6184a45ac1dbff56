// "structloc synthesise-odometry --log CORRECTED.log --out EVAL.log --truth
// TRUTH.tum [--scale-error X] [--heading-drift DEG_PER_M] [--noise-xy M]
// [--noise-theta DEG] [--turn-scale-error X] [--noise-theta-turn DEG] [--seed N]
// [--restamp SPEED] [--scan-latency S] [--scans A:B]": turns a recording whose
// poses are SLAM-corrected into an evaluation log for `structloc replay`: the
// same scans, with odometry re-synthesised from the corrected poses with
// documented systematic errors and noise (none: the corrected poses as perfect
// odometry), and the corrected poses as ground truth (TUM). --scans keeps one
// part of the recording (numbered as `structloc map build --scans` numbers
// them), to localise on a part the map was not built from. --scan-latency
// writes a laser stamped late: each scan stamped S after it was taken, with
// the odometry of that later moment, as a logger does that stamps a scan
// when its readings arrive (the truth keeps the scan's pose at its stamp).
#include <iomanip>
#include <iostream>
#include <random>

#include "structloc/config/command_line.hpp"
#include "structloc/geometry/pose2d.hpp"
#include "structloc/log_formats/carmen_reader.hpp"
#include "structloc/log_formats/recording_writers.hpp"
#include "structloc/map_building/posed_scans.hpp"
#include "structloc/simulation_core/odometry_errors.hpp"
#include "subcommands.hpp"

namespace structloc::cli {
namespace {

constexpr double kDegree = geometry::kPi / 180.0;

// One scan to write: when it was taken, its odometric and true poses then.
struct Synthesised {
  double taken;
  geometry::Pose2D odometry, known, mount;
  log_formats::CarmenRecord record;
};

// The odometric pose at `t` along `scans` (taken times increasing): linear
// between neighbours, along the last step beyond the end.
geometry::Pose2D OdometryAt(const std::vector<Synthesised>& scans, double t) {
  if (scans.size() < 2) return scans.front().odometry;
  size_t j = 0;
  while (j + 2 < scans.size() && scans[j + 1].taken <= t) ++j;
  const auto& a = scans[j];
  const auto& b = scans[j + 1];
  return geometry::Interpolate(a.odometry, b.odometry, (t - a.taken) / (b.taken - a.taken));
}

struct Restamp {
  bool enabled = false;
  double speed_m_s = 0.5;
  double turn_rate_rad_s = 0.5;
  double min_step_s = 0.1;
};

}  // namespace

int SynthesiseOdometryCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"log", true, "CARMEN log whose poses are corrected (e.g. by SLAM), .gz or plain"},
      {"out", true, "CARMEN log to write: ODOM + ROBOTLASER1 lines, one pair per scan"},
      {"truth", true, "TUM file to write: the corrected robot pose of every scan"},
      {"scale-error", true, "distance travelled scaled by (1 + X), e.g. 0.015 (default 0)"},
      {"heading-drift", true, "heading error per metre travelled, deg/m, e.g. 0.3 (default 0)"},
      {"noise-xy", true, "random translation error, m per sqrt(m) travelled, 1 sigma (default 0)"},
      {"noise-theta", true, "random heading error, deg per sqrt(m) travelled, 1 sigma (default 0)"},
      {"turn-scale-error", true, "each turn scaled by (1 + X), e.g. 0.02 (default 0)"},
      {"noise-theta-turn", true,
       "random heading error, deg per sqrt(rad) turned, 1 sigma: wheels slipping in turns "
       "(default 0)"},
      {"seed", true, "seed of the noise generator (default 1)"},
      {"restamp", true,
       "new stamps as if driven at this speed, m/s (and 0.5 rad/s, at least 0.1 s apart), for "
       "logs whose stamps are not motion times (default: keep the log's stamps)"},
      {"scans", true,
       "use only the scans FIRST:LAST of the log (numbered from 0 as by map build --scans, LAST "
       "not included; default: all)"},
      {"scan-latency", true,
       "a laser stamped late: each scan stamped this many seconds after it was taken, with the "
       "odometry of that moment (default 0)"},
  };
  try {
    const config::CommandLine cli(inv.argc, inv.argv, 2, specs);
    const std::string log_path = cli.Required("log");
    const std::string out_path = cli.Required("out");
    const std::string truth_path = cli.Required("truth");
    simulation_core::OdometryErrorModel model;
    model.scale_error = cli.NumberIn("scale-error", 0.0, -0.5, 0.5);
    model.heading_drift_rad_per_m = cli.NumberIn("heading-drift", 0.0, -90.0, 90.0) * kDegree;
    model.noise_xy_m_per_sqrt_m = cli.NumberIn("noise-xy", 0.0, 0.0, 1.0);
    model.noise_theta_rad_per_sqrt_m = cli.NumberIn("noise-theta", 0.0, 0.0, 90.0) * kDegree;
    model.turn_scale_error = cli.NumberIn("turn-scale-error", 0.0, -0.5, 0.5);
    model.noise_theta_rad_per_sqrt_rad = cli.NumberIn("noise-theta-turn", 0.0, 0.0, 90.0) * kDegree;
    std::mt19937 rng(static_cast<uint32_t>(cli.IntegerIn("seed", 1, 0, 4294967295LL)));
    Restamp restamp;
    if (cli.Has("restamp")) {
      restamp.enabled = true;
      restamp.speed_m_s = cli.NumberIn("restamp", restamp.speed_m_s, 0.01, 100.0);
    }
    const double latency_s = cli.NumberIn("scan-latency", 0.0, -1.0, 1.0);
    const auto [first, last] =
        map_building::ParseScanRange(cli.Has("scans") ? cli.Required("scans") : ":");
    log_formats::CarmenReader reader(log_path);
    log_formats::CarmenWriter out(out_path, {log_path});
    log_formats::TumWriter truth(truth_path, {log_path, out_path});
    out.Comment("made by structloc synthesise-odometry from " + log_path);
    std::optional<simulation_core::OdometrySynthesiser> odometry;
    std::vector<Synthesised> synthesised;
    log_formats::CarmenRecord record;
    geometry::Pose2D previous_known;
    double stamp = 0.0;
    size_t without_pose = 0, index = 0;
    while (reader.Next(record)) {
      if (record.kind != log_formats::CarmenRecord::Kind::kScan) continue;
      const auto& known = record.robot_pose ? record.robot_pose : record.laser_pose;
      if (!known || !geometry::IsFinite(*known)) {
        ++without_pose;
        continue;
      }
      if (index < first || index >= last) {
        ++index;
        continue;
      }
      ++index;
      const geometry::Pose2D mount = record.robot_pose && record.laser_pose
                                         ? geometry::Between(*record.robot_pose, *record.laser_pose)
                                         : geometry::Pose2D{};
      if (!odometry) odometry.emplace(model, rng, *known);
      stamp = !restamp.enabled ? record.stamp
              : synthesised.empty()
                  ? record.stamp
                  : simulation_core::RestampedTime(stamp, previous_known, *known, restamp.speed_m_s,
                                                   restamp.turn_rate_rad_s, restamp.min_step_s);
      previous_known = *known;
      if (!synthesised.empty() && !(stamp > synthesised.back().taken) && latency_s != 0.0)
        throw config::ConfigError(log_path + ": scan " + std::to_string(index - 1) +
                                  " is not stamped after the one before; --scan-latency needs "
                                  "increasing stamps (add --restamp)");
      synthesised.push_back({stamp, odometry->Next(*known), *known, mount, record});
    }
    for (const auto& s : synthesised) {
      const double stamped = s.taken + latency_s;
      const geometry::Pose2D pose =
          latency_s == 0.0 ? s.odometry : OdometryAt(synthesised, stamped);
      // The field of view from the first beam to the last (none for a scan of
      // no beams), within one turn: the reader refuses beams beyond it.
      const auto& r = s.record;
      const size_t beams = r.ranges.size();
      log_formats::CarmenLaser laser{
          r.start_angle, beams > 0 ? r.angular_resolution * static_cast<double>(beams - 1) : 0.0,
          r.angular_resolution, r.max_range, 0.01};
      out.Odometry(stamped, pose, 0.0, 0.0);
      out.RobotLaser(stamped, laser, r.ranges, geometry::Compose(pose, s.mount), pose, 0.0, 0.0);
      truth.Pose(stamped, s.known);
    }
    const size_t scans = synthesised.size();
    std::cerr << log_formats::MalformedLinesText(reader.Stats(), log_path);
    if (scans == 0)
      throw config::ConfigError(log_path + ": no laser scan with a pose to make odometry from" +
                                (cli.Has("scans") ? " in --scans " + cli.Required("scans") : ""));
    out.Flush();
    truth.Flush();
    out.Close();
    truth.Close();
    std::cout << "structloc synthesise-odometry: " << scans << " scans";
    if (without_pose > 0) std::cout << " (" << without_pose << " without a pose left out)";
    std::cout << std::setprecision(4) << "\n  odometry: scale error " << model.scale_error
              << ", heading drift " << model.heading_drift_rad_per_m / kDegree << " deg/m, noise "
              << model.noise_xy_m_per_sqrt_m << " m and "
              << model.noise_theta_rad_per_sqrt_m / kDegree << " deg per sqrt(m)";
    if (model.turn_scale_error != 0.0 || model.noise_theta_rad_per_sqrt_rad != 0.0)
      std::cout << "; turn scale error " << model.turn_scale_error << ", heading noise "
                << model.noise_theta_rad_per_sqrt_rad / kDegree << " deg per sqrt(rad) turned";
    std::cout << (restamp.enabled ? ", restamped at " : "");
    if (restamp.enabled) std::cout << restamp.speed_m_s << " m/s";
    if (latency_s != 0.0) std::cout << ", scans stamped " << latency_s << " s late";
    std::cout << "\n  wrote " << out_path << " and " << truth_path << "\n";
    return 0;
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc synthesise-odometry: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "structloc synthesise-odometry: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::cli
