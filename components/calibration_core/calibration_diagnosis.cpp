// Likely causes of a failed calibration (see header).
#include "structloc/calibration_core/calibration_diagnosis.hpp"

#include <cmath>
#include <cstdint>
#include <iomanip>
#include <sstream>

namespace structloc::calibration_core {
namespace {

std::string Text(double value, int digits = 4) {
  std::ostringstream out;
  out << std::setprecision(digits) << value;
  return out.str();
}

// Path length and total turn of the fixes inside [t0, t1], measured between
// anchor points at least `step` apart so that fix noise does not add up.
struct FixMotion {
  double distance_m = 0.0;
  double turn_rad = 0.0;
};

FixMotion MotionOfFixes(const std::vector<Fix>& fixes, double t0, double t1, double step) {
  FixMotion motion;
  const Fix* anchor = nullptr;
  const Fix* heading_anchor = nullptr;
  for (const auto& f : fixes) {
    if (f.t < t0 || f.t > t1) continue;
    if (anchor == nullptr) {
      anchor = heading_anchor = &f;
      continue;
    }
    const double d = (f.pose.Translation() - anchor->pose.Translation()).norm();
    if (d >= step) {
      motion.distance_m += d;
      anchor = &f;
    }
    const double turn = std::abs(geometry::WrapAngle(f.pose.theta - heading_anchor->pose.theta));
    if (turn >= 0.1) {
      motion.turn_rad += turn;
      heading_anchor = &f;
    }
  }
  return motion;
}

int BitWidth(uint64_t value) {
  int bits = 0;
  for (; value != 0; value >>= 1) ++bits;
  return bits;
}

}  // namespace

std::vector<std::string> LikelyCauses(const std::vector<EncoderSample>& encoders,
                                      const std::vector<Fix>& fixes,
                                      const kinematics::RobotParameters& nominal,
                                      const DiagnosisLimits& limits) {
  std::vector<std::string> causes;
  if (encoders.size() < 2 || fixes.empty()) return causes;
  const double t0 = encoders.front().t, t1 = encoders.back().t;
  const FixMotion fix_motion = MotionOfFixes(fixes, t0, t1, limits.anchor_step_m);

  bool traction_constant = true, steering_constant = true;
  uint64_t largest_tick = 0;
  double odometry_m = 0.0;
  for (size_t k = 0; k < encoders.size(); ++k) {
    largest_tick = std::max(largest_tick, encoders[k].traction_ticks);
    if (k == 0) continue;
    traction_constant &= encoders[k].traction_ticks == encoders[0].traction_ticks;
    steering_constant &= encoders[k].steering_ticks == encoders[0].steering_ticks;
    const int64_t delta =
        nominal.TickDelta(encoders[k - 1].traction_ticks, encoders[k].traction_ticks);
    odometry_m += std::abs(nominal.WheelAngle(delta) * nominal.wheel_radius);
  }
  if (traction_constant && fix_motion.distance_m >= limits.min_fix_travel_m) {
    causes.push_back("the traction encoder never changes (always " +
                     std::to_string(encoders[0].traction_ticks) + ") while the fixes travel " +
                     Text(fix_motion.distance_m) +
                     " m: check that traction_ticks holds the drive wheel's counter");
  }
  if (steering_constant && fix_motion.turn_rad >= limits.min_fix_turn_rad) {
    causes.push_back("the steering encoder never changes (always " +
                     Text(encoders[0].steering_ticks) + ") while the fixes turn " +
                     Text(fix_motion.turn_rad) +
                     " rad: check that steering_ticks holds the steering encoder");
  }
  // A counter that never exceeds 2^w - 1 but drops by more than half of 2^w
  // wraps at 2^w, whatever the robot file says.
  const int width = BitWidth(largest_tick);
  if (width >= 1 && width < nominal.traction_counter_bits) {
    const uint64_t half = uint64_t{1} << (width - 1);
    for (size_t k = 1; k < encoders.size(); ++k) {
      const uint64_t before = encoders[k - 1].traction_ticks, after = encoders[k].traction_ticks;
      if (before > after && before - after > half) {
        causes.push_back("the traction counter seems to wrap at 2^" + std::to_string(width) +
                         " (it drops from " + std::to_string(before) + " to " +
                         std::to_string(after) + " at t = " + Text(encoders[k].t, 12) +
                         " s), but the robot file says traction_counter_bits=\"" +
                         std::to_string(nominal.traction_counter_bits) + "\"");
        break;
      }
    }
  }
  if (!traction_constant && fix_motion.distance_m >= limits.min_fix_travel_m) {
    const double ratio = odometry_m / fix_motion.distance_m;
    if (ratio > limits.max_distance_ratio || ratio < 1.0 / limits.max_distance_ratio) {
      causes.push_back("with the nominal parameters the wheel travels " + Text(odometry_m) +
                       " m while the fixes travel " + Text(fix_motion.distance_m) +
                       " m: check traction_ticks_per_rev, traction_counter_bits and "
                       "wheel_radius");
    }
  }
  if (fix_motion.distance_m < limits.min_fix_travel_m) {
    causes.push_back("the fixes inside the encoder recording travel only " +
                     Text(fix_motion.distance_m) +
                     " m: record a longer drive (see structloc calibrate --advice)");
  }
  return causes;
}

}  // namespace structloc::calibration_core
