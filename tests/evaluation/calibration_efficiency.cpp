// How close the odometry calibration comes to what the data allow: simulates
// the calibration loop (maps/scenarios/calibration_loop.xml: radius +1 %,
// axle -2 %, steering offset 0.5 deg, wrapping 32-bit counter; with
// --differential calibration_loop_differential.xml: left radius +0.5 %, right
// -0.5 %, separation +2 %) with many seeds, takes fixes of the robot every 0.1 s with 5 mm and
// 0.0055 rad noise, calibrates, and compares per parameter the mean error, the observed spread, the
// mean reported standard deviation and the Cramer-Rao bound of the same model at the truth, and the
// open-loop drift over the loop before and after. The model's process noise is the simulator's
// (simulated_calibration.hpp).
//   structloc_calibration_efficiency [SEEDS=20] [--differential] [--check]
// --check exits 1 unless every seed is within the bars (radius 0.02 %, axle
// 0.1 %, steering offset 0.01 deg; left and right radius 0.02 %, separation
// 0.1 %), each spread is within 1.5x of the bound and of the reported
// deviation, and the drift drops at least 10-fold in every seed.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "simulated_calibration.hpp"
#include "structloc/calibration_core/calibration_problem.hpp"

namespace {

using namespace structloc;
namespace cc = calibration_core;

struct Bar {
  cc::Parameter parameter;
  const char* label;
  double unit_scale;  // to the printed unit
  const char* unit;
  double limit;  // in the printed unit, relative to the truth where relative
  bool relative;
};

const std::vector<Bar> kTricycleBars = {
    {cc::kWheelRadius, "wheel radius", 100.0, "%", 0.02, true},
    {cc::kAxleDistance, "axle distance", 100.0, "%", 0.1, true},
    {cc::kSteeringOffset, "steering offset", 180.0 / geometry::kPi, "deg", 0.01, false},
};
const std::vector<Bar> kDifferentialBars = {
    {cc::kLeftWheelRadius, "left radius", 100.0, "%", 0.02, true},
    {cc::kRightWheelRadius, "right radius", 100.0, "%", 0.02, true},
    {cc::kWheelSeparation, "separation", 100.0, "%", 0.1, true},
};

struct Seed {
  std::vector<double> error, reported, bound;  // per bar, printed units
  double seconds = 0.0;
  double drift_nominal_m = 0.0, drift_calibrated_m = 0.0;  // open loop vs truth, RMS
};

Seed RunSeed(simulation_core::Scenario scenario, uint32_t seed, const std::string& dir,
             const std::vector<Bar>& bars) {
  const auto truth = scenario.TrueParameters();
  const auto run = testing::RecordCalibration(scenario, seed, dir);
  const auto options = testing::SimulatorNoiseOptions(scenario);
  const auto start = std::chrono::steady_clock::now();
  const auto report = cc::Calibrate(run.encoders, run.fixes, scenario.nominal, options);
  Seed s;
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!report.success)
    throw std::runtime_error("seed " + std::to_string(seed) + ": " + report.failure);
  const Eigen::MatrixXd bound =
      cc::CramerRaoCovariance(run.encoders, run.fixes, run.true_poses, truth, options);
  const auto estimate = cc::ValuesOf(report.parameters);
  const auto true_values = cc::ValuesOf(truth);
  std::vector<cc::Fix> truth_fixes;
  for (size_t k = 0; k < run.true_poses.size(); ++k) {
    truth_fixes.push_back({run.fixes[k].t, run.true_poses[k]});
  }
  s.drift_nominal_m = cc::DeadReckoningRms(run.encoders, truth_fixes, scenario.nominal);
  s.drift_calibrated_m = cc::DeadReckoningRms(run.encoders, truth_fixes, report.parameters);
  for (size_t b = 0; b < bars.size(); ++b) {
    const Bar& bar = bars[b];
    const double scale = bar.unit_scale / (bar.relative ? true_values[bar.parameter] : 1.0);
    s.error.push_back((estimate[bar.parameter] - true_values[bar.parameter]) * scale);
    s.reported.push_back(report.standard_deviation[bar.parameter] * scale);
    const auto k = static_cast<Eigen::Index>(b);  // the estimated parameters, in order
    s.bound.push_back(std::sqrt(bound(k, k)) * scale);
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  int seeds = 20;
  bool check = false, differential = false;
  for (int a = 1; a < argc; ++a) {
    if (std::strcmp(argv[a], "--check") == 0) {
      check = true;
    } else if (std::strcmp(argv[a], "--differential") == 0) {
      differential = true;
    } else {
      seeds = std::atoi(argv[a]);
    }
  }
  if (seeds < 2) {
    std::fprintf(stderr,
                 "usage: structloc_calibration_efficiency [SEEDS>=2] [--differential] [--check]\n");
    return 2;
  }
  try {
    auto scenario = simulation_core::LoadScenario(
        std::string(STRUCTLOC_SOURCE_DIR) + "/maps/scenarios/" +
        (differential ? "calibration_loop_differential.xml" : "calibration_loop.xml"));
    const auto& bars = differential ? kDifferentialBars : kTricycleBars;
    scenario.laser.beams = 10;  // the calibration uses no scans
    const auto dir = std::filesystem::temp_directory_path() /
                     ("structloc_calibration_efficiency_" + std::to_string(getpid()));
    std::vector<Seed> runs;
    for (int k = 0; k < seeds; ++k) {
      runs.push_back(RunSeed(scenario, static_cast<uint32_t>(k + 1), dir.string(), bars));
    }
    std::filesystem::remove_all(dir);
    double worst_drift_gain = 1e300;
    for (const auto& r : runs) {
      worst_drift_gain = std::min(worst_drift_gain, r.drift_nominal_m / r.drift_calibrated_m);
    }
    std::printf(
        "%s, %d seeds, fixes every 0.1 s with %.0f mm / %.4f rad noise; %.2f s per calibration;\n"
        "open-loop drift RMS over the loop %.3f m nominal -> %.4f m calibrated (seed 1), at least "
        "%.0fx smaller in every seed\n",
        scenario.name.c_str(), seeds, 1000 * testing::kFixSigmaXy_m, testing::kFixSigmaTheta_rad,
        runs.front().seconds, runs.front().drift_nominal_m, runs.front().drift_calibrated_m,
        worst_drift_gain);
    bool ok = worst_drift_gain >= 10.0;
    std::printf("%-16s %10s %10s %10s %10s %10s %8s %8s\n", "parameter", "max |err|", "mean err",
                "spread", "reported", "CR bound", "spr/CRB", "spr/rep");
    for (size_t b = 0; b < bars.size(); ++b) {
      double mean = 0, worst = 0, reported = 0, bound = 0;
      for (const auto& r : runs) {
        mean += r.error[b] / seeds;
        worst = std::max(worst, std::abs(r.error[b]));
        reported += r.reported[b] / seeds;
        bound += r.bound[b] / seeds;
      }
      double var = 0;
      for (const auto& r : runs) var += (r.error[b] - mean) * (r.error[b] - mean) / (seeds - 1);
      const double spread = std::sqrt(var);
      std::printf("%-16s %9.5f%s %9.5f%s %9.5f%s %9.5f%s %9.5f%s %8.2f %8.2f\n", bars[b].label,
                  worst, bars[b].unit, mean, bars[b].unit, spread, bars[b].unit, reported,
                  bars[b].unit, bound, bars[b].unit, spread / bound, spread / reported);
      const bool within = worst <= bars[b].limit && spread <= 1.5 * bound &&
                          spread <= 1.5 * reported && reported <= 1.5 * spread;
      if (!within) {
        std::printf(
            "  %s misses a bar (|error| <= %g %s, spread within 1.5x of bound and reported)\n",
            bars[b].label, bars[b].limit, bars[b].unit);
      }
      ok = ok && within;
    }
    return check && !ok ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "structloc_calibration_efficiency: %s\n", e.what());
    return 1;
  }
}
