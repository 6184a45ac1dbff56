// Walls, corners and pillars from an occupancy grid (`structloc map import
// --grid`): the occupied cells are split into connected blobs; blobs shaped
// like a round pillar get a circle fitted to their boundary cells, blobs too
// small for a wall (furniture, noise; judged together with the blobs a gap of
// up to max_join_gap_m away, since a wall seen by few scans is dotted) are
// left out and counted, and the rest give walls: OpenCV's probabilistic
// Hough transform proposes segments, and each wall's line is then the total
// least-squares fit (FitWall, thesis 3.5.2) of the cell centres near it, so
// that its position is good to a fraction of a cell.
//
// Which cells are fitted: the "face" cells, occupied cells with a free
// 4-neighbour, i.e. what a laser in the free space sees. A wall one or two
// cells thick has both its faces within capture_cells of one line and gives
// one wall along its middle; a thicker wall (from SLAM, or a drawn plan) gives
// one wall per face, each through the centres of the face cells (a laser hit
// lies somewhere in its cell; the centre is the unbiased guess). An
// axis-aligned wall is thus known to +-half a cell only when it is thin and
// lies inside one row of cells; oblique walls, and walls whose cells straddle
// a cell border, come out to ~cell / sqrt(cells). Pieces of one line on both
// sides of a door share one fitted line and keep the door as a gap. DDS-free.
#pragma once

#include <cstddef>
#include <vector>

#include "structloc/map_building/occupancy_grid.hpp"
#include "structloc/map_building/wall_fitting.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::map_building {

struct GridVectoriseOptions {
  int occupied_min_value = 65;        // cells >= this are occupied (map_saver's 0.65)
  int free_max_value = 19;            // cells 0..this are free (map_saver's 0.196)
  double min_wall_length_m = 0.3;     // shorter wall pieces are dropped
  double max_gap_m = 0.25;            // a wider gap in a wall's cells splits it (a door)
  double min_wall_blob_size_m = 1.0;  // blobs whose bounding box is smaller are not walls
  // Blobs at most this far apart (empty cells between them, rounded down to
  // whole cells, at most 64; diagonally counted in cells) are judged together,
  // for min_wall_blob_size_m and max_speck_cells: a wall seen by few scans is
  // dotted in a ray-cast grid. Furniture this near a wall is judged with the
  // wall, as furniture touching it always was. 0 judges each blob alone.
  double max_join_gap_m = 0.1;
  double proposal_capture_cells = 1.25;  // cells this near a proposed segment start its fit
  double capture_cells = 0.8;            // cells this near a fitted line belong to it
  // Fits this close in angle (~2 deg) that share at least half their cells
  // are one wall (several Hough proposals of one wall); the one with more cells is kept.
  double same_line_angle_rad = 0.035;
  int hough_votes = 10;  // Hough accumulator threshold, cells
  double min_pillar_radius_m = 0.05;
  double max_pillar_radius_m = 0.6;
  double max_pillar_rms_cells = 0.5;  // RMS of the boundary cells about the fitted circle
  double min_pillar_roundness = 0.7;  // bounding box: short side / long side
  size_t max_speck_cells = 2;         // blobs this small are noise, counted apart
  CornerJoinOptions corners{0.15, 0.5};
  // Work bounds, so that a noisy or hostile grid is refused within about a
  // second instead of running for minutes (a 45 kB PNG of noise asked for
  // hours). A grid beyond one is refused naming the option. The grids of the
  // real recordings need 7 200 face cells and 290 000 of refit work; Freiburg
  // 079's tiled 2 x 2 (93 x 37 m) 29 000 and 1.9 million: the refits' work
  // grows faster than the area, so max_refit_work binds a building long
  // before max_face_cells does.
  size_t max_face_cells = 100000;  // occupied cells next to open space (~5 km of wall face at 5 cm)
  size_t max_blobs = 100000;       // connected blobs of occupied cells
  // Refitting Hough's proposals: the face cells each refit gathers (counted
  // every time), plus one for every 16 grid columns or rows walked to find them.
  size_t max_refit_work = 2000000;
};

struct GridVectorisation {
  std::vector<FittedWall> walls;
  std::vector<world_model::Cylinder> pillars;
  size_t cells = 0;                // in the grid
  size_t occupied_cells = 0;       // at or above occupied_min_value
  size_t face_cells = 0;           // occupied cells of wall blobs next to free space
  size_t wall_blobs = 0;           // connected blobs that gave walls
  size_t blobs_left_out = 0;       // neither wall nor pillar (furniture, clutter)
  size_t specks_left_out = 0;      // blobs of at most max_speck_cells (noise)
  size_t corners_joined = 0;       // wall ends pulled onto a corner (JoinCorners)
  size_t short_after_joining = 0;  // shortened below min_wall_length_m by that, dropped
};

// Throws std::invalid_argument when the grid's cells do not match its size,
// when it has no occupied cell, when it gives more walls than a world may
// hold (WorldLimits), when it needs more work than a bound of the options
// allows, or when the options are out of range (each naming the option).
GridVectorisation VectoriseGrid(const map_building::OccupancyGrid& grid,
                                const GridVectoriseOptions& options);

// Circle through points by algebraic (Kasa) then geometric least squares:
// centre, radius and the RMS of the radial residuals. Throws
// std::invalid_argument for fewer than three points or collinear points.
struct FittedCircle {
  Eigen::Vector2d centre{0, 0};
  double radius = 0.0;
  double rms_m = 0.0;
};
FittedCircle FitCircle(const std::vector<Eigen::Vector2d>& points);

}  // namespace structloc::map_building
