// structloc_localisation: entry point of the localisation component.
#include <chrono>
#include <cmath>
#include <iostream>
#include <optional>

#include "structloc/config/output_file.hpp"
#include "structloc/config/strict_number.hpp"
#include "structloc/dds_common/topics.hpp"
#include "structloc/localisation/localisation_component.hpp"
#include "structloc/localisation/parameters_from_first_scan.hpp"
#include "structloc/localisation_core/localiser/localiser_options.hpp"
#include "structloc/localisation_core/tracking/tracking_session_options.hpp"
#include "structloc/world_model/world_model_xml.hpp"

int main(int argc, char** argv) {
  using structloc::config::ConfigError;
  namespace loc = structloc::localisation;
  std::vector<structloc::config::OptionSpec> specs = {
      {"map", true, "world model XML (default: maps/office_floor.xml in structloc's data folder)"},
      {"params", true,
       "localisation parameters (default: the shipped laser preset the first scan's geometry "
       "names, with the laser's mounting from " +
           structloc::dds_common::topics::kTfStatic.name + " when it is published)"},
      {"initial-pose", true,
       "\"X Y THETA\": map pose of the robot when the first odometry arrives (start while "
       "it stands, or publish " +
           structloc::dds_common::topics::kInitialPose.name + " with a stamp)"},
      {"state-file", true, "where the pose is saved and resumed from (default: none)"},
      {"max-cpu-wake-latency-us", true,
       "while it runs, hold every CPU of the machine to wake within this many us, 0..1000000 "
       "(Linux PM QoS, /dev/cpu_dma_latency; needs write access to it; 0: idle CPUs poll): "
       "a scan's pose comes sooner, the CPUs never sleep deeply (default: not limited)"},
      {"max-walls", true,
       "refuse maps with more walls than this (default " +
           std::to_string(structloc::world_model::WorldLimits::kDefaultMaxWalls) + ")"}};
  // Its messages are in the map, odom and laser frames; the base frame is the
  // simulator's (or the robot's) to name.
  const auto frame_options =
      structloc::dds_common::FrameIdOptions(structloc::dds_common::BaseFrame::kNotUsed);
  specs.insert(specs.end(), frame_options.begin(), frame_options.end());
  return structloc::dds_common::RunComponent(
      argc, argv, "localisation", specs,
      [](structloc::dds_common::Node& node, const structloc::config::CommandLine& cli,
         const structloc::dds_common::StopWait& stop)
          -> std::unique_ptr<loc::LocalisationComponent> {
        structloc::world_model::WorldLimits limits;
        limits.max_walls = static_cast<size_t>(
            cli.IntegerIn("max-walls", static_cast<long long>(limits.max_walls), 1, 100000000));
        const std::string map = cli.PathOr("map", "maps/office_floor.xml");
        std::cout << "localisation: loading map " << map << std::endl;
        const auto started = std::chrono::steady_clock::now();
        auto world = std::make_unique<structloc::world_model::WorldModel>(
            structloc::world_model::LoadWorldModel(map, limits));
        std::cout
            << "localisation: map has " << world->Walls().size() << " walls, "
            << world->Corners().size() << " corners, " << world->Cylinders().size()
            << " cylinders (loaded in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count()
            << " s)" << std::endl;
        loc::LocalisationComponentOptions options;
        options.frames = structloc::dds_common::FrameIdsFrom(cli);
        options.state_file = cli.GetOr("state-file", "");
        if (cli.Has("max-cpu-wake-latency-us")) {
          options.max_cpu_wake_latency_us =
              static_cast<int>(cli.IntegerIn("max-cpu-wake-latency-us", 0, 0, 1000000));
        }
        const std::string given_params = cli.Has("params") ? cli.PathOr("params", "") : "";
        // The saved pose is written over and over: never over a file read.
        if (!options.state_file.empty()) {
          structloc::config::RefuseOverwritingInput(options.state_file,
                                                    {map, given_params, node.Options().qos_file});
        }
        if (auto text = cli.Get("initial-pose")) {
          const auto pose = structloc::config::ParseNumberList(*text, 3);
          if (!pose) {
            throw ConfigError("--initial-pose must be exactly three numbers \"X Y THETA\", got '" +
                              *text + "'");
          }
          const double bound = structloc::world_model::WorldLimits::kDefaultMaxAbsCoordinateM;
          if (std::abs((*pose)[0]) > bound || std::abs((*pose)[1]) > bound) {
            throw ConfigError("--initial-pose must lie within " +
                              std::to_string(static_cast<long long>(bound)) +
                              " m of the map origin, got '" + *text + "'");
          }
          options.initial_pose = structloc::geometry::Pose2D{(*pose)[0], (*pose)[1], (*pose)[2]};
        }
        // Without --params: the preset the first scan names (the options above are
        // checked before this wait, so a bad one fails at once).
        std::string params_path = given_params;
        std::optional<structloc::geometry::Pose2D> mount;
        std::optional<geometry_msgs::msg::PoseWithCovarianceStamped> pose_while_waiting;
        if (!cli.Has("params")) {
          const auto chosen = loc::WaitForFirstScan(node, stop, options.frames.base_link);
          if (!chosen) return nullptr;
          params_path = chosen->file;
          mount = chosen->mount;
          pose_while_waiting = chosen->initial_pose;
          std::cout << "localisation: parameters: " << chosen->choice
                    << "\nlocalisation: " << chosen->mount_source << std::endl;
          if (pose_while_waiting) {
            std::cout << "localisation: a pose came on "
                      << structloc::dds_common::topics::kInitialPose.name
                      << " while waiting for the first scan; it is kept" << std::endl;
          }
        }
        auto params = params_path.empty()
                          ? structloc::localisation_core::LocaliserOptions{}
                          : structloc::localisation_core::LoadLocaliserOptions(params_path);
        const auto session = params_path.empty()
                                 ? structloc::localisation_core::SessionOptions{}
                                 : structloc::localisation_core::LoadSessionOptions(params_path);
        if (mount) params.sensor_mount = *mount;
        auto component = std::make_unique<loc::LocalisationComponent>(node, std::move(world),
                                                                      params, session, options);
        if (pose_while_waiting) component->OfferInitialPose(*pose_while_waiting);
        return component;
      },
      [](std::ostream& out) {
        structloc::localisation_core::PrintLocaliserOptions(out);
        structloc::localisation_core::PrintSessionOptions(out);
      });
}
