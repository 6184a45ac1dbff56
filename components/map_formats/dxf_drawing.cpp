// DXF drawings read with dxflib (see header). dxflib calls the adapter back
// per entity; the raw group codes it also passes on (processCodeValuePair,
// called before the callback of the entity that a group 0 ends) tell which
// section we are in, the kinds dxflib has no callback for, and whether a
// polyline was a LWPOLYLINE or an old-style POLYLINE.
#include "structloc/map_formats/dxf_drawing.hpp"

#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

#include "dxf_checked_copy.hpp"
#include "structloc/config/strict_xml.hpp"

namespace structloc::map_formats {
namespace {

using map_building::CadDrawing;

std::string Lower(std::string text) {
  for (auto& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// A DXF real: optional blanks around a number strtod reads entirely, finite.
bool IsNumber(const std::string& text) {
  const char* start = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(start, &end);
  if (end == start) return false;
  while (*end == ' ' || *end == '\t' || *end == '\r') ++end;
  return *end == '\0' && std::isfinite(value);
}

class DrawingCollector : public DL_CreationAdapter {
 public:
  explicit DrawingCollector(CadDrawing& drawing) : drawing_(drawing) {}

  bool SawSection() const { return saw_section_; }
  // Whether the ENTITIES section was closed (ENDSEC) and the file ended with
  // EOF: a drawing cut short has neither, and would import in part.
  bool EntitiesEnded() const { return entities_ended_; }
  bool SawEof() const { return saw_eof_; }
  // The first coordinate, length or angle that is no number (dxflib reads it as 0).
  const std::string& BadNumber() const { return bad_number_; }
  size_t Entities() const { return entities_; }

  void processCodeValuePair(unsigned int code, const std::string& value) override {
    if (code == 0 || code == 9) {
      // dxflib ends the object before at a group 9 as at a group 0 (see
      // dxf_checked_copy.cpp) and calls back for it: it is finished here too.
      FinishRawEntity();
      // Sections and the file's end are marked by a group 0 only.
      const auto marks = [&](const char* name) { return code == 0 && value == name; };
      expect_section_name_ = marks("SECTION");
      saw_section_ = saw_section_ || expect_section_name_;
      if (marks("ENDSEC")) {
        entities_ended_ = entities_ended_ || section_ == "ENTITIES";
        section_.clear();
      }
      saw_eof_ = saw_eof_ || marks("EOF");
      raw_kind_ = value;
      raw_layer_ = "0";
      raw_paper_space_ = false;
    } else if (code == 2 && expect_section_name_) {
      section_ = value;
      expect_section_name_ = false;
      raw_kind_.clear();  // "SECTION" itself is no entity
    } else if (code >= 10 && code <= 59 && section_ == "ENTITIES" && bad_number_.empty() &&
               !IsNumber(value)) {
      bad_number_ = "a " + raw_kind_ + " entity on layer " + raw_layer_ + " has '" + value +
                    "' for group code " + std::to_string(code) + ", not a finite number";
    } else if (code == 8) {
      raw_layer_ = value;
    } else if (code == 67) {
      raw_paper_space_ = value.find('1') != std::string::npos;
    }
  }

  void addLayer(const DL_LayerData& data) override { NoteLayer(data.name); }
  void addBlock(const DL_BlockData&) override { in_block_ = true; }
  void endBlock() override { in_block_ = false; }
  void setVariableInt(const std::string& key, int value, int) override {
    if (key == "$INSUNITS") drawing_.insunits = value;
  }

  void addLine(const DL_LineData& d) override {
    if (!ModelSpace()) return;
    drawing_.lines.push_back({Layer(), {d.x1, d.y1}, {d.x2, d.y2}});
  }
  void addPoint(const DL_PointData& d) override {
    if (!ModelSpace()) return;
    drawing_.points.push_back({Layer(), {d.x, d.y}});
  }
  void addCircle(const DL_CircleData& d) override {
    if (!ModelSpace()) return;
    const auto mirror = Mirror("CIRCLE");
    if (!mirror) return;
    drawing_.circles.push_back({Layer(), {*mirror * d.cx, d.cy}, d.radius});
  }
  void addArc(const DL_ArcData& d) override {
    if (!ModelSpace()) return;
    const auto mirror = Mirror("ARC");
    if (!mirror) return;
    // Seen from below (extrusion -z) the arc runs the other way round.
    const double start = *mirror > 0 ? d.angle1 : 180.0 - d.angle2;
    const double end = *mirror > 0 ? d.angle2 : 180.0 - d.angle1;
    drawing_.arcs.push_back({Layer(), {*mirror * d.cx, d.cy}, d.radius, start, end});
  }
  void addPolyline(const DL_PolylineData& d) override {
    polyline_open_ = false;
    if (!ModelSpace()) return;
    const std::string kind = finished_kind_ == "POLYLINE" ? "POLYLINE" : "LWPOLYLINE";
    // Old-style POLYLINE flags 8, 16 and 64: 3-D polyline, 3-D mesh, polyface mesh.
    if (kind == "POLYLINE" && (d.flags & (8 | 16 | 64)) != 0) {
      ++drawing_.unusable[Layer()][kind]["a 3-D polyline or mesh, not a floor plan line"];
      return;
    }
    const auto mirror = Mirror(kind);
    if (!mirror) return;
    polyline_mirror_ = *mirror;
    drawing_.polylines.push_back({Layer(), kind, {}, (d.flags & 1) != 0});
    polyline_open_ = true;
  }
  void addVertex(const DL_VertexData& d) override {
    if (!polyline_open_) return;
    // The bulge's sign (turning direction) flips when seen from below; only
    // whether it is zero matters to the import.
    drawing_.polylines.back().vertices.push_back({{polyline_mirror_ * d.x, d.y}, d.bulge});
  }
  void endSequence() override { polyline_open_ = false; }

 private:
  CadDrawing& drawing_;
  std::set<std::string> known_layers_;  // lower case
  bool saw_section_ = false;
  bool entities_ended_ = false;
  bool saw_eof_ = false;
  std::string bad_number_;
  bool expect_section_name_ = false;
  std::string section_;
  bool in_block_ = false;
  size_t entities_ = 0;
  // The entity whose group codes are being passed on, and the one a group 0
  // has just ended (whose dxflib callback comes next).
  std::string raw_kind_, raw_layer_ = "0", finished_kind_, finished_section_;
  bool raw_paper_space_ = false;
  bool polyline_open_ = false;
  double polyline_mirror_ = 1.0;

  void NoteLayer(const std::string& name) {
    if (known_layers_.insert(Lower(name)).second) drawing_.layers.push_back(name);
  }

  // Called at every group 0: the entity that it ends is complete.
  void FinishRawEntity() {
    finished_kind_ = raw_kind_;
    finished_section_ = section_;
    if (section_ != "ENTITIES" || in_block_ || raw_paper_space_ || raw_kind_.empty()) return;
    if (raw_kind_ == "VERTEX" || raw_kind_ == "SEQEND") return;
    ++entities_;
    NoteLayer(raw_layer_);
    static const std::set<std::string> kRead = {"LINE",   "LWPOLYLINE", "POLYLINE",
                                                "CIRCLE", "ARC",        "POINT"};
    if (kRead.count(raw_kind_) != 0) return;
    const std::string reason =
        raw_kind_ == "INSERT"
            ? "a block reference, not expanded: explode blocks in the CAD program to import them"
            : "not a kind that makes walls, pillars or corners";
    ++drawing_.unusable[raw_layer_][raw_kind_][reason];
  }

  bool ModelSpace() {
    return finished_section_ == "ENTITIES" && !in_block_ && !attributes.isInPaperSpace();
  }
  std::string Layer() { return attributes.getLayer(); }

  // +1 for an entity drawn in the x-y plane seen from above, -1 seen from
  // below (object coordinates then have x mirrored), nullopt (and counted as
  // unusable) for one in another plane.
  std::optional<double> Mirror(const std::string& kind) {
    const double* dir = getExtrusion()->getDirection();
    const double tilt = std::hypot(dir[0], dir[1]);
    if (tilt < 1e-9 && dir[2] > 0) return 1.0;
    if (tilt < 1e-9 && dir[2] < 0) return -1.0;
    ++drawing_.unusable[Layer()][kind]["not in the floor plane (tilted extrusion direction)"];
    return std::nullopt;
  }
};

}  // namespace

CadDrawing ReadDxfDrawing(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error))
    throw config::ConfigError(path + ": no such file (expected a DXF drawing)");
  if (std::filesystem::is_directory(path, error))
    throw config::ConfigError(path + ": is a folder, not a DXF drawing");
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw config::ConfigError(path + ": cannot be opened for reading");
    std::string start(22, '\0');
    in.read(start.data(), static_cast<std::streamsize>(start.size()));
    if (start.rfind("AutoCAD Binary DXF", 0) == 0) {
      throw config::ConfigError(path +
                                ": is a binary DXF; save the drawing as ASCII DXF and try again");
    }
  }
  // dxflib reads the checked copy: what it reads is what was checked.
  const DxfCheckedCopy copy(path);
  CadDrawing drawing;
  drawing.path = path;
  DrawingCollector collector(drawing);
  DL_Dxf dxf;
  bool read = false;
  try {
    read = dxf.in(copy.Path(), &collector);
  } catch (...) {
    read = false;
  }
  if (!read) throw config::ConfigError(path + ": dxflib could not read it as a DXF drawing");
  if (!collector.SawSection()) {
    throw config::ConfigError(path +
                              ": not a DXF drawing (no SECTION found; is it a DWG or another "
                              "format? Save it as ASCII DXF)");
  }
  if (!collector.BadNumber().empty())
    throw config::ConfigError(path + ": " + collector.BadNumber());
  if (!collector.EntitiesEnded() || !collector.SawEof()) {
    throw config::ConfigError(
        path + ": ends before " +
        (collector.EntitiesEnded() ? std::string("its EOF") : "the ENTITIES section's ENDSEC") +
        ": the drawing is cut short (copied in part?); save it again from the CAD program");
  }
  if (collector.Entities() == 0) {
    throw config::ConfigError(path +
                              ": no DXF entities in the drawing's model space (ENTITIES section)");
  }
  return drawing;
}

}  // namespace structloc::map_formats
