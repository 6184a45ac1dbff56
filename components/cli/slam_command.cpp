// "structloc slam --log RAW.log --poses-out POSES.tum [--out WORLD.xml]
// [--plot P.png] [--relations R] [--truth T.tum] [--params MAP_BUILD.xml]
// [--slam-params SLAM.xml] [--scans F:L]": the robot's path from its raw
// odometry and scans (slam_core::Slam: keyframes matched, loops closed, the
// pose graph optimised with Ceres), each scan's odometry taken at its stamp
// less the laser's latency the options give or the log shows; then, with
// --out or --plot, the wall map built on those poses as "structloc map
// build" builds one and checked against the same scans as "structloc map
// check" checks one. With --relations, the path is judged by Kuemmerle et
// al.'s relation metric beside raw odometry; with --truth, against ground
// truth as it is, after one rigid alignment (the path's frame is the first
// scan's odometry's, not the truth's) and after one that also scales it.
// Ctrl-C stops adding scans: the path and map of the scans added so far are
// written.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <utility>

#include "file_names.hpp"
#include "map_check_findings.hpp"
#include "structloc/config/command_line.hpp"
#include "structloc/config/output_file.hpp"
#include "structloc/log_formats/recording_writers.hpp"
#include "structloc/log_formats/relations_reader.hpp"
#include "structloc/map_building/map_builder.hpp"
#include "structloc/map_building/map_check.hpp"
#include "structloc/process/shutdown_signal.hpp"
#include "structloc/rendering/map_canvas.hpp"
#include "structloc/replay/relation_error.hpp"
#include "structloc/replay/trajectory_alignment.hpp"
#include "structloc/slam_core/slam.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "subcommands.hpp"

namespace structloc::cli {
namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;

void PrintRelations(const char* what, const replay::RelationError& e) {
  std::printf("  %-12s %.3f +- %.3f m, %.2f +- %.2f deg (%zu relations", what, e.translation_mean_m,
              e.translation_std_m, kDeg * e.rotation_mean_rad, kDeg * e.rotation_std_rad, e.used);
  if (e.missing > 0) std::printf(", %zu without both scans", e.missing);
  std::printf(")\n");
}

// `what` against the truth as it is, after one rigid alignment and after one
// with a scale as well.
void PrintTruthErrors(const char* what, const std::vector<log_formats::StampedPose>& path,
                      const std::vector<log_formats::StampedPose>& truth) {
  const auto raw = replay::CompareTrajectories(path, truth);
  if (raw.matched == 0) {
    std::printf("  %-9s n/a (no pose matches a truth stamp)\n", what);
    return;
  }
  std::printf("  %-9s RMSE %.1f mm, max %.1f mm, heading RMSE %.2f deg (%zu poses)", what,
              1e3 * raw.position_rmse_m, 1e3 * raw.position_max_m, kDeg * raw.heading_rmse_rad,
              raw.matched);
  if (const auto e = replay::CompareAligned(path, truth)) {
    std::printf("; aligned: RMSE %.1f mm, max %.1f mm, heading RMSE %.2f deg",
                1e3 * e->position_rmse_m, 1e3 * e->position_max_m, kDeg * e->heading_rmse_rad);
  }
  if (const auto e = replay::CompareAlignedWithScale(path, truth)) {
    std::printf("; with scale %.5f: RMSE %.1f mm, max %.1f mm", e->scale,
                1e3 * e->error.position_rmse_m, 1e3 * e->error.position_max_m);
  }
  std::printf("\n");
}

// Each scan's odometric laser pose at the moment it was taken, the latency
// printed where there is one; the log's points de-skewed to that moment
// where it gives its beam timing (it was read without de-skewing). The points
// are moved out of the log and back, not copied: a long log's points are
// most of what slam holds.
std::vector<geometry::Pose2D> OdometryAndPointsAsTaken(map_building::PosedScanLog& log,
                                                       const slam_core::SlamOptions& options) {
  std::vector<double> stamps;
  std::vector<geometry::Pose2D> odometry;
  std::vector<std::vector<Eigen::Vector2d>> points;
  slam_core::PointTimes times;
  for (auto& s : log.scans) {
    stamps.push_back(s.stamp);
    odometry.push_back(s.laser_pose);
    points.push_back(std::move(s.points));
    if (log.time_increment_s > 0.0) {
      auto& t = times.emplace_back();
      t.reserve(s.point_beams.size());
      for (const uint32_t beam : s.point_beams) t.push_back(log.time_increment_s * beam);
    }
  }
  slam_core::ScanLatencyEstimate e;
  auto taken = slam_core::AsTaken(options, stamps, odometry, std::move(points), times, &e);
  for (size_t i = 0; i < log.scans.size(); ++i) log.scans[i].points = std::move(taken.points[i]);
  if (!times.empty()) log.deskewed = log.scans.size();
  if (options.estimate_scan_latency && !e.untold.empty()) {
    std::printf("  scan latency: the log does not tell it (%s); none applied\n", e.untold.c_str());
  } else if (options.estimate_scan_latency) {
    std::printf(
        "  scan latency estimated from the log: %.3f s, %.0f %% interval %.3f to %.3f s: %s (%zu "
        "pairs of consecutive scans; their matched rotations against odometry's %.2f deg RMS at "
        "the estimate, %.2f deg at none)\n",
        e.latency_s, 100.0 * options.latency.confidence, e.interval_low_s, e.interval_high_s,
        e.Shown() ? "applied" : "none shown, none applied", e.pairs, kDeg * e.rms_at_estimate_rad,
        kDeg * e.rms_at_zero_rad);
    if (e.Shown())
      std::printf(
          "  track this laser with it too: <tracking scan_latency_s=\"%.3f\"/> in the "
          "localisation parameters\n",
          e.latency_s);
  } else if (options.scan_latency_s != 0.0) {
    std::printf("  scan latency %.3f s (the options')\n", options.scan_latency_s);
  }
  return taken.odometry;
}

}  // namespace

int SlamCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"log", true, "CARMEN log with raw odometry (the robot or laser pose of each laser line)"},
      {"poses-out", true, "the robot's path, one TUM line per scan (t x y z qx qy qz qw)"},
      {"out", true, "also build the wall map on that path and write it (world XML)"},
      {"params", true,
       "map-build options (<map_build_params>, see structloc params --map-build); their range "
       "limits also choose the readings SLAM matches"},
      {"slam-params", true,
       "SLAM options (<slam_params>, see structloc params --slam): keyframes, matching, loop "
       "closure, pose graph"},
      {"relations", true,
       "judge the path by this relations file (Kuemmerle et al. 2009), beside raw odometry"},
      {"truth", true,
       "judge the path against these ground-truth poses (TUM, matched by stamp), as it is, "
       "after one rigid alignment and after one that also scales it, beside raw odometry"},
      {"plot", true,
       "PNG of the map built on the path over the readings, each wall coloured by the check "
       "(as structloc map check draws it)"},
      {"scans", true,
       "use only the scans FIRST:LAST of the log (numbers from 0, LAST not included; default: "
       "all)"},
  };
  // First, before Ceres or anything else starts a thread that would inherit the signals.
  process::ShutdownSignal shutdown;
  try {
    const config::CommandLine cli(inv.argc, inv.argv, 2, specs);
    const std::string log_path = cli.Required("log");
    const std::string poses_path = cli.Required("poses-out");
    const std::string params_path = cli.GetOr("params", "");
    const auto build = params_path.empty() ? map_building::MapBuildOptions{}
                                           : map_building::LoadMapBuildOptions(params_path);
    const std::string slam_params_path = cli.GetOr("slam-params", "");
    const auto slam_options = slam_params_path.empty()
                                  ? slam_core::SlamOptions{}
                                  : slam_core::LoadSlamOptions(slam_params_path);
    std::vector<std::string> inputs{log_path};
    if (!params_path.empty()) inputs.push_back(params_path);
    if (!slam_params_path.empty()) inputs.push_back(slam_params_path);
    std::vector<log_formats::Relation> relations;
    if (cli.Has("relations")) {
      relations = log_formats::ReadRelations(cli.Required("relations"));
      inputs.push_back(cli.Required("relations"));
    }
    std::vector<log_formats::StampedPose> truth;
    if (cli.Has("truth")) {
      truth = log_formats::ReadTum(cli.Required("truth"));
      inputs.push_back(cli.Required("truth"));
    }
    log_formats::TumWriter poses_out(poses_path, inputs);
    inputs.push_back(poses_path);
    std::optional<config::OutputFile> world_out, plot;
    if (cli.Has("out")) world_out.emplace(cli.Required("out"), inputs);
    if (cli.Has("plot")) {
      rendering::MapCanvas::CheckPictureName(cli.Required("plot"));
      if (world_out) inputs.push_back(world_out->Path());
      plot.emplace(cli.Required("plot"), inputs);
    }
    const auto range = map_building::ParseScanRange(cli.GetOr("scans", ":"));

    const auto start = std::chrono::steady_clock::now();
    auto log = map_building::ReadPosedScans(log_path, build.scans, map_building::ScanDeskew::kNone);
    map_building::KeepScans(log, range.first, range.second);
    // The laser on the robot, from the first line with both poses.
    geometry::Pose2D mount;
    for (const auto& s : log.scans) {
      if (!s.robot_pose) continue;
      mount = geometry::Between(*s.robot_pose, s.laser_pose);
      break;
    }
    const geometry::Pose2D unmount = geometry::Inverse(mount);
    const std::vector<geometry::Pose2D> laser_odometry =
        OdometryAndPointsAsTaken(log, slam_options);
    // SLAM in the laser's frame: its odometric pose and its own readings.
    slam_core::Slam slam(slam_options);
    for (size_t i = 0; i < log.scans.size(); ++i) {
      if (shutdown.WaitFor(std::chrono::milliseconds(0))) {
        std::printf("  stopped (Ctrl-C) after %zu of %zu scans: the path and map so far\n", i,
                    log.scans.size());
        log.scans.resize(i);
        break;
      }
      const auto& s = log.scans[i];
      slam.Add({s.stamp, laser_odometry[i], s.points});
      if ((i + 1) % 1000 == 0) {
        std::printf("  %zu of %zu scans, %zu keyframes, %zu loops closed\n", i + 1,
                    log.scans.size(), slam.Stats().keyframes, slam.Stats().loops_closed);
        std::fflush(stdout);
      }
    }
    slam.Finish();
    const auto laser_path = slam.Trajectory();
    std::vector<log_formats::StampedPose> path, odometry;
    for (size_t i = 0; i < laser_path.size(); ++i) {
      path.push_back({laser_path[i].stamp, geometry::Compose(laser_path[i].pose, unmount)});
      odometry.push_back({log.scans[i].stamp, geometry::Compose(log.scans[i].laser_pose, unmount)});
      poses_out.Pose(path.back().stamp, path.back().pose);
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto& st = slam.Stats();
    std::printf("structloc slam: %zu scans in %.1f s: %zu keyframes (%zu steps on odometry alone",
                st.scans, seconds, st.keyframes, st.odometry_edges);
    if (slam_options.partial_matches)
      std::printf(", %zu on odometry beside a match along a corridor", st.partial_matches);
    std::printf("), %zu loops closed of %zu tried\n", st.loops_closed, st.loops_tried);
    std::printf("%s", map_building::DeskewText(log).c_str());
    if (slam_options.walls.enabled)
      std::printf("  refined with %zu walls seen from two keyframes or more (%zu sightings)%s\n",
                  st.walls.walls, st.walls.observations,
                  st.walls.usable ? "" : "; the solver ended without a usable solution");
    if (!relations.empty()) {
      std::printf("relation errors (Kuemmerle et al. 2009):\n");
      PrintRelations("slam", replay::CompareRelations(path, relations));
      PrintRelations("odometry", replay::CompareRelations(odometry, relations));
    }
    if (!truth.empty()) {
      std::printf("position against the truth:\n");
      PrintTruthErrors("slam", path, truth);
      PrintTruthErrors("odometry", odometry, truth);
    }
    if (world_out || plot) {
      for (size_t i = 0; i < log.scans.size(); ++i) log.scans[i].laser_pose = laser_path[i].pose;
      const auto result = map_building::BuildMap(log.scans, build);
      const auto world =
          map_building::MakeWorld(Stem(log_path, "slam"), result.walls, result.pillars);
      std::printf(
          "  %zu walls and %zu pillars built on the path%s%s (%zu more pillars seen through and "
          "dropped: people who moved)\n",
          result.walls.size(), world.Cylinders().size(), world_out ? " in " : "",
          world_out ? cli.Required("out").c_str() : "", result.pillar_report.seen_through);
      if (world_out) {
        world_model::WriteWorldModel(world,
                                     {"Built by `structloc slam` from " + FileName(log_path) +
                                      ": " + std::to_string(result.walls.size()) + " walls, " +
                                      std::to_string(world.Cylinders().size()) + " pillars."},
                                     world_out->Stream());
        world_out->Flush();
      }
      // The map against the scans it was built from, on the path found.
      const map_building::MapCheckOptions check;
      std::vector<Eigen::Vector2d> unexplained;
      const auto report = map_building::CheckMap(world, log.scans, check, &unexplained);
      std::cout << "map check of the built map against the scans on the path:\n";
      PrintMapCheckFindings(world, report, check, build.scans.max_range_m);
      if (plot) {
        WriteMapPicture(
            *plot, world,
            MapCheckPicture("slam: " + FileName(log_path), log.scans, report, check, unexplained));
        plot->Flush();
        std::cout << "  picture: " << plot->Path() << "\n";
      }
    }
    poses_out.Close();
    if (world_out) world_out->Commit();
    if (plot) plot->Commit();
    return 0;
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc slam: " << e.what() << "\n" << config::CommandLine::Usage(specs);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "structloc slam: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::cli
