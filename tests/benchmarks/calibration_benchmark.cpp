// Time to calibrate a long recording: the calibration loop
// (maps/scenarios/calibration_loop.xml) driven round and round for HOURS of
// simulated time, encoders at 100 Hz, fixes every 0.1 s with 5 mm noise; the
// wall-clock time of structloc's calibration (single-threaded) and its errors.
//   structloc_calibration_benchmark [HOURS=1]
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "simulated_calibration.hpp"

int main(int argc, char** argv) {
  using namespace structloc;
  const double hours = argc > 1 ? std::atof(argv[1]) : 1.0;
  if (!(hours > 0 && hours <= 1.0)) {
    std::fprintf(stderr, "usage: structloc_calibration_benchmark [HOURS in (0, 1]]\n");
    return 2;
  }
  try {
    auto scenario = simulation_core::LoadScenario(std::string(STRUCTLOC_SOURCE_DIR) +
                                                  "/maps/scenarios/calibration_loop.xml");
    scenario.laser.beams = 10;  // the calibration uses no scans
    scenario.path.loop = true;
    scenario.duration_s = hours * 3600.0;
    const auto dir = std::filesystem::temp_directory_path() /
                     ("structloc_calibration_benchmark_" + std::to_string(getpid()));
    const auto run = testing::RecordCalibration(scenario, 1, dir.string());
    std::filesystem::remove_all(dir);
    const auto options = testing::SimulatorNoiseOptions(scenario);
    const auto start = std::chrono::steady_clock::now();
    const auto report =
        calibration_core::Calibrate(run.encoders, run.fixes, scenario.nominal, options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto truth = scenario.TrueParameters();
    std::printf(
        "%.2f h recording: %zu encoder samples, %zu fixes; calibrated in %.2f s (%s, %d "
        "iterations)\n  radius error %+.5f %%, axle %+.5f %%, steering offset %+.5f deg\n",
        hours, run.encoders.size(), run.fixes.size(), seconds,
        report.success ? "success" : report.failure.c_str(), report.iterations,
        100 * (report.parameters.wheel_radius / truth.wheel_radius - 1),
        100 * (report.parameters.axle_distance / truth.axle_distance - 1),
        (report.parameters.steering_offset - truth.steering_offset) * 180 / geometry::kPi);
    return report.success ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "structloc_calibration_benchmark: %s\n", e.what());
    return 1;
  }
}
