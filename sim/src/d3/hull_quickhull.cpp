// SPDX-License-Identifier: MIT
// The exact triangle hull: Quickhull on the builder's integer grid. Every
// "is this point above that face" is decided exactly (side_of_plane), so
// the visible region of a new point is always a disk, its horizon one
// loop, and no edge of the result is concave. Doubles only measure how far
// a point is from the hull, to pick the next one and to skip the ones
// within the slack; they never decide the structure.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "d3/hull_build_steps.h"

namespace rwd::sim::d3::hull_steps {

GridNormal grid_normal(GridPoint a, GridPoint b, GridPoint c) {
  // Differences fit 31 bits, so each product fits 61 and the result 62.
  const int64_t ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  const int64_t vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  return {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
}

int side_of_plane(const GridNormal& n, GridPoint a, GridPoint p) {
  // dot(n, p - a) needs up to 94 bits. Split each normal component as
  // hi * 2^31 + lo with 0 <= lo < 2^31 (C++20 shifts are arithmetic): each
  // partial product then fits 62 bits and each sum of three 64.
  constexpr int64_t kLowMask = (int64_t{1} << 31) - 1;
  const int64_t n3[3] = {n.x, n.y, n.z};
  const int64_t d3[3] = {p.x - a.x, p.y - a.y, p.z - a.z};
  int64_t hi = 0;
  int64_t lo = 0;
  for (int i = 0; i < 3; ++i) {
    hi += (n3[i] >> 31) * d3[i];
    lo += (n3[i] & kLowMask) * d3[i];
  }
  hi += lo >> 31;  // the value is hi * 2^31 + lo with 0 <= lo < 2^31
  lo &= kLowMask;
  if (hi != 0) return hi > 0 ? 1 : -1;
  return lo != 0 ? 1 : 0;
}

namespace {

GridPoint minus(GridPoint a, GridPoint b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}

int64_t axis_value(GridPoint p, int axis) {
  return axis == 0 ? p.x : (axis == 1 ? p.y : p.z);
}

DVec3 unit_normal(const GridNormal& n) {
  const DVec3 d{static_cast<double>(n.x), static_cast<double>(n.y), static_cast<double>(n.z)};
  return d * (1.0 / std::sqrt(dot(d, d)));
}

// Distance from p to the triangle a b c (Ericson, Real-Time Collision
// Detection 5.1.5: the Voronoi region of p), all relative to a so the
// differences are exact.
double triangle_distance(GridPoint p, GridPoint a, GridPoint b, GridPoint c) {
  const DVec3 ab = to_dvec(minus(b, a));
  const DVec3 ac = to_dvec(minus(c, a));
  const DVec3 ap = to_dvec(minus(p, a));
  auto gap = [&](DVec3 closest) {
    const DVec3 d = ap - closest;
    return std::sqrt(dot(d, d));
  };
  const double d1 = dot(ab, ap);
  const double d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return gap({});
  const DVec3 bp = ap - ab;
  const double d3 = dot(ab, bp);
  const double d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return gap(ab);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return gap(ab * (d1 / (d1 - d3)));
  const DVec3 cp = ap - ac;
  const double d5 = dot(ab, cp);
  const double d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return gap(ac);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return gap(ac * (d2 / (d2 - d6)));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    return gap(ab + (ac - ab) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
  }
  const double denom = 1.0 / (va + vb + vc);
  return gap(ab * (vb * denom) + ac * (vc * denom));
}

class QuickHull {
 public:
  QuickHull(std::span<const GridPoint> points, double slack)
      : points_(points), slack_(slack), mark_(points.size(), 0) {}

  TriHull run(std::span<const uint32_t> subset, uint32_t max_vertices) {
    TriHull out;
    uint32_t simplex[4];
    out.shape = initial_simplex(subset, simplex, out.plane);
    if (out.shape != TriHullShape::kSolid) return out;
    for (uint32_t p : subset) {
      if (p != simplex[0] && p != simplex[1] && p != simplex[2] && p != simplex[3]) assign(p);
    }
    uint32_t vertex_count = 4;
    while (true) {
      uint32_t best = kNone;
      for (uint32_t f : alive_) {
        if (faces_[f].far != kNone && (best == kNone || farther(faces_[f], faces_[best]))) best = f;
      }
      if (best == kNone) break;
      // Distances only shrink as the hull grows, and only the points of
      // removed faces were measured again: refresh the front runner first.
      if (!refresh_far(faces_[best])) continue;
      if (vertex_count >= max_vertices) {
        out.capped = true;
        break;
      }
      uint32_t removed = 0;
      if (!insert(faces_[best].far, best, removed)) {
        out.shape = TriHullShape::kFailed;
        return out;
      }
      vertex_count = vertex_count + 1 - removed;
    }
    collect(out);
    return out;
  }

 private:
  struct Face {
    uint32_t v[3] = {0, 0, 0};
    uint32_t adj[3] = {kNone, kNone, kNone};
    GridNormal n;
    DVec3 unit;
    std::vector<uint32_t> outside;  // points assigned to this face
    std::vector<double> distance;   // and their distance from the hull when measured
    uint32_t far = kNone;           // the farthest of them (ties to the lower index)
    double far_distance = 0.0;
    uint32_t visit = 0;    // the insertion that last tested this face
    bool visible = false;  // and its answer
    bool alive = true;
  };

  static bool farther(const Face& f, const Face& g) {
    return f.far_distance > g.far_distance || (f.far_distance == g.far_distance && f.far < g.far);
  }

  bool above(const Face& f, uint32_t p) const {
    return side_of_plane(f.n, points_[f.v[0]], points_[p]) > 0;
  }

  double plane_distance(const Face& f, uint32_t p) const {
    return dot(f.unit, to_dvec(minus(points_[p], points_[f.v[0]])));
  }

  // Distance from p, outside, to the hull: to the nearest face it lies
  // above (the nearest point of the hull is on one of those).
  double hull_distance(uint32_t p) const {
    double best = -1.0;
    for (uint32_t f : alive_) {
      const Face& face = faces_[f];
      if (!above(face, p)) continue;
      const double d =
          triangle_distance(points_[p], points_[face.v[0]], points_[face.v[1]], points_[face.v[2]]);
      if (best < 0.0 || d < best) best = d;
    }
    return best;
  }

  bool keep(double distance) const { return !(slack_ > 0.0 && distance <= slack_); }

  void update_far(Face& f) {
    f.far = kNone;
    for (size_t k = 0; k < f.outside.size(); ++k) {
      const uint32_t p = f.outside[k];
      const double d = f.distance[k];
      if (f.far == kNone || d > f.far_distance || (d == f.far_distance && p < f.far)) {
        f.far = p;
        f.far_distance = d;
      }
    }
  }

  // Measures f's farthest point again. True if its distance held; else
  // records the new one (dropping the point once within the slack).
  bool refresh_far(Face& f) {
    const double d = hull_distance(f.far);
    if (d == f.far_distance) return true;
    const size_t k = static_cast<size_t>(std::find(f.outside.begin(), f.outside.end(), f.far) -
                                         f.outside.begin());
    if (keep(d)) {
      f.distance[k] = d;
    } else {
      f.outside.erase(f.outside.begin() + static_cast<std::ptrdiff_t>(k));
      f.distance.erase(f.distance.begin() + static_cast<std::ptrdiff_t>(k));
    }
    update_far(f);
    return false;
  }

  uint32_t add_face(uint32_t a, uint32_t b, uint32_t c) {
    Face f;
    f.v[0] = a;
    f.v[1] = b;
    f.v[2] = c;
    f.n = grid_normal(points_[a], points_[b], points_[c]);
    f.unit = unit_normal(f.n);
    faces_.push_back(std::move(f));
    return static_cast<uint32_t>(faces_.size() - 1);
  }

  // The widest axis' two extremes, the point farthest from their line and
  // the point farthest from the plane of the three (ties to the lower
  // index; "zero" decided exactly).
  TriHullShape initial_simplex(std::span<const uint32_t> subset, uint32_t s[4], uint32_t plane[3]) {
    if (subset.empty()) return TriHullShape::kCoincident;
    int axis = -1;
    int64_t spread = 0;
    uint32_t lo_best = kNone;
    uint32_t hi_best = kNone;
    for (int a = 0; a < 3; ++a) {
      uint32_t lo = subset[0];
      uint32_t hi = subset[0];
      for (uint32_t p : subset) {
        const int64_t v = axis_value(points_[p], a);
        const int64_t vl = axis_value(points_[lo], a);
        const int64_t vh = axis_value(points_[hi], a);
        if (v < vl || (v == vl && p < lo)) lo = p;
        if (v > vh || (v == vh && p < hi)) hi = p;
      }
      const int64_t w = axis_value(points_[hi], a) - axis_value(points_[lo], a);
      if (w > spread) {
        spread = w;
        axis = a;
        lo_best = lo;
        hi_best = hi;
      }
    }
    if (axis < 0) return TriHullShape::kCoincident;
    s[0] = lo_best;
    s[1] = hi_best;

    const GridPoint a = points_[s[0]];
    const GridPoint line = minus(points_[s[1]], a);
    s[2] = kNone;
    double best = -1.0;
    for (uint32_t p : subset) {
      const GridPoint d = minus(points_[p], a);
      const GridNormal c = grid_normal({}, d, line);
      if (c.x == 0 && c.y == 0 && c.z == 0) continue;
      const DVec3 cd{static_cast<double>(c.x), static_cast<double>(c.y), static_cast<double>(c.z)};
      const double m = dot(cd, cd);
      if (m > best || (m == best && p < s[2])) {
        best = m;
        s[2] = p;
      }
    }
    if (s[2] == kNone) return TriHullShape::kCollinear;

    const GridNormal n = grid_normal(a, points_[s[1]], points_[s[2]]);
    const DVec3 u = unit_normal(n);
    s[3] = kNone;
    best = -1.0;
    for (uint32_t p : subset) {
      if (side_of_plane(n, a, points_[p]) == 0) continue;
      const double m = std::fabs(dot(u, to_dvec(minus(points_[p], a))));
      if (m > best || (m == best && p < s[3])) {
        best = m;
        s[3] = p;
      }
    }
    if (s[3] == kNone) {
      plane[0] = s[0];
      plane[1] = s[1];
      plane[2] = s[2];
      return TriHullShape::kCoplanar;
    }
    // Faces counter-clockwise from outside need the fourth point below
    // the first face.
    if (side_of_plane(n, a, points_[s[3]]) > 0) {
      const uint32_t t = s[1];
      s[1] = s[2];
      s[2] = t;
    }
    const uint32_t f[4] = {add_face(s[0], s[1], s[2]), add_face(s[0], s[3], s[1]),
                           add_face(s[1], s[3], s[2]), add_face(s[2], s[3], s[0])};
    for (uint32_t i : f) {
      for (int e = 0; e < 3; ++e) {
        const uint32_t from = faces_[i].v[e];
        const uint32_t to = faces_[i].v[(e + 1) % 3];
        for (uint32_t j : f) {
          for (int k = 0; k < 3; ++k) {
            if (faces_[j].v[k] == to && faces_[j].v[(k + 1) % 3] == from) faces_[i].adj[e] = j;
          }
        }
      }
      alive_.push_back(i);
    }
    return TriHullShape::kSolid;
  }

  // Gives p to the live face it lies farthest above (exactly above), if it
  // is farther from the hull than the slack; else drops it: it is inside
  // the hull, or near enough, and stays so as the hull grows.
  void assign(uint32_t p) {
    uint32_t best = kNone;
    double best_height = 0.0;
    for (uint32_t f : alive_) {
      if (!above(faces_[f], p)) continue;
      const double h = plane_distance(faces_[f], p);
      if (best == kNone || h > best_height) {
        best = f;
        best_height = h;
      }
    }
    if (best == kNone) return;
    const double d = hull_distance(p);
    if (!keep(d)) return;
    Face& f = faces_[best];
    f.outside.push_back(p);
    f.distance.push_back(d);
    if (f.far == kNone || d > f.far_distance || (d == f.far_distance && p < f.far)) {
      f.far = p;
      f.far_distance = d;
    }
  }

  struct HorizonEdge {
    uint32_t a;
    uint32_t b;
    uint32_t beyond;  // the face on the far side, which stays
  };

  // Adds point p, which lies above face `start`: removes the faces it sees,
  // closes the hole with a fan of new faces about p, and hands the points
  // of the removed faces back out. `removed` counts vertices that fell
  // inside. False if the horizon is not one loop.
  bool insert(uint32_t p, uint32_t start, uint32_t& removed) {
    ++stamp_;
    visible_.clear();
    visible_.push_back(start);
    faces_[start].visit = stamp_;
    faces_[start].visible = true;
    for (size_t k = 0; k < visible_.size(); ++k) {
      for (uint32_t g : faces_[visible_[k]].adj) {
        Face& fg = faces_[g];
        if (fg.visit == stamp_) continue;
        fg.visit = stamp_;
        fg.visible = above(fg, p);
        if (fg.visible) visible_.push_back(g);
      }
    }
    horizon_.clear();
    for (uint32_t f : visible_) {
      for (int i = 0; i < 3; ++i) {
        const uint32_t g = faces_[f].adj[i];
        if (!faces_[g].visible) horizon_.push_back({faces_[f].v[i], faces_[f].v[(i + 1) % 3], g});
      }
    }
    // Chain the horizon edges into one loop.
    for (size_t k = 1; k < horizon_.size(); ++k) {
      size_t next = k;
      while (next < horizon_.size() && horizon_[next].a != horizon_[k - 1].b) ++next;
      if (next == horizon_.size()) return false;
      const HorizonEdge t = horizon_[k];
      horizon_[k] = horizon_[next];
      horizon_[next] = t;
    }
    if (horizon_.size() < 3 || horizon_.back().b != horizon_[0].a) return false;

    // Vertices of the removed faces that are not on the horizon are gone.
    for (const HorizonEdge& e : horizon_) mark_[e.a] = stamp_;
    removed = 0;
    for (uint32_t f : visible_) {
      for (uint32_t v : faces_[f].v) {
        if (mark_[v] != stamp_) {
          mark_[v] = stamp_;
          ++removed;
        }
      }
    }

    const uint32_t first = static_cast<uint32_t>(faces_.size());
    const uint32_t count = static_cast<uint32_t>(horizon_.size());
    for (uint32_t k = 0; k < count; ++k) {
      const HorizonEdge& e = horizon_[k];
      const uint32_t nf = add_face(e.a, e.b, p);
      Face& f = faces_[nf];
      if (f.n.x == 0 && f.n.y == 0 && f.n.z == 0) return false;
      f.adj[0] = e.beyond;
      f.adj[1] = first + (k + 1) % count;
      f.adj[2] = first + (k + count - 1) % count;
      Face& beyond = faces_[e.beyond];
      for (int j = 0; j < 3; ++j) {
        if (beyond.v[j] == e.b && beyond.v[(j + 1) % 3] == e.a) beyond.adj[j] = nf;
      }
    }

    orphans_.clear();
    for (uint32_t f : visible_) {
      Face& face = faces_[f];
      for (uint32_t q : face.outside) {
        if (q != p) orphans_.push_back(q);
      }
      face.outside = {};
      face.distance = {};
      face.far = kNone;
      face.alive = false;
    }
    size_t live = 0;
    for (uint32_t f : alive_) {
      if (faces_[f].alive) alive_[live++] = f;
    }
    alive_.resize(live);
    for (uint32_t k = 0; k < count; ++k) alive_.push_back(first + k);
    for (uint32_t q : orphans_) assign(q);
    return true;
  }

  // The live faces in creation order, renumbered.
  void collect(TriHull& out) {
    std::vector<uint32_t> index(faces_.size(), kNone);
    for (uint32_t i = 0; i < alive_.size(); ++i) index[alive_[i]] = i;
    ++stamp_;
    for (uint32_t f : alive_) {
      TriFace t;
      for (int k = 0; k < 3; ++k) {
        t.v[k] = faces_[f].v[k];
        t.adj[k] = index[faces_[f].adj[k]];
        if (mark_[t.v[k]] != stamp_) {
          mark_[t.v[k]] = stamp_;
          out.vertices.push_back(t.v[k]);
        }
      }
      out.faces.push_back(t);
    }
    std::sort(out.vertices.begin(), out.vertices.end());  // distinct indices: one order
  }

  std::span<const GridPoint> points_;
  double slack_;
  std::vector<Face> faces_;
  std::vector<uint32_t> alive_;  // live faces, ascending
  std::vector<uint32_t> visible_;
  std::vector<HorizonEdge> horizon_;
  std::vector<uint32_t> orphans_;
  std::vector<uint32_t> mark_;  // per point: the stamp that last touched it
  uint32_t stamp_ = 0;
};

}  // namespace

TriHull build_tri_hull(std::span<const GridPoint> points, std::span<const uint32_t> subset,
                       double slack, uint32_t max_vertices) {
  QuickHull qh(points, slack);
  return qh.run(subset, max_vertices);
}

double distance_to_faces(std::span<const GridPoint> points, std::span<const TriFace> faces,
                         GridPoint p, uint32_t skip) {
  double best = -1.0;
  for (const TriFace& f : faces) {
    if (f.v[0] == skip || f.v[1] == skip || f.v[2] == skip) continue;
    const double d = triangle_distance(p, points[f.v[0]], points[f.v[1]], points[f.v[2]]);
    if (best < 0.0 || d < best) best = d;
  }
  return best;
}

}  // namespace rwd::sim::d3::hull_steps
