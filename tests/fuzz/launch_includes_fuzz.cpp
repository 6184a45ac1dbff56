// libFuzzer target: a launch file with the files it reads, as `structloc
// launch` reads them: the input is up to three files separated by lines
// "----", written as top.launch.xml, inc.launch.xml (which the others may
// include, also through $(find-pkg-share structloc) or $(dirname)) and
// params.yaml (a <param from>), so that includes, their arguments and scopes,
// parameter files and the reading bounds are fuzzed together.
#include <string>

#include "fuzz_input.hpp"
#include "structloc/process/launch_file.hpp"

namespace {

// The input's parts, at most three.
std::vector<std::string> Parts(const std::string& text) {
  static const std::string kSeparator = "\n----\n";
  std::vector<std::string> parts;
  size_t from = 0;
  for (size_t at; parts.size() < 2 && (at = text.find(kSeparator, from)) != std::string::npos;
       from = at + kSeparator.size()) {
    parts.push_back(text.substr(from, at - from));
  }
  parts.push_back(text.substr(from));
  return parts;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using structloc::fuzz::WriteFile;
  const auto parts = Parts(std::string(reinterpret_cast<const char*>(data), size));
  const char* names[] = {"top.launch.xml", "inc.launch.xml", "params.yaml"};
  std::string top;
  for (size_t k = 0; k < 3; ++k) {
    const std::string text = k < parts.size() ? parts[k] : std::string();
    const std::string path = WriteFile(names[k], text.data(), text.size());
    if (k == 0) top = path;
  }
  structloc::process::LaunchContext context;
  context.package_share_dir = structloc::fuzz::InputFolder();
  context.executables_dir = "/nonexistent/bin";
  // Bounds lowered so that a fan-out is refused after a few hundred reads
  // under the sanitizers (the refusal is still reached).
  context.max_files_read = 200;
  context.max_read_bytes = 1 << 20;
  structloc::fuzz::Parse([&] { (void)structloc::process::ReadLaunchFile(top, context); });
  return 0;
}
