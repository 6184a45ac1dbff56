// The steady-state update allocates nothing: global operator new is counted
// while a warmed-up Localiser processes fresh scans (walls, corners,
// cylinders and the weighted solve all active). Its own executable, since it
// replaces the global allocation functions.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdlib>
#include <new>

#include "office_scene.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace structloc {
namespace {

TEST(LocaliserAllocation, SteadyStateUpdateDoesNotAllocate) {
  for (const auto& [beams, fov] :
       {std::pair{300, 2 * geometry::kPi}, {1081, 1.5 * geometry::kPi}}) {
    testing::OfficeScene office(fov);
    localisation_core::Localiser localiser(office.world, office.options);
    std::mt19937 rng(5);
    std::vector<testing::SyntheticScan> scans;
    for (int i = 0; i < 10; ++i) scans.push_back(office.Scan(beams, rng));
    for (int i = 0; i < 2; ++i) localiser.Update(office.Input(scans[static_cast<size_t>(i)]));
    // No assertion inside the counted region: a failure message allocates.
    std::array<int, 8> cylinders{};
    std::array<int, 8> features{};
    const long before = g_allocations.load();
    for (size_t i = 2; i < scans.size(); ++i) {
      const auto& r = localiser.Update(office.Input(scans[i]));
      cylinders[i - 2] = r.features[2].Matched();  // walls, corners, cylinders
      features[i - 2] = r.Matched();
    }
    const long allocations = g_allocations.load() - before;
    EXPECT_EQ(allocations, 0) << beams << " beams";
    ASSERT_NE(localiser.Update(office.Input(scans[0])).Kind("cylinders"), nullptr);
    EXPECT_GT(*std::max_element(cylinders.begin(), cylinders.end()), 0) << beams;
    EXPECT_GT(*std::min_element(features.begin(), features.end()), 3) << beams;
  }
}

}  // namespace
}  // namespace structloc
