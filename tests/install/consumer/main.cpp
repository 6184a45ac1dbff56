// Loads the installed office map and parameters through the installed headers
// and libraries and builds a localiser from them: proof that the package is
// usable from another CMake project. Prints the number of walls.
#include <iostream>

#include "structloc/localisation_core/localiser/localiser.hpp"
#include "structloc/world_model/world_model_xml.hpp"

int main() {
  using namespace structloc;
  const std::string share = STRUCTLOC_SHARE;
  const auto world = world_model::LoadWorldModel(share + "/maps/office_floor.xml");
  const auto options =
      localisation_core::LoadLocaliserOptions(share + "/maps/params/office_sick.xml");
  const localisation_core::Localiser localiser(world, options);
  std::cout << "consumer: " << world.Walls().size() << " walls\n";
  return world.Walls().empty() ? 1 : 0;
}
