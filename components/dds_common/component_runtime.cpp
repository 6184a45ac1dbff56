// Shared component main loop (see header).
#include "component_runtime.hpp"

#include <iostream>

#include "shutdown_signal.hpp"

namespace structloc::dds {
namespace {

struct CallbacksDetachedAtExit {
  explicit CallbacksDetachedAtExit(Node& node) : node(node) {}
  ~CallbacksDetachedAtExit() { node.DetachCallbacks(); }
  CallbacksDetachedAtExit(const CallbacksDetachedAtExit&) = delete;
  CallbacksDetachedAtExit& operator=(const CallbacksDetachedAtExit&) = delete;
  Node& node;
};

}  // namespace

std::vector<config::OptionSpec> StandardOptions() {
  return {
      {"domain", true,
       "DDS domain id, 0..232; keep to 0..101 on Linux (ephemeral ports above; default 0)"},
      {"qos", true,
       "Fast DDS QoS profiles file (default: qos/structloc_qos.xml in structloc's data folder)"},
      {"participant-profile", true,
       "participant profile in the QoS file (default structloc_localhost)"},
      {"help", false, "print the options and exit"},
  };
}

double WallClockSeconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

int RunComponent(int argc, char** argv, const std::string& name,
                 std::vector<config::OptionSpec> extra_options, const ComponentFactory& factory) {
  process::ShutdownSignal shutdown;  // before any DDS thread exists
  auto specs = StandardOptions();
  specs.insert(specs.end(), extra_options.begin(), extra_options.end());
  try {
    const config::CommandLine cli(argc, argv, 1, specs);
    if (cli.Has("help")) {
      std::cout << "usage: " << argv[0] << " [options]\n" << config::CommandLine::Usage(specs);
      return 0;
    }
    NodeOptions options;
    options.name = name;
    options.domain_id = static_cast<int>(cli.IntegerIn("domain", 0, 0, 232));
    options.qos_file = cli.PathOr("qos", "qos/structloc_qos.xml");
    options.participant_profile = cli.GetOr("participant-profile", "structloc_localhost");
    Node node(options);
    node.HoldCallbacks();  // none may reach a component still being built
    auto component = factory(node, cli);
    // Declared after the component, so destroyed before it, also when an
    // exception leaves: no DDS callback can reach a destroyed component.
    const CallbacksDetachedAtExit detach(node);
    node.ReleaseCallbacks();
    std::cout << node.EndpointReport() << std::flush;
    std::cout << name << ": running (SIGINT or SIGTERM stops)" << std::endl;
    while (!component->Done() && !shutdown.WaitFor(component->Period())) component->Step();
    component->Stop();
    std::cout << name << ": stopped cleanly" << std::endl;
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

}  // namespace structloc::dds
