// The SLAM options declared once (key, range, unit, description; the struct
// members hold the defaults) for a <slam_params> file, so that a building or a
// laser unlike the recordings the defaults were chosen on can be mapped
// without a rebuild.
#include <stdexcept>
#include <string>
#include <utility>

#include "structloc/config/option_table.hpp"
#include "structloc/slam_core/slam.hpp"

namespace structloc::slam_core {
namespace {

using config::Range;
using O = SlamOptions;
using Table = config::OptionTable<O>;

Table KeyframesSection() {
  Table t("keyframes", "the scans that enter the pose graph");
  t.Number("distance_m", &O::keyframe_distance_m, Range::Positive(), "m",
           "a keyframe after this much travel since the last ...");
  t.Number("angle_rad", &O::keyframe_angle_rad, Range::Positive(), "rad", "... or this much turn");
  return t;
}

Table StepsSection() {
  Table t("steps", "each keyframe matched against the keyframes just before it");
  t.Number("submap_keyframes", &O::submap_keyframes, Range::Closed(1, 100), "",
           "the keyframes a new one is matched against");
  t.Number("min_match_share", &O::min_match_share, Range::Closed(0, 1), "",
           "a match is taken when it explains this share of the scan ...");
  t.Number("max_match_correction_m", &O::max_match_correction_m, Range::NonNegative(), "m",
           "... and moves odometry's step by at most this ...");
  t.Number("max_match_correction_share", &O::max_match_correction_share, Range::NonNegative(), "",
           "... plus this share of the step's length");
  t.Flag("partial_matches", &O::partial_matches,
         "a match that passes those gates but does not pin every direction (along a corridor) "
         "enters beside odometry's step and places the keyframe, its ICP holding odometry's "
         "position along the corridor, so that the heading there comes from the walls; false: "
         "odometry's step alone, the heading drifting with odometry's");
  t.Number("odometry_sigma_per_m", &O::odometry_sigma_per_m, Range::Positive(), "m/m",
           "odometry's noise per metre driven, where no match is taken");
  t.Number("odometry_sigma_per_rad", &O::odometry_sigma_per_rad, Range::NonNegative(), "",
           "... its heading's per radian turned ...");
  t.Number("odometry_sigma_theta_per_m", &O::odometry_sigma_theta_per_m, Range::NonNegative(),
           "rad/m", "... and per metre driven");
  t.Number("odometry_min_sigma_xy_m", &O::odometry_min_sigma_xy_m, Range::Positive(), "m",
           "odometry's position noise on a step is never taken as smaller");
  t.Number("odometry_min_sigma_theta_rad", &O::odometry_min_sigma_theta_rad, Range::Positive(),
           "rad", "... nor its heading noise");
  return t;
}

// The point-to-line ICP's options, as section `name` of the part `part` finds.
template <class Part>
Table MatchSection(const char* name, const char* description, Part part) {
  using M = ScanMatchOptions;
  config::OptionTable<M> t(name, description);
  t.Number("iterations", &M::iterations, Range::Closed(1, 1000), "", "ICP iterations at most");
  t.Number("first_pair_distance_m", &M::first_pair_distance_m, Range::Positive(), "m",
           "points pair with reference points this far at first ...");
  t.Number("last_pair_distance_m", &M::last_pair_distance_m, Range::Positive(), "m",
           "... shrinking to this over the first half of the iterations; a scan's share "
           "explained counts its points this close to a surface");
  t.Number("normal_radius_m", &M::normal_radius_m, Range::Closed(0.02, 5), "m",
           "the reference points within this radius give a point's surface direction");
  t.Number("point_sigma_m", &M::point_sigma_m, Range::Positive(), "m",
           "a point's noise across its surface (range noise, wall roughness); the Huber loss "
           "starts at twice this");
  t.Number("correlated_points", &M::correlated_points, Range::Closed(1, 1e6), "",
           "the covariance counts one point in this many (neighbours see the same stretch "
           "of wall)");
  t.Number("min_sigma_xy_m", &M::min_sigma_xy_m, Range::Positive(), "m",
           "the covariance never claims a position better than this ...");
  t.Number("min_sigma_theta_rad", &M::min_sigma_theta_rad, Range::Positive(), "rad",
           "... nor a heading");
  return Table::Of(t, part);
}

Table LoopsSection() {
  Table t("loops", "loops closed by matching a new keyframe against places seen long ago");
  t.Number("min_separation_keyframes", &O::loop_min_separation, Range::Closed(1, 1000000), "",
           "only keyframes at least this many before the new one are tried");
  t.Number("radius_m", &O::loop_radius_m, Range::Positive(), "m",
           "... whose estimate lies within this radius of the new one's ...");
  t.Number("radius_per_m", &O::loop_radius_per_m, Range::NonNegative(), "m/m",
           "... widened by this share of the odometric distance counted since a loop last "
           "closed (every scan's distance from its keyframe) ...");
  t.Number("max_radius_m", &O::loop_max_radius_m, Range::Positive(), "m", "... to at most this");
  t.Number("candidates", &O::loop_candidates, Range::Closed(1, 100), "",
           "the nearest this many are tried per keyframe");
  t.Number("submap_keyframes", &O::loop_submap_keyframes, Range::Closed(0, 100), "",
           "a candidate's reference: it and this many keyframes each side of it");
  t.Number("min_share", &O::loop_min_share, Range::Closed(0, 1), "",
           "a loop closes when the match explains this share of the scan ...");
  t.Number("max_rms_m", &O::loop_max_rms_m, Range::Positive(), "m",
           "... with the explained points' distances at most this RMS");
  return t;
}

Table GraphSection() {
  using G = PoseGraphOptions;
  Table t("graph", "the pose graph (Ceres Solver)");
  t.Number("robust_scale_sigmas", &O::graph, &G::robust_scale_sigmas, Range::Positive(), "",
           "loop closures go through a Cauchy loss of this scale, in their own standard "
           "deviations");
  t.Number("max_iterations", &O::graph, &G::max_iterations, Range::Closed(1, 100000), "",
           "solver iterations per optimisation at most");
  return t;
}

Table WallsSection() {
  using W = WallRefinementOptions;
  Table t("walls", "the pose-and-wall refinement that ends SLAM (Ceres Solver)");
  t.Flag("enabled", &O::walls, &W::enabled,
         "refine the keyframe poses with the straight walls they see");
  t.Number("rounds", &O::walls, &W::rounds, Range::Closed(1, 100), "",
           "association and optimisation, alternating");
  t.Number("max_angle_rad", &O::walls, &W::max_angle_rad, Range::Closed(0, 1), "rad",
           "a keyframe's segment belongs to a wall facing the same way within this ...");
  t.Number("max_offset_m", &O::walls, &W::max_offset_m, Range::Positive(), "m",
           "... whose line both its ends lie within this of ...");
  t.Number("max_gap_m", &O::walls, &W::max_gap_m, Range::NonNegative(), "m",
           "... and which it overlaps or comes this close to along it");
  t.Number("correlated_points", &O::walls, &W::correlated_points, Range::Closed(1, 1e6), "",
           "a segment end's standard deviation counts one of its points in this many ...");
  t.Number("min_sigma_m", &O::walls, &W::min_sigma_m, Range::Positive(), "m",
           "... and is never below this");
  t.Number("robust_scale_sigmas", &O::walls, &W::robust_scale_sigmas, Range::Positive(), "",
           "segment ends go through a Cauchy loss of this scale, in their own standard "
           "deviations (a segment given to the wrong wall weighs little)");
  return t;
}

Table ScanLatencySection() {
  using L = ScanLatencyOptions;
  Table t("scan_latency",
          "the laser's latency against odometry (a scan stamped when its readings arrived)");
  t.Flag("estimate", &O::estimate_scan_latency,
         "estimate it from the recording: consecutive scans matched where the robot's turn "
         "speeds up or slows down, their rotations against odometry's sampled at each stamp "
         "minus the latency, applied where the recording shows one; false: latency_s");
  t.Number("latency_s", &O::scan_latency_s, Range::Closed(-1, 1), "s",
           "with estimate false, each scan's odometry is taken this long before its stamp "
           "(negative: after)");
  t.Number("max_latency_s", &O::latency, &L::max_latency_s, Range::Closed(0.001, 1), "s",
           "the estimate is sought within this either way ...");
  t.Number("step_s", &O::latency, &L::step_s, Range::Closed(0.0001, 0.1), "s",
           "... on a grid of this step");
  t.Number("min_sensitivity_rad", &O::latency, &L::min_sensitivity_rad, Range::Positive(), "rad",
           "a pair of consecutive scans enters when the latencies searched move its odometric "
           "rotation by this much ...");
  t.Number("min_share", &O::latency, &L::min_share, Range::Closed(0, 1), "",
           "... and its match explains this share of the later scan ...");
  t.Number("max_rms_m", &O::latency, &L::max_rms_m, Range::Positive(), "m",
           "... with the explained points' distances at most this RMS");
  t.Number("huber_rad", &O::latency, &L::huber_rad, Range::Positive(), "rad",
           "a pair's rotation residual enters through a Huber loss from this on");
  t.Number("max_pairs", &O::latency, &L::max_pairs, Range::Closed(1, 1000000), "",
           "at most this many pairs, spread evenly over the log");
  t.Number("rounds", &O::latency, &L::rounds, Range::Closed(1, 10), "",
           "rounds of matching, each from the last estimate (a pair in a quick turn matches "
           "only from a guess near its latency)");
  t.Number("max_rounds", &O::latency, &L::max_rounds, Range::Closed(1, 20), "",
           "where the log gives its beams' times, rounds go on while the estimate still moves, "
           "each de-skewing the scans at the last estimate, up to this many");
  t.Number("confidence", &O::latency, &L::confidence, Range::Open(0, 1), "",
           "the estimate is applied only when its interval at this confidence excludes 0 (the "
           "recording shows a latency) ...");
  t.Number("resamples", &O::latency, &L::resamples, Range::Closed(1, 100000), "",
           "... found from this many resamplings of the matched pairs ...");
  t.Number("block_pairs", &O::latency, &L::block_pairs, Range::Closed(1, 100000), "",
           "... in blocks of this many consecutive pairs ...");
  t.Number("seed", &O::latency, &L::seed, Range::Closed(0, 4294967295.0), "",
           "... drawn by a generator seeded with this");
  return t;
}

Table RunSection() {
  Table t("run", "how the work is done (the results do not depend on it)");
  t.Number("threads", &O::threads, Range::Closed(1, 256), "",
           "independent matches (a keyframe's loop candidates, the scans between keyframes, the "
           "latency estimate's pairs) run on this many threads at once");
  return t;
}

config::OptionFile<O> SlamOptionFile() {
  const auto step = [](auto& o) -> auto& {
    return o.match;
  };
  const auto loop = [](auto& o) -> auto& {
    return o.loop_match;
  };
  return config::OptionFile<O>(
      "slam_params",
      {KeyframesSection(), StepsSection(),
       MatchSection("step_match", "the ICP of a keyframe against the keyframes before it", step),
       LoopsSection(),
       MatchSection("loop_match", "the ICP of a keyframe against a place seen long ago", loop),
       GraphSection(), WallsSection(), ScanLatencySection(), RunSection()});
}

}  // namespace

void SlamOptions::Validate() const {
  SlamOptionFile().Validate(*this);
  for (const auto& [section, m] : {std::pair{"step_match", &match}, {"loop_match", &loop_match}}) {
    if (!(m->first_pair_distance_m >= m->last_pair_distance_m))
      throw std::invalid_argument(std::string(section) +
                                  ": first_pair_distance_m must be >= last_pair_distance_m");
  }
  latency.Validate();
  if (estimate_scan_latency && scan_latency_s != 0.0)
    throw std::invalid_argument(
        "scan_latency: latency_s is " + config::FormatNumber(scan_latency_s) +
        " but estimate is true, which would replace it; set estimate=\"false\" to give the "
        "latency, or latency_s=\"0\" to have it estimated");
  if (!(loop_max_radius_m >= loop_radius_m))
    throw std::invalid_argument("loops: max_radius_m must be >= radius_m");
}

SlamOptions LoadSlamOptions(const std::string& path) {
  return SlamOptionFile().LoadValidated(path);
}

void PrintSlamOptions(std::ostream& out) {
  SlamOptionFile().Print(out, SlamOptions{});
}

void WriteExpandedSlamOptions(const std::string& path, std::ostream& out) {
  SlamOptionFile().WriteExpanded(path, out);
}

}  // namespace structloc::slam_core
