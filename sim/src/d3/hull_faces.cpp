// SPDX-License-Identifier: MIT
// Polygon faces from the exact triangle hull. Triangles whose corners lie
// within a band of one support plane become one face. The builder only
// merges hulls whose every vertex lies farther than twice the band from
// the hull of the others, so no merged face can have a vertex inside it or
// on a straight stretch of its loop. The checks here catch what still
// slips through (nearly coplanar faces meeting at a very shallow angle)
// and name a vertex to blame; the builder then merges exactly coplanar
// triangles only.
#include <algorithm>
#include <cmath>

#include "d3/hull_build_steps.h"

namespace rwd::sim::d3::hull_steps {
namespace {

struct DirectedEdge {
  uint64_t key;  // from << 32 | to: distinct per edge, so a strict order
  uint32_t face;
};

uint64_t edge_key(uint32_t from, uint32_t to) {
  return (static_cast<uint64_t>(from) << 32) | to;
}

PolygonFaces failure(uint32_t vertex, const char* problem) {
  PolygonFaces out;
  out.bad_vertex = vertex;
  out.problem = problem;
  return out;
}

// Grows face clusters: largest triangle first (ties to the lower index),
// each over neighbours whose corners all lie within `band` of its plane.
std::vector<std::vector<uint32_t>> cluster_triangles(std::span<const GridPoint> points,
                                                     const TriHull& hull, double band) {
  const uint32_t count = static_cast<uint32_t>(hull.faces.size());
  std::vector<DVec3> normal(count);
  std::vector<double> area(count);
  std::vector<uint32_t> order(count);
  for (uint32_t t = 0; t < count; ++t) {
    const TriFace& f = hull.faces[t];
    const GridNormal n = grid_normal(points[f.v[0]], points[f.v[1]], points[f.v[2]]);
    const DVec3 d{static_cast<double>(n.x), static_cast<double>(n.y), static_cast<double>(n.z)};
    area[t] = std::sqrt(dot(d, d));
    normal[t] = d * (1.0 / area[t]);
    order[t] = t;
  }
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return area[a] > area[b] || (area[a] == area[b] && a < b);
  });

  std::vector<uint32_t> claim(count, kNone);
  std::vector<std::vector<uint32_t>> clusters;
  for (uint32_t seed : order) {
    if (claim[seed] != kNone) continue;
    const uint32_t c = static_cast<uint32_t>(clusters.size());
    const DVec3 u = normal[seed];
    // The support plane along the seed's normal: every vertex is behind it.
    double offset = -1e300;
    for (uint32_t v : hull.vertices) offset = std::max(offset, dot(u, to_dvec(points[v])));
    const TriFace& s = hull.faces[seed];
    const GridNormal exact = grid_normal(points[s.v[0]], points[s.v[1]], points[s.v[2]]);
    auto in_band = [&](uint32_t v) {
      if (band == 0.0) return side_of_plane(exact, points[s.v[0]], points[v]) == 0;
      return dot(u, to_dvec(points[v])) >= offset - band;
    };
    clusters.push_back({seed});
    claim[seed] = c;
    for (size_t k = 0; k < clusters[c].size(); ++k) {
      for (uint32_t g : hull.faces[clusters[c][k]].adj) {
        const TriFace& f = hull.faces[g];
        if (claim[g] == kNone && in_band(f.v[0]) && in_band(f.v[1]) && in_band(f.v[2])) {
          claim[g] = c;
          clusters[c].push_back(g);
        }
      }
    }
  }
  return clusters;
}

// The boundary of one cluster as a single loop from its lowest vertex, or
// empty with `bad` set when the cluster is pinched or holed.
std::vector<uint32_t> boundary_loop(const TriHull& hull, const std::vector<uint32_t>& cluster,
                                    const std::vector<uint32_t>& claim, uint32_t c, uint32_t& bad) {
  std::vector<uint32_t> from;
  std::vector<uint32_t> to;
  for (uint32_t t : cluster) {
    const TriFace& f = hull.faces[t];
    for (int i = 0; i < 3; ++i) {
      if (claim[f.adj[i]] == c) continue;
      const uint32_t a = f.v[i];
      if (std::find(from.begin(), from.end(), a) != from.end()) {
        bad = a;  // two boundary edges leave this vertex: the face is pinched
        return {};
      }
      from.push_back(a);
      to.push_back(f.v[(i + 1) % 3]);
    }
  }
  if (from.empty()) {
    bad = hull.faces[cluster[0]].v[0];  // the whole hull within the band: flat
    return {};
  }
  const uint32_t start = *std::min_element(from.begin(), from.end());
  std::vector<uint32_t> loop{start};
  while (true) {
    const size_t k =
        static_cast<size_t>(std::find(from.begin(), from.end(), loop.back()) - from.begin());
    if (k == from.size() || to[k] == start || loop.size() > from.size()) break;
    loop.push_back(to[k]);
  }
  if (loop.size() != from.size() || loop.size() < 3) {
    bad = start;  // more than one boundary loop: a hole
    return {};
  }
  return loop;
}

}  // namespace

PolygonFaces merge_coplanar(std::span<const GridPoint> points, const TriHull& hull, double band) {
  const std::vector<std::vector<uint32_t>> clusters = cluster_triangles(points, hull, band);
  std::vector<uint32_t> claim(hull.faces.size(), kNone);
  for (uint32_t c = 0; c < clusters.size(); ++c) {
    for (uint32_t t : clusters[c]) claim[t] = c;
  }
  PolygonFaces out;
  for (uint32_t c = 0; c < clusters.size(); ++c) {
    uint32_t bad = kNone;
    std::vector<uint32_t> loop = boundary_loop(hull, clusters[c], claim, c, bad);
    if (loop.empty())
      return failure(bad, "nearly coplanar faces around it do not form one convex face");
    out.loops.push_back(std::move(loop));
  }

  // Every vertex on three faces or more: otherwise it sits inside a face or
  // on a straight stretch between two.
  for (uint32_t v : hull.vertices) {
    uint32_t faces = 0;
    for (const std::vector<uint32_t>& loop : out.loops) {
      faces += static_cast<uint32_t>(std::count(loop.begin(), loop.end(), v));
    }
    if (faces < 3) return failure(v, "it lies on fewer than three faces");
  }

  // Each edge twice, once each way; two faces meet along one edge at most.
  std::vector<DirectedEdge> edges;
  for (uint32_t f = 0; f < out.loops.size(); ++f) {
    const std::vector<uint32_t>& loop = out.loops[f];
    for (size_t k = 0; k < loop.size(); ++k) {
      edges.push_back({edge_key(loop[k], loop[(k + 1) % loop.size()]), f});
    }
  }
  std::sort(edges.begin(), edges.end(),
            [](const DirectedEdge& a, const DirectedEdge& b) { return a.key < b.key; });
  auto face_across = [&](uint32_t from, uint32_t to) {
    const uint64_t key = edge_key(to, from);
    auto it = std::lower_bound(edges.begin(), edges.end(), key,
                               [](const DirectedEdge& e, uint64_t k) { return e.key < k; });
    return it != edges.end() && it->key == key ? it->face : kNone;
  };
  for (uint32_t f = 0; f < out.loops.size(); ++f) {
    const std::vector<uint32_t>& loop = out.loops[f];
    std::vector<uint32_t> neighbours;
    for (size_t k = 0; k < loop.size(); ++k) {
      const uint32_t g = face_across(loop[k], loop[(k + 1) % loop.size()]);
      if (g == kNone) return failure(loop[k], "the faces around it do not close");
      if (std::find(neighbours.begin(), neighbours.end(), g) != neighbours.end()) {
        return failure(loop[k], "two faces around it meet along more than one edge");
      }
      neighbours.push_back(g);
    }
  }
  const int64_t euler = static_cast<int64_t>(hull.vertices.size()) -
                        static_cast<int64_t>(edges.size() / 2) +
                        static_cast<int64_t>(out.loops.size());
  if (euler != 2) return failure(hull.vertices[0], "the faces do not form a closed surface");

  // Convex loops, turning left about the face's (Newell) normal.
  for (const std::vector<uint32_t>& loop : out.loops) {
    const size_t n = loop.size();
    const DVec3 base = to_dvec(points[loop[0]]);
    DVec3 normal;
    for (size_t k = 0; k < n; ++k) {
      normal = normal +
               cross(to_dvec(points[loop[k]]) - base, to_dvec(points[loop[(k + 1) % n]]) - base);
    }
    for (size_t k = 0; k < n; ++k) {
      const DVec3 p = to_dvec(points[loop[k]]);
      const DVec3 q = to_dvec(points[loop[(k + 1) % n]]);
      const DVec3 r = to_dvec(points[loop[(k + 2) % n]]);
      if (!(dot(cross(q - p, r - q), normal) > 0.0)) {
        return failure(loop[(k + 1) % n], "a face through it is not convex");
      }
    }
  }
  return out;
}

}  // namespace rwd::sim::d3::hull_steps
