// "structloc launch FILE.launch.xml [NAME:=VALUE ...] [--duration S]": starts
// the components a launch file names, as ros2 launch would.
#include <iostream>
#include <sstream>

#include "structloc/config/install_layout.hpp"
#include "structloc/config/strict_number.hpp"
#include "structloc/config/strict_xml.hpp"
#include "structloc/process/launch_runner.hpp"
#include "subcommands.hpp"

namespace structloc::cli {
namespace {

std::string Usage() {
  std::ostringstream out;
  out << "usage: structloc launch FILE.launch.xml [NAME:=VALUE ...] [options]\n"
      << "options:\n"
      << "  --duration S  stop every node after S seconds (default: run until SIGINT/SIGTERM)\n"
      << "  --max-value-bytes N  longest value one <arg> or <param> may substitute to (default "
      << process::LaunchContext::kDefaultMaxValueBytes << ")\n"
      << "  --max-total-bytes N  all substituted values of the file together (default "
      << process::LaunchContext::kDefaultMaxTotalBytes << ")\n"
      << "  --max-files N  launch and parameter files read in all, an include counted each "
         "time (default "
      << process::LaunchContext::kDefaultMaxFilesRead << ")\n"
      << "  --max-read-bytes N  their sizes together (default "
      << process::LaunchContext::kDefaultMaxReadBytes << ")\n"
      << "  --help  print this and exit\n";
  return out.str();
}

// The value of option argv[i], which must exist.
std::string OptionValue(const Invocation& inv, int* i) {
  if (*i + 1 >= inv.argc) {
    throw config::ConfigError(std::string("option '") + inv.argv[*i] + "' needs a value");
  }
  return inv.argv[++*i];
}

size_t PositiveLimit(const std::string& option, const std::string& text) {
  const auto value = config::ParseInteger(text);
  if (!value || *value < 1) {
    throw config::ConfigError("option " + option + " '" + text + "' must be a positive integer");
  }
  return static_cast<size_t>(*value);
}

}  // namespace

int LaunchCommand(const Invocation& inv) {
  for (int i = 2; i < inv.argc; ++i) {
    if (std::string(inv.argv[i]) == "--help") {
      std::cout << Usage();
      return 0;
    }
  }
  if (inv.argc < 3 || std::string(inv.argv[2]).rfind("--", 0) == 0) {
    std::cerr << "structloc launch: the first argument must be the launch file\n" << Usage();
    return 2;
  }
  process::LaunchContext context{config::ShareDirectory(), inv.bin_dir, {}};
  process::LaunchRunOptions options;
  try {
    for (int i = 3; i < inv.argc; ++i) {
      const std::string arg = inv.argv[i];
      const auto sep = arg.find(":=");
      if (arg == "--duration") {
        const std::string text = OptionValue(inv, &i);
        const auto seconds = config::ParseFiniteDouble(text);
        if (!seconds || *seconds <= 0.0) {
          throw config::ConfigError("option --duration '" + text +
                                    "' must be a finite number of seconds > 0");
        }
        options.duration_s = *seconds;
      } else if (arg == "--max-value-bytes") {
        context.max_value_bytes = PositiveLimit(arg, OptionValue(inv, &i));
      } else if (arg == "--max-total-bytes") {
        context.max_total_bytes = PositiveLimit(arg, OptionValue(inv, &i));
      } else if (arg == "--max-files") {
        context.max_files_read = PositiveLimit(arg, OptionValue(inv, &i));
      } else if (arg == "--max-read-bytes") {
        context.max_read_bytes = PositiveLimit(arg, OptionValue(inv, &i));
      } else if (sep != std::string::npos && sep > 0) {
        context.overrides[arg.substr(0, sep)] = arg.substr(sep + 2);
      } else {
        throw config::ConfigError("unexpected argument '" + arg +
                                  "' (structloc launch --help lists the options)");
      }
    }
    const auto description = process::ReadLaunchFile(inv.argv[2], context);
    // SIGINT and SIGTERM are collected from here on, once the file is read:
    // while it is read they stop the launcher at once, as they would any
    // program (nothing has been started yet).
    process::ShutdownSignal shutdown;
    return process::RunLaunch(description, options, shutdown);
  } catch (const config::ConfigError& e) {
    std::cerr << "structloc launch: " << e.what() << std::endl;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "structloc launch: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace structloc::cli
