// Options declared once (config/option_table.hpp): loading, validation and the
// listing all follow the one declaration, and every error names the section,
// the key and, when read from a file, file:line.
#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>
#include <vector>

#include "structloc/config/option_table.hpp"
#include "temp_dir.hpp"

namespace structloc::config {
namespace {

enum class Colour { kRed, kBlue };

struct Inner {
  double gate_m = 0.2;
};

struct Example {
  int count = 3;
  bool enabled = true;
  Colour colour = Colour::kBlue;
  Inner inner;
};

OptionFile<Example> ExampleFile() {
  OptionTable<Example> t("things", "an example section");
  t.Number("count", &Example::count, Range::Closed(1, 10), "", "how many");
  t.Flag("enabled", &Example::enabled, "whether at all");
  t.Choice("colour", &Example::colour, {{"red", Colour::kRed}, {"blue", Colour::kBlue}},
           "which colour");
  t.Number("gate_m", &Example::inner, &Inner::gate_m, Range::Positive(), "m", "a nested gate");
  return OptionFile<Example>("example", {t});
}

std::string Problem(const std::string& text) {
  const testing::TempDir dir;
  const std::string path = dir.Write("example.xml", text);
  try {
    ExampleFile().Load(XmlFile::Load(path));
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path + ":", 0), 0u) << what;  // starts with file:line
    return what;
  }
  return "accepted";
}

const char* kGood =
    "<example>\n<things count=\"4\" enabled=\"false\" colour=\"red\" gate_m=\"0.5\"/>\n"
    "</example>\n";

TEST(OptionTable, LoadsEveryDeclaredKeyIntoItsMember) {
  const testing::TempDir dir;
  const auto o = ExampleFile().Load(XmlFile::Load(dir.Write("example.xml", kGood)));
  EXPECT_EQ(o.count, 4);
  EXPECT_FALSE(o.enabled);
  EXPECT_EQ(o.colour, Colour::kRed);
  EXPECT_DOUBLE_EQ(o.inner.gate_m, 0.5);
}

TEST(OptionTable, UnknownKeyIsAnErrorNamingIt) {
  const auto what = Problem(
      "<example>\n<things count=\"4\" enabled=\"false\" colour=\"red\" gate_m=\"0.5\" "
      "gate_x=\"1\"/>\n</example>\n");
  EXPECT_NE(what.find(":2: <things>: unknown attribute(s): gate_x"), std::string::npos) << what;
}

TEST(OptionTable, MissingKeyAndMissingSectionAreErrors) {
  auto what = Problem(
      "<example>\n<things count=\"4\" enabled=\"false\" colour=\"red\"/>\n"
      "</example>\n");
  EXPECT_NE(what.find("missing attribute gate_m"), std::string::npos) << what;
  what = Problem("<example>\n</example>\n");
  EXPECT_NE(what.find("missing section <things>"), std::string::npos) << what;
  what = Problem(std::string(kGood).insert(10, "<other/>\n"));
  EXPECT_NE(what.find("unknown element"), std::string::npos) << what;
}

TEST(OptionTable, OutOfRangeValuesNameSectionAndKey) {
  auto what = Problem(
      "<example>\n<things count=\"4\" enabled=\"false\" colour=\"red\" gate_m=\"-1\"/>\n"
      "</example>\n");
  EXPECT_NE(what.find(":2: <things>: things: gate_m must be > 0, not -1"), std::string::npos)
      << what;
  what = Problem(
      "<example>\n<things count=\"11\" enabled=\"false\" colour=\"red\" gate_m=\"1\"/>\n"
      "</example>\n");
  EXPECT_NE(what.find("count must be an integer from 1 to 10"), std::string::npos) << what;
  what = Problem(
      "<example>\n<things count=\"1\" enabled=\"false\" colour=\"green\" gate_m=\"1\"/>\n"
      "</example>\n");
  EXPECT_NE(what.find("colour must be red or blue, not 'green'"), std::string::npos) << what;
}

TEST(OptionTable, ValidateNamesTheBrokenOptionOfAStructBuiltInCode) {
  Example e;
  EXPECT_NO_THROW(ExampleFile().Validate(e));
  e.inner.gate_m = 0.0;
  try {
    ExampleFile().Validate(e);
    ADD_FAILURE() << "accepted gate_m = 0";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "things: gate_m must be > 0, not 0");
  }
  e.inner.gate_m = 1.0;
  e.count = 0;
  EXPECT_THROW(ExampleFile().Validate(e), std::invalid_argument);
}

TEST(OptionTable, ListingShowsKeyDefaultUnitRangeAndDescription) {
  std::ostringstream out;
  ExampleFile().Print(out, Example{});
  const std::string text = out.str();
  EXPECT_NE(text.find("<things>  an example section"), std::string::npos) << text;
  for (const char* line : {"count", "in [1, 10]", "how many", "blue", "red or blue", "gate_m",
                           "0.2", "> 0", "a nested gate", "true or false"}) {
    EXPECT_NE(text.find(line), std::string::npos) << line << "\n" << text;
  }
}

struct Tagged {
  std::string name = "none";
  double scale = 0.5;
  double offset_m = 0.0;
  int bits = 32;
};

OptionTable<Tagged> TaggedTable() {
  OptionTable<Tagged> t("tagged", "text, a magnitude range, an optional key, own wording");
  t.Wording([](const std::string& key, const std::string& value, const std::string& valid,
               const std::string& unit) {
    return key + " = " + value + " is implausible; it must be " + valid + " " + unit;
  });
  t.Text("name", &Tagged::name, "a name");
  t.Number("scale", &Tagged::scale, Range::Magnitude(0.1, 1), "m", "either sign");
  t.Number("offset_m", &Tagged::offset_m, Range::Closed(-1, 1), "m", "may be left out").Optional();
  t.Number("bits", &Tagged::bits, Range::Closed(8, 63), "bit", "checked before narrowing");
  return t;
}

std::string TaggedProblem(const std::string& attributes, Tagged* loaded = nullptr) {
  const testing::TempDir dir;
  const std::string path = dir.Write("tagged.xml", "<tagged " + attributes + "/>\n");
  try {
    const auto file = XmlFile::Load(path);
    Tagged t;
    TaggedTable().Load(file, file.Root(), t);
    if (loaded != nullptr) *loaded = t;
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(OptionTable, TextOptionalKeysMagnitudesAndOwnWording) {
  Tagged t;
  EXPECT_EQ(TaggedProblem("name=\"a b\" scale=\"-0.5\" bits=\"16\"", &t), "accepted");
  EXPECT_EQ(t.name, "a b");
  EXPECT_DOUBLE_EQ(t.scale, -0.5);
  EXPECT_DOUBLE_EQ(t.offset_m, 0.0);  // left out: the default
  EXPECT_EQ(t.bits, 16);
  EXPECT_EQ(TaggedProblem("name=\"a\" scale=\"1\" offset_m=\"-1\" bits=\"8\"", &t), "accepted");
  EXPECT_DOUBLE_EQ(t.offset_m, -1.0);
  auto what = TaggedProblem("name=\"a\" scale=\"0.01\" bits=\"16\"");
  EXPECT_NE(what.find("tagged: scale = 0.01 is implausible; it must be magnitude in [0.1, 1] m"),
            std::string::npos)
      << what;
  what = TaggedProblem("name=\"a\" scale=\"1\" offset_m=\"2\" bits=\"16\"");
  EXPECT_NE(what.find("tagged: offset_m = 2 is implausible"), std::string::npos) << what;
  what = TaggedProblem("name=\"a\" scale=\"1\" bits=\"4294967304\"");
  EXPECT_NE(what.find("tagged: bits = 4294967304 is implausible; it must be in [8, 63] bit"),
            std::string::npos)
      << what;
  what = TaggedProblem("scale=\"1\" bits=\"16\"");
  EXPECT_NE(what.find("missing attribute name"), std::string::npos) << what;
}

TEST(OptionTable, ValuesGiveEveryKeyAsWrittenAndTheListingMarksOptionalKeys) {
  Tagged t;
  t.scale = -0.123456789012;
  const auto values = TaggedTable().Values(t);
  ASSERT_EQ(values.size(), 4u);
  EXPECT_EQ(values[0], std::make_pair(std::string("name"), std::string("none")));
  EXPECT_EQ(values[1], std::make_pair(std::string("scale"), std::string("-0.123456789")));
  EXPECT_EQ(values[3], std::make_pair(std::string("bits"), std::string("32")));
  std::ostringstream out;
  TaggedTable().Print(out, Tagged{});
  EXPECT_NE(out.str().find("[optional] may be left out"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("magnitude in [0.1, 1]"), std::string::npos) << out.str();
}

// A file with a base states only what differs from it; strict all the same.
TEST(OptionTable, AFileWithBaseDefaultsStatesOnlyWhatDiffers) {
  const testing::TempDir dir;
  const auto o = ExampleFile().Load(XmlFile::Load(dir.Write(
      "example.xml", "<example base=\"defaults\">\n<things count=\"5\"/>\n</example>\n")));
  EXPECT_EQ(o.count, 5);
  const Example defaults;
  EXPECT_EQ(o.enabled, defaults.enabled);
  EXPECT_EQ(o.colour, defaults.colour);
  EXPECT_DOUBLE_EQ(o.inner.gate_m, defaults.inner.gate_m);
  // A section left out is all the base's.
  const auto empty =
      ExampleFile().Load(XmlFile::Load(dir.Write("empty.xml", "<example base=\"defaults\"/>\n")));
  EXPECT_EQ(empty.count, defaults.count);
}

TEST(OptionTable, ABaseFileBesideItGivesWhatTheFileLeavesOut) {
  const testing::TempDir dir;
  dir.Write("robot.xml", kGood);  // count 4, not enabled, red, gate 0.5
  const auto o = ExampleFile().Load(XmlFile::Load(dir.Write(
      "mine.xml", "<example base=\"robot.xml\">\n<things gate_m=\"0.25\"/>\n</example>\n")));
  EXPECT_EQ(o.count, 4);
  EXPECT_FALSE(o.enabled);
  EXPECT_EQ(o.colour, Colour::kRed);
  EXPECT_DOUBLE_EQ(o.inner.gate_m, 0.25);
}

TEST(OptionTable, AFileWithABaseIsStillStrict) {
  auto what = Problem("<example base=\"defaults\">\n<things gate_x=\"1\"/>\n</example>\n");
  EXPECT_NE(what.find("unknown attribute(s): gate_x"), std::string::npos) << what;
  what = Problem("<example base=\"defaults\">\n<things gate_m=\"-1\"/>\n</example>\n");
  EXPECT_NE(what.find("gate_m must be > 0, not -1"), std::string::npos) << what;
  what = Problem("<example basis=\"defaults\"/>\n");
  EXPECT_NE(what.find("unknown attribute(s): basis"), std::string::npos) << what;
  what = Problem("<example base=\"example.xml\"/>\n");  // itself
  EXPECT_NE(what.find("more than 8 files based on one another"), std::string::npos) << what;
  what = Problem("<example base=\"missing.xml\"/>\n");
  EXPECT_NE(what.find("missing.xml"), std::string::npos) << what;
}

TEST(Range, DescribesAndChecksItsEnds) {
  EXPECT_TRUE(Range::Positive().Contains(1e-9));
  EXPECT_FALSE(Range::Positive().Contains(0.0));
  EXPECT_FALSE(Range::Any().Contains(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_TRUE(Range::LeftOpen(0, 1).Contains(1.0));
  EXPECT_FALSE(Range::Open(0, 1).Contains(1.0));
  EXPECT_EQ(Range::Open(0, 1).Describe(), "in (0, 1)");
  EXPECT_EQ(Range::AtLeast(1).Describe(), ">= 1");
  EXPECT_EQ(Range::Any().Describe(), "finite");
  EXPECT_TRUE(Range::Magnitude(0.1, 1).Contains(-1.0));
  EXPECT_FALSE(Range::Magnitude(0.1, 1).Contains(0.0));
  EXPECT_FALSE(Range::Magnitude(0.1, 1).Contains(-1.5));
}

// A part declared on its own type (as a feature kind declares its options)
// and found inside the whole by a function: loads, checks and lists like a
// table of the whole, with the part's keys, ranges and defaults.
struct Whole {
  int count = 3;
  std::vector<Inner> parts{Inner{}};  // reached only through a function
};

TEST(OptionTable, APartDeclaredOnItsOwnTypeLoadsChecksAndListsInsideTheWhole) {
  OptionTable<Inner> part("gates", "a part's own section");
  part.Number("gate_m", &Inner::gate_m, Range::Positive(), "m", "a gate");
  const auto in_whole = [](auto& w) -> auto& {
    return w.parts.front();
  };
  OptionTable<Whole> counts("counts", "the whole's own section");
  counts.Number("count", &Whole::count, Range::Closed(1, 10), "", "how many");
  const OptionFile<Whole> file("whole", {counts, OptionTable<Whole>::Of(part, in_whole)});
  const testing::TempDir dir;
  const auto loaded = file.Load(XmlFile::Load(dir.Write(
      "whole.xml", "<whole>\n<counts count=\"4\"/>\n<gates gate_m=\"0.7\"/>\n</whole>\n")));
  EXPECT_EQ(loaded.count, 4);
  EXPECT_DOUBLE_EQ(loaded.parts.front().gate_m, 0.7);

  Whole broken;
  broken.parts.front().gate_m = -1.0;
  try {
    file.Validate(broken);
    ADD_FAILURE() << "a negative gate in the part was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "gates: gate_m must be > 0, not -1");
  }
  const std::string path =
      dir.Write("bad.xml", "<whole>\n<counts count=\"4\"/>\n<gates gate_m=\"-2\"/>\n</whole>\n");
  try {
    file.Load(XmlFile::Load(path));
    ADD_FAILURE() << "a negative gate in the part's section was loaded";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":3: <gates>: gates: gate_m must be > 0, not -2"),
              std::string::npos)
        << e.what();
  }
  std::ostringstream listing;
  file.Print(listing, Whole{});
  EXPECT_NE(listing.str().find("gate_m"), std::string::npos) << listing.str();
  EXPECT_NE(listing.str().find("0.2"), std::string::npos) << listing.str();
}

// A part's own wording and optional keys come along with it.
TEST(OptionTable, APartKeepsItsOwnWordingAndOptionalKeys) {
  struct Holder {
    Tagged tagged;
  };
  const auto in_holder = [](auto& h) -> auto& {
    return h.tagged;
  };
  const auto table = OptionTable<Holder>::Of(TaggedTable(), in_holder);
  Holder h;
  h.tagged.scale = 5.0;
  try {
    table.Validate(h);
    ADD_FAILURE() << "scale 5 was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "tagged: scale = 5 is implausible; it must be magnitude in [0.1, 1] m");
  }
  EXPECT_TRUE(table.HasOptionalKeys());
  const testing::TempDir dir;
  const std::string path =
      dir.Write("tagged.xml", "<tagged name=\"a\" scale=\"-0.5\" bits=\"9\"/>\n");
  const auto file = XmlFile::Load(path);
  Holder loaded;
  table.Load(file, file.Root(), loaded);
  EXPECT_EQ(loaded.tagged.name, "a");
  EXPECT_DOUBLE_EQ(loaded.tagged.scale, -0.5);
  EXPECT_DOUBLE_EQ(loaded.tagged.offset_m, 0.0) << "the optional key keeps its default";
  EXPECT_EQ(loaded.tagged.bits, 9);
}

}  // namespace
}  // namespace structloc::config
