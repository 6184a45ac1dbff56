// MapCanvas drawing (see header).
#include "structloc/rendering/map_canvas.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <stdexcept>

#include "structloc/config/strict_xml.hpp"

namespace structloc::rendering {
namespace {
constexpr int kLegendBand = 70;
constexpr int kTitleBand = 30;
// Pixel coordinates are clamped to this far outside the picture: drawing then
// still clips correctly for everything near it, and no cast to int overflows.
constexpr double kFarPx = 1 << 24;

int ToPixelInt(double v) {
  if (!(v > -kFarPx)) return static_cast<int>(-kFarPx);  // also NaN
  if (v > kFarPx) return static_cast<int>(kFarPx);
  return static_cast<int>(v);
}
}  // namespace

MapCanvas::MapCanvas(const Eigen::Vector4d& bounds, double pixels_per_metre, int margin_px,
                     int max_side_px)
    : bounds_(bounds), scale_(pixels_per_metre), margin_(margin_px) {
  const double span_x = bounds[2] - bounds[0], span_y = bounds[3] - bounds[1];
  if (!std::isfinite(span_x) || !std::isfinite(span_y) || span_x < 0.0 || span_y < 0.0) {
    throw std::runtime_error("cannot draw the picture: its extent is not finite");
  }
  if (!(scale_ > 0.0) || !std::isfinite(scale_)) {
    throw std::runtime_error("cannot draw the picture: pixels per metre must be positive");
  }
  const double room = std::max(1, max_side_px - 2 * margin_ - kTitleBand - kLegendBand);
  const double span = std::max(span_x, span_y);
  if (span * scale_ > room) {
    scale_ = room / span;
    scaled_down_ = true;
  }
  const int w = ToPixelInt(span_x * scale_) + 2 * margin_;
  // A band of kLegendBand pixels above the map holds the legend; kTitleBand below, the title.
  const int h = ToPixelInt(span_y * scale_) + 2 * margin_ + kTitleBand + kLegendBand;
  image_ = cv::Mat(std::max(h, 100), std::max(w, 100), CV_8UC3, cv::Scalar(255, 255, 255));
}

cv::Point MapCanvas::ToPixel(const Eigen::Vector2d& p) const {
  return {ToPixelInt(margin_ + (p.x() - bounds_[0]) * scale_),
          ToPixelInt(image_.rows - margin_ - kTitleBand - (p.y() - bounds_[1]) * scale_)};
}

void MapCanvas::DrawWorld(const world_model::WorldModel& world) {
  for (const auto& w : world.Walls())
    cv::line(image_, ToPixel(w.a), ToPixel(w.b), colours::kWall, 3);
  for (const auto& c : world.Cylinders()) {
    cv::circle(image_, ToPixel(c.centre), std::max(2, ToPixelInt(c.radius * scale_)),
               colours::kPillar, cv::FILLED, cv::LINE_AA);
  }
  for (const auto& c : world.Corners()) {
    const cv::Point p = ToPixel(c.position);
    cv::rectangle(image_, p - cv::Point(3, 3), p + cv::Point(3, 3), colours::kWall, 1);
  }
}

void MapCanvas::DrawObstacles(const world_model::Scene& obstacles, const cv::Scalar& colour) {
  for (const auto& s : obstacles.segments) cv::line(image_, ToPixel(s.a), ToPixel(s.b), colour, 2);
  for (const auto& c : obstacles.circles) {
    cv::circle(image_, ToPixel(c.centre), std::max(2, ToPixelInt(c.radius * scale_)), colour, 2,
               cv::LINE_AA);
  }
}

void MapCanvas::DrawPath(const std::vector<Eigen::Vector2d>& points, const cv::Scalar& colour,
                         int thickness) {
  for (size_t i = 1; i < points.size(); ++i) {
    cv::line(image_, ToPixel(points[i - 1]), ToPixel(points[i]), colour, thickness, cv::LINE_AA);
  }
}

void MapCanvas::DrawPose(const geometry::Pose2D& pose, const cv::Scalar& colour, double size_m) {
  const Eigen::Vector2d tip = pose.Apply({size_m, 0.0});
  const Eigen::Vector2d left = pose.Apply({-0.5 * size_m, 0.4 * size_m});
  const Eigen::Vector2d right = pose.Apply({-0.5 * size_m, -0.4 * size_m});
  const std::vector<cv::Point> triangle = {ToPixel(tip), ToPixel(left), ToPixel(right)};
  cv::fillConvexPoly(image_, triangle, colour, cv::LINE_AA);
}

void MapCanvas::DrawPoints(const std::vector<Eigen::Vector2d>& points, const cv::Scalar& colour,
                           int radius_px) {
  for (const auto& p : points) cv::circle(image_, ToPixel(p), radius_px, colour, cv::FILLED);
}

void MapCanvas::DrawMarker(const Eigen::Vector2d& p, const std::string& label,
                           const cv::Scalar& colour) {
  const cv::Point px = ToPixel(p);
  cv::circle(image_, px, 5, colour, 2, cv::LINE_AA);
  cv::putText(image_, label, px + cv::Point(7, -7), cv::FONT_HERSHEY_SIMPLEX, 0.5, colour, 1,
              cv::LINE_AA);
}

void MapCanvas::DrawLegend(const std::vector<std::pair<cv::Scalar, std::string>>& entries) {
  // Two columns in the band above the map.
  for (size_t i = 0; i < entries.size(); ++i) {
    const int x = margin_ + static_cast<int>(i % 2) * std::max(280, image_.cols / 2 - margin_);
    const int y = 18 + static_cast<int>(i / 2) * 20;
    cv::line(image_, {x, y}, {x + 25, y}, entries[i].first, 3);
    cv::putText(image_, entries[i].second, {x + 33, y + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.5,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
}

void MapCanvas::DrawTitle(const std::string& text) {
  cv::putText(image_, text, {margin_, image_.rows - 12}, cv::FONT_HERSHEY_SIMPLEX, 0.55,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}

void MapCanvas::WriteTo(config::OutputFile& file) const {
  const std::string& path = file.Path();
  const size_t dot = path.find_last_of('.');
  std::vector<uchar> encoded;
  if (dot == std::string::npos || !cv::imencode(path.substr(dot), image_, encoded)) {
    throw std::runtime_error(path + ": cannot encode the picture");
  }
  file.Stream().write(reinterpret_cast<const char*>(encoded.data()),
                      static_cast<std::streamsize>(encoded.size()));
}

void MapCanvas::Save(const std::string& path) const {
  CheckPictureName(path);
  config::OutputFile file(path);
  WriteTo(file);
  file.Commit();
}

void MapCanvas::CheckPictureName(const std::string& path) {
  // Colour formats only: OpenCV also "writes" .pgm and .pbm, then fails on a
  // colour picture after all the work.
  static const std::set<std::string> kColour = {".png", ".jpg", ".jpeg", ".bmp"};
  const auto dot = path.find_last_of('.');
  std::string extension = dot == std::string::npos ? "" : path.substr(dot);
  for (auto& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  bool known = false;
  try {
    known = kColour.count(extension) != 0 && cv::haveImageWriter(path);
  } catch (const cv::Exception&) {
    known = false;
  }
  if (!known) {
    throw config::ConfigError(path +
                              ": not a name for a colour picture; name it .png (or .jpg, .bmp)");
  }
}

}  // namespace structloc::rendering
