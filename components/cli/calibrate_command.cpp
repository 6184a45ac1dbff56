// "structloc calibrate --encoders E.csv --fixes F.csv --robot NOMINAL.xml
//  --out CALIBRATED.xml [--estimate LIST] [--advice]": offline odometry
// calibration; prints each parameter with its standard deviation. Writes the
// robot file only for a successful estimate (exit 0); a meaningless one exits
// 1 with its likely cause and leaves --out untouched.
#include <algorithm>
#include <array>
#include <cstdio>
#include <iostream>

#include "structloc/calibration_core/calibration_problem.hpp"
#include "structloc/calibration_core/odometry_calibration.hpp"
#include "structloc/config/command_line.hpp"
#include "structloc/config/output_file.hpp"
#include "structloc/config/strict_number.hpp"
#include "subcommands.hpp"

namespace structloc::cli {
namespace {

void PrintReport(const calibration_core::CalibrationReport& report,
                 const calibration_core::CalibrationOptions& options,
                 const kinematics::RobotParameters& nominal) {
  const auto nominal_values = calibration_core::ValuesOf(nominal);
  const auto values = calibration_core::ValuesOf(report.parameters);
  const bool estimated_any =
      std::find(report.estimated.begin(), report.estimated.end(), true) != report.estimated.end();
  for (int k = 0; k < calibration_core::kParameterCount && report.iterations > 0; ++k) {
    const auto param = static_cast<calibration_core::Parameter>(k);
    const size_t i = static_cast<size_t>(k);
    if (report.estimated[i]) {
      std::printf("  %-22s %.8g +- %.2g %s   (nominal %.8g)\n",
                  calibration_core::ParameterName(param), values[i], report.standard_deviation[i],
                  calibration_core::ParameterUnit(param), nominal_values[i]);
    } else if (options.estimate[i]) {
      std::printf("  %-22s NOT OBSERVABLE: kept nominal %.8g %s\n",
                  calibration_core::ParameterName(param), nominal_values[i],
                  calibration_core::ParameterUnit(param));
    }
  }
  if (report.correlation.rows() > 1) {
    std::cout << "  correlations of the estimated parameters:\n" << report.correlation << "\n";
  }
  if (estimated_any) {
    std::printf(
        "  relative motion between fixes, whitened residual RMS: %.4g with the nominal parameters, "
        "%.4g estimated (%d iterations)\n",
        report.residual_rms_before, report.residual_rms_after, report.iterations);
  } else if (report.intervals_used > 0) {
    std::printf("  weighted residual RMS with the nominal parameters: %.4g\n",
                report.residual_rms_before);
  }
  if (report.dead_reckoning_rms_nominal > 0) {
    std::printf(
        "  dead reckoning over the whole recording, RMS against the fixes: %.4g m nominal, "
        "%.4g m calibrated\n",
        report.dead_reckoning_rms_nominal, report.dead_reckoning_rms_calibrated);
  }
  if (!report.observability.empty()) std::printf("  what this trajectory determines:\n");
  for (const auto& line : report.observability) std::printf("    %s\n", line.c_str());
  for (const auto& w : report.warnings) std::printf("  WARNING: %s\n", w.c_str());
}

// A variance option's value (a finite number >= 0), or `fallback` when not given.
double Variance(const config::CommandLine& cli, const char* key, double fallback) {
  const auto text = cli.Get(key);
  if (!text) return fallback;
  const auto value = config::ParseFiniteDouble(*text);
  if (!value || *value < 0) {
    throw config::ConfigError(std::string("--") + key + " '" + *text +
                              "' is not a finite number >= 0");
  }
  return *value;
}

}  // namespace

int CalibrateCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"encoders", true,
       "encoders.csv (t,traction_ticks,steering_ticks; differential drive: "
       "t,left_ticks,right_ticks)"},
      {"fixes", true, "fixes.csv (t,x,y,theta[,var_x,var_y,var_theta])"},
      {"robot", true, "nominal robot parameter file"},
      {"out", true,
       "calibrated robot parameter file to write (only when the estimate succeeds; never over "
       "an input)"},
      {"estimate", true,
       "comma-separated parameters (default wheel_radius,axle_distance,steering_offset; also "
       "steering_rad_per_tick,sensor_x,sensor_y,sensor_theta; differential drive: default "
       "left_wheel_radius,right_wheel_radius,wheel_separation)"},
      {"slip-variance-m2-per-m", true,
       "process noise: wheel slip, variance of the distance per metre rolled (default 1e-6)"},
      {"heading-variance-rad2-per-m", true,
       "process noise: heading variance per metre rolled (default 1e-6)"},
      {"advice", false, "print which manoeuvres make which parameter observable, and exit"},
  };
  try {
    const config::CommandLine cli(inv.argc, inv.argv, 2, specs);
    if (cli.Has("advice")) {
      std::cout << calibration_core::TrajectoryAdvice();
      return 0;
    }
    calibration_core::CalibrationOptions options;
    options.slip_variance_m2_per_m =
        Variance(cli, "slip-variance-m2-per-m", options.slip_variance_m2_per_m);
    options.heading_variance_rad2_per_m =
        Variance(cli, "heading-variance-rad2-per-m", options.heading_variance_rad2_per_m);
    const std::string robot_path = cli.Required("robot");
    const std::string encoders_path = cli.Required("encoders");
    const std::string fixes_path = cli.Required("fixes");
    config::OutputFile out(cli.Required("out"), {robot_path, encoders_path, fixes_path});
    const auto nominal = kinematics::LoadRobotParameters(robot_path);
    options.estimate = calibration_core::DefaultEstimate(nominal.kind);
    if (auto list = cli.Get("estimate")) {
      options.estimate = calibration_core::ParseParameterList(*list);
    }
    const auto encoders = calibration_core::ReadEncodersCsv(
        encoders_path, nominal.traction_counter_bits, nominal.kind);
    const auto fixes = calibration_core::ReadFixesCsv(fixes_path);
    const auto report = calibration_core::Calibrate(encoders, fixes.fixes, nominal, options);
    std::printf(
        "%zu encoder samples, %zu fixes (%s), %zu inside the encoder recording, %zu fix "
        "intervals linked by the encoders, %zu not (encoder gaps)\n",
        encoders.size(), fixes.fixes.size(), calibration_core::DescribeDropped(fixes).c_str(),
        report.fixes_used, report.intervals_used, report.intervals_skipped);
    PrintReport(report, options, nominal);
    if (!report.success) {
      std::cerr << "structloc calibrate: calibration FAILED: " << report.failure << "\n";
      for (const auto& cause : report.likely_causes) {
        std::cerr << "  likely cause: " << cause << "\n";
      }
      std::cerr << "  " << out.Path() << " was not written" << std::endl;
      return 1;
    }
    kinematics::WriteRobotParameters(
        report.parameters, out.Stream(),
        "calibrated by structloc calibrate from " + encoders_path + " and " + fixes_path);
    out.Commit();
    std::cout << "wrote " << out.Path() << "\n";
    return 0;
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc calibrate: " << e.what() << "\n" << config::CommandLine::Usage(specs);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "structloc calibrate: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::cli
