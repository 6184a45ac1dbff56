// A world model from the chosen layers of a CAD drawing (see header).
//
// Choices, documented in docs/guides/maps.md, "From a CAD drawing":
// - a polyline segment with a bulge (an arc) is skipped and counted: the world
//   model has straight walls only, and chords of a curve would be walls the
//   laser never sees as such;
// - an ARC is a pillar only when it closes to a full circle; otherwise skipped;
// - a POINT is a given corner (a cabinet edge, a column corner: thesis 3.5.4);
// - segments shorter than min_segment_m are skipped as degenerate;
// - collinear pieces of one wall that touch or overlap are merged into one;
// - corners where wall ends meet are derived by the world model as for any map.
#include "structloc/map_building/dxf_import.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "structloc/config/strict_xml.hpp"
#include "structloc/map_building/collinear_merging.hpp"
#include "structloc/world_model/world_model_xml.hpp"

namespace structloc::map_building {
namespace {

std::string Lower(std::string text) {
  for (auto& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

// At most 40 names, then how many more.
std::string JoinSome(const std::vector<std::string>& items) {
  constexpr size_t kMost = 40;
  if (items.size() <= kMost) return Join(items);
  return Join(std::vector<std::string>(items.begin(), items.begin() + kMost)) + " and " +
         std::to_string(items.size() - kMost) + " more";
}

std::string Number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Walks the drawing's entities and turns those of the chosen layers into
// world model elements, counting everything.
class Importer {
 public:
  Importer(const CadDrawing& drawing, const DxfImportOptions& options)
      : drawing_(drawing), options_(options) {}

  DxfImport Run() {
    ChooseLayers();
    ChooseUnit();
    for (const auto& l : drawing_.lines) {
      Count* c = Entity(l.layer, "LINE");
      AddSegment(c, l.layer, "LINE", l.a, l.b, 0.0);
    }
    for (const auto& p : drawing_.polylines) AddPolyline(p);
    for (const auto& c : drawing_.circles) AddCircle(c.layer, "CIRCLE", c.centre, c.radius);
    for (const auto& a : drawing_.arcs) AddArc(a);
    for (const auto& p : drawing_.points) AddPoint(p);
    for (const auto& [layer, kinds] : drawing_.unusable) {
      for (const auto& [kind, reasons] : kinds) {
        for (const auto& [reason, n] : reasons) {
          Count* c = Entity(layer, kind);
          if (c == nullptr) continue;
          c->read += n - 1;
          c->skipped[reason] += n;
        }
      }
    }
    CheckLayersUsed();
    return Finish();
  }

 private:
  using Count = DxfImportReport::KindCount;

  const CadDrawing& drawing_;
  const DxfImportOptions& options_;
  std::map<std::string, std::string> chosen_;  // lower-case name -> name as drawn
  DxfImportReport report_;
  std::vector<world_model::Wall> walls_;
  std::vector<world_model::Corner> corners_;
  std::vector<world_model::Cylinder> cylinders_;
  world_model::Scene left_out_;

  [[noreturn]] void Fail(const std::string& what) const {
    throw config::ConfigError(drawing_.path + ": " + what);
  }

  void ChooseLayers() {
    if (options_.layers.empty()) Fail("no layers chosen: name the layers to import");
    std::map<std::string, std::string> drawn;  // lower-case -> as drawn
    for (const auto& l : drawing_.layers) drawn.emplace(Lower(l), l);
    std::vector<std::string> missing;
    for (const auto& wanted : options_.layers) {
      const auto it = drawn.find(Lower(wanted));
      if (it == drawn.end()) {
        missing.push_back(wanted);
        continue;
      }
      chosen_[it->first] = it->second;
      report_.layers[it->second];
    }
    if (!missing.empty()) {
      Fail("the drawing has no layer " + Join(missing) +
           (drawing_.layers.empty() ? std::string("; it has no layers at all")
                                    : "; its layers are: " + JoinSome(drawing_.layers)));
    }
    for (const auto& l : drawing_.layers) {
      if (chosen_.count(Lower(l)) == 0) report_.left_out_layers.push_back(l);
    }
  }

  void ChooseUnit() {
    if (options_.units) {
      report_.unit = *options_.units;
      report_.unit_source = "--units";
      if (drawing_.insunits && *drawing_.insunits != 0)
        report_.unit_source += ", overriding $INSUNITS = " + std::to_string(*drawing_.insunits);
      return;
    }
    std::optional<LengthUnit> drawn;
    if (drawing_.insunits) drawn = UnitOfInsunits(*drawing_.insunits, drawing_.path);
    if (drawn) {
      report_.unit = *drawn;
      report_.unit_source = "$INSUNITS = " + std::to_string(*drawing_.insunits);
      return;
    }
    report_.unit = ParseLengthUnit("mm");
    report_.unit_assumed = true;
    report_.unit_source = std::string("ASSUMED: the drawing ") +
                          (drawing_.insunits ? "is unitless ($INSUNITS = 0)" : "has no $INSUNITS") +
                          "; give --units mm|cm|m|in|ft if that is wrong";
  }

  // The counts of a chosen layer's entity (one more read), or nullptr when
  // the layer is left out.
  Count* Entity(const std::string& layer, const std::string& kind) {
    const auto it = chosen_.find(Lower(layer));
    if (it == chosen_.end()) return nullptr;
    Count& c = report_.layers[it->second][kind];
    ++c.read;
    return &c;
  }

  // A drawing point in metres; a chosen layer's point beyond the world limits
  // is an error (usually a wrong unit), a left-out layer's one is not drawn.
  std::optional<Eigen::Vector2d> Metres(const Eigen::Vector2d& p, bool chosen,
                                        const std::string& layer, const std::string& kind) const {
    // As the world file will hold it, so that the checks below judge that.
    const Eigen::Vector2d m(world_model::AsWritten(p.x() * report_.unit.metres),
                            world_model::AsWritten(p.y() * report_.unit.metres));
    const double limit = options_.limits.max_abs_coordinate_m;
    if (std::isfinite(m.x()) && std::isfinite(m.y()) && std::abs(m.x()) <= limit &&
        std::abs(m.y()) <= limit)
      return m;
    if (!chosen) return std::nullopt;
    Fail("a " + kind + " on layer " + layer + " has the point (" + Number(p.x()) + ", " +
         Number(p.y()) + ") drawing units = (" + Number(m.x()) + ", " + Number(m.y()) +
         ") m, beyond the world limit of " + Number(limit) + " m from the origin; is the unit (" +
         report_.unit.name + ", " + report_.unit_source + ") right? Give --units");
  }

  void AddSegment(Count* c, const std::string& layer, const std::string& kind,
                  const Eigen::Vector2d& a, const Eigen::Vector2d& b, double bulge) {
    const auto ma = Metres(a, c != nullptr, layer, kind);
    const auto mb = Metres(b, c != nullptr, layer, kind);
    if (c == nullptr) {
      if (ma && mb) left_out_.segments.push_back({*ma, *mb});
      return;
    }
    if (bulge != 0.0) {
      ++c->skipped["curved (bulge): walls are straight; draw it as lines to keep it"];
      return;
    }
    if ((*mb - *ma).norm() < options_.min_segment_m) {
      ++c->skipped["shorter than " + Number(options_.min_segment_m * 1000.0) + " mm"];
      return;
    }
    walls_.push_back(world_model::MakeWall(static_cast<int>(walls_.size()) + 1, *ma, *mb));
    ++c->used;
  }

  void AddPolyline(const CadDrawing::Polyline& p) {
    const std::string segment_kind = p.kind + " segments";
    const bool chosen = chosen_.count(Lower(p.layer)) != 0;
    if (chosen) ++report_.layers[chosen_.at(Lower(p.layer))][p.kind].read;
    const size_t used_before = walls_.size();
    const size_t n = p.vertices.size();
    // Closed: a segment back to the first vertex, unless the drawing repeats
    // that vertex at the end (as many CAD programs do).
    const bool ends_at_start =
        n > 2 && (p.vertices.back().p - p.vertices.front().p).norm() * report_.unit.metres <
                     options_.min_segment_m;
    const size_t segments = n < 2 ? 0 : (p.closed && n > 2 && !ends_at_start ? n : n - 1);
    for (size_t i = 0; i < segments; ++i) {
      const auto& from = p.vertices[i];
      const auto& to = p.vertices[(i + 1) % n];
      Count* c = Entity(p.layer, segment_kind);
      AddSegment(c, p.layer, segment_kind, from.p, to.p, from.bulge);
    }
    if (!chosen) return;
    Count& entity = report_.layers[chosen_.at(Lower(p.layer))][p.kind];
    if (walls_.size() > used_before) {
      ++entity.used;
    } else {
      ++entity.skipped[segments == 0 ? "fewer than two vertices" : "no usable segment"];
    }
  }

  void AddCircle(const std::string& layer, const std::string& kind, const Eigen::Vector2d& centre,
                 double radius) {
    Count* c = Entity(layer, kind);
    const auto m = Metres(centre, c != nullptr, layer, kind);
    const double r = world_model::AsWritten(radius * report_.unit.metres);
    if (c == nullptr) {
      if (m && std::isfinite(r) && r > 0.0 && r <= options_.limits.max_radius_m)
        left_out_.circles.push_back({*m, r});
      return;
    }
    if (!(std::isfinite(r) && r > 0.0)) {
      ++c->skipped["radius not positive (at 0.1 mm)"];
      return;
    }
    if (r > options_.limits.max_radius_m) {
      Fail("a " + kind + " on layer " + layer + " has the radius " + Number(radius) +
           " drawing units = " + Number(r) + " m, beyond the world limit of " +
           Number(options_.limits.max_radius_m) + " m; is the unit (" + report_.unit.name + ", " +
           report_.unit_source + ") right? Give --units");
    }
    cylinders_.push_back({static_cast<int>(cylinders_.size()) + 1, *m, r});
    ++c->used;
  }

  void AddArc(const CadDrawing::Arc& a) {
    double sweep = std::fmod(a.end_deg - a.start_deg, 360.0);
    if (sweep <= 0.0) sweep += 360.0;
    if (std::abs(sweep - 360.0) <= options_.full_circle_tolerance_deg) {
      AddCircle(a.layer, "ARC", a.centre, a.radius);
      return;
    }
    Count* c = Entity(a.layer, "ARC");
    if (c != nullptr) ++c->skipped["not a full circle: only closed arcs are pillars"];
  }

  void AddPoint(const CadDrawing::Point& p) {
    Count* c = Entity(p.layer, "POINT");
    if (c == nullptr) return;
    const auto m = Metres(p.p, true, p.layer, "POINT");
    corners_.push_back({static_cast<int>(corners_.size()) + 1, *m, false});
    ++c->used;
  }

  void CheckLayersUsed() const {
    for (const auto& [layer, kinds] : report_.layers) {
      size_t used = 0, read = 0;
      for (const auto& [kind, c] : kinds) {
        used += c.used;
        read += c.read;
      }
      if (used > 0) continue;
      if (read == 0) Fail("layer " + layer + " has no entities");
      std::string what;
      for (const auto& [kind, c] : kinds) {
        for (const auto& [reason, n] : c.skipped)
          what += (what.empty() ? "" : "; ") + std::to_string(n) + " " + kind + " " + reason;
      }
      Fail("layer " + layer + " has no usable entity (LINE, LWPOLYLINE, POLYLINE, CIRCLE, " +
           "closed ARC, POINT): " + what);
    }
  }

  DxfImport Finish() {
    report_.merged_pieces = MergeCollinear(walls_, options_.merge_tolerance_m);
    if (walls_.size() > options_.limits.max_walls) {
      Fail("the chosen layers make " + std::to_string(walls_.size()) +
           " walls, more than the limit of " + std::to_string(options_.limits.max_walls));
    }
    report_.walls = walls_.size();
    report_.given_corners = corners_.size();
    report_.pillars = cylinders_.size();
    try {
      world_model::WorldModel world(options_.world_name, std::move(walls_), std::move(corners_),
                                    std::move(cylinders_), {}, options_.limits);
      report_.derived_corners = world.Corners().size() - report_.given_corners;
      return DxfImport{std::move(world), std::move(report_), std::move(left_out_)};
    } catch (const std::invalid_argument& e) {
      Fail(std::string("the imported map is not a valid world model: ") + e.what());
    }
  }
};

std::string Plural(size_t n, const std::string& word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

}  // namespace

LengthUnit ParseLengthUnit(const std::string& symbol) {
  static const LengthUnit kUnits[] = {{"millimetres", "mm", 0.001},
                                      {"centimetres", "cm", 0.01},
                                      {"metres", "m", 1.0},
                                      {"inches", "in", 0.0254},
                                      {"feet", "ft", 0.3048}};
  for (const auto& u : kUnits) {
    if (u.symbol == symbol) return u;
  }
  throw config::ConfigError("unknown unit '" + symbol + "': give mm, cm, m, in or ft");
}

std::optional<LengthUnit> UnitOfInsunits(int code, const std::string& path) {
  switch (code) {
    case 0:
      return std::nullopt;
    case 1:
      return ParseLengthUnit("in");
    case 2:
      return ParseLengthUnit("ft");
    case 4:
      return ParseLengthUnit("mm");
    case 5:
      return ParseLengthUnit("cm");
    case 6:
      return ParseLengthUnit("m");
    default:
      throw config::ConfigError(path + ": the drawing's unit $INSUNITS = " + std::to_string(code) +
                                " is not one structloc imports (inches 1, feet 2, millimetres 4, " +
                                "centimetres 5, metres 6); give --units mm|cm|m|in|ft");
  }
}

DxfImport ImportDrawing(const CadDrawing& drawing, const DxfImportOptions& options) {
  return Importer(drawing, options).Run();
}

std::string FormatImportReport(const DxfImportReport& report) {
  std::ostringstream out;
  out << "unit: " << report.unit.name << " (" << report.unit_source
      << "): 1 drawing unit = " << report.unit.metres << " m\n";
  for (const auto& [layer, kinds] : report.layers) {
    out << "layer " << layer << ":";
    bool first = true;
    for (const auto& [kind, c] : kinds) {
      out << (first ? " " : "; ") << c.read << " " << kind << " read, " << c.used << " used";
      first = false;
    }
    out << "\n";
    for (const auto& [kind, c] : kinds) {
      for (const auto& [reason, n] : c.skipped)
        out << "  skipped " << n << " " << kind << ": " << reason << "\n";
    }
  }
  out << "left out: "
      << (report.left_out_layers.empty() ? std::string("no layers")
                                         : "layers " + Join(report.left_out_layers))
      << "\n";
  if (report.merged_pieces > 0) {
    out << "merged " << Plural(report.merged_pieces, "wall piece")
        << " into collinear neighbours they touch or overlap\n";
  }
  out << "world: " << Plural(report.walls, "wall") << ", "
      << Plural(report.given_corners + report.derived_corners, "corner") << " ("
      << report.given_corners << " given, " << report.derived_corners
      << " derived where wall ends meet), " << Plural(report.pillars, "pillar") << "\n";
  return out.str();
}

}  // namespace structloc::map_building
