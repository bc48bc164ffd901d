// SPDX-License-Identifier: MIT
// rewind-rays2d: closest-hit raycasts per second in the large pyramid
// (5,050 boxes, as built), Rewind's 2D lane against Box2D 2.4 and, when
// built with it (REWIND_BOX2D3_DIR), Box2D v3 on the same rays in the same
// process, the engines taking turns in blocks so a shared machine's load
// falls on all alike. Prints CSV:
//   engine,settings,rays,rays_per_s,hits,agree_pct
// agree_pct is the share of rays a peer and Rewind answer alike (Rewind's
// row: Rewind and Box2D 2.4): both miss, or both hit within 1 cm of each
// other along the ray (Box2D 2.4's boxes carry a 1 cm skin, so its hits
// come up to 1 cm early).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "box2d_engine.h"
#include "rewind2d_engine.h"
#include "scene2d.h"
#ifdef REWIND_HAVE_BOX2D3
#include "box2d3_engine.h"
#endif

namespace {

using rwd::bench::Engine2D;

struct Ray {
  double x0, y0, x1, y1;
};

// Rays from above and from the sides through the pyramid: a fixed set, so
// both engines answer the same questions.
std::vector<Ray> make_rays(int count) {
  std::vector<Ray> rays;
  uint32_t seed = 12345;
  auto next = [&] {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<double>(seed >> 8) / 16777216.0;
  };
  for (int i = 0; i < count; ++i) {
    const double x = -70.0 + 140.0 * next();
    const double y = 5.0 + 100.0 * next();
    const double tx = -60.0 + 120.0 * next();
    rays.push_back(i % 2 == 0 ? Ray{x, 110.0, tx, -1.0} : Ray{-80.0, y, 80.0, y * next()});
  }
  return rays;
}

}  // namespace

int main(int argc, char** argv) {
  const int count = argc > 1 ? std::atoi(argv[1]) : 100000;
  if (count < 1 || count > 10000000) {
    std::fprintf(stderr, "usage: rewind-rays2d [RAYS]   (1..10000000, default 100000)\n");
    return 2;
  }
  rwd::bench::Scene2D scene;
  rwd::bench::make_scene2d("large_pyramid", 100, scene);
  // Rewind first and Box2D 2.4 second: agree_pct compares against them.
  std::vector<std::unique_ptr<Engine2D>> engines;
  engines.push_back(std::make_unique<rwd::bench::Rewind2DEngine>(4, 1));
  engines.push_back(std::make_unique<rwd::bench::Box2DEngine>(8, 3));
#ifdef REWIND_HAVE_BOX2D3
  engines.push_back(std::make_unique<rwd::bench::Box2D3Engine>(4));
#endif
  const size_t n = engines.size();
  for (const auto& e : engines) {
    std::string error;
    if (!e->build(scene, error)) {
      std::fprintf(stderr, "rewind-rays2d: %s\n", error.c_str());
      return 1;
    }
    // Not stepped: every engine answers for the same poses (the settled
    // pyramids would differ by the engines' own sag).
  }
  const std::vector<Ray> rays = make_rays(count);
  std::vector<double> seconds(n, 0.0);
  std::vector<int> hits(n, 0);
  std::vector<double> fraction(n * rays.size(), -1.0);  // ray i, engine k at n * i + k
  const size_t block = 1000;
  for (size_t start = 0; start < rays.size(); start += block) {
    const size_t end = std::min(rays.size(), start + block);
    for (size_t k = 0; k < n; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      for (size_t i = start; i < end; ++i) {
        double f = 0.0;
        if (engines[k]->raycast(rays[i].x0, rays[i].y0, rays[i].x1, rays[i].y1, f)) {
          fraction[n * i + k] = f;
          ++hits[k];
        }
      }
      seconds[k] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
  }
  // Rays engines j and k answer alike.
  auto agree = [&](size_t j, size_t k) {
    int alike = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      const double a = fraction[n * i + j];
      const double b = fraction[n * i + k];
      const double length = std::hypot(rays[i].x1 - rays[i].x0, rays[i].y1 - rays[i].y0);
      if ((a < 0 && b < 0) || (a >= 0 && b >= 0 && std::fabs(a - b) * length <= 0.0101)) ++alike;
    }
    return alike;
  };
  std::printf("engine,settings,rays,rays_per_s,hits,agree_pct\n");
  for (size_t k = 0; k < n; ++k) {
    const int alike = agree(0, k == 0 ? 1 : k);
    std::printf("%s,%s,%d,%.0f,%d,%.2f\n", engines[k]->name().c_str(),
                engines[k]->settings().c_str(), count, count / seconds[k], hits[k],
                100.0 * alike / count);
  }
  return 0;
}
