// Run-time lookup of structloc's data folder: found beside the executable in
// the build tree (no source path compiled in), overridden by
// STRUCTLOC_SHARE_DIR, and a missing folder is an error that names it.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>

#include "structloc/config/install_layout.hpp"
#include "structloc/config/strict_xml.hpp"
#include "temp_dir.hpp"

namespace structloc {
namespace {

// Sets STRUCTLOC_SHARE_DIR for one test and restores the environment after it.
class ShareDirEnvironment {
 public:
  explicit ShareDirEnvironment(const std::string& value) {
    if (const char* old = std::getenv("STRUCTLOC_SHARE_DIR")) old_ = old;
    setenv("STRUCTLOC_SHARE_DIR", value.c_str(), 1);
  }
  ~ShareDirEnvironment() {
    if (old_.empty()) {
      unsetenv("STRUCTLOC_SHARE_DIR");
    } else {
      setenv("STRUCTLOC_SHARE_DIR", old_.c_str(), 1);
    }
  }

 private:
  std::string old_;
};

TEST(InstallLayout, FindsTheShippedFilesBesideTheBuildTreesExecutables) {
  unsetenv("STRUCTLOC_SHARE_DIR");
  EXPECT_TRUE(std::filesystem::is_regular_file(config::SharePath("maps/office_floor.xml")));
  EXPECT_TRUE(std::filesystem::is_regular_file(config::SharePath("qos/structloc_qos.xml")));
  EXPECT_TRUE(std::filesystem::is_regular_file(config::SharePath("launch_xml/demo.launch.xml")));
}

TEST(InstallLayout, TheEnvironmentOverridesTheLookup) {
  testing::TempDir dir;
  const ShareDirEnvironment env(dir.Path());
  EXPECT_EQ(std::filesystem::canonical(config::ShareDirectory()),
            std::filesystem::canonical(dir.Path()));
}

TEST(InstallLayout, AMissingDataFolderIsAnErrorNamingIt) {
  testing::TempDir dir;
  const ShareDirEnvironment env(dir / "nowhere");
  try {
    config::SharePath("maps/office_floor.xml");
    FAIL() << "no error for a missing data folder";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(dir / "nowhere"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("STRUCTLOC_SHARE_DIR"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace structloc
