// Pictures of built and checked maps (see header).
#include "map_picture.hpp"

#include <algorithm>

#include "structloc/rendering/map_canvas.hpp"

namespace structloc::cli {

std::vector<Eigen::Vector2d> MapFrameReadings(const std::vector<map_building::PosedScan>& scans,
                                              size_t step) {
  std::vector<Eigen::Vector2d> out;
  for (size_t i = 0; i < scans.size(); i += std::max<size_t>(step, 1)) {
    for (const auto& p : scans[i].points) out.push_back(scans[i].laser_pose.Apply(p));
  }
  return out;
}

void WriteMapPicture(config::OutputFile& file, const world_model::WorldModel& world,
                     const MapPicture& picture) {
  Eigen::Vector4d bounds = world.Bounds();
  for (const auto& p : picture.readings) {
    bounds = {std::min(bounds[0], p.x()), std::min(bounds[1], p.y()), std::max(bounds[2], p.x()),
              std::max(bounds[3], p.y())};
  }
  rendering::MapCanvas canvas(bounds, 50.0);
  canvas.DrawPoints(picture.readings, cv::Scalar(200, 200, 200), 1);
  canvas.DrawPoints(picture.marked, cv::Scalar(60, 60, 255), 1);
  if (picture.wall_colours.size() == world.Walls().size()) {
    const auto& walls = world.Walls();
    for (size_t i = 0; i < walls.size(); ++i)
      canvas.DrawPath({walls[i].a, walls[i].b}, picture.wall_colours[i], 2);
    world_model::Scene pillars;
    for (const auto& c : world.Cylinders()) pillars.circles.push_back({c.centre, c.radius});
    canvas.DrawObstacles(pillars, rendering::colours::kPillar);
  } else {
    canvas.DrawWorld(world);
  }
  canvas.DrawLegend(picture.legend);
  canvas.DrawTitle(picture.title);
  canvas.WriteTo(file);
}

}  // namespace structloc::cli
