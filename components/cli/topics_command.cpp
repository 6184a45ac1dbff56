// "structloc topics": the DDS topics the components publish and subscribe,
// as a Markdown table (name, ROS 2 name, type, QoS profile, publisher,
// subscriber) from the components' own table (dds_common/topic_table.hpp).
#include <iostream>

#include "structloc/config/command_line.hpp"
#include "structloc/dds_common/topic_table.hpp"
#include "subcommands.hpp"

namespace structloc::cli {

int TopicsCommand(const Invocation& inv) {
  try {
    const config::CommandLine cli(inv.argc, inv.argv, 2, {});
    std::cout << "| DDS topic (ROS 2 name) | type | QoS profile | published by | subscribed by |\n"
                 "|---|---|---|---|---|\n";
    for (const auto& row : dds_common::TopicTable()) {
      const std::string& name = row.topic->name;
      const std::string ros_name = name.rfind("rt/", 0) == 0 ? "/" + name.substr(3) : name;
      std::cout << "| `" << name << "` (`" << ros_name << "`) | " << row.type << " | "
                << row.topic->qos_profile << " | " << row.published_by << " | " << row.subscribed_by
                << " |\n";
    }
    return 0;
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc topics: " << e.what() << "\n";
    return 2;
  }
}

}  // namespace structloc::cli
