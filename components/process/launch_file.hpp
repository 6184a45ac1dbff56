// Reads launch files written in a subset of ROS 2's launch XML, so users
// deploy structloc the way they deploy ROS 2 nodes:
//   <launch>
//     <arg name="domain" default="0" description="..."/>
//     <node pkg="structloc" exec="structloc_simulator" name="simulator">
//       <param name="domain" value="$(var domain)"/>
//     </node>
//   </launch>
// Substitutions: $(var NAME), $(find-pkg-share structloc), $(env NAME).
// Each <param name="N" value="V"/> becomes the command-line option "--N V".
// Unknown elements and attributes are errors (file:line). DDS-free.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace structloc::process {

struct NodeLaunch {
  std::string name;        // unique within the file
  std::string executable;  // "exec", resolved against the executables folder
  std::vector<std::string> arguments;
};

struct LaunchDescription {
  std::vector<NodeLaunch> nodes;
  std::map<std::string, std::string> arguments;  // final values of <arg>s
};

struct LaunchContext {
  std::string package_share_dir;                 // what $(find-pkg-share structloc) gives
  std::string executables_dir;                   // where exec names are looked up
  std::map<std::string, std::string> overrides;  // NAME:=VALUE from the command line
};

// Throws config::ConfigError naming the file, line and problem.
LaunchDescription ReadLaunchFile(const std::string& path, const LaunchContext& context);

}  // namespace structloc::process
