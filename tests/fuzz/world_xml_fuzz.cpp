// libFuzzer target: world XML (maps), as `--map` reads it, and the map's
// derived corners and visibility structures built from it.
#include "fuzz_input.hpp"
#include "structloc/world_model/ray_cast.hpp"
#include "structloc/world_model/world_model_xml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = structloc::fuzz::WriteInput(data, size, "world.xml");
  structloc::fuzz::Parse([&] {
    const auto world = structloc::world_model::LoadWorldModel(path);
    (void)structloc::world_model::Scene::FromWorld(world);
  });
  return 0;
}
