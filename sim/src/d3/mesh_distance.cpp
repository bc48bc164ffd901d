// SPDX-License-Identifier: MIT
// The signed distance from a point to a mesh (mesh.h).
//
// Nearest triangle: a depth-first walk of the tree, the nearer child first,
// skipping a node whose box lies farther than the best triangle so far.
// The skip is widened by a few parts per million, so rounding in the box's
// distance cannot skip a triangle tied with the best: the answer is the
// least (squared distance, index) over every triangle, whatever order the
// walk takes.
//
// Sign: the side of the angle-weighted pseudo-normal (Baerentzen and
// Aanaes, "Signed distance computation using the angle weighted
// pseudonormal", 2005) at the nearest point: inside a face its normal; on
// an edge the sum of the normals of the triangles sharing the edge; at a
// vertex the sum of the normals of the triangles meeting there, each
// weighted by its angle at the vertex. For a closed mesh wound
// consistently this is negative exactly inside, including where the
// nearest point is an edge or a vertex, where one face's normal can give
// the wrong side (a point outside a sharp convex edge can lie behind one
// of its faces). For an open mesh it is the side of the surface the point
// is on; a lone triangle's pseudo-normals are all its face normal, so
// every point behind its plane is negative. Triangles share an edge or a
// vertex when their corners have the same coordinates, so a mesh whose
// vertices were not welded still reads as one surface. A pseudo-normal
// that cancels (a sheet folded back onto itself) falls back to the
// nearest triangle's face normal; a point on the surface reads 0.
//
// Cost: the walk visits the nodes near q (about log n of them for a point
// near the surface); the pseudo-normal one more query at the feature.
#include <cmath>

#include "d3/mesh.h"
#include "d3/triangle_closest.h"
#include "rewind/core/det_math.h"

namespace rwd::sim::d3 {
namespace {

// A node is skipped when its box is farther than the best by more than
// this factor on squared distances (about 4 ulps of relative error in the
// box distance and the triangle's).
constexpr float kSkipFactor = 1.0f + 1e-6f;

float box_distance_sq(const Aabb& box, Vec3 q) {
  float sum = 0.0f;
  for (int i = 0; i < 3; ++i) {
    const float v = component(q, i);
    const float lo = component(box.lower, i);
    const float hi = component(box.upper, i);
    const float gap = v < lo ? lo - v : (v > hi ? v - hi : 0.0f);
    sum += gap * gap;
  }
  return sum;
}

void corners(const TriangleMesh& mesh, uint32_t t, Vec3 p[3]) {
  const MeshTriangle& tri = mesh.triangles[t];
  for (int k = 0; k < 3; ++k) p[k] = mesh.vertices[tri.v[k]];
}

struct Nearest {
  uint32_t triangle = 0;
  PointTriangleClosest at;
  bool found = false;
};

Nearest nearest_triangle(const TriangleMesh& mesh, Vec3 q) {
  Nearest best;
  uint32_t stack[2 * kMeshMaxDepth + 2];
  uint32_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& node = mesh.nodes[stack[--top]];
    if (best.found && box_distance_sq(node.box, q) > best.at.distance_sq * kSkipFactor) continue;
    if (node.count == 0) {
      // The nearer child is popped first, so the best shrinks early.
      const float d0 = box_distance_sq(mesh.nodes[node.first].box, q);
      const float d1 = box_distance_sq(mesh.nodes[node.first + 1].box, q);
      const bool second_nearer = d1 < d0;
      stack[top++] = second_nearer ? node.first : node.first + 1;
      stack[top++] = second_nearer ? node.first + 1 : node.first;
      continue;
    }
    for (uint32_t i = 0; i < node.count; ++i) {
      const uint32_t t = mesh.order[node.first + i];
      Vec3 p[3];
      corners(mesh, t, p);
      const PointTriangleClosest c = closest_point_triangle(q, p);
      if (!best.found || c.distance_sq < best.at.distance_sq ||
          (c.distance_sq == best.at.distance_sq && t < best.triangle)) {
        best.triangle = t;
        best.at = c;
        best.found = true;
      }
    }
  }
  return best;
}

// The index of p's corner at v, or 3.
uint32_t corner_at(const Vec3 p[3], Vec3 v) {
  for (uint32_t k = 0; k < 3; ++k) {
    if (p[k] == v) return k;
  }
  return 3;
}

// The (unnormalized) pseudo-normal at the nearest point: of the face, the
// edge or the vertex it lies on. The triangles around an edge or a vertex
// are those whose bounds touch it and that have its corners; the query's
// order is fixed, so the sum is the same bits every time.
Vec3 pseudo_normal(const TriangleMesh& mesh, const Nearest& nearest) {
  const PointTriangleClosest& at = nearest.at;
  if (at.feature == TriangleFeature::kFace) return mesh.triangles[nearest.triangle].normal;
  Vec3 own[3];
  corners(mesh, nearest.triangle, own);
  Vec3 sum;
  if (at.feature == TriangleFeature::kEdge) {
    const Vec3 a = own[at.index];
    const Vec3 b = own[(at.index + 1) % 3];
    mesh_query(mesh, Aabb{min(a, b), max(a, b)}, [&](uint32_t t) {
      Vec3 p[3];
      corners(mesh, t, p);
      if (corner_at(p, a) < 3 && corner_at(p, b) < 3) sum += mesh.triangles[t].normal;
    });
    return sum;
  }
  const Vec3 v = own[at.index];
  mesh_query(mesh, Aabb{v, v}, [&](uint32_t t) {
    Vec3 p[3];
    corners(mesh, t, p);
    const uint32_t k = corner_at(p, v);
    if (k == 3) return;
    const Vec3 e1 = p[(k + 1) % 3] - v;
    const Vec3 e2 = p[(k + 2) % 3] - v;
    const float angle = det_atan2(length(cross(e1, e2)), dot(e1, e2));
    sum += mesh.triangles[t].normal * angle;
  });
  return sum;
}

}  // namespace

SurfaceDistance mesh_signed_distance(const TriangleMesh& mesh, Vec3 q) {
  const Nearest nearest = nearest_triangle(mesh, q);
  const Vec3 face = mesh.triangles[nearest.triangle].normal;
  const Vec3 pseudo = pseudo_normal(mesh, nearest);
  const Vec3 off = q - nearest.at.point;
  float side = dot(off, pseudo);
  if (side == 0.0f) side = dot(off, face);
  const Vec3 unit = normalize_or_zero(pseudo);
  return signed_surface_distance(q, nearest.at, face, side < 0.0f, unit == Vec3{} ? face : unit);
}

}  // namespace rwd::sim::d3
