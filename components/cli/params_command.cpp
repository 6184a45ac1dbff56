// "structloc params [--localiser] [--robot] [--scenario] [--map-build] [--slam]
// [--check FILE]": lists every option of the localiser parameter files, the
// robot files, the scenario files, the map builder's and SLAM's files (key,
// default, unit, valid values, meaning) from the one place each is declared
// (all when none is chosen), or checks that a file of any of these kinds, or
// a world map, loads (the kind from its root element), or prints a parameter
// file with every key it takes from its base (--expand).
#include <iostream>

#include "structloc/config/command_line.hpp"
#include "structloc/config/strict_xml.hpp"
#include "structloc/kinematics/robot_parameters.hpp"
#include "structloc/localisation_core/localiser/localiser_options.hpp"
#include "structloc/localisation_core/tracking/tracking_session_options.hpp"
#include "structloc/map_building/map_builder.hpp"
#include "structloc/simulation_core/scenario_options.hpp"
#include "structloc/slam_core/slam.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "subcommands.hpp"

namespace structloc::cli {
namespace {

// Loads `path` as what its root element says it is; throws ConfigError.
void Check(const std::string& path) {
  const std::string root = config::XmlFile::Load(path).Root().Name();
  if (root == "localisation_params") {
    localisation_core::LoadLocaliserOptions(path);
    localisation_core::LoadSessionOptions(path);
  } else if (root == "robot") {
    kinematics::LoadRobotParameters(path);
  } else if (root == "scenario") {
    simulation_core::LoadScenario(path);
  } else if (root == "map_build_params") {
    map_building::LoadMapBuildOptions(path);
  } else if (root == "slam_params") {
    slam_core::LoadSlamOptions(path);
  } else if (root == "world") {
    world_model::LoadWorldModel(path);
  } else {
    throw config::ConfigError(path + ": root element is <" + root +
                              ">, expected <localisation_params>, <robot>, <scenario>, "
                              "<map_build_params>, <slam_params> or <world>");
  }
}

}  // namespace

int ParamsCommand(const Invocation& inv) {
  const std::vector<config::OptionSpec> specs = {
      {"localiser", false, "list the <localisation_params> file's options"},
      {"robot", false, "list the <robot> file's options"},
      {"scenario", false, "list the <scenario> file's options"},
      {"map-build", false, "list the <map_build_params> file's options (structloc map build)"},
      {"slam", false, "list the <slam_params> file's options (structloc slam)"},
      {"check", true,
       "a <localisation_params>, <robot>, <scenario>, <map_build_params>, <slam_params> or "
       "<world> file to load and validate instead of listing"},
      {"expand", true,
       "a <localisation_params>, <map_build_params> or <slam_params> file to print whole: every "
       "key with the value it takes, its own or its base's"},
  };
  try {
    const config::CommandLine cli(inv.argc, inv.argv, 2, specs);
    if (const auto path = cli.Get("expand")) {
      const std::string root = config::XmlFile::Load(*path).Root().Name();
      if (root == "localisation_params") {
        localisation_core::WriteExpandedLocalisationParams(*path, std::cout);
      } else if (root == "map_build_params") {
        map_building::WriteExpandedMapBuildOptions(*path, std::cout);
      } else if (root == "slam_params") {
        slam_core::WriteExpandedSlamOptions(*path, std::cout);
      } else {
        throw config::ConfigError(*path + ": root element is <" + root +
                                  ">, expected <localisation_params>, <map_build_params> or "
                                  "<slam_params>");
      }
      return 0;
    }
    if (const auto path = cli.Get("check")) {
      Check(*path);
      std::cout << *path << ": valid\n";
      return 0;
    }
    const bool all = !cli.Has("localiser") && !cli.Has("robot") && !cli.Has("scenario") &&
                     !cli.Has("map-build") && !cli.Has("slam");
    if (all || cli.Has("localiser")) {
      localisation_core::PrintLocaliserOptions(std::cout);
      localisation_core::PrintSessionOptions(std::cout);
    }
    if (all || cli.Has("robot")) {
      std::cout << (all ? "\n" : "");
      kinematics::PrintRobotParameters(std::cout);
    }
    if (all || cli.Has("scenario")) {
      std::cout << (all ? "\n" : "");
      simulation_core::PrintScenarioOptions(std::cout);
    }
    if (all || cli.Has("map-build")) {
      std::cout << (all ? "\n" : "");
      map_building::PrintMapBuildOptions(std::cout);
    }
    if (all || cli.Has("slam")) {
      std::cout << (all ? "\n" : "");
      slam_core::PrintSlamOptions(std::cout);
    }
    return 0;
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc params: " << e.what() << "\n";
    return 2;
  }
}

}  // namespace structloc::cli
