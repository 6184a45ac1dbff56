// "structloc calibrate --encoders E.csv --fixes F.csv --robot NOMINAL.xml
//  --out CALIBRATED.xml [--estimate LIST] [--advice]": offline odometry
// calibration; prints each parameter with its standard deviation.
#include <cstdio>
#include <iostream>
#include <sstream>

#include "command_line.hpp"
#include "odometry_calibration.hpp"
#include "subcommands.hpp"

namespace structloc::cli {

int CalibrateCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"encoders", true, "encoders.csv (t,traction_ticks,steering_ticks)"},
      {"fixes", true, "fixes.csv (t,x,y,theta[,var_x,var_y,var_theta])"},
      {"robot", true, "nominal robot parameter file"},
      {"out", true, "calibrated robot parameter file to write"},
      {"estimate", true,
       "comma-separated parameters (default wheel_radius,axle_distance,steering_offset; also "
       "steering_rad_per_tick,sensor_x,sensor_y,sensor_theta)"},
      {"advice", false, "print which manoeuvres make which parameter observable, and exit"},
  };
  try {
    const config::CommandLine cli(inv.argc, inv.argv, 2, specs);
    if (cli.Has("advice")) {
      std::cout << calibration::TrajectoryAdvice();
      return 0;
    }
    calibration::CalibrationOptions options;
    if (auto list = cli.Get("estimate")) {
      options.estimate.fill(false);
      std::stringstream ss(*list);
      for (std::string name; std::getline(ss, name, ',');) {
        bool known = false;
        for (int k = 0; k < calibration::kParameterCount; ++k) {
          if (name == calibration::ParameterName(static_cast<calibration::Parameter>(k))) {
            options.estimate[static_cast<size_t>(k)] = known = true;
          }
        }
        if (!known) throw config::ConfigError("--estimate: unknown parameter '" + name + "'");
      }
    }
    const auto nominal = kinematics::LoadRobotParameters(cli.Required("robot"));
    const auto encoders = calibration::ReadEncodersCsv(cli.Required("encoders"));
    const auto fixes = calibration::ReadFixesCsv(cli.Required("fixes"));
    const std::string out = cli.Required("out");
    const auto report = calibration::Calibrate(encoders, fixes.fixes, nominal, options);
    std::printf(
        "%zu encoder samples, %zu fixes (%zu with NaN dropped), %zu fix intervals used, "
        "%zu skipped\n",
        encoders.size(), fixes.fixes.size(), fixes.dropped_non_finite, report.intervals_used,
        report.intervals_skipped);
    const auto nominal_values = std::array<double, calibration::kParameterCount>{
        nominal.wheel_radius,          nominal.axle_distance, nominal.steering_offset,
        nominal.steering_rad_per_tick, nominal.sensor.x,      nominal.sensor.y,
        nominal.sensor.theta};
    const auto& p = report.parameters;
    const auto values = std::array<double, calibration::kParameterCount>{
        p.wheel_radius, p.axle_distance, p.steering_offset, p.steering_rad_per_tick,
        p.sensor.x,     p.sensor.y,      p.sensor.theta};
    for (int k = 0; k < calibration::kParameterCount; ++k) {
      const auto param = static_cast<calibration::Parameter>(k);
      if (report.estimated[static_cast<size_t>(k)]) {
        std::printf("  %-22s %.8g +- %.2g %s   (nominal %.8g)\n", calibration::ParameterName(param),
                    values[static_cast<size_t>(k)],
                    report.standard_deviation[static_cast<size_t>(k)],
                    calibration::ParameterUnit(param), nominal_values[static_cast<size_t>(k)]);
      } else if (options.estimate[static_cast<size_t>(k)]) {
        std::printf("  %-22s NOT OBSERVABLE: kept nominal %.8g %s\n",
                    calibration::ParameterName(param), nominal_values[static_cast<size_t>(k)],
                    calibration::ParameterUnit(param));
      }
    }
    if (report.correlation.rows() > 1) {
      std::cout << "  correlations of the estimated parameters:\n" << report.correlation << "\n";
    }
    std::printf("  weighted residual RMS: %.3f before, %.3f after (%d iterations)\n",
                report.residual_rms_before, report.residual_rms_after, report.iterations);
    std::printf(
        "  dead reckoning over the whole recording, RMS against the fixes: %.3f m nominal, "
        "%.3f m calibrated\n",
        calibration::DeadReckoningRms(encoders, fixes.fixes, nominal),
        calibration::DeadReckoningRms(encoders, fixes.fixes, report.parameters));
    for (const auto& w : report.warnings) std::printf("  WARNING: %s\n", w.c_str());
    kinematics::SaveRobotParameters(report.parameters, out,
                                    "calibrated by structloc calibrate from " +
                                        cli.Required("encoders") + " and " + cli.Required("fixes"));
    std::cout << "wrote " << out << "\n";
    return report.success ? 0 : 1;
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc calibrate: " << e.what() << "\n" << config::CommandLine::Usage(specs);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "structloc calibrate: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::cli
