// structloc: the command-line front end (launch, demo, record, slam and, as they land,
// simulate, replay, calibrate, render, params, topics, map, synthesise-odometry). Each
// subcommand calls the same core libraries as the components.
#include <cstring>
#include <iostream>
#include <string>

#include "structloc/config/command_line.hpp"
#include "structloc/config/install_layout.hpp"
#include "subcommands.hpp"

namespace {

struct Subcommand {
  const char* name;
  int (*run)(const structloc::cli::Invocation&);
  const char* help;
};

const Subcommand kSubcommands[] = {
    {"launch", structloc::cli::LaunchCommand,
     "FILE.launch.xml [NAME:=VALUE ...] [--duration S] [--max-value-bytes N] "
     "[--max-total-bytes N]  start components from a launch file"},
    {"demo", structloc::cli::DemoCommand,
     "[--domain N] [--time-scale X] [--out PICTURE.png]  run the main demo"},
    {"watch", structloc::cli::WatchCommand,
     "[--domain N] [--participant-profile P] [--timeout-s S] ...  judge a running simulated "
     "robot's localisation against ground truth (exit 0: the demo's bar met)"},
    {"record", structloc::cli::RecordCommand,
     "--out RUN.log [--domain N] [--sensor-mount \"X Y THETA\"] [--encoders-out E.csv] "
     "[--truth-out T.tum] [--duration-s S] [--quiet-s S]  record a robot's laser and odometry "
     "from DDS into a CARMEN log"},
    {"slam", structloc::cli::SlamCommand,
     "--log RAW.log --poses-out POSES.tum [--out WORLD.xml] [--plot P.png] [--relations R] "
     "[--truth T.tum] [--params P.xml] [--slam-params S.xml] [--scans F:L]  the robot's path "
     "(and its wall map, checked) from raw odometry and scans; Ctrl-C keeps what is done"},
    {"simulate", structloc::cli::SimulateCommand,
     "--scenario S.xml --out DIR [--seed N]  record a scenario without DDS"},
    {"replay", structloc::cli::ReplayCommand,
     "--map W.xml --log RUN.clf --initial-pose \"X Y THETA\" --out T.tum [--params P.xml] "
     "[--truth T.tum] [--plot P.png] [--no-map]  localise a recorded log offline"},
    {"calibrate", structloc::cli::CalibrateCommand,
     "--encoders E.csv --fixes F.csv --robot NOMINAL.xml --out CALIBRATED.xml [--estimate LIST] "
     "[--advice]  estimate wheel radius, axle distance, steering offset"},
    {"render", structloc::cli::RenderCommand,
     "--scenario S.xml --out PICTURE.png [--time T]  draw a scenario and one scan"},
    {"params", structloc::cli::ParamsCommand,
     "[--localiser] [--robot] [--scenario] [--map-build] [--check FILE.xml] [--expand FILE.xml]  "
     "list every option of the localiser, robot, scenario and map-build files, check such a file "
     "or a world map, or print a parameter file with what it takes from its base"},
    {"topics", structloc::cli::TopicsCommand,
     " list the DDS topics the components publish and subscribe (a Markdown table)"},
    {"map", structloc::cli::MapCommand,
     "build|grid|import|export|check ...  make world maps from recordings, occupancy grids "
     "and CAD drawings, export grids, check maps"},
    {"synthesise-odometry", structloc::cli::SynthesiseOdometryCommand,
     "--log CORRECTED.log --out EVAL.log --truth TRUTH.tum [--scale-error X] [--heading-drift "
     "DEG_PER_M] [--noise-xy M] [--noise-theta DEG] [--seed N] [--restamp SPEED] "
     "[--scan-latency S] ...  an evaluation log with re-synthesised odometry from a corrected "
     "recording"},
};

void Usage(std::ostream& out) {
  out << "usage: structloc SUBCOMMAND ...  (structloc SUBCOMMAND --help lists its options)\n";
  for (const auto& s : kSubcommands) out << "  " << s.name << " " << s.help << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::strcmp(argv[1], "--help") == 0) {
    Usage(std::cout);
    return 0;
  }
  if (argc < 2) {
    Usage(std::cerr);
    return 2;
  }
  for (const auto& s : kSubcommands) {
    if (std::strcmp(argv[1], s.name) != 0) continue;
    try {
      return s.run({argc, argv, structloc::config::ExecutableDirectory()});
    } catch (const structloc::config::HelpRequested& help) {
      std::cout << help.usage;
      return 0;
    }
  }
  std::cerr << "structloc: unknown subcommand '" << argv[1] << "'\n";
  Usage(std::cerr);
  return 2;
}
