// libFuzzer target: launch XML as `structloc launch` reads it (arguments,
// substitutions, groups, conditions; <include> and <param from> name files
// that do not exist here and are refused).
#include "fuzz_input.hpp"
#include "structloc/process/launch_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "fuzz.launch.xml");
  structloc::process::LaunchContext context;
  context.package_share_dir = "/nonexistent/share/structloc";
  context.executables_dir = "/nonexistent/bin";
  structloc::fuzz::Parse([&] { (void)structloc::process::ReadLaunchFile(path, context); });
  return 0;
}
