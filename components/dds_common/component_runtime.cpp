// Shared component main loop (see header).
#include "structloc/dds_common/component_runtime.hpp"

#include <charconv>
#include <cstdlib>
#include <iostream>

#include "structloc/dds_common/topic_namespace.hpp"
#include "structloc/process/shutdown_signal.hpp"

namespace structloc::dds_common {
std::vector<config::OptionSpec> StandardOptions() {
  return {
      {"domain", true,
       "DDS domain id, 0..232; keep to 0..101 on Linux (ephemeral ports above; default "
       "$ROS_DOMAIN_ID, else 0)"},
      {"qos", true,
       "Fast DDS QoS profiles file (default: qos/structloc_qos.xml in structloc's data folder)"},
      {"participant-profile", true,
       "participant profile in the QoS file (default structloc_localhost)"},
      {"namespace", true,
       "ROS 2 namespace of every topic: rt/X becomes rt/NS/X (e.g. robot1, for several robots on "
       "one domain; default none)"},
      {"security-keystore", true,
       "DDS Security: a keystore made by structloc_keystore; authenticates, encrypts and "
       "access-controls every topic, and refuses to start when a file is missing or invalid "
       "(default none: security off)"},
      {"security-identity", true,
       "DDS Security: this participant's enclave in the keystore (default the component's "
       "kind, e.g. localisation)"},
      {"help", false, "print the options and exit"},
  };
}

std::vector<config::OptionSpec> FrameIdOptions(BaseFrame base_frame) {
  const FrameIds defaults;
  std::vector<config::OptionSpec> options = {
      {"map-frame", true, "frame id of the map (default " + defaults.map + ")"},
      {"odom-frame", true, "frame id of odometry (default " + defaults.odom + ")"},
      {"laser-frame", true, "frame id of the laser scanner (default " + defaults.laser + ")"}};
  if (base_frame == BaseFrame::kNamed) {
    options.push_back(
        {"base-frame", true, "frame id of the robot base (default " + defaults.base_link + ")"});
  }
  return options;
}

FrameIds FrameIdsFrom(const config::CommandLine& cli) {
  FrameIds frames;
  auto read = [&cli](const std::string& option, std::string& frame) {
    frame = cli.GetOr(option, frame);
    if (frame.empty() || frame.find_first_of(" \t\n\r") != std::string::npos) {
      throw config::ConfigError("--" + option + " '" + frame +
                                "' must be a non-empty frame id without spaces");
    }
  };
  read("map-frame", frames.map);
  read("odom-frame", frames.odom);
  read("base-frame", frames.base_link);
  read("laser-frame", frames.laser);
  return frames;
}

NodeOptions NodeOptionsFrom(const config::CommandLine& cli, const std::string& name,
                            const std::string& identity) {
  NodeOptions options;
  options.ros_namespace = NormaliseNamespace(cli.GetOr("namespace", ""));
  // Two robots' components differ by namespace, not by kind.
  options.name = options.ros_namespace.empty() ? name : options.ros_namespace + "/" + name;
  options.domain_id = static_cast<int>(cli.IntegerIn("domain", DefaultDomain(), 0, 232));
  options.qos_file = cli.PathOr("qos", "qos/structloc_qos.xml");
  options.participant_profile = cli.GetOr("participant-profile", "structloc_localhost");
  options.security.keystore = cli.GetOr("security-keystore", "");
  options.security.identity = cli.GetOr("security-identity", identity.empty() ? name : identity);
  return options;
}

int DefaultDomain() {
  const char* text = std::getenv("ROS_DOMAIN_ID");
  if (text == nullptr || *text == '\0') return 0;
  const std::string value = text;
  int domain = -1;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), domain);
  if (error != std::errc() || end != value.data() + value.size() || domain < 0 || domain > 232) {
    throw config::ConfigError("ROS_DOMAIN_ID '" + value +
                              "' is not a DDS domain id 0..232 (keep to 0..101 on Linux)");
  }
  return domain;
}

double WallClockSeconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

int RunComponent(int argc, char** argv, const std::string& name,
                 std::vector<config::OptionSpec> extra_options, const ComponentFactory& factory,
                 const ParameterListing& listing) {
  process::ShutdownSignal shutdown;  // before any DDS thread exists
  auto specs = StandardOptions();
  specs.insert(specs.end(), extra_options.begin(), extra_options.end());
  if (listing) {
    specs.push_back({"print-params", false,
                     "list every key of the parameter file(s) with default, unit, range and "
                     "meaning, and exit"});
  }
  try {
    const config::CommandLine cli(argc, argv, 1, specs);
    if (listing && cli.Has("print-params")) {
      listing(std::cout);
      return 0;
    }
    Node node(NodeOptionsFrom(cli, name));
    node.HoldCallbacks();  // none may reach a component still being built
    // The component owns its subscriptions: destroying it (before the node,
    // also when an exception leaves) ends every callback into it.
    auto component = factory(
        node, cli, [&](std::chrono::milliseconds timeout) { return shutdown.WaitFor(timeout); });
    if (!component) {
      std::cout << name << ": stopped cleanly before it started" << std::endl;
      return 0;
    }
    node.ReleaseCallbacks();
    std::cout << node.EndpointReport() << std::flush;
    std::cout << name << ": running (SIGINT or SIGTERM stops)" << std::endl;
    while (!component->Done() && !shutdown.WaitFor(component->Period())) component->Step();
    component->Stop();
    std::cout << name << ": stopped cleanly" << std::endl;
    return 0;
  } catch (const config::HelpRequested& help) {
    std::cout << help.usage;
    return 0;
  } catch (const config::ConfigError& e) {
    std::cerr << name << ": configuration error: " << e.what() << std::endl;
    return 2;
  } catch (const QosError& e) {
    std::cerr << name << ": configuration error: " << e.what() << std::endl;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << name << ": error: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::dds_common
