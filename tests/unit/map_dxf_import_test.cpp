// `structloc map import --dxf` (issue 11): small drawings written here for
// each unit, entity kind and bad input, and the office floor fixture
// (tests/data/maps/office_floor_mm.dxf) against maps/office_floor.xml.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "structloc/config/strict_xml.hpp"
#include "structloc/map_building/dxf_import.hpp"
#include "structloc/map_formats/dxf_drawing.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using map_building::DxfImportOptions;
using testing::ReadFile;
using testing::RunCli;
using testing::SourcePath;
using testing::TempDir;

// An ASCII DXF: an optional $INSUNITS and the given entity text.
std::string Dxf(const std::string& entities, int insunits = 4, const std::string& blocks = "") {
  std::ostringstream d;
  d << "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1015\n";
  if (insunits >= 0) d << "9\n$INSUNITS\n70\n" << insunits << "\n";
  d << "0\nENDSEC\n";
  if (!blocks.empty()) d << "0\nSECTION\n2\nBLOCKS\n" << blocks << "0\nENDSEC\n";
  d << "0\nSECTION\n2\nENTITIES\n" << entities << "0\nENDSEC\n0\nEOF\n";
  return d.str();
}

std::string Line(const std::string& layer, double x1, double y1, double x2, double y2) {
  std::ostringstream e;
  e << "0\nLINE\n8\n"
    << layer << "\n10\n"
    << x1 << "\n20\n"
    << y1 << "\n11\n"
    << x2 << "\n21\n"
    << y2 << "\n";
  return e.str();
}

std::string Circle(const std::string& layer, double x, double y, double r,
                   const std::string& extra = "") {
  std::ostringstream e;
  e << "0\nCIRCLE\n8\n"
    << layer << "\n"
    << extra << "10\n"
    << x << "\n20\n"
    << y << "\n40\n"
    << r << "\n";
  return e.str();
}

std::string Arc(const std::string& layer, double x, double y, double r, double a1, double a2) {
  std::ostringstream e;
  e << "0\nARC\n8\n"
    << layer << "\n10\n"
    << x << "\n20\n"
    << y << "\n40\n"
    << r << "\n50\n"
    << a1 << "\n51\n"
    << a2 << "\n";
  return e.str();
}

std::string Point(const std::string& layer, double x, double y) {
  std::ostringstream e;
  e << "0\nPOINT\n8\n" << layer << "\n10\n" << x << "\n20\n" << y << "\n";
  return e.str();
}

// Vertices (x, y, bulge).
std::string LwPolyline(const std::string& layer, const std::vector<std::array<double, 3>>& v,
                       bool closed) {
  std::ostringstream e;
  e << "0\nLWPOLYLINE\n8\n"
    << layer << "\n90\n"
    << v.size() << "\n70\n"
    << (closed ? 1 : 0) << "\n";
  for (const auto& p : v) {
    e << "10\n" << p[0] << "\n20\n" << p[1] << "\n";
    if (p[2] != 0.0) e << "42\n" << p[2] << "\n";
  }
  return e.str();
}

std::string Polyline(const std::string& layer, const std::vector<std::array<double, 2>>& v,
                     bool closed) {
  std::ostringstream e;
  e << "0\nPOLYLINE\n8\n" << layer << "\n66\n1\n70\n" << (closed ? 1 : 0) << "\n";
  for (const auto& p : v)
    e << "0\nVERTEX\n8\n" << layer << "\n10\n" << p[0] << "\n20\n" << p[1] << "\n";
  e << "0\nSEQEND\n8\n" << layer << "\n";
  return e.str();
}

std::string Text(const std::string& layer) {
  return "0\nTEXT\n8\n" + layer + "\n10\n0\n20\n0\n40\n100\n1\nlabel\n";
}

map_building::DxfImport Import(const TempDir& dir, const std::string& dxf_text,
                               const std::vector<std::string>& layers,
                               const std::optional<std::string>& units = std::nullopt) {
  const std::string path = dir.Write("drawing.dxf", dxf_text);
  DxfImportOptions options;
  options.layers = layers;
  if (units) options.units = map_building::ParseLengthUnit(*units);
  return map_building::ImportDrawing(map_formats::ReadDxfDrawing(path), options);
}

// The message of the ConfigError that importing `dxf_text` throws.
std::string ImportError(const TempDir& dir, const std::string& dxf_text,
                        const std::vector<std::string>& layers,
                        const std::optional<std::string>& units = std::nullopt) {
  try {
    Import(dir, dxf_text, layers, units);
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << dxf_text;
  return "";
}

TEST(DxfImport, TheDrawingsUnitScalesToMetres) {
  const TempDir dir;
  const struct {
    int insunits;
    double metres;
  } cases[] = {{4, 1.0}, {5, 10.0}, {6, 1000.0}, {1, 25.4}, {2, 304.8}};
  for (const auto& c : cases) {
    const auto imported = Import(dir, Dxf(Line("W", 0, 0, 1000, 0), c.insunits), {"W"});
    ASSERT_EQ(imported.world.Walls().size(), 1u);
    EXPECT_NEAR(imported.world.Walls()[0].Length(), c.metres, 1e-9) << c.insunits;
    EXPECT_FALSE(imported.report.unit_assumed);
  }
}

TEST(DxfImport, AMissingOrUnitlessUnitIsAssumedMillimetresAndSaid) {
  const TempDir dir;
  for (const int insunits : {-1, 0}) {
    const auto imported = Import(dir, Dxf(Line("W", 0, 0, 1000, 0), insunits), {"W"});
    EXPECT_TRUE(imported.report.unit_assumed);
    EXPECT_EQ(imported.report.unit.symbol, "mm");
    EXPECT_NE(imported.report.unit_source.find("ASSUMED"), std::string::npos);
    EXPECT_NEAR(imported.world.Walls()[0].Length(), 1.0, 1e-9);
  }
  // --units overrides both a missing unit and the drawing's own.
  auto imported = Import(dir, Dxf(Line("W", 0, 0, 10, 0), -1), {"W"}, "ft");
  EXPECT_FALSE(imported.report.unit_assumed);
  EXPECT_NEAR(imported.world.Walls()[0].Length(), 3.048, 1e-9);
  imported = Import(dir, Dxf(Line("W", 0, 0, 10, 0), 4), {"W"}, "in");
  EXPECT_NEAR(imported.world.Walls()[0].Length(), 0.254, 1e-9);
  EXPECT_NE(imported.report.unit_source.find("overriding $INSUNITS = 4"), std::string::npos);
}

TEST(DxfImport, AnUnsupportedUnitAsksForUnits) {
  const TempDir dir;
  const auto message = ImportError(dir, Dxf(Line("W", 0, 0, 1, 0), 7), {"W"});
  EXPECT_NE(message.find("$INSUNITS = 7"), std::string::npos) << message;
  EXPECT_NE(message.find("--units"), std::string::npos) << message;
  EXPECT_EQ(Import(dir, Dxf(Line("W", 0, 0, 1, 0), 7), {"W"}, "m").world.Walls().size(), 1u);
  EXPECT_THROW(map_building::ParseLengthUnit("yd"), config::ConfigError);
}

TEST(DxfImport, EveryEntityKindBecomesItsFeature) {
  const TempDir dir;
  const std::string entities =
      Line("W", 0, 0, 4000, 0) +
      LwPolyline("W", {{{0, 1000, 0}, {2000, 1000, 0}, {2000, 3000, 0}}}, false) +  // 2 walls
      Polyline("W", {{{5000, 0}, {6000, 0}, {6000, 1000}}}, true) +  // 3 walls, closing one too
      Circle("W", 3000, 5000, 250) +                                 // pillar
      Arc("W", 8000, 5000, 150, 0, 360) +                            // closed arc: pillar
      Arc("W", 9000, 5000, 150, 0, 90) +                             // open arc: skipped
      Point("W", 7000, 7000);                                        // given corner
  const auto imported = Import(dir, Dxf(entities), {"W"});
  const auto& world = imported.world;
  ASSERT_EQ(world.Walls().size(), 6u);
  EXPECT_EQ(world.Walls()[0].b, Eigen::Vector2d(4, 0));
  EXPECT_EQ(world.Walls()[2].b, Eigen::Vector2d(2, 3));
  EXPECT_EQ(world.Walls()[5].a, Eigen::Vector2d(6, 1));  // the closing segment
  EXPECT_EQ(world.Walls()[5].b, Eigen::Vector2d(5, 0));
  ASSERT_EQ(world.Cylinders().size(), 2u);
  EXPECT_EQ(world.Cylinders()[0].centre, Eigen::Vector2d(3, 5));
  EXPECT_DOUBLE_EQ(world.Cylinders()[0].radius, 0.25);
  EXPECT_EQ(world.Cylinders()[1].centre, Eigen::Vector2d(8, 5));
  size_t given = 0;
  for (const auto& c : world.Corners()) {
    if (c.derived) continue;
    ++given;
    EXPECT_EQ(c.position, Eigen::Vector2d(7, 7));
  }
  EXPECT_EQ(given, 1u);
  const auto& counts = imported.report.layers.at("W");
  EXPECT_EQ(counts.at("ARC").read, 2u);
  EXPECT_EQ(counts.at("ARC").used, 1u);
  EXPECT_EQ(counts.at("ARC").skipped.size(), 1u);
  EXPECT_EQ(counts.at("POLYLINE segments").used, 3u);
  EXPECT_EQ(counts.at("LWPOLYLINE segments").used, 2u);
  const auto summary = map_building::FormatImportReport(imported.report);
  EXPECT_NE(summary.find("not a full circle"), std::string::npos) << summary;
}

TEST(DxfImport, CurvedAndDegenerateSegmentsAreSkippedAndCounted) {
  const TempDir dir;
  const std::string entities =
      LwPolyline("W", {{{0, 0, 0}, {1000, 0, 0.5}, {2000, 0, 0}, {2000.5, 0, 0}}}, false) +
      Line("W", 0, 5000, 0.2, 5000) + Line("W", 0, 6000, 3000, 6000);
  const auto imported = Import(dir, Dxf(entities), {"W"});
  EXPECT_EQ(imported.world.Walls().size(), 2u);  // 0-1000 and the long line
  const auto& counts = imported.report.layers.at("W");
  const auto& segments = counts.at("LWPOLYLINE segments");
  EXPECT_EQ(segments.read, 3u);
  EXPECT_EQ(segments.used, 1u);
  size_t curved = 0, short_ones = 0;
  for (const auto& [reason, n] : segments.skipped) {
    if (reason.find("curved") != std::string::npos) curved += n;
    if (reason.find("shorter than 1 mm") != std::string::npos) short_ones += n;
  }
  EXPECT_EQ(curved, 1u);
  EXPECT_EQ(short_ones, 1u);
  EXPECT_EQ(counts.at("LINE").skipped.begin()->second, 1u);

  // A closed polyline that repeats its first vertex has no zero-length closing segment.
  const auto square = Import(
      dir, Dxf(LwPolyline("W", {{{0, 0, 0}, {1000, 0, 0}, {1000, 1000, 0}, {0, 0, 0}}}, true)),
      {"W"});
  EXPECT_EQ(square.world.Walls().size(), 3u);
  EXPECT_TRUE(square.report.layers.at("W").at("LWPOLYLINE segments").skipped.empty());
}

TEST(DxfImport, PiecesOfOneWallAreMergedAsAHandWrittenMapHasThem) {
  const TempDir dir;
  const std::string entities = Line("W", 0, 0, 1000, 0) + Line("W", 1000, 0, 2500, 0) +  // touching
                               Line("W", 2400, 0, 4000, 0) +     // overlapping
                               Line("W", 5000, 0.5, 4000, 0) +   // reversed, 0.5 mm off
                               Line("W", 0, 0, 1000, 0) +        // drawn twice
                               Line("W", 5010, 0, 6000, 0) +     // beyond a 10 mm gap
                               Line("W", 0, 50, 3000, 50) +      // parallel, 50 mm away
                               Line("W", 2500, 0, 2500, -2000);  // T junction at a joint
  const auto imported = Import(dir, Dxf(entities), {"W"});
  const auto& walls = imported.world.Walls();
  ASSERT_EQ(walls.size(), 4u);
  EXPECT_EQ(imported.report.merged_pieces, 4u);
  EXPECT_LE((walls[0].a - Eigen::Vector2d(0, 0)).norm(), 1e-3);
  EXPECT_LE((walls[0].b - Eigen::Vector2d(5, 0)).norm(), 1e-3);
  EXPECT_EQ(walls[1].a, Eigen::Vector2d(5.01, 0));
  EXPECT_EQ(walls[2].a, Eigen::Vector2d(0, 0.05));
  // The T junction meets the merged wall in its middle: no corner there.
  for (const auto& c : imported.world.Corners())
    EXPECT_GT((c.position - Eigen::Vector2d(2.5, 0)).norm(), 0.1);
  EXPECT_NE(map_building::FormatImportReport(imported.report).find("merged 4 wall pieces"),
            std::string::npos);

  DxfImportOptions keep;
  keep.layers = {"W"};
  keep.merge_tolerance_m = 0.0;
  const auto pieces = map_building::ImportDrawing(
      map_formats::ReadDxfDrawing(dir.Write("pieces.dxf", Dxf(entities))), keep);
  EXPECT_EQ(pieces.world.Walls().size(), 8u);
}

TEST(DxfImport, OnlyTheChosenLayersMatchedIgnoringCase) {
  const TempDir dir;
  const std::string entities = Line("Walls", 0, 0, 1000, 0) + Line("FURNITURE", 0, 500, 800, 500) +
                               Circle("furniture", 300, 300, 100) + Circle("Pillars", 0, 0, 100);
  const auto imported = Import(dir, Dxf(entities), {"WALLS", "pillars"});
  EXPECT_EQ(imported.world.Walls().size(), 1u);
  EXPECT_EQ(imported.world.Cylinders().size(), 1u);
  EXPECT_EQ(imported.report.layers.count("Walls"), 1u);  // spelt as drawn
  EXPECT_EQ(imported.report.left_out_layers, std::vector<std::string>{"FURNITURE"});
  EXPECT_EQ(imported.left_out.segments.size(), 1u);
  EXPECT_EQ(imported.left_out.circles.size(), 1u);
}

TEST(DxfImport, BlockDefinitionsPaperSpaceAndOtherKindsAreNotImported) {
  const TempDir dir;
  const std::string block = "0\nBLOCK\n8\n0\n2\nDOOR\n70\n0\n10\n0\n20\n0\n" +
                            Line("W", 0, 0, 900, 0) + "0\nENDBLK\n8\n0\n";
  const std::string entities = Line("W", 0, 0, 5000, 0) +
                               "0\nLINE\n67\n1\n8\nW\n10\n0\n20\n0\n11\n0\n21\n10\n" +  // paper
                               "0\nINSERT\n8\nW\n2\nDOOR\n10\n100\n20\n0\n" + Text("W");
  const auto imported = Import(dir, Dxf(entities, 4, block), {"W"});
  ASSERT_EQ(imported.world.Walls().size(), 1u);
  EXPECT_DOUBLE_EQ(imported.world.Walls()[0].Length(), 5.0);
  const auto& counts = imported.report.layers.at("W");
  EXPECT_EQ(counts.at("INSERT").read, 1u);
  EXPECT_NE(counts.at("INSERT").skipped.begin()->first.find("explode"), std::string::npos);
  EXPECT_EQ(counts.at("TEXT").skipped.begin()->second, 1u);
  EXPECT_EQ(counts.at("LINE").read, 1u);
}

// dxflib keeps the group code it read last for a line that starts with NUL,
// so a count after one is still the LWPOLYLINE's (a fuzzer's 1 kB file made
// dxflib ask for 12.8 GB); the guard must read the file as dxflib does.
TEST(DxfImport, ACountAfterALineStartingWithNulIsStillCheckedAsTheEntitys) {
  const TempDir dir;
  const std::string entities = std::string("0\nLWPOLYLINE\n8\nW\n90\n2\n10\n0.0\n20\n0.0\n") +
                               std::string(1, '\0') + "\nW\n90\n4000001010\n";
  const std::string path = dir.Write("nul_code.dxf", Dxf(entities));
  try {
    map_formats::ReadDxfDrawing(path);
    ADD_FAILURE() << "accepted";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("announces 4000001010 items"), std::string::npos)
        << e.what();
  }
}

TEST(DxfImport, ACircleSeenFromBelowIsMirrored) {
  const TempDir dir;
  const auto imported =
      Import(dir, Dxf(Circle("P", 2000, 3000, 100, "210\n0\n220\n0\n230\n-1\n")), {"P"});
  ASSERT_EQ(imported.world.Cylinders().size(), 1u);
  EXPECT_EQ(imported.world.Cylinders()[0].centre, Eigen::Vector2d(-2, 3));
  const auto tilted =
      ImportError(dir, Dxf(Circle("P", 2000, 3000, 100, "210\n1\n220\n0\n230\n0\n")), {"P"});
  EXPECT_NE(tilted.find("not in the floor plane"), std::string::npos) << tilted;
}

TEST(DxfImport, BadDrawingsAreErrorsThatSayWhatIsWrong) {
  const TempDir dir;
  const auto read_error = [&dir](const std::string& name, const std::string& text) {
    const std::string path = dir.Write(name, text);
    try {
      map_formats::ReadDxfDrawing(path);
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      return std::string(e.what());
    }
    ADD_FAILURE() << name << " was accepted";
    return std::string();
  };
  EXPECT_NE(read_error("garbage.dxf", "hello\nthis is no drawing\n").find("not a DXF"),
            std::string::npos);
  EXPECT_NE(read_error("empty.dxf", "").find("not a DXF"), std::string::npos);
  EXPECT_NE(
      read_error("binary.dxf", std::string("AutoCAD Binary DXF\r\n\x1a\0", 22)).find("binary DXF"),
      std::string::npos);
  EXPECT_NE(read_error("no_entities.dxf", Dxf("")).find("no DXF entities"), std::string::npos);
  const auto nan = read_error("nan.dxf", Dxf("0\nLINE\n8\nW\n10\nnan\n20\n0\n11\n1\n21\n0\n"));
  EXPECT_NE(nan.find("'nan' for group code 10"), std::string::npos) << nan;
  EXPECT_THROW(map_formats::ReadDxfDrawing(dir / "missing.dxf"), config::ConfigError);
  EXPECT_THROW(map_formats::ReadDxfDrawing(dir.Path()), config::ConfigError);

  const auto no_layer =
      ImportError(dir, Dxf(Line("WALLS", 0, 0, 1, 0) + Text("NOTES")), {"WALLS", "PILLARS"});
  EXPECT_NE(no_layer.find("no layer PILLARS"), std::string::npos) << no_layer;
  EXPECT_NE(no_layer.find("WALLS, NOTES"), std::string::npos) << no_layer;
  const auto unusable =
      ImportError(dir, Dxf(Line("WALLS", 0, 0, 1000, 0) + Text("NOTES")), {"WALLS", "notes"});
  EXPECT_NE(unusable.find("layer NOTES has no usable entity"), std::string::npos) << unusable;
  EXPECT_NE(unusable.find("TEXT"), std::string::npos) << unusable;
  const auto only_short = ImportError(dir, Dxf(Line("W", 0, 0, 0.5, 0)), {"W"});
  EXPECT_NE(only_short.find("shorter than 1 mm"), std::string::npos) << only_short;
  // A millimetre drawing read as metres lands beyond the 100 km world limit.
  const auto far = ImportError(dir, Dxf(Line("W", 0, 0, 2e8, 0), 6), {"W"});
  EXPECT_NE(far.find("beyond the world limit"), std::string::npos) << far;
  EXPECT_NE(far.find("--units"), std::string::npos) << far;
  const auto huge_pillar = ImportError(dir, Dxf(Circle("P", 0, 0, 5e6), 4), {"P"});
  EXPECT_NE(huge_pillar.find("radius"), std::string::npos) << huge_pillar;
}

TEST(DxfImportCli, WritesALoadableMapAndSaysWhatItDid) {
  const TempDir dir;
  const std::string dxf = dir.Write(
      "plan.dxf",
      Dxf(Line("W", 0, 0, 4000, 0) + Line("W", 4000, 0, 4000, 3000) + Circle("P", 2000, 1500, 200),
          -1));
  const auto r = RunCli({"map", "import", "--dxf", dxf, "--layers", "w,p", "--out", dir / "w.xml",
                         "--plot", dir / "w.png"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("assumed millimetres"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("2 walls"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 pillar"), std::string::npos) << r.output;
  const auto xml = ReadFile(dir / "w.xml");
  EXPECT_NE(xml.find("ASSUMED"), std::string::npos) << xml;
  const auto world = world_model::LoadWorldModel(dir / "w.xml");
  EXPECT_EQ(world.Walls().size(), 2u);
  EXPECT_EQ(world.Cylinders().size(), 1u);
  EXPECT_EQ(world.Name(), "plan");
  EXPECT_GT(std::filesystem::file_size(dir / "w.png"), 1000u);
}

// What the importer accepts the world file holds and LoadWorldModel reads
// back: coordinates are judged at the 0.1 mm the file is written with (a line
// 1.0013 mm long whose ends round to 0.99 mm apart, a circle of 0.04 mm
// radius), and only a closed arc is a pillar (not a 0.5 deg piece of a curve).
TEST(DxfImportCli, WhatItImportsLoadsBack) {
  const TempDir dir;
  const std::string dxf =
      dir.Write("edge.dxf", Dxf(Line("W", 0, 0, 4000, 0) + Line("W", 4000, 0, 4000, 3000) +
                                Line("W", 1000.3, 1000.3, 1001.008, 1001.008) +
                                Circle("W", 2000, 1500, 0.04) + Arc("W", 0, 0, 300, 10, 10.5)));
  const auto r = RunCli({"map", "import", "--dxf", dxf, "--layers", "w", "--out", dir / "w.xml"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("shorter than 1 mm"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("radius not positive (at 0.1 mm)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("not a full circle"), std::string::npos) << r.output;
  const auto world = world_model::LoadWorldModel(dir / "w.xml");
  EXPECT_EQ(world.Walls().size(), 2u);
  EXPECT_EQ(world.Cylinders().size(), 0u);
}

// dxflib allocates for the vertices an LWPOLYLINE announces before reading
// them: a few hundred bytes announcing 20 million must be refused first.
TEST(DxfImportCli, AHugeAnnouncedVertexCountIsRefusedWithItsLine) {
  const TempDir dir;
  std::string entities = LwPolyline("W", {{{0, 0, 0}, {1000, 0, 0}}}, false);
  entities.replace(entities.find("90\n2\n"), 6, "90\n20000000\n");
  const std::string dxf = dir.Write("huge.dxf", Dxf(entities));
  const auto r = RunCli({"map", "import", "--dxf", dxf, "--layers", "w", "--out", dir / "w.xml"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("huge.dxf:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("announces 20000000 items"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "w.xml"));
}

TEST(DxfImportCli, BadInputLeavesTheOutputAloneAndNamesTheFile) {
  const TempDir dir;
  const std::string out = dir.Write("w.xml", "previous");
  const std::string garbage = dir.Write("garbage.dxf", "not a drawing\n");
  const std::string good = dir.Write("good.dxf", Dxf(Line("WALLS", 0, 0, 1000, 0)));
  const std::vector<std::vector<std::string>> cases = {
      {"--dxf", dir / "missing.dxf", "--layers", "WALLS"},
      {"--dxf", garbage, "--layers", "WALLS"},
      {"--dxf", good, "--layers", "PILLARS"},
      {"--dxf", good, "--layers", "WALLS", "--units", "furlong"},
      {"--dxf", good, "--layers", ","},
  };
  for (const auto& args : cases) {
    std::vector<std::string> full = {"map", "import"};
    full.insert(full.end(), args.begin(), args.end());
    full.insert(full.end(), {"--out", out});
    const auto r = RunCli(full);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("structloc map import: "), std::string::npos) << r.output;
    EXPECT_EQ(ReadFile(out), "previous");
  }
  const auto r = RunCli({"map", "import", "--dxf", good, "--layers", "PILLARS", "--out", out});
  EXPECT_NE(r.output.find(good), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("its layers are: WALLS"), std::string::npos) << r.output;
  // The drawing itself is never overwritten.
  const auto same = RunCli({"map", "import", "--dxf", good, "--layers", "WALLS", "--out", good});
  EXPECT_EQ(same.exit_code, 2) << same.output;
}

// Every wall of `a` has a wall in `b` with the same ends (either way round)
// within `tolerance_m`.
void ExpectWallsMatch(const world_model::WorldModel& a, const world_model::WorldModel& b,
                      double tolerance_m) {
  for (const auto& w : a.Walls()) {
    bool found = false;
    for (const auto& v : b.Walls()) {
      const double same = std::max((w.a - v.a).norm(), (w.b - v.b).norm());
      const double swapped = std::max((w.a - v.b).norm(), (w.b - v.a).norm());
      found = found || std::min(same, swapped) <= tolerance_m;
    }
    EXPECT_TRUE(found) << a.Name() << " wall " << w.id << " (" << w.a.transpose() << ") - ("
                       << w.b.transpose() << ") is not in " << b.Name();
  }
}

map_building::DxfImport ImportOffice(const std::vector<std::string>& layers) {
  DxfImportOptions options;
  options.layers = layers;
  return map_building::ImportDrawing(
      map_formats::ReadDxfDrawing(SourcePath("tests/data/maps/office_floor_mm.dxf")), options);
}

TEST(DxfImportOffice, WallsAndPillarsMatchTheOfficeWorldWithoutTheFurniture) {
  const auto original = world_model::LoadWorldModel(SourcePath("maps/office_floor.xml"));
  const auto imported = ImportOffice({"WALLS", "PILLARS"});
  const auto& world = imported.world;
  EXPECT_EQ(imported.report.unit.symbol, "mm");
  EXPECT_FALSE(imported.report.unit_assumed);
  ASSERT_EQ(world.Walls().size(), original.Walls().size());
  ExpectWallsMatch(original, world, 0.001);
  ExpectWallsMatch(world, original, 0.001);
  ASSERT_EQ(world.Cylinders().size(), original.Cylinders().size());
  for (const auto& c : original.Cylinders()) {
    bool found = false;
    for (const auto& d : world.Cylinders()) {
      found = found ||
              ((c.centre - d.centre).norm() <= 0.001 && std::abs(c.radius - d.radius) <= 0.001);
    }
    EXPECT_TRUE(found) << "pillar " << c.id;
  }
  // The corners where wall ends meet are derived as in the original; its
  // free-standing corner 100 (a cabinet edge) lives on layer CORNERS.
  size_t derived = 0;
  for (const auto& c : original.Corners()) derived += c.derived;
  EXPECT_EQ(imported.report.derived_corners, derived);
  EXPECT_EQ(imported.report.given_corners, 0u);
  const auto& left_out = imported.report.left_out_layers;
  EXPECT_NE(std::find(left_out.begin(), left_out.end(), "FURNITURE"), left_out.end());
  EXPECT_EQ(imported.report.layers.at("WALLS").at("LINE").read, 7u);  // not the DOOR block's
}

TEST(DxfImportOffice, TheCornersLayerAddsTheCabinetEdgeAndFurnitureChangesTheMap) {
  const auto with_corner = ImportOffice({"WALLS", "PILLARS", "CORNERS"});
  ASSERT_EQ(with_corner.report.given_corners, 1u);
  for (const auto& c : with_corner.world.Corners()) {
    if (!c.derived) {
      EXPECT_LE((c.position - Eigen::Vector2d(2, 12)).norm(), 1e-9);
    }
  }
  const auto plain = ImportOffice({"WALLS", "PILLARS"});
  const auto furnished = ImportOffice({"WALLS", "PILLARS", "FURNITURE"});
  EXPECT_GT(furnished.world.Walls().size(), plain.world.Walls().size());
  EXPECT_GT(furnished.world.Cylinders().size(), plain.world.Cylinders().size());
  EXPECT_EQ(furnished.report.layers.at("FURNITURE").at("TEXT").used, 0u);
}

TEST(DxfImportOffice, TheCliImportsTheFixture) {
  const TempDir dir;
  const auto r = RunCli(
      {"map", "import", "--dxf", SourcePath("tests/data/maps/office_floor_mm.dxf"), "--layers",
       "WALLS,PILLARS", "--out", dir / "office.xml", "--plot", dir / "office.png"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("millimetres ($INSUNITS = 4)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("16 walls"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("FURNITURE"), std::string::npos) << r.output;
  EXPECT_EQ(world_model::LoadWorldModel(dir / "office.xml").Walls().size(), 16u);
}

}  // namespace
}  // namespace structloc
