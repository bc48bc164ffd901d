// SPDX-License-Identifier: MIT
#pragma once
// Building blocks the scenes share: body specs, a scene base that creates
// and remembers its bodies, and observers for resting boxes.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "rewind/scenes/scene.h"

namespace rwd::scenes::kit {

constexpr float kPi = 3.14159265358979f;

inline float radians(float degrees) {
  return degrees * kPi / 180.0f;
}

/// Rotation by `angle` radians about the unit axis.
inline Quat axis_angle(Vec3 axis, float angle) {
  float s = std::sin(0.5f * angle);
  return {axis.x * s, axis.y * s, axis.z * s, std::cos(0.5f * angle)};
}

inline float horizontal_distance(Vec3 a, Vec3 b) {
  float dx = a.x - b.x;
  float dz = a.z - b.z;
  return std::sqrt(dx * dx + dz * dz);
}

inline BodySpec box(Vec3 position, Vec3 half_extents, float friction = 0.6f) {
  BodySpec s;
  s.shape = Shape::make_box(half_extents);
  s.position = position;
  s.friction = friction;
  return s;
}

inline BodySpec sphere(Vec3 position, float radius, float friction = 0.6f) {
  BodySpec s;
  s.shape = Shape::make_sphere(radius);
  s.position = position;
  s.friction = friction;
  return s;
}

/// A capsule of `radius` whose cap centres are half_height from its centre
/// along its local y axis.
inline BodySpec capsule(Vec3 position, float radius, float half_height, float friction = 0.6f) {
  BodySpec s;
  s.shape = Shape::make_capsule(radius, half_height);
  s.position = position;
  s.friction = friction;
  return s;
}

/// A body of a hull shape (SpecScene::add_hull) whose points' origin is at
/// `position`.
inline BodySpec hull(Shape shape, Vec3 position, float friction = 0.6f) {
  BodySpec s;
  s.shape = shape;
  s.position = position;
  s.friction = friction;
  return s;
}

/// The corners of a prism standing on the plane y = 0 (its points' origin
/// is the centre of its base): a regular `sides`-gon of circumradius
/// `radius`, `height` tall.
inline std::vector<Vec3> prism_points(int sides, float radius, float height) {
  std::vector<Vec3> points;
  for (float y : {0.0f, height}) {
    for (int i = 0; i < sides; ++i) {
      const float a = 2.0f * kPi * static_cast<float>(i) / static_cast<float>(sides);
      points.push_back({radius * std::cos(a), y, radius * std::sin(a)});
    }
  }
  return points;
}

/// The corners of a rock: an icosahedron stretched to half sizes `half`
/// about its centre (every vertex stays a corner).
inline std::vector<Vec3> rock_points(Vec3 half) {
  const float g = 1.6180339887f;  // the golden ratio
  const float n = 1.0f / std::sqrt(1.0f + g * g);
  std::vector<Vec3> points;
  for (float s1 : {-1.0f, 1.0f}) {
    for (float s2 : {-1.0f, 1.0f}) {
      points.push_back({0.0f, s1 * n, s2 * g * n});
      points.push_back({s1 * n, s2 * g * n, 0.0f});
      points.push_back({s2 * g * n, 0.0f, s1 * n});
    }
  }
  for (Vec3& p : points) p = {p.x * half.x, p.y * half.y, p.z * half.z};
  return points;
}

inline BodySpec fixed(BodySpec s) {
  s.kind = BodyKind::kStatic;
  return s;
}

/// A static slab whose top face is the plane y = top_y, centred on (x, z).
inline BodySpec ground(float top_y = 0.0f, float x = 0.0f, float z = 0.0f, float friction = 0.6f) {
  return fixed(box({x, top_y - 0.5f, z}, {50.0f, 0.5f, 50.0f}, friction));
}

/// A scene that adds the bodies of `specs_` in build() and keeps their handles.
class SpecScene : public Scene {
 public:
  uint32_t body_capacity() const override { return static_cast<uint32_t>(specs_.size()); }
  /// Registers the scene's geometry with the engine, then adds its bodies,
  /// each shape of registered geometry pointing at the id the engine gave.
  bool build(Engine& engine, std::string& error) override {
    handles_.clear();
    std::vector<sim::GeometryId> ids;
    for (const Geometry& g : geometry_) {
      sim::GeometryId id;
      bool ok = false;
      if (g.kind == sim::ShapeType::kCompound) {
        // Children of registered geometry (hulls) point at the engine's ids.
        std::vector<sim::CompoundChild> children = g.children;
        for (sim::CompoundChild& c : children) {
          if (c.shape.uses_geometry()) c.shape.geometry = ids[c.shape.geometry].value;
        }
        ok = engine.add_compound(children, id, error);
      } else if (g.kind == sim::ShapeType::kHull) {
        ok = engine.add_hull(g.points, id, error);
      } else if (g.kind == sim::ShapeType::kMesh) {
        ok = engine.add_mesh(g.points, g.indices, id, error);
      } else {
        ok = engine.add_height_field(g.rows, g.cols, g.scale, g.heights, id, error);
      }
      if (!ok) return false;
      ids.push_back(id);
    }
    for (BodySpec s : specs_) {
      if (s.shape.uses_geometry()) s.shape.geometry = ids[s.shape.geometry].value;
      BodyHandle h = 0;
      if (!engine.add_body(s, h, error)) return false;
      handles_.push_back(h);
    }
    return true;
  }

 protected:
  explicit SpecScene(int size) : Scene(size) {}
  /// Adds a spec; returns its index in specs_ (and handles_ after build).
  size_t add(const BodySpec& s) {
    specs_.push_back(s);
    return specs_.size() - 1;
  }
  /// Adds a hull's corners (m, in the frame bodies of it are placed by);
  /// returns the shape bodies of it take (its id is the scene's own index
  /// until build() maps it to the engine's).
  Shape add_hull(std::vector<Vec3> points) {
    Geometry g;
    g.kind = sim::ShapeType::kHull;
    g.points = std::move(points);
    geometry_.push_back(std::move(g));
    return Shape::make_hull(next_geometry());
  }
  /// The same for a compound (Engine::add_compound); hull children name the
  /// scene's own hull shapes (add_hull's).
  Shape add_compound(std::vector<sim::CompoundChild> children) {
    Geometry g;
    g.kind = sim::ShapeType::kCompound;
    g.children = std::move(children);
    geometry_.push_back(std::move(g));
    return Shape::make_compound(next_geometry());
  }
  /// The same for a triangle mesh (Engine::add_mesh).
  Shape add_mesh(std::vector<Vec3> vertices, std::vector<uint32_t> indices) {
    Geometry g;
    g.kind = sim::ShapeType::kMesh;
    g.points = std::move(vertices);
    g.indices = std::move(indices);
    geometry_.push_back(std::move(g));
    return Shape::make_mesh(next_geometry());
  }
  /// The same for a height field (Engine::add_height_field).
  Shape add_height_field(uint32_t rows, uint32_t cols, Vec3 scale, std::vector<float> heights) {
    Geometry g;
    g.kind = sim::ShapeType::kHeightField;
    g.rows = rows;
    g.cols = cols;
    g.scale = scale;
    g.heights = std::move(heights);
    geometry_.push_back(std::move(g));
    return Shape::make_height_field(next_geometry());
  }
  std::vector<BodySpec> specs_;
  std::vector<BodyHandle> handles_;

 private:
  struct Geometry {
    sim::ShapeType kind = sim::ShapeType::kHull;
    std::vector<Vec3> points;  // hull corners or mesh vertices
    std::vector<uint32_t> indices;
    uint32_t rows = 0;
    uint32_t cols = 0;
    Vec3 scale;
    std::vector<float> heights;
    std::vector<sim::CompoundChild> children;
  };
  sim::GeometryId next_geometry() const {
    return sim::GeometryId{static_cast<uint32_t>(geometry_.size() - 1)};
  }
  std::vector<Geometry> geometry_;
};

/// Boxes resting on one another: records how far each wanders sideways from
/// where it started, and how deep each resting pair overlaps (from centre
/// heights). A pair counts only while it is still in place (its sideways
/// offset within 0.25 m of the start), so a fallen stack reports the
/// overlaps of what still stands rather than heights of boxes on the floor.
class RestingBoxes {
 public:
  struct Support {
    int lower = -1;          ///< body index, or -1 for the ground plane
    int upper = 0;           ///< body index
    float centre_gap_m = 0;  ///< centre height difference when just touching
  };

  void track(int body, Vec3 start) {
    if (static_cast<size_t>(body) >= start_.size()) start_.resize(body + 1, Vec3{});
    if (static_cast<size_t>(body) >= tracked_.size()) tracked_.resize(body + 1, false);
    start_[body] = start;
    tracked_[body] = true;
  }
  void support(int lower, int upper, float centre_gap_m) {
    supports_.push_back({lower, upper, centre_gap_m});
  }
  /// The y of the ground plane a Support with lower = -1 measures against.
  void set_ground(float top_y) { ground_y_ = top_y; }

  /// Updates drift; when `measure_depth`, updates the deepest overlap too.
  void observe(const Engine& engine, const std::vector<BodyHandle>& handles, bool measure_depth) {
    for (size_t i = 0; i < tracked_.size(); ++i) {
      if (!tracked_[i]) continue;
      Vec3 p = engine.position(handles[i]);
      float d = horizontal_distance(p, start_[i]);
      if (!engine.enabled(handles[i]) || !std::isfinite(d)) d = 1e9f;
      if (d > drift_m_) drift_m_ = d;
      float drop = start_[i].y - p.y;
      if (drop > drop_m_ || !std::isfinite(drop)) drop_m_ = std::isfinite(drop) ? drop : 1e9f;
    }
    if (!measure_depth) return;
    for (const Support& s : supports_) {
      const Vec3 upper = engine.position(handles[s.upper]);
      float lower_y = ground_y_;
      if (s.lower >= 0) {
        const Vec3 lower = engine.position(handles[s.lower]);
        const float offset = horizontal_distance(upper, lower);
        const float start_offset = horizontal_distance(start_[s.upper], start_[s.lower]);
        if (!(std::fabs(offset - start_offset) <= 0.25f)) continue;
        lower_y = lower.y;
      } else if (!(horizontal_distance(upper, start_[s.upper]) <= 0.25f)) {
        continue;
      }
      float depth = s.centre_gap_m - (upper.y - lower_y);
      if (depth > depth_m_) depth_m_ = depth;
    }
  }

  float drift_m() const { return drift_m_; }
  float drop_m() const { return drop_m_; }
  /// Deepest overlap seen; NaN (which fails every criterion) once a box has
  /// moved more than 0.25 m sideways: the structure fell, and the overlaps
  /// of what is left standing say nothing about resting contact.
  float depth_m() const {
    return drift_m_ > 0.25f ? std::numeric_limits<float>::quiet_NaN() : depth_m_;
  }

 private:
  std::vector<Vec3> start_;
  std::vector<bool> tracked_;
  std::vector<Support> supports_;
  float ground_y_ = 0.0f;
  float drift_m_ = 0.0f;
  float drop_m_ = 0.0f;
  float depth_m_ = 0.0f;
};

/// Speed bound of every point of a body: |v| + extent * |w|.
inline float point_speed(const Engine& engine, BodyHandle h, float extent_m) {
  return std::sqrt(sim::length_squared(engine.linear_velocity(h))) +
         extent_m * std::sqrt(sim::length_squared(engine.angular_velocity(h)));
}

inline Metric at_most(std::string name, std::string unit, double value, double limit,
                      std::string criterion) {
  return {std::move(name),        std::move(unit), value,
          Metric::Bound::kAtMost, limit,           std::move(criterion)};
}
inline Metric at_least(std::string name, std::string unit, double value, double limit,
                       std::string criterion) {
  return {std::move(name),         std::move(unit), value,
          Metric::Bound::kAtLeast, limit,           std::move(criterion)};
}

/// Relative error in percent.
inline double error_pct(double measured, double expected) {
  return 100.0 * std::fabs(measured - expected) / std::fabs(expected);
}

}  // namespace rwd::scenes::kit
