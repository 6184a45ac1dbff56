// Hostile input (issue 16): XML that tries entity expansion ("billion
// laughs") or external entities is refused before anything is expanded or
// read, and an XML file over the size limit is refused naming the limit,
// through the same reader every structloc XML file goes through.
#include <gtest/gtest.h>

#include <string>

#include "structloc/config/strict_xml.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "temp_dir.hpp"

namespace structloc {
namespace {

std::string RefusalOf(const std::string& path, size_t max_bytes) {
  try {
    config::XmlFile::Load(path, max_bytes);
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(HostileXml, EntityExpansionIsRefusedBeforeAnyEntityIsExpanded) {
  testing::TempDir dir;
  std::string laughs = "<?xml version=\"1.0\"?>\n<!DOCTYPE world [\n  <!ENTITY lol \"lol\">\n";
  for (int i = 1; i <= 9; ++i) {
    laughs += "  <!ENTITY lol" + std::to_string(i) + " \"";
    for (int k = 0; k < 10; ++k) laughs += "&lol" + (i > 1 ? std::to_string(i - 1) : "") + ";";
    laughs += "\">\n";
  }
  laughs +=
      "]>\n<world name=\"&lol9;\">\n  <wall id=\"1\" x1=\"0\" y1=\"0\" x2=\"1\" "
      "y2=\"0\"/>\n</world>\n";
  const std::string path = dir.Write("laughs.xml", laughs);
  const std::string why = RefusalOf(path, config::XmlFile::kDefaultMaxBytes);
  EXPECT_EQ(why.rfind(path + ":2: a document type declaration", 0), 0u) << why;
  // And so through a loader a user runs.
  EXPECT_THROW(world_model::LoadWorldModel(path), config::ConfigError);
}

TEST(HostileXml, ExternalEntitiesAreRefusedAndNeverRead) {
  testing::TempDir dir;
  const std::string path =
      dir.Write("external.xml",
                "<?xml version=\"1.0\"?>\n<!DOCTYPE world [ <!ENTITY secret SYSTEM "
                "\"file:///etc/passwd\"> ]>\n<world name=\"&secret;\"/>\n");
  const std::string why = RefusalOf(path, config::XmlFile::kDefaultMaxBytes);
  EXPECT_NE(why.find("document type declaration"), std::string::npos) << why;
  EXPECT_EQ(why.find("root:"), std::string::npos) << why;  // nothing of the file was read
}

TEST(HostileXml, AFileOverTheSizeLimitIsRefusedNamingTheLimit) {
  testing::TempDir dir;
  const std::string path =
      dir.Write("big.xml", "<world name=\"w\">" + std::string(5000, ' ') + "</world>\n");
  const std::string why = RefusalOf(path, 4096);
  EXPECT_NE(why.find("over the limit of 4096 bytes for an XML file"), std::string::npos) << why;
  EXPECT_EQ(RefusalOf(path, 8192), "");
}

}  // namespace
}  // namespace structloc
