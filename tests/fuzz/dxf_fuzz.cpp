// libFuzzer target: ASCII DXF drawings as `map import --dxf` reads them
// (dxflib), and the import of their WALLS and PILLARS layers.
#include "fuzz_input.hpp"
#include "structloc/map_building/dxf_import.hpp"
#include "structloc/map_formats/dxf_drawing.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "drawing.dxf");
  structloc::fuzz::Parse([&] {
    const auto drawing = structloc::map_formats::ReadDxfDrawing(path);
    structloc::map_building::DxfImportOptions options;
    options.layers = {"WALLS", "PILLARS"};
    (void)structloc::map_building::ImportDrawing(drawing, options);
  });
  return 0;
}
