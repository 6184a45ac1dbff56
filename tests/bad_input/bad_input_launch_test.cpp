// Launch files written to hurt (issue 42; the findings' ids are those of the
// bad-input review of 36dc199): an over-long malformed
// substitution, parameter files whose aliases repeat an entry thousands of
// times, keys that are lists, and includes that fan out to millions of reads
// are refused quickly with the file, the line and the limit; and a launcher
// still reading a file stops on SIGINT or SIGTERM.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <thread>

#include "cli_runner.hpp"
#include "config_test_support.hpp"
#include "structloc/config/strict_xml.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc/process/launch_file.hpp"
#include "temp_dir.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;

process::LaunchContext Context() {
  return {STRUCTLOC_SOURCE_DIR, STRUCTLOC_BIN_DIR, {}};
}

void Read(const std::string& path) {
  process::ReadLaunchFile(path, Context());
}

// What reading `path` throws ("" when it reads).
std::string RefusalOf(const std::string& path, const process::LaunchContext& context) {
  try {
    process::ReadLaunchFile(path, context);
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(BadInputLaunch, H2_AnOverLongMalformedSubstitutionIsRefusedWithoutExhaustingTheStack) {
  // 60 000 characters is under the 64 KiB value limit; a recursive matcher
  // overflowed an 8 MB stack from about 30 000.
  for (const size_t letters : {30000u, 60000u}) {
    const std::string text = "<launch><let name='x' value='$(" + std::string(letters, 'a') +
                             "'/><executable cmd='true' name='t'/></launch>";
    testing::ExpectRejected(text, ":1: <let>: malformed substitution", Read);
    const testing::TempDir temp;
    const std::string why = RefusalOf(temp.Write("long.xml", text), Context());
    EXPECT_LT(why.size(), 400u) << "the message should quote a part of the text, not all of it";
    EXPECT_NE(why.find("(" + std::to_string(letters + 2) + " characters)"), std::string::npos)
        << why;
  }
  // The substitutions around a malformed one still read as before.
  testing::ExpectRejected(
      "<launch><let name='y' value='1'/><let name='x' value='$(var y)$(var'/></launch>",
      "malformed substitution", Read);
  testing::ExpectRejected("<launch><let name='x' value='$(Var y)'/></launch>",
                          "malformed substitution", Read);
}

// A node's entry repeated through an alias: N entries of M parameters made
// N x M x M steps (N = 2000: 23 s). YAML keys are unique; a second is refused.
TEST(BadInputLaunch, M5_ParameterFileEntriesAndNamesAreEachGivenOnce) {
  const testing::TempDir temp;
  std::string yaml = "base: &p {ros__parameters: {";
  for (int k = 0; k < 2000; ++k) yaml += (k ? ", k" : "k") + std::to_string(k) + ": 1";
  yaml += "}}\n";
  for (int n = 0; n < 2000; ++n) yaml += "loc: *p\n";
  const std::string aliases = temp.Write("aliases.yaml", yaml);
  const auto launch = [](const std::string& params) {
    return "<launch><node pkg='structloc' exec='structloc_localisation' name='loc'>"
           "<param from='" +
           params + "'/></node></launch>";
  };
  testing::ExpectRejected(
      launch(aliases), aliases + ":3: a node entry 'loc' appears a second time (first on line 2)",
      Read);
  const std::string twice =
      temp.Write("twice.yaml", "loc:\n  ros__parameters:\n    a: 1\n    b: 2\n    a: 3\n");
  testing::ExpectRejected(launch(twice), twice + ":5: a parameter name 'a' appears a second time",
                          Read);
  // One entry through an alias is fine: it is read once.
  const std::string once = temp.Write("once.yaml",
                                      "base: &p {ros__parameters: {domain: 7}}\n"
                                      "loc: *p\n");
  const auto d = process::ReadLaunchFile(temp.Write("once.launch.xml", launch(once)), Context());
  ASSERT_EQ(d.nodes.size(), 1u);
  EXPECT_EQ(d.nodes[0].arguments, (std::vector<std::string>{"--domain", "7"}));
}

// A list or map as a key was a yaml-cpp conversion error without the file,
// and exit 1; it is bad input like any other.
TEST(BadInputLaunch, L4_AKeyThatIsAListIsRefusedWithTheFileAndLine) {
  const testing::TempDir temp;
  const std::string entry = temp.Write("entry.yaml", "[a, b]:\n  ros__parameters:\n    x: 1\n");
  const std::string name = temp.Write("name.yaml", "loc:\n  ros__parameters:\n    [x]: 1\n");
  for (const auto& [params, problem] :
       {std::pair{entry, entry + ":1: a node entry must be a plain name, not a list or map"},
        std::pair{name, name + ":3: a parameter name must be a plain name, not a list or map"}}) {
    const std::string path =
        temp.Write("key.launch.xml",
                   "<launch><node pkg='structloc' exec='structloc_localisation' name='loc'>"
                   "<param from='" +
                       params + "'/></node></launch>");
    const auto run = testing::RunCli({"launch", path});
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_NE(run.output.find(problem), std::string::npos) << run.output;
  }
}

// Six files of forty includes each: 40^5 reads from 5 kB.
std::string WriteFanOut(const testing::TempDir& temp) {
  const std::string names = "bcdefg";
  for (size_t i = 0; i < names.size(); ++i) {
    std::string body = "<launch>";
    for (int k = 0; k < 40 && i + 1 < names.size(); ++k) {
      body += "<include file='" + temp / std::string(1, names[i + 1]) + "'/>";
    }
    temp.Write(std::string(1, names[i]), body + "</launch>");
  }
  std::string top = "<launch>";
  for (int k = 0; k < 40; ++k) top += "<include file='" + temp / "b" + "'/>";
  return temp.Write("fan.launch.xml", top + "<executable cmd='true' name='t'/></launch>");
}

TEST(BadInputLaunch, M5_IncludesThatFanOutAreRefusedAtTheReadingBounds) {
  const testing::TempDir temp;
  const std::string fan = WriteFanOut(temp);
  std::string why = RefusalOf(fan, Context());
  EXPECT_NE(why.find(fan + ":1: <include>"), std::string::npos) << why;
  EXPECT_NE(why.find("more than 1000 launch and parameter files read in all"), std::string::npos)
      << why;
  EXPECT_NE(why.find("--max-files"), std::string::npos) << why;

  auto context = Context();
  context.max_files_read = 1000000;
  context.max_read_bytes = 20000;
  why = RefusalOf(fan, context);
  EXPECT_NE(why.find("bytes of launch and parameter files read in all"), std::string::npos) << why;
  EXPECT_NE(why.find("--max-read-bytes"), std::string::npos) << why;

  // A file within the bounds reads (the bounds count what they should).
  const std::string small =
      temp.Write("small.launch.xml", "<launch><include file='" + temp / "f" +
                                         "'/><executable cmd='true' name='t'/></launch>");
  context = Context();
  context.max_files_read = 42;  // small, f, and f's forty includes of g
  EXPECT_EQ(RefusalOf(small, context), "");
  context.max_files_read = 41;
  EXPECT_NE(RefusalOf(small, context).find("more than 41"), std::string::npos);
}

TEST(BadInputLaunch, M5_ALauncherStillReadingItsFileStopsOnSigintAndSigterm) {
  const testing::TempDir temp;
  const std::string fan = WriteFanOut(temp);
  for (const int signal_number : {SIGINT, SIGTERM}) {
    // Bounds lifted so that reading goes on for minutes.
    process::ChildProcess launch(
        std::string(STRUCTLOC_BIN_DIR) + "/structloc",
        {"launch", fan, "--max-files", "1000000000", "--max-read-bytes", "1000000000000"});
    std::this_thread::sleep_for(500ms);
    ASSERT_FALSE(launch.Poll().has_value()) << launch.CapturedOutput();
    launch.Signal(signal_number);
    const auto code = launch.WaitExit(5s);
    ASSERT_TRUE(code.has_value()) << "signal " << signal_number << " was not answered";
    EXPECT_EQ(launch.EndingSignal(), signal_number);
  }
}

// A node writing without pause ("yes") kept the launcher reading until the
// pipe ran dry, which it never did: --duration 2 took 9 s and 243 MB.
TEST(BadInputLaunch, L5_AChattyNodeIsRelayedWithoutOverrunningTheDuration) {
  const testing::TempDir temp;
  const std::string path =
      temp.Write("yes.launch.xml", "<launch><executable cmd='yes' name='chatty'/></launch>");
  const auto started = std::chrono::steady_clock::now();
  const auto run = testing::RunCli({"launch", path, "--duration", "2"}, std::chrono::seconds(60));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  EXPECT_EQ(run.exit_code, 0) << run.output.substr(run.output.size() -
                                                   std::min<size_t>(2000, run.output.size()));
  EXPECT_NE(run.output.find("[chatty] y"), std::string::npos);
  // Two seconds, and the stop (SIGINT ends it at once) with room for a busy host.
  EXPECT_LT(seconds, 6.0);
}

}  // namespace
}  // namespace structloc
