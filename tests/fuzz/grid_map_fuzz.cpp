// libFuzzer targets: ROS map_server maps as `map import --grid` reads them,
// and the walls vectorised from them. Built twice: with
// STRUCTLOC_FUZZ_GRID_IMAGE the input is the image (PGM, or PNG through
// OpenCV) under a fixed YAML; otherwise the YAML beside a fixed small PGM.
#include <stdexcept>
#include <string>

#include "fuzz_input.hpp"
#include "structloc/map_building/grid_vectoriser.hpp"
#include "structloc/map_formats/grid_map_file.hpp"

namespace {

#ifndef STRUCTLOC_FUZZ_GRID_IMAGE
// A 24 x 16 trinary PGM: a room's outline and a pillar-sized blob.
std::string FixedPgm() {
  const int w = 24, h = 16;
  std::string image = "P5\n" + std::to_string(w) + " " + std::to_string(h) + "\n255\n";
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      const bool wall = r == 1 || r == h - 2 || c == 1 || c == w - 2;
      const bool blob = r >= 6 && r <= 8 && c >= 10 && c <= 12;
      image.push_back(static_cast<char>(wall || blob ? 0 : (r == 0 || c == 0 ? 205 : 254)));
    }
  }
  return image;
}
#endif

// The image limit is lowered from its default 1.6 * 10^7 cells to 2^20: a deflated
// PNG of 64 kB decodes to tens of millions of cells, which runs the same loops
// as a small one for seconds under the sanitizers, and a long run (10^6
// executions) collected such inputs until it crawled at 45 per second. The
// refusal of a too-large image is still reached, at the lower limit.
// The vectoriser's work bounds are lowered likewise (a tenth; the face-cell
// bound, whose default is already low, a third), so that the noise seed
// reaches their refusals in a fraction of a second.
void Import(const std::string& yaml) {
  structloc::map_formats::GridMapReadOptions options;
  options.max_cells = size_t{1} << 20;
  const auto grid = structloc::map_formats::LoadGridMap(yaml, options);
  structloc::map_building::GridVectoriseOptions vectorise;
  vectorise.max_face_cells /= 3;
  vectorise.max_blobs /= 10;
  vectorise.max_refit_work /= 10;
  if (grid.cells.size() <= 200000) (void)structloc::map_building::VectoriseGrid(grid, vectorise);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using structloc::fuzz::WriteFile;
#ifdef STRUCTLOC_FUZZ_GRID_IMAGE
  for (const char* image : {"map.pgm", "map.png"}) {
    const std::string yaml = std::string("image: ") + image +
                             "\nresolution: 0.05\norigin: [-1.0, -2.0, 0.0]\nnegate: 0\n"
                             "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
    WriteFile(image, data, size);
    structloc::fuzz::Parse([&] { Import(WriteFile("map.yaml", yaml.data(), yaml.size())); });
  }
#else
  const std::string pgm = FixedPgm();
  WriteFile("map.pgm", pgm.data(), pgm.size());
  structloc::fuzz::Parse([&] { Import(WriteFile("map.yaml", data, size)); });
#endif
  return 0;
}
