// The main loop every component executable shares: standard options (domain,
// QoS file, participant profile), node creation, endpoint report, a periodic
// Step(), clean stop on SIGINT/SIGTERM, and exit code 2 with a message on bad
// configuration.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "structloc/config/command_line.hpp"
#include "structloc/dds_common/node.hpp"

namespace structloc::dds_common {

class Component {
 public:
  virtual ~Component() = default;
  // Called every Period() on the main thread until a stop signal arrives.
  virtual void Step() = 0;
  virtual std::chrono::milliseconds Period() const { return std::chrono::milliseconds(100); }
  // Called once after the stop signal, before the node is destroyed.
  virtual void Stop() {}
  // True when the component has finished its work and the process should exit 0.
  virtual bool Done() const { return false; }
};

// Waits up to the time given; true once SIGINT or SIGTERM has arrived. For a
// factory that waits on the network before it can build its component.
using StopWait = std::function<bool(std::chrono::milliseconds)>;
// Builds the component; nullptr when `stop` said to stop before it could.
using ComponentFactory = std::function<std::unique_ptr<Component>(
    Node& node, const config::CommandLine& cli, const StopWait& stop)>;

// Options every component accepts, documented with their defaults.
std::vector<config::OptionSpec> StandardOptions();
// The node those options describe (`name`: the participant's, before any
// namespace; `identity`: its DDS Security enclave unless --security-identity
// names one, "" = `name`); throws config::ConfigError for a bad domain or namespace.
NodeOptions NodeOptionsFrom(const config::CommandLine& cli, const std::string& name,
                            const std::string& identity = "");

// The frame-id options of components that stamp frames (--map-frame,
// --odom-frame, --laser-frame and, for one that names the robot base,
// --base-frame), with the defaults of FrameIds.
enum class BaseFrame { kNamed, kNotUsed };
std::vector<config::OptionSpec> FrameIdOptions(BaseFrame base_frame);
// Reads them; throws config::ConfigError for an empty or blank frame id.
FrameIds FrameIdsFrom(const config::CommandLine& cli);

// Lists the keys of the component's parameter file(s) (declared once, see
// structloc/config/option_table.hpp).
using ParameterListing = std::function<void(std::ostream&)>;

// Parses the command line, builds the node and runs the component. With a
// `listing`, "--print-params" prints it and exits before any DDS entity exists.
// Returns the process exit code (0 clean stop, 2 configuration error, 1 other failure).
int RunComponent(int argc, char** argv, const std::string& name,
                 std::vector<config::OptionSpec> extra_options, const ComponentFactory& factory,
                 const ParameterListing& listing = nullptr);

// Wall-clock seconds since the epoch, for stamps of live data.
// The domain when --domain is not given: ROS_DOMAIN_ID as ROS 2 reads it, else 0;
// throws config::ConfigError for a value that is not 0..232.
int DefaultDomain();
double WallClockSeconds();

}  // namespace structloc::dds_common
