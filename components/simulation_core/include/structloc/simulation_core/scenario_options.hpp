// The numeric, flag and choice attributes of each scenario element declared
// once (key, range, unit, description; the struct members hold the defaults),
// so that the scenario reader and the `structloc params --scenario` listing
// cannot drift apart. Elements that are lists or files (<world>, <robot>,
// <waypoint>, <blocked>, <box>, <cylinder>) are read by hand in scenario_xml.cpp.
// Ranges that follow the run-time limits are built from them.
#pragma once

#include <ostream>

#include "structloc/config/option_table.hpp"
#include "structloc/simulation_core/scenario.hpp"

namespace structloc::simulation_core {

// <scenario name seed duration_s step_s odom_rate_hz>
config::OptionTable<Scenario> ScenarioAttributes(const ScenarioLimits& limits);
// <true_robot>: traction_start_tick must fit the nominal robot's counter,
// 2^min(traction_counter_bits, 52) - 1 at most (the simulated counter is a double).
config::OptionTable<TrueRobotErrors> TrueRobotAttributes(int traction_counter_bits);
// <initial_pose x y theta>, the robot base in the map frame.
config::OptionTable<geometry::Pose2D> InitialPoseAttributes(const world_model::WorldLimits& limits);
// <laser>; its <blocked> children are read by hand.
config::OptionTable<LaserSpec> LaserAttributes(const ScenarioLimits& limits);
// <path>; its <waypoint> children are read by hand.
config::OptionTable<PathSpec> PathAttributes();
// <obstacles><person>; its <waypoint> children are read by hand.
config::OptionTable<Person> PersonAttributes(const world_model::WorldLimits& limits);

// Lists every declared attribute with the defaults and the default limits.
void PrintScenarioOptions(std::ostream& out);

}  // namespace structloc::simulation_core
