// The simulation (see header).
#include "structloc/simulation_core/simulation.hpp"

#include <cmath>
#include <limits>

namespace structloc::simulation_core {
namespace {

constexpr double kMaxSteering = 80.0 * geometry::kPi / 180.0;

// Position of a walker along a closed polyline after `distance` metres.
Eigen::Vector2d AlongLoop(const std::vector<Eigen::Vector2d>& points, double distance) {
  double total = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    total += (points[(i + 1) % points.size()] - points[i]).norm();
  }
  if (total <= 0.0) return points.front();
  double d = std::fmod(distance, total);
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d a = points[i], b = points[(i + 1) % points.size()];
    const double len = (b - a).norm();
    if (d <= len && len > 0.0) return a + (b - a) * (d / len);
    d -= len;
  }
  return points.front();
}

// Independent, reproducible random streams derived from the scenario seed.
std::mt19937 Engine(uint32_t seed, uint32_t stream) {
  std::seed_seq sequence{seed, stream};
  return std::mt19937(sequence);
}

}  // namespace

Simulation::Simulation(const Scenario& scenario)
    : scenario_(scenario),
      true_params_(scenario.TrueParameters()),
      dead_reckoning_(scenario.nominal),
      motion_rng_(Engine(scenario.seed, 1)),
      laser_rng_(Engine(scenario.seed, 2)) {
  state_.truth = scenario.initial_pose;
  segment_start_ = scenario.initial_pose.Translation();
  // What the laser sees: built once; only the people's circles move each step.
  scene_ = world_model::Scene::FromWorld(*scenario.world);
  scene_.Add(scenario.obstacles);
  static_circles_ = scene_.circles.size();
  MovePeople(0.0);
  wheel_ticks_ = static_cast<double>(scenario.errors.traction_start_tick);
  const uint64_t mask = (uint64_t{1} << scenario.nominal.traction_counter_bits) - 1;
  state_.traction_ticks =
      static_cast<uint64_t>(static_cast<int64_t>(std::floor(wheel_ticks_))) & mask;
  state_.steering_ticks = static_cast<int64_t>(std::llround(scenario.nominal.steering_zero_tick));
  left_wheel_ticks_ = right_wheel_ticks_ = wheel_ticks_;
  state_.left_ticks = state_.right_ticks = state_.traction_ticks;
  if (scenario.nominal.kind == kinematics::DriveKind::kDifferential) {
    dead_reckoning_.AddWheels(state_.left_ticks, state_.right_ticks);
  } else {
    dead_reckoning_.Add(state_.traction_ticks, static_cast<double>(state_.steering_ticks));
  }
  last_truth_ = state_.truth;
  const auto& l = scenario.laser;
  const bool full = l.field_of_view_rad >= 2 * geometry::kPi - 1e-9;
  scan_.angle_increment =
      full ? l.field_of_view_rad / l.beams : l.field_of_view_rad / (l.beams - 1);
  scan_.angle_min = full ? -geometry::kPi : -0.5 * l.field_of_view_rad;
  // A rotating scanner: one revolution per 1/rate, beams spread over its field of view.
  const double beams_per_rev = 2 * geometry::kPi / scan_.angle_increment;
  scan_.time_increment = 1.0 / (l.rate_hz * beams_per_rev);
  scan_.scan_time = 1.0 / l.rate_hz;
  scan_.range_min = l.min_range_m;
  scan_.range_max = l.max_range_m;
  scan_.ranges.reserve(static_cast<size_t>(l.beams));
}

bool Simulation::Finished() const {
  return state_.time >= scenario_.duration_s - 1e-9 || (path_done_ && state_.time >= dwell_until_);
}

void Simulation::CommandVelocity(double linear, double angular) {
  cmd_linear_ = linear;
  cmd_angular_ = angular;
}

std::vector<world_model::Circle> Simulation::People() const {
  return {scene_.circles.begin() + static_cast<std::ptrdiff_t>(static_circles_),
          scene_.circles.end()};
}

void Simulation::MovePeople(double t) {
  scene_.circles.resize(static_circles_);
  for (const auto& p : scenario_.people) {
    scene_.circles.push_back({AlongLoop(p.waypoints, p.speed_m_s * t), p.radius_m});
  }
}

// Path following with the true pose (an ideal guidance, so that the robot
// stays on its path whatever its odometry believes): pure pursuit of a
// look-ahead point on the current path segment (from the previous waypoint,
// or the start, to the next), steering = atan(curvature * axle distance). In
// stop-look-move mode every waypoint is a stop with a dwell. The wheel rate is
// what the robot commands with its nominal wheel radius.
void Simulation::Control(double* wheel_rate, double* steering) {
  const auto& path = scenario_.path;
  const auto& nominal = scenario_.nominal;
  *wheel_rate = 0.0;
  *steering = 0.0;
  if (path.mode == PathSpec::Mode::kCmdVel) {
    const double v = cmd_linear_, w = cmd_angular_;
    if (std::abs(v) < 1e-6 && std::abs(w) < 1e-6) return;
    *steering = std::abs(v) < 1e-6 ? std::copysign(geometry::kPi / 2, w)
                                   : std::atan(w * nominal.axle_distance / v);
    *steering = std::clamp(*steering, -geometry::kPi / 2, geometry::kPi / 2);
    const double c = std::cos(*steering);
    *wheel_rate = std::abs(c) > 1e-3 ? v / (nominal.wheel_radius * c)
                                     : w * nominal.axle_distance / nominal.wheel_radius;
    return;
  }
  if (path_done_ || state_.time < dwell_until_) return;
  const bool stops = path.mode == PathSpec::Mode::kStopLookMove;
  const Eigen::Vector2d here = state_.truth.Translation();
  const Eigen::Vector2d a = waypoint_ == 0 ? segment_start_ : path.waypoints[waypoint_ - 1];
  const Eigen::Vector2d b = path.waypoints[waypoint_];
  const bool last = waypoint_ + 1 == path.waypoints.size() && !path.loop;
  const bool stop_at_b = stops || last;
  const Eigen::Vector2d d = b - a;
  const double len = d.norm();
  const double t = len > 1e-9 ? std::clamp((here - a).dot(d) / (len * len), 0.0, 1.0) : 1.0;
  const double to_b = (b - here).norm();
  if (stop_at_b ? to_b < 0.05 : (t >= 1.0 || to_b < path.lookahead_m)) {
    if (stops) dwell_until_ = state_.time + path.dwell_s;
    if (last) {
      path_done_ = true;  // finished once the last dwell is over
    } else {
      segment_start_ = b;
      waypoint_ = (waypoint_ + 1) % path.waypoints.size();
    }
    return;
  }
  // The look-ahead point: along this segment, then onto the next one.
  Eigen::Vector2d target = b;
  const double ahead = t * len + path.lookahead_m;
  if (ahead < len) {
    target = a + d * (ahead / len);
  } else if (!stop_at_b) {
    const Eigen::Vector2d c = path.waypoints[(waypoint_ + 1) % path.waypoints.size()];
    target = b + (c - b).normalized() * std::min(ahead - len, (c - b).norm());
  }
  const Eigen::Vector2d local = state_.truth.ApplyInverse(target);
  const double ld2 = std::max(local.squaredNorm(), 1e-6);
  const double curvature = 2.0 * local.y() / ld2;
  *steering = std::clamp(std::atan(curvature * nominal.axle_distance), -kMaxSteering, kMaxSteering);
  // Slow down in sharp turns and before a stop.
  double speed = path.speed_m_s * std::max(0.2, std::cos(*steering));
  if (stop_at_b) speed = std::min(speed, std::max(0.05, 1.5 * to_b));
  *wheel_rate = speed / (nominal.wheel_radius * std::cos(*steering));
}

const SimState& Simulation::Step() {
  if (next_teleport_ < scenario_.teleports.size() &&
      state_.time >= scenario_.teleports[next_teleport_].at_s) {
    const auto& t = scenario_.teleports[next_teleport_++];
    state_.truth = t.pose;  // carried: the encoders see nothing
    waypoint_ = t.next_waypoint;
    segment_start_ = t.pose.Translation();
  }
  const double dt = scenario_.step_s;
  double wheel_rate = 0.0, steering_cmd = 0.0;
  Control(&wheel_rate, &steering_cmd);
  // The robot servoes its steering so that its *nominal* decoding reads the
  // command; physically the wheel then stands at command + offset error.
  const double steering_true =
      steering_cmd + (true_params_.steering_offset - scenario_.nominal.steering_offset);
  const double wheel_angle = wheel_rate * dt;
  std::normal_distribution<double> slip(0.0, scenario_.errors.wheel_slip_std);
  const double slip_factor = scenario_.errors.wheel_slip_std > 0 ? 1.0 + slip(motion_rng_) : 1.0;
  last_truth_ = state_.truth;
  last_odometry_ = state_.odometry;
  last_step_time_ = state_.time;
  if (scenario_.nominal.kind == kinematics::DriveKind::kDifferential) {
    StepDifferential(wheel_angle, steering_cmd, slip_factor);
    return state_;
  }
  state_.truth = kinematics::Advance(state_.truth, wheel_angle * slip_factor, steering_true,
                                     true_params_.wheel_radius, true_params_.axle_distance);
  state_.time += dt;
  state_.steering_true_rad = steering_true;
  // Encoders: the traction counter counts wheel rotation (slip included: the
  // wheel turns, the robot slides), quantised and wrapped; the absolute
  // steering encoder reads the physical angle with the true offset.
  wheel_ticks_ += wheel_angle * scenario_.nominal.traction_ticks_per_rev / (2 * geometry::kPi);
  const uint64_t mask = (uint64_t{1} << scenario_.nominal.traction_counter_bits) - 1;
  state_.traction_ticks =
      static_cast<uint64_t>(static_cast<int64_t>(std::floor(wheel_ticks_))) & mask;
  state_.steering_ticks = static_cast<int64_t>(std::llround(
      (steering_true - true_params_.steering_offset) / true_params_.steering_rad_per_tick +
      true_params_.steering_zero_tick));
  dead_reckoning_.Add(state_.traction_ticks, static_cast<double>(state_.steering_ticks));
  state_.odometry = dead_reckoning_.Pose();
  const geometry::Pose2D delta = geometry::Between(last_odometry_, state_.odometry);
  state_.odom_linear = delta.x / dt;
  state_.odom_angular = delta.theta / dt;
  CastBeams(last_truth_, state_.truth, last_step_time_, state_.time);
  return state_;
}

void Simulation::StepDifferential(double wheel_angle, double steering, double slip_factor) {
  const double dt = scenario_.step_s;
  // The control law's motion (its virtual tricycle has the default geometry).
  const kinematics::RobotParameters law;
  const double path = wheel_angle * law.wheel_radius;
  const double ds = path * std::cos(steering),
               dtheta = path * std::sin(steering) / law.axle_distance;
  // Wheel angles commanded with the nominal parameters; the true ones move the robot.
  const auto& nominal = scenario_.nominal;
  const double left_angle =
      (ds - 0.5 * dtheta * nominal.wheel_separation) / nominal.left_wheel_radius;
  const double right_angle =
      (ds + 0.5 * dtheta * nominal.wheel_separation) / nominal.right_wheel_radius;
  state_.truth = kinematics::AdvanceDifferential(
      state_.truth, left_angle * true_params_.left_wheel_radius * slip_factor,
      right_angle * true_params_.right_wheel_radius * slip_factor, true_params_.wheel_separation);
  state_.time += dt;
  const double ticks_per_rad = nominal.traction_ticks_per_rev / (2 * geometry::kPi);
  left_wheel_ticks_ += left_angle * ticks_per_rad;
  right_wheel_ticks_ += right_angle * ticks_per_rad;
  const uint64_t mask = (uint64_t{1} << nominal.traction_counter_bits) - 1;
  state_.left_ticks =
      static_cast<uint64_t>(static_cast<int64_t>(std::floor(left_wheel_ticks_))) & mask;
  state_.right_ticks =
      static_cast<uint64_t>(static_cast<int64_t>(std::floor(right_wheel_ticks_))) & mask;
  dead_reckoning_.AddWheels(state_.left_ticks, state_.right_ticks);
  state_.odometry = dead_reckoning_.Pose();
  const geometry::Pose2D delta = geometry::Between(last_odometry_, state_.odometry);
  state_.odom_linear = delta.x / dt;
  state_.odom_angular = delta.theta / dt;
  CastBeams(last_truth_, state_.truth, last_step_time_, state_.time);
}

void Simulation::CastBeams(const geometry::Pose2D& from, const geometry::Pose2D& to, double t0,
                           double t1) {
  const auto& l = scenario_.laser;
  MovePeople(t1);
  for (;;) {
    const double scan_start = scan_index_ * scan_.scan_time;
    const double t = scan_start + next_beam_ * scan_.time_increment;
    if (t > t1 + 1e-12) break;
    const double f = t1 > t0 ? std::clamp((t - t0) / (t1 - t0), 0.0, 1.0) : 1.0;
    const geometry::Pose2D base = geometry::Interpolate(from, to, f);
    if (next_beam_ == 0) {
      scan_.stamp = t;
      scan_.truth = base;
      scan_.odometry = geometry::Interpolate(last_odometry_, state_.odometry, f);
      scan_.ranges.clear();
    }
    scan_.ranges.push_back(Measure(scene_, geometry::Compose(base, l.mount), next_beam_));
    if (++next_beam_ == l.beams) {
      if (l.stamp_latency_s > 0) {
        stamped_late_.push_back(scan_);
        stamped_late_.back().stamp += l.stamp_latency_s;
      } else {
        completed_ = scan_;
      }
      next_beam_ = 0;
      ++scan_index_;
    }
  }
  ReleaseStampedLate(t0, t1);
}

void Simulation::ReleaseStampedLate(double t0, double t1) {
  if (scenario_.laser.stamp_latency_s <= 0) return;
  // Odometry as far back as a stamp can lie behind the scan's last beam.
  if (odometry_history_.empty()) odometry_history_.push_back({t0, last_odometry_});
  odometry_history_.push_back({t1, state_.odometry});
  while (odometry_history_.size() > 2 &&
         odometry_history_[1].first < t1 - scan_.scan_time - scenario_.step_s)
    odometry_history_.pop_front();
  while (!stamped_late_.empty() && stamped_late_.front().stamp <= t1 + 1e-12) {
    SimScan& scan = stamped_late_.front();
    size_t j = 0;
    while (j + 2 < odometry_history_.size() && odometry_history_[j + 1].first < scan.stamp) ++j;
    const auto& [ta, a] = odometry_history_[j];
    const auto& [tb, b] = odometry_history_[j + 1];
    scan.odometry =
        geometry::Interpolate(a, b, std::clamp((scan.stamp - ta) / (tb - ta), 0.0, 1.0));
    completed_ = std::move(scan);
    stamped_late_.pop_front();
  }
}

float Simulation::Measure(const world_model::Scene& scene, const geometry::Pose2D& laser_pose,
                          int beam) {
  const auto& l = scenario_.laser;
  const double bearing = scan_.angle_min + beam * scan_.angle_increment;
  for (const auto& [from, to] : l.blocked_sectors) {
    if (bearing >= from && bearing <= to) return static_cast<float>(0.5 * l.min_range_m);
  }
  const double a = laser_pose.theta + bearing;
  double range = scene.Cast(laser_pose.Translation(), {std::cos(a), std::sin(a)}, l.max_range_m);
  const double true_range = range;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  if (std::isfinite(range)) {
    // Mixed pixel: the spot straddles a depth jump and returns an average.
    if (beam > 0 && std::isfinite(previous_true_range_) &&
        std::abs(range - previous_true_range_) > 0.2 && u(laser_rng_) < l.mixed_pixel_probability) {
      const double mix = u(laser_rng_);
      range = mix * range + (1.0 - mix) * previous_true_range_;
    }
    if (u(laser_rng_) < l.spurious_probability) {
      range = l.min_range_m + u(laser_rng_) * (range - l.min_range_m);
    }
    if (l.noise_std_m > 0)
      range += std::normal_distribution<double>(0.0, l.noise_std_m)(laser_rng_);
    if (l.resolution_m > 0) range = l.resolution_m * std::round(range / l.resolution_m);
    range = std::max(range, 0.0);
  }
  previous_true_range_ = true_range;
  if (!std::isfinite(range) || range > l.max_range_m) {
    return l.no_return_is_max ? static_cast<float>(l.max_range_m + 1.0)
                              : std::numeric_limits<float>::infinity();
  }
  return static_cast<float>(range);
}

std::optional<SimScan> Simulation::TakeScan() {
  std::optional<SimScan> out;
  out.swap(completed_);
  return out;
}

}  // namespace structloc::simulation_core
