// SPDX-License-Identifier: MIT
// The 2D world stepped with its pairs collided on 1, 2, 4 and 8 threads:
// every tick's checksum the same as without a pool, through a tumble of
// boxes, circles, capsules and polygons in a closed box and a restore.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "rewind/core/thread_pool.h"
#include "rewind/fixed/fx_literal.h"
#include "rewind/sim2d/world2d.h"
#include "world2d_test_scenes.h"

namespace rwd::sim2d {
namespace {

using testing::add_body;

void build_bin(World2D& world, int bodies) {
  add_body(world, BodyKind2D::kStatic, make_box(12_fx, 0.5_fx), {Fx(), -0.5_fx});
  add_body(world, BodyKind2D::kStatic, make_box(0.5_fx, 10_fx), {-12_fx, 10_fx});
  add_body(world, BodyKind2D::kStatic, make_box(0.5_fx, 10_fx), {12_fx, 10_fx});
  const Vec2 wedge[3] = {{-0.3_fx, -0.2_fx}, {0.3_fx, -0.2_fx}, {Fx(), 0.35_fx}};
  for (int i = 0; i < bodies; ++i) {
    const Vec2 at{Fx::ratio(((i * 37) % 40) - 20, 2), Fx::ratio(2 + (i / 20) * 3, 4)};
    const Fx angle = Fx::ratio((i * 13) % 31, 10);
    switch (i % 4) {
      case 0:
        add_body(world, BodyKind2D::kDynamic, make_box(0.3_fx, 0.2_fx), at, angle);
        break;
      case 1:
        add_body(world, BodyKind2D::kDynamic, make_circle(0.25_fx), at, angle);
        break;
      case 2:
        add_body(world, BodyKind2D::kDynamic,
                 make_capsule({-0.2_fx, Fx()}, {0.2_fx, Fx()}, 0.15_fx), at, angle);
        break;
      default:
        add_body(world, BodyKind2D::kDynamic, make_polygon(wedge), at, angle);
        break;
    }
  }
}

std::vector<uint64_t> run_bin(rwd::ThreadPool* pool, int bodies, int ticks) {
  World2D world;
  build_bin(world, bodies);
  world.set_thread_pool(pool);
  std::vector<uint64_t> sums;
  World2DState saved;
  for (int t = 0; t < ticks; ++t) {
    if (t == 80) saved = world.state();
    if (t == 120) world.restore(saved);
    world.step();
    sums.push_back(world.checksum());
  }
  return sums;
}

TEST(World2DThreads, EveryTickTheSameOnOneTwoFourAndEightThreads) {
  constexpr int kBodies = 600;
  constexpr int kTicks = 180;
  const std::vector<uint64_t> alone = run_bin(nullptr, kBodies, kTicks);
  for (uint32_t threads : {1u, 2u, 4u, 8u}) {
    rwd::ThreadPool pool(threads);
    const std::vector<uint64_t> sums = run_bin(&pool, kBodies, kTicks);
    ASSERT_EQ(sums.size(), alone.size());
    for (size_t t = 0; t < sums.size(); ++t) {
      ASSERT_EQ(sums[t], alone[t]) << threads << " threads, tick " << t;
    }
  }
}

}  // namespace
}  // namespace rwd::sim2d
