// A world model from a CAD drawing as integrators receive one (issue 11,
// "maps from what users have"): the entities of the chosen layers become the
// map elements of the thesis' feature kinds: every straight LINE and polyline
// segment a wall (3.5.3), every CIRCLE (and every ARC closed to a full circle)
// a cylindrical pillar (3.5.6), every POINT a given corner (3.5.4); the
// drawing's unit is scaled to metres. What is left out, and why, is counted
// per layer and entity kind. The drawing itself is read by
// map_formats::ReadDxfDrawing (dxflib); this part is format-independent and
// DDS-free.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "structloc/world_model/ray_cast.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::map_building {

// The geometry of a 2-D drawing in its own unit (not yet metres), with the
// layer of every entity. Entities inside block definitions are not included.
struct CadDrawing {
  struct Line {
    std::string layer;
    Eigen::Vector2d a{0, 0}, b{0, 0};
  };
  struct Vertex {
    Eigen::Vector2d p{0, 0};
    double bulge = 0.0;  // tan(sweep / 4) of the segment to the next vertex; 0 straight
  };
  struct Polyline {
    std::string layer;
    std::string kind;  // "LWPOLYLINE" or "POLYLINE"
    std::vector<Vertex> vertices;
    bool closed = false;  // a segment from the last vertex back to the first
  };
  struct Circle {
    std::string layer;
    Eigen::Vector2d centre{0, 0};
    double radius = 0.0;
  };
  struct Arc {
    std::string layer;
    Eigen::Vector2d centre{0, 0};
    double radius = 0.0;
    double start_deg = 0.0, end_deg = 0.0;  // counter-clockwise from start to end
  };
  struct Point {
    std::string layer;
    Eigen::Vector2d p{0, 0};
  };

  std::string path;                 // for messages
  std::optional<int> insunits;      // the header's $INSUNITS, when present
  std::vector<std::string> layers;  // the LAYER table and the entities' layers, first seen first
  std::vector<Line> lines;
  std::vector<Polyline> polylines;
  std::vector<Circle> circles;
  std::vector<Arc> arcs;
  std::vector<Point> points;
  // Entities of the kinds above that cannot be used (reason -> count) and of
  // other kinds (TEXT, INSERT, SPLINE...: "KIND entities" -> count), per layer.
  std::map<std::string, std::map<std::string, std::map<std::string, size_t>>> unusable;
};

// A length unit of a drawing.
struct LengthUnit {
  std::string name;     // "millimetres"
  std::string symbol;   // "mm"
  double metres = 1.0;  // metres per drawing unit
};

// "mm", "cm", "m", "in" or "ft"; throws config::ConfigError otherwise.
LengthUnit ParseLengthUnit(const std::string& symbol);
// The unit of an $INSUNITS code (1 in, 2 ft, 4 mm, 5 cm, 6 m); nullopt for 0
// (unitless); throws config::ConfigError for codes of other units.
std::optional<LengthUnit> UnitOfInsunits(int code, const std::string& path);

struct DxfImportOptions {
  std::vector<std::string> layers;         // layers to import, matched case-insensitively
  std::optional<LengthUnit> units;         // overrides the drawing's $INSUNITS (default: none)
  double min_segment_m = 0.001;            // shorter segments are skipped as degenerate
  double full_circle_tolerance_deg = 1.0;  // an ARC sweeping 360 deg +- this is a pillar
  // Pieces of one straight wall (drawn in parts, or twice) whose ends lie
  // within this of each other's line and that touch or overlap within it
  // become one wall, as a hand-written map has it; 0 keeps every piece.
  double merge_tolerance_m = 0.001;
  std::string world_name = "imported";
  world_model::WorldLimits limits;  // coordinates, radii and wall count
};

// What an import read, used and skipped, for the summary and the map's comment.
struct DxfImportReport {
  struct KindCount {
    size_t read = 0;
    size_t used = 0;
    std::map<std::string, size_t> skipped;  // reason -> count
  };
  // layer (as the drawing spells it) -> entity kind -> counts; chosen layers only.
  std::map<std::string, std::map<std::string, KindCount>> layers;
  std::vector<std::string> left_out_layers;  // the drawing's other layers
  LengthUnit unit;
  std::string unit_source;    // "$INSUNITS = 4", "--units", or why the unit was assumed
  bool unit_assumed = false;  // no unit in the drawing and none given
  size_t walls = 0, given_corners = 0, derived_corners = 0, pillars = 0;
  size_t merged_pieces = 0;  // wall pieces merged into a collinear neighbour
};

struct DxfImport {
  world_model::WorldModel world;
  DxfImportReport report;
  world_model::Scene left_out;  // the other layers' lines and circles, metres, for pictures
};

// Throws config::ConfigError naming the drawing and the problem: a chosen
// layer the drawing does not have (the message lists the layers it has), a
// chosen layer without a usable entity, an $INSUNITS of an unsupported unit,
// coordinates or radii beyond options.limits (usually a wrong unit), more walls
// than options.limits allow.
DxfImport ImportDrawing(const CadDrawing& drawing, const DxfImportOptions& options);

// The summary printed by `structloc map import --dxf`, several lines.
std::string FormatImportReport(const DxfImportReport& report);

}  // namespace structloc::map_building
