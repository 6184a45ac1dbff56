// Scenario attributes declared once (see scenario_options.hpp).
#include "structloc/simulation_core/scenario_options.hpp"

#include <algorithm>
#include <cstdint>

namespace structloc::simulation_core {

using config::OptionTable;
using config::Range;

namespace {

// A map-frame coordinate within the world limits.
Range Coordinate(const world_model::WorldLimits& limits) {
  return Range::Closed(-limits.max_abs_coordinate_m, limits.max_abs_coordinate_m);
}

}  // namespace

OptionTable<Scenario> ScenarioAttributes(const ScenarioLimits& limits) {
  using S = Scenario;
  OptionTable<S> t("scenario", "the run: name, random seed, length and rates");
  t.Text("name", &S::name, "names the run (recordings, plots)");
  t.Number("seed", &S::seed, Range::Closed(0, UINT32_MAX), "",
           "seeds every random draw: the same seed, the same run");
  t.Number("duration_s", &S::duration_s, Range::LeftOpen(0, limits.max_duration_s), "s",
           "simulated time");
  t.Number("step_s", &S::step_s, Range::Closed(limits.min_step_s, limits.max_step_s), "s",
           "integration step of the kinematics (EQ 48)");
  t.Number("odom_rate_hz", &S::odom_rate_hz,
           Range::Closed(limits.min_rate_hz, limits.max_odom_rate_hz), "Hz",
           "odometry and encoder publication rate");
  return t;
}

OptionTable<TrueRobotErrors> TrueRobotAttributes(int traction_counter_bits) {
  using T = TrueRobotErrors;
  // The simulated counter runs in double precision: exact up to 2^52 ticks.
  const int bits = std::min(traction_counter_bits, 52);
  OptionTable<T> t("true_robot", "how the real robot differs from the nominal robot file");
  t.Number("wheel_radius_scale", &T::wheel_radius_scale, Range::Positive(), "",
           "tricycle: true wheel radius = nominal * scale")
      .Optional();
  t.Number("axle_distance_scale", &T::axle_distance_scale, Range::Positive(), "",
           "tricycle: true axle distance = nominal * scale")
      .Optional();
  t.Number("steering_offset_rad", &T::steering_offset_rad, Range::Any(), "rad",
           "tricycle: added to the nominal steering offset")
      .Optional();
  t.Number("wheel_slip_std", &T::wheel_slip_std, Range::NonNegative(), "",
           "relative wheel slip per 10 ms step (standard deviation)");
  t.Number("traction_start_tick", &T::traction_start_tick,
           Range::Closed(0, static_cast<double>((int64_t{1} << bits) - 1)), "",
           "initial traction counter, or both wheel counters of a differential drive (tests "
           "the wrap); up to 2^min(counter bits, 52) - 1");
  t.Number("left_wheel_radius_scale", &T::left_wheel_radius_scale, Range::Positive(), "",
           "differential drive: true left wheel radius = nominal * scale")
      .Optional();
  t.Number("right_wheel_radius_scale", &T::right_wheel_radius_scale, Range::Positive(), "",
           "differential drive: true right wheel radius = nominal * scale")
      .Optional();
  t.Number("wheel_separation_scale", &T::wheel_separation_scale, Range::Positive(), "",
           "differential drive: true wheel separation = nominal * scale")
      .Optional();
  return t;
}

OptionTable<geometry::Pose2D> InitialPoseAttributes(const world_model::WorldLimits& limits) {
  using P = geometry::Pose2D;
  OptionTable<P> t("initial_pose", "the robot base (rear-axle middle) at the start, map frame");
  t.Number("x", &P::x, Coordinate(limits), "m", "map frame");
  t.Number("y", &P::y, Coordinate(limits), "m", "map frame");
  t.Number("theta", &P::theta, Range::Any(), "rad", "heading, counter-clockwise from x");
  return t;
}

OptionTable<LaserSpec> LaserAttributes(const ScenarioLimits& limits) {
  using L = LaserSpec;
  using P = geometry::Pose2D;
  OptionTable<L> t("laser", "the simulated scanner and its faults");
  t.Number("x", &L::mount, &P::x, Coordinate(limits.world), "m", "mount: ahead of the base");
  t.Number("y", &L::mount, &P::y, Coordinate(limits.world), "m", "mount: left of the base");
  t.Number("theta", &L::mount, &P::theta, Range::Any(), "rad", "mount: heading on the robot");
  t.Number("field_of_view_rad", &L::field_of_view_rad, Range::LeftOpen(0, 2 * geometry::kPi + 1e-9),
           "rad", "centred on the laser's heading");
  t.Number("beams", &L::beams, Range::Closed(limits.min_beams, limits.max_beams), "",
           "readings per revolution");
  t.Number("rate_hz", &L::rate_hz, Range::Closed(limits.min_rate_hz, limits.max_laser_rate_hz),
           "Hz", "revolutions per second");
  t.Number("min_range_m", &L::min_range_m, Range::NonNegative(), "m", "nearer: no return");
  t.Number("max_range_m", &L::max_range_m, Range::Positive(), "m",
           "farther: no return; must be > min_range_m");
  t.Number("noise_std_m", &L::noise_std_m, Range::NonNegative(), "m", "Gaussian range noise");
  t.Number("resolution_m", &L::resolution_m, Range::NonNegative(), "m",
           "range quantisation (SICK: 0.05), 0 = none");
  t.Choice("no_return", &L::no_return_is_max, {{"inf", false}, {"max", true}},
           "a missing return reads +inf, or max_range_m + 1");
  t.Number("spurious_probability", &L::spurious_probability, Range::Closed(0, 1), "",
           "per beam: a short random return");
  t.Number("mixed_pixel_probability", &L::mixed_pixel_probability, Range::Closed(0, 1), "",
           "per beam at a depth jump > 0.2 m: a range between the two");
  t.Number("stamp_latency_s", &L::stamp_latency_s, Range::Closed(0, 1), "s",
           "each scan stamped, and given out, this long after its first beam was taken (a "
           "laser stamped when its readings arrive)")
      .Optional();
  return t;
}

OptionTable<PathSpec> PathAttributes() {
  using P = PathSpec;
  OptionTable<P> t("path", "how the robot drives (pure pursuit on its true pose)");
  t.Choice("mode", &P::mode,
           {{"waypoints", P::Mode::kWaypoints},
            {"stop_look_move", P::Mode::kStopLookMove},
            {"cmd_vel", P::Mode::kCmdVel}},
           "through the waypoints, stopping at each, or by rt/cmd_vel commands");
  t.Number("speed_m_s", &P::speed_m_s, Range::Positive(), "m/s", "driving speed");
  t.Number("dwell_s", &P::dwell_s, Range::NonNegative(), "s",
           "stop_look_move: standing time at each waypoint");
  t.Number("lookahead_m", &P::lookahead_m, Range::Positive(), "m", "pure-pursuit look-ahead");
  t.Flag("loop", &P::loop, "start again after the last waypoint");
  return t;
}

OptionTable<Person> PersonAttributes(const world_model::WorldLimits& limits) {
  OptionTable<Person> t("person", "an unmodelled person walking its waypoints in a loop");
  t.Number("radius_m", &Person::radius_m, Range::LeftOpen(0, limits.max_radius_m), "m",
           "seen by the laser as a cylinder");
  t.Number("speed_m_s", &Person::speed_m_s, Range::Positive(), "m/s", "walking speed");
  return t;
}

void PrintScenarioOptions(std::ostream& out) {
  const ScenarioLimits limits;
  out << "<scenario>: every attribute below is required; columns: key, default, unit, valid "
         "values, meaning\n";
  ScenarioAttributes(limits).Print(out, Scenario{});
  out << "<world file=\"...\"/>  the world model file, relative to the scenario\n"
      << "<robot file=\"...\"/>  the nominal robot file (structloc params --robot)\n";
  TrueRobotAttributes(kinematics::RobotParameters{}.traction_counter_bits)
      .Print(out, TrueRobotErrors{});
  InitialPoseAttributes(limits.world).Print(out, geometry::Pose2D{});
  LaserAttributes(limits).Print(out, LaserSpec{});
  out << "  <blocked from_rad to_rad/>  children: sectors of the laser frame that return short\n";
  PathAttributes().Print(out, PathSpec{});
  out << "  <waypoint x y/>  children, map frame; none needed for cmd_vel\n"
      << "<obstacles>  optional, not in the world model: <box x y width_m depth_m theta/>, "
         "<cylinder x y radius_m/> and\n";
  PersonAttributes(limits.world).Print(out, Person{});
  out << "  <waypoint x y/>  children, at least two\n"
      << "See maps/scenarios/README.md.\n";
}

}  // namespace structloc::simulation_core
