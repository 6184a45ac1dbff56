// Global localisation without an initial pose on simulated symmetric floors
// (issue 38): the scenario is simulated once; from START random scans of its
// first loop of the tour, a robot without a pose is started (GlobalStart, as
// the localisation component and replay start one) and given the scans of one
// more loop to commit. Counts the right commits (within 0.2 m and 5 deg of
// the truth at that scan), the wrong ones and the starts that never
// committed, and prints the median odometric travel to the commit and the
// CPU time per scan: weighing hypotheses, while they were held (the searches
// made then, such as the check before a commit, included), and over all
// scans up to the commit.
//   structloc_global_start_evaluation SCENARIO.xml [STARTS=100] [--seed N] [--check]
//                                     [--start SCAN]  (every start there; with
//                                     STRUCTLOC_TRACE set, each scan's hypotheses)
// --check exits 1 on any wrong commit or when fewer than 98 % of the starts
// committed.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "scenario_trials.hpp"
#include "structloc/localisation_core/global/global_start.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "structloc/simulation_core/simulation.hpp"

namespace {

using namespace structloc;

std::vector<simulation_core::SimScan> Simulate(const simulation_core::Scenario& scenario) {
  simulation_core::Simulation sim(scenario);
  std::vector<simulation_core::SimScan> scans;
  while (!sim.Finished()) {
    sim.Step();
    if (auto scan = sim.TakeScan()) scans.push_back(std::move(*scan));
  }
  return scans;
}

// The scans of the tour's first loop: up to where the robot is back at its
// start after having left it.
size_t LoopScans(const std::vector<simulation_core::SimScan>& scans,
                 const geometry::Pose2D& start) {
  bool left = false;
  for (size_t i = 0; i < scans.size(); ++i) {
    const double d = std::hypot(scans[i].truth.x - start.x, scans[i].truth.y - start.y);
    left = left || d > 2.0;
    if (left && d < 0.3) return i;
  }
  return scans.size() / 2;
}

localisation_core::SessionScan ToSessionScan(const simulation_core::SimScan& s) {
  localisation_core::SessionScan scan;
  scan.geometry.stamp = s.stamp;
  scan.geometry.angle_min = s.angle_min;
  scan.geometry.angle_increment = s.angle_increment;
  scan.geometry.time_increment = s.time_increment;
  scan.geometry.range_min = s.range_min;
  scan.geometry.range_max = s.range_max;
  scan.ranges = s.ranges;
  scan.odometry = s.odometry;
  return scan;
}

struct Trial {
  enum class Outcome { kRight, kWrong, kNone } outcome = Outcome::kNone;
  double travel_m = 0.0;  // odometric path from the start to the commit
  double error_m = 0.0, error_deg = 0.0;
  size_t searches = 0, held_scans = 0, most_hypotheses = 0, refused = 0, scans = 0;
  double held_cpu_us = 0.0;  // weighing hypotheses, the scans without a search
  size_t alive_scans = 0;    // the scans while hypotheses were held, checks included
  double alive_cpu_us = 0.0;
  double search_cpu_us = 0.0;  // the scans with a search (to start, or to check a commit)
  double cpu_us = 0.0;         // every scan up to the commit
};

Trial Run(const world_model::WorldModel& world, const simulation_core::Scenario& scenario,
          const std::vector<simulation_core::SimScan>& scans, size_t first, size_t count) {
  localisation_core::GlobalStart start(world, scenario.laser.mount,
                                       Eigen::Matrix3d::Identity() * 0.01);
  Trial trial;
  for (size_t k = first; k < std::min(scans.size(), first + count); ++k) {
    const auto& s = scans[k];
    if (k > first) {
      const auto& p = scans[k - 1].odometry;
      trial.travel_m += std::hypot(s.odometry.x - p.x, s.odometry.y - p.y);
    }
    const bool holding = start.HoldingHypotheses();
    const double t0 = testing::ThreadCpuUs();
    const auto attempt = start.Try(ToSessionScan(s), s.odometry);
    const double cpu_us = testing::ThreadCpuUs() - t0;
    trial.cpu_us += cpu_us;
    ++trial.scans;
    if (attempt.searched) trial.search_cpu_us += cpu_us;
    if (holding) {
      trial.alive_cpu_us += cpu_us;
      ++trial.alive_scans;
    }
    if (holding && !attempt.searched) {
      trial.held_cpu_us += cpu_us;
      ++trial.held_scans;
    }
    trial.refused += attempt.refused ? 1 : 0;
    trial.searches += attempt.searched ? 1 : 0;
    trial.most_hypotheses = std::max(trial.most_hypotheses, attempt.hypotheses.size());
    if (std::getenv("STRUCTLOC_TRACE")) {
      std::printf("    scan %zu truth (%.2f %.2f %.1f)%s:", k, s.truth.x, s.truth.y,
                  s.truth.theta * 180 / geometry::kPi, attempt.searched ? " searched" : "");
      for (const auto& h : attempt.hypotheses)
        std::printf(" [%.2f %.2f %.1f L%.1f s%.2f]", h.pose.x, h.pose.y,
                    h.pose.theta * 180 / geometry::kPi, h.log_likelihood, h.share);
      if (attempt.found)
        std::printf(" FOUND (%.2f %.2f)", attempt.found->pose.x, attempt.found->pose.y);
      std::printf("\n");
    }
    if (!attempt.found) continue;
    const auto& p = attempt.found->pose;
    trial.error_m = std::hypot(p.x - s.truth.x, p.y - s.truth.y);
    trial.error_deg =
        std::abs(geometry::WrapAngle(p.theta - s.truth.theta)) * 180.0 / geometry::kPi;
    trial.outcome = trial.error_m <= 0.2 && trial.error_deg <= 5.0 ? Trial::Outcome::kRight
                                                                   : Trial::Outcome::kWrong;
    return trial;
  }
  return trial;
}

}  // namespace

int main(int argc, char** argv) {
  const auto args = testing::ParseTrialArguments(
      argc, argv, 100,
      "structloc_global_start_evaluation SCENARIO.xml [STARTS=100] [--seed N] [--check] "
      "[--start SCAN]");
  if (!args) return 2;
  const size_t starts = args->count;
  const unsigned seed = args->seed;
  const bool check = args->check;
  const auto only_start = args->only_start;
  try {
    const auto scenario = simulation_core::LoadScenario(args->scenario);
    const auto scans = Simulate(scenario);
    const size_t loop = LoopScans(scans, scenario.initial_pose);
    if (starts == 0 || loop == 0 || (only_start && *only_start >= scans.size()))
      throw std::runtime_error("nothing to evaluate: " + std::to_string(starts) + " starts, " +
                               std::to_string(loop) + " scans in a loop, " +
                               std::to_string(scans.size()) + " scans in all");
    Eigen::AlignedBox2d extent;
    for (const auto& s : scans) extent.extend(s.truth.Translation());
    std::printf(
        "%s: %zu scans, one loop of the tour %zu scans, the robot within x %.1f..%.1f m, y "
        "%.1f..%.1f m; %zu starts (seed %u)\n",
        scenario.name.c_str(), scans.size(), loop, extent.min().x(), extent.max().x(),
        extent.min().y(), extent.max().y(), starts, seed);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<size_t> pick(0, loop - 1);
    size_t right = 0, wrong = 0, none = 0, held_scans = 0, all_scans = 0, searches = 0, refused = 0,
           alive_scans = 0;
    double held_cpu = 0.0, search_cpu = 0.0, all_cpu = 0.0, alive_cpu = 0.0;
    std::vector<double> travel;
    for (size_t i = 0; i < starts; ++i) {
      const size_t first = only_start ? *only_start : pick(rng);
      const auto t = Run(*scenario.world, scenario, scans, first, loop);
      held_scans += t.held_scans;
      held_cpu += t.held_cpu_us;
      alive_scans += t.alive_scans;
      alive_cpu += t.alive_cpu_us;
      all_scans += t.scans;
      all_cpu += t.cpu_us;
      searches += t.searches;
      search_cpu += t.search_cpu_us;
      refused += t.refused;
      const char* what = "never committed";
      if (t.outcome == Trial::Outcome::kRight) {
        ++right;
        travel.push_back(t.travel_m);
        what = "right";
      } else if (t.outcome == Trial::Outcome::kWrong) {
        ++wrong;
        what = "WRONG";
      } else {
        ++none;
      }
      std::printf(
          "  start at scan %5zu (%.2f, %.2f, %.0f deg): %s after %.1f m, %zu searches, at most "
          "%zu hypotheses, %zu commits refused (error %.3f m, %.2f deg)\n",
          first, scans[first].truth.x, scans[first].truth.y,
          scans[first].truth.theta * 180.0 / geometry::kPi, what, t.travel_m, t.searches,
          t.most_hypotheses, t.refused, t.error_m, t.error_deg);
    }
    const double share = static_cast<double>(right) / static_cast<double>(starts);
    auto per = [](double us, size_t n) { return n ? us / static_cast<double>(n) : 0.0; };
    std::printf(
        "%s: right %zu of %zu (%.1f %%), wrong %zu, never committed %zu; median travel to the "
        "commit %.1f m\n  CPU: %.0f us per scan weighing hypotheses (%zu scans), %.0f ms per "
        "search (%zu, %zu of them checks that refused a commit), %.0f us per scan while "
        "hypotheses were held, the searches then included (%zu scans), %.0f us per scan over all "
        "scans up to the commit, the first search included (%zu)\n",
        scenario.name.c_str(), right, starts, 100.0 * share, wrong, none, testing::Median(travel),
        per(held_cpu, held_scans), held_scans, 1e-3 * per(search_cpu, searches), searches, refused,
        per(alive_cpu, alive_scans), alive_scans, per(all_cpu, all_scans), all_scans);
    if (check && (wrong > 0 || share < 0.98)) {
      std::printf("FAILED: the bar is >= 98 %% right and no wrong commit\n");
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "structloc_global_start_evaluation: %s\n", e.what());
    return 2;
  }
  return 0;
}
