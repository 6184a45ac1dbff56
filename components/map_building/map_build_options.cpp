// The map builder's options declared once (key, range, unit, description; the
// struct members hold the defaults) for a <map_build_params> file.
#include <stdexcept>

#include "structloc/config/option_table.hpp"
#include "structloc/map_building/map_builder.hpp"

namespace structloc::map_building {
namespace {

using config::Range;
using O = MapBuildOptions;
using Table = config::OptionTable<O>;

Table ScansSection() {
  Table t("scans", "which readings of the recording are used");
  t.Number("min_range_m", &O::scans, &PosedScanOptions::min_range_m, Range::NonNegative(), "m",
           "closer readings are dropped");
  t.Number("max_range_m", &O::scans, &PosedScanOptions::max_range_m, Range::Positive(), "m",
           "farther readings are dropped (too sparse and noisy to map walls)");
  return t;
}

Table SegmentsSection() {
  using S = ScanSegmentOptions;
  Table t("segments", "straight pieces of each scan (window line fit, thesis 3.5.2, EQ 18)");
  t.Number("window_points", &O::segments, &S::window_points, Range::Closed(3, 1000), "",
           "points of the seed window");
  t.Number("max_window_rms_m", &O::segments, &S::max_window_rms_m, Range::Positive(), "m",
           "seed windows scattering more are not walls");
  t.Number("max_point_distance_m", &O::segments, &S::max_point_distance_m, Range::Positive(), "m",
           "a point farther from the growing line ends the segment");
  t.Number("max_point_gap_m", &O::segments, &S::max_point_gap_m, Range::Positive(), "m",
           "consecutive points farther apart belong to different objects");
  t.Number("min_points", &O::segments, &S::min_points, Range::Closed(2, 100000), "",
           "segments with fewer points are clutter");
  t.Number("min_length_m", &O::segments, &S::min_length_m, Range::NonNegative(), "m",
           "shorter segments are clutter");
  return t;
}

Table WallsSection() {
  using W = WallMergeOptions;
  Table t("walls", "segments of all scans merged into walls, refitted by total least squares");
  t.Number("max_angle_rad", &O::walls, &W::max_angle_rad, Range::Open(0, 1.5707963), "rad",
           "a segment joins a wall whose line is within this angle");
  t.Number("max_offset_m", &O::walls, &W::max_offset_m, Range::Positive(), "m",
           "... and whose line passes this close to both its ends");
  t.Number("max_extent_gap_m", &O::walls, &W::max_extent_gap_m, Range::NonNegative(), "m",
           "... and whose extent it overlaps or nearly touches");
  t.Number("inlier_distance_m", &O::walls, &W::inlier_distance_m, Range::Positive(), "m",
           "the final refit keeps points this close to the line");
  t.Number("max_gap_m", &O::walls, &W::max_gap_m, Range::Positive(), "m",
           "walls are split where no point supports them this long (doors)");
  t.Number("min_scans", &O::walls, &W::min_scans, Range::Closed(1, 1000000), "",
           "walls seen from fewer scans are dropped");
  t.Number("min_points", &O::walls, &W::min_points, Range::Closed(2, 100000000), "",
           "walls with fewer supporting points are dropped");
  t.Number("max_rms_m", &O::walls, &W::max_rms_m, Range::Positive(), "m",
           "rougher walls are dropped");
  t.Number("min_length_m", &O::walls, &W::min_length_m, Range::NonNegative(), "m",
           "shorter walls are dropped");
  return t;
}

Table ShadowsSection() {
  using S = ShadowWallOptions;
  Table t("shadows", "the shorter of two nearly parallel walls side by side is a shadow, dropped");
  t.Number("max_offset_m", &O::shadows, &S::max_offset_m, Range::NonNegative(), "m",
           "both ends of the shorter wall this close to the longer's line (0: keep shadows)");
  t.Number("max_angle_rad", &O::shadows, &S::max_angle_rad, Range::Open(0, 1.5707963), "rad",
           "... the two walls within this angle");
  t.Number("min_overlap", &O::shadows, &S::min_overlap, Range::Closed(0, 1), "",
           "... and at least this share of the shorter alongside the longer");
  return t;
}

Table CornersSection() {
  using C = CornerJoinOptions;
  Table t("corners", "wall ends pulled to where two walls meet (corners are derived there)");
  t.Number("max_end_distance_m", &O::corners, &C::max_end_distance_m, Range::NonNegative(), "m",
           "wall ends this close to the walls' intersection are moved onto it");
  t.Number("min_angle_rad", &O::corners, &C::min_angle_rad, Range::Open(0, 1.5707964), "rad",
           "walls meeting at a smaller angle are not joined");
  return t;
}

Table PillarsSection() {
  using P = PillarOptions;
  Table t("pillars", "pillars from circular arcs seen repeatedly (circle fit, thesis EQ 38)");
  t.Flag("enabled", &O::pillars, &P::enabled, "look for pillars");
  t.Number("min_radius_m", &O::pillars, &P::min_radius_m, Range::Positive(), "m",
           "thinner arcs are legs");
  t.Number("max_radius_m", &O::pillars, &P::max_radius_m, Range::Positive(), "m",
           "wider arcs are not pillars");
  t.Number("min_points", &O::pillars, &P::min_points, Range::Closed(3, 100000), "",
           "points on one arc");
  t.Number("max_rms_m", &O::pillars, &P::max_rms_m, Range::Positive(), "m",
           "arcs scattering more about their circle are not pillars");
  t.Number("min_line_rms_m", &O::pillars, &P::min_line_rms_m, Range::NonNegative(), "m",
           "arcs fitting a line better than this are walls");
  t.Number("min_arc_rad", &O::pillars, &P::min_arc_rad, Range::Open(0, 3.1415927), "rad",
           "arcs spanning less about their centre are not pillars");
  t.Number("max_point_gap_m", &O::pillars, &P::max_point_gap_m, Range::Positive(), "m",
           "consecutive points farther apart end an arc");
  t.Number("merge_distance_m", &O::pillars, &P::merge_distance_m, Range::Positive(), "m",
           "sightings whose centres are closer are one pillar");
  t.Number("min_scans", &O::pillars, &P::min_scans, Range::Closed(1, 1000000), "",
           "pillars seen from fewer scans are dropped");
  t.Flag("drop_seen_through", &O::pillars, &P::drop_seen_through,
         "drop pillars more scans saw through than sighted (a person's trail)");
  t.Number("see_through_margin_m", &O::pillars, &P::see_through_margin_m, Range::NonNegative(), "m",
           "a scan saw through a pillar when its readings within half the radius of the "
           "centre's bearing all lie this far beyond the far side");
  return t;
}

config::OptionFile<O> MapBuildOptionFile() {
  return config::OptionFile<O>("map_build_params",
                               {ScansSection(), SegmentsSection(), WallsSection(), ShadowsSection(),
                                CornersSection(), PillarsSection()});
}

}  // namespace

void MapBuildOptions::Validate() const {
  MapBuildOptionFile().Validate(*this);
  if (!(scans.max_range_m > scans.min_range_m))
    throw std::invalid_argument("scans: max_range_m must be > min_range_m");
  if (!(pillars.max_radius_m > pillars.min_radius_m))
    throw std::invalid_argument("pillars: max_radius_m must be > min_radius_m");
}

MapBuildOptions LoadMapBuildOptions(const std::string& path) {
  return MapBuildOptionFile().LoadValidated(path);
}

void PrintMapBuildOptions(std::ostream& out) {
  MapBuildOptionFile().Print(out, MapBuildOptions{});
}

void WriteExpandedMapBuildOptions(const std::string& path, std::ostream& out) {
  MapBuildOptionFile().WriteExpanded(path, out);
}

}  // namespace structloc::map_building
