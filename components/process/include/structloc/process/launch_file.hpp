// Reads launch files written in a subset of ROS 2's launch XML, so users
// deploy structloc the way they deploy ROS 2 nodes:
//   <launch>
//     <arg name="domain" default="0" description="..."/>
//     <let name="scale" value="2"/>
//     <group if="$(var two)">
//       <push-ros-namespace namespace="robot1"/>
//       <node pkg="structloc" exec="structloc_simulator" name="simulator" [namespace="..."]
//             [if="..."] [unless="..."] [respawn="true" respawn_delay="1.0"]>
//         <param name="domain" value="$(var domain)"/>
//       </node>
//     </group>
//     <executable cmd="fast-discovery-server -i 0 -p 11811" name="discovery_server" if="..."/>
//   </launch>
// Substitutions: $(var NAME) (an <arg> or <let> above), $(find-pkg-share
// structloc), $(env NAME), $(dirname) (the folder of the file being read).
// Each <param name="N" value="V"/> becomes the command-line option "--N V"; a
// pushed or node namespace becomes "--namespace NS" (nested as ROS 2 nests
// them) and prefixes the node's name.
// An <include file="F"> with <arg name value/>s reads F as if written in its
// place, as ROS 2 does: F sees the variables set so far (NAME:=VALUE from the
// command line among them), an <arg> keeps a value already set and takes its
// default otherwise, and what F sets stays set after it.
// A <group> scopes its <let>s, namespace and <set_env name="N" value="V"/>
// (an environment variable for the nodes after it; <env> inside a <node> is
// that node's own; ROS_DOMAIN_ID picks the components' default domain); if= /
// unless= (not both) take true, false, 1 or 0 and come first: a node left out
// is not substituted. A node's name may use substitutions. An <executable
// cmd="PROGRAM ARGS"> runs a program that is not a structloc node (PROGRAM an
// absolute path or on PATH), its words split as ROS 2 splits them, with the
// same output/respawn/if/unless attributes and <env> children. Unknown
// elements and attributes, duplicate <arg> names or node names, executables
// that do not exist, and substituted values above the size limits are errors
// (file:line). DDS-free.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace structloc::process {

struct NodeLaunch {
  std::string name;        // unique within the file
  std::string executable;  // "exec" in the executables folder, or <executable>'s program
  std::vector<std::string> arguments;
  // Variables laid over the launcher's environment (<set_env>, <env>).
  std::vector<std::pair<std::string, std::string>> environment;
  bool respawn = false;          // started again whenever it ends (respawn="true")
  double respawn_delay_s = 0.0;  // after this long (respawn_delay="S")
};

struct LaunchDescription {
  std::vector<NodeLaunch> nodes;
  std::map<std::string, std::string> arguments;  // final values of <arg>s
};

struct LaunchContext {
  static constexpr size_t kDefaultMaxValueBytes = 64 * 1024;
  static constexpr size_t kDefaultMaxTotalBytes = 4 * 1024 * 1024;
  static constexpr size_t kDefaultMaxFilesRead = 1000;
  static constexpr size_t kDefaultMaxReadBytes = 8 * 1024 * 1024;

  std::string package_share_dir;                 // what $(find-pkg-share structloc) gives
  std::string executables_dir;                   // where exec names are looked up
  std::map<std::string, std::string> overrides;  // NAME:=VALUE from the command line
  // Substitution bounds: $(var ...) can double a value per <arg>, so forty
  // lines would otherwise ask for terabytes.
  size_t max_value_bytes = kDefaultMaxValueBytes;  // one <arg> or <param> value
  size_t max_total_bytes = kDefaultMaxTotalBytes;  // all values of the file together
  // Reading bounds: forty <include>s in each of six nested files would read
  // 40^5 files from 5 kB. An included or parameter file counts each time it is
  // read, the file named on the command line too.
  size_t max_files_read = kDefaultMaxFilesRead;  // launch and parameter files read
  size_t max_read_bytes = kDefaultMaxReadBytes;  // their sizes together
};

// Throws config::ConfigError naming the file, line and problem.
LaunchDescription ReadLaunchFile(const std::string& path, const LaunchContext& context);

}  // namespace structloc::process
