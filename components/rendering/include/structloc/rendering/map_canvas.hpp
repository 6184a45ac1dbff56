// Draws maps, scenes, paths, poses and scans into a PNG with OpenCV: the
// pictures of `structloc render`, the replay's --plot and the demo's
// Fig. 44-style summary. DDS-free. Map frame x right, y up.
//
// The picture never exceeds max_side_px on a side: a larger extent (a map in
// millimetres, walls a million metres long) is drawn at a smaller scale
// instead of requesting gigabytes, and coordinates far outside the picture
// are clamped before they become pixel integers.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "structloc/config/output_file.hpp"
#include "structloc/geometry/pose2d.hpp"
#include "structloc/world_model/ray_cast.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::rendering {

class MapCanvas {
 public:
  static constexpr int kDefaultMaxSidePx = 4096;

  // bounds: min x, min y, max x, max y of what must be visible (metres);
  // pixels_per_metre is lowered when the map would exceed max_side_px. Throws
  // std::runtime_error when the bounds are not finite.
  MapCanvas(const Eigen::Vector4d& bounds, double pixels_per_metre = 40.0, int margin_px = 40,
            int max_side_px = kDefaultMaxSidePx);

  // The scale used, and whether it is below the one asked for.
  double PixelsPerMetre() const { return scale_; }
  bool ScaledDown() const { return scaled_down_; }

  void DrawWorld(const world_model::WorldModel& world);
  void DrawObstacles(const world_model::Scene& obstacles, const cv::Scalar& colour);
  void DrawPath(const std::vector<Eigen::Vector2d>& points, const cv::Scalar& colour,
                int thickness = 2);
  void DrawPose(const geometry::Pose2D& pose, const cv::Scalar& colour, double size_m = 0.4);
  void DrawPoints(const std::vector<Eigen::Vector2d>& points, const cv::Scalar& colour,
                  int radius_px = 2);
  void DrawMarker(const Eigen::Vector2d& p, const std::string& label, const cv::Scalar& colour);
  // Legend entries (colour, text), drawn top left.
  void DrawLegend(const std::vector<std::pair<cv::Scalar, std::string>>& entries);
  void DrawTitle(const std::string& text);
  // Encodes the picture in the format its file name asks for and writes it
  // through `file` (Commit() is left to the caller); throws std::runtime_error.
  void WriteTo(config::OutputFile& file) const;
  // WriteTo a new file and Commit(): an existing picture is replaced only on success.
  void Save(const std::string& path) const;
  // Throws config::ConfigError unless `path` names a colour picture OpenCV
  // writes (.png, .jpg, .jpeg, .bmp; not "p.xyz", nor a grey-only ".pgm"), so
  // that callers refuse it before doing any work.
  static void CheckPictureName(const std::string& path);

  cv::Point ToPixel(const Eigen::Vector2d& p) const;

 private:
  Eigen::Vector4d bounds_;
  double scale_;
  bool scaled_down_ = false;
  int margin_;
  cv::Mat image_;
};

// Colours used consistently across pictures (BGR).
namespace colours {
inline const cv::Scalar kWall(40, 40, 40);
inline const cv::Scalar kPillar(90, 90, 90);
inline const cv::Scalar kObstacle(0, 140, 255);
inline const cv::Scalar kPerson(200, 0, 200);
inline const cv::Scalar kTruth(0, 150, 0);
inline const cv::Scalar kOdometry(0, 0, 220);
inline const cv::Scalar kEstimate(220, 90, 0);
inline const cv::Scalar kScan(255, 0, 0);
inline const cv::Scalar kPlanned(170, 170, 170);
}  // namespace colours

}  // namespace structloc::rendering
