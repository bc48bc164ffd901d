// SPDX-License-Identifier: MIT
#pragma once
// The broadphase: one structure that both the step (candidate pairs) and
// every query (boxes, rays, sweeps) and continuous collision ask which
// bodies may touch a region. Each kind of body is held the way it moves:
//   - awake bodies are swept and pruned along the axis where their centres
//     spread most, in an order kept from step to step (a scene that moved a
//     little re-sorts in one pass), their bounds copied beside that order
//     so the sweep reads memory in sequence;
//   - sleeping bodies live in an AABB tree they enter when they fall asleep
//     and leave when they wake;
//   - static bodies live in a four-wide tree (wide_box_tree.h) built in
//     bulk and rebuilt only when the world is edited;
//   - for queries, the awake bodies also get a four-wide tree over their
//     exact bounds, built the first time a query needs it after they
//     moved, so a world nobody queries never pays for it.
// Resting and static geometry costs nothing per step, and a query through
// a level of 10,000 static boxes walks a tree instead of a list.
//
// Nothing here is state. The sweep axis and the shape of the trees depend
// on history and differ after a restore, so callers decide on exact bounds
// or exact shapes and sort what they keep: pairs come out sorted by
// (a, b), and queries report candidates whose order they must not rely on.
#include <cstdint>
#include <span>
#include <vector>

#include "d3/aabb_tree.h"
#include "d3/wide_box_tree.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

struct BodyPair {
  uint32_t a;  ///< lower index
  uint32_t b;  ///< higher index
};

class Broadphase {
 public:
  /// The world was edited (bodies created, destroyed, moved by hand,
  /// enabled or disabled, or the state restored): the trees are rebuilt in
  /// bulk before their next use.
  void mark_edited();

  /// Brings the broadphase to the state at the start of a step. `awake`
  /// lists the awake movable bodies, ascending; `bounds[i]` is body i's
  /// box for pairing this step (fattened by what it may reach).
  void update(const WorldState& state, std::span<const uint32_t> awake,
              std::span<const Aabb> bounds);

  /// Candidate pairs of the last update (given the same `bounds`) into
  /// `out` (cleared first), sorted by (a, b): both bodies' bounds overlap
  /// and the layers and kinds allow a contact or a trigger (never two
  /// static bodies).
  void find_pairs(const WorldState& state, std::span<const Aabb> bounds,
                  std::vector<BodyPair>& out);

  /// Readies the query side for the poses in `state`. `pose_serial`
  /// names those poses (the step they were reached in): nothing is done
  /// until it changes, or after an edit or forget_poses().
  void prepare_queries(const WorldState& state, uint64_t pose_serial);
  /// The awake bodies moved without a new serial (mid-step): the next
  /// prepare_queries() rebuilds the awake tree.
  void forget_poses() { query_serial_ = kNoSerial; }

  /// Calls visit(body) for every simulated body whose exact bounds overlap
  /// `box`. Valid after prepare_queries() until the bodies move.
  template <typename Visit>
  void query(const Aabb& box, Visit&& visit) const {
    static_tree_.query(box, visit);
    sleeping_tree_.query(box, visit);
    awake_tree_.query(box, visit);
  }
  /// Same, for the bounds the segment origin + t * dir, 0 <= t <= max_t,
  /// touches.
  template <typename Visit>
  void ray_query(Vec3 origin, Vec3 dir, float max_t, Visit&& visit) const {
    static_tree_.ray_query(origin, dir, max_t, visit);
    sleeping_tree_.ray_query(origin, dir, max_t, visit);
    awake_tree_.ray_query(origin, dir, max_t, visit);
  }
  /// For the closest hit (AabbTree::ray_query_nearest): every tree near to
  /// far, `reach` shortened by visit(body) as it finds hits.
  template <typename Visit>
  void ray_query_nearest(Vec3 origin, Vec3 dir, float& reach, Visit&& visit) const {
    static_tree_.ray_query_nearest(origin, dir, reach, visit);
    sleeping_tree_.ray_query_nearest(origin, dir, reach, visit);
    awake_tree_.ray_query_nearest(origin, dir, reach, visit);
  }
  /// Same, for the bounds the box `start` touches on its way along
  /// `translation`.
  template <typename Visit>
  void sweep_query(const Aabb& start, Vec3 translation, Visit&& visit) const {
    static_tree_.sweep_query(start, translation, visit);
    sleeping_tree_.sweep_query(start, translation, visit);
    awake_tree_.sweep_query(start, translation, visit);
  }
  /// For the closest hit of a sweep (AabbTree::sweep_query_nearest):
  /// every tree near to far, `reach` (a fraction of `translation`)
  /// shortened by visit(body) as it finds hits.
  template <typename Visit>
  void sweep_query_nearest(const Aabb& start, Vec3 translation, float& reach, Visit&& visit) const {
    static_tree_.sweep_query_nearest(start, translation, reach, visit);
    sleeping_tree_.sweep_query_nearest(start, translation, reach, visit);
    awake_tree_.sweep_query_nearest(start, translation, reach, visit);
  }

  /// For tests: the trees' leaf counts (static, sleeping, awake queries).
  uint32_t static_leaves() const { return static_tree_.leaf_count(); }
  uint32_t sleeping_leaves() const { return sleeping_tree_.leaf_count(); }
  uint32_t awake_query_leaves() const { return awake_tree_.leaf_count(); }

 private:
  static constexpr uint64_t kNoSerial = ~0ull;

  void rebuild_trees(const WorldState& state);
  void update_sleeping_tree(const WorldState& state);
  void sort_sweep(const WorldState& state, std::span<const uint32_t> awake,
                  std::span<const Aabb> bounds, int axis);
  size_t sweep_one(size_t k, uint32_t* hits) const;
  void sort_pairs(std::vector<BodyPair>& pairs, uint32_t body_count);

  // trees of exact bounds
  WideBoxTree static_tree_;
  AabbTree sleeping_tree_;
  WideBoxTree awake_tree_;                ///< queries only
  std::vector<uint32_t> sleeping_proxy_;  ///< by body index; AabbTree::kNull if none
  bool edited_ = true;
  /// The awake bodies the sleeping tree was last brought up to date with
  /// in update(): while they and the world stay the same, so do the
  /// sleeping bodies (every movable simulated body that is not awake), and
  /// the tree needs no pass over the bodies.
  std::vector<uint32_t> tree_awake_;
  bool tree_awake_valid_ = false;
  uint64_t query_serial_ = kNoSerial;   ///< pose serial the awake tree was built at
  std::vector<uint32_t> build_bodies_;  ///< bulk-build input
  std::vector<Aabb> build_boxes_;
  std::vector<uint32_t> build_proxies_;
  // the awake bodies' sweep
  std::vector<uint32_t> sweep_order_;
  std::vector<float> sweep_lower_;  ///< on the sweep axis
  std::vector<float> sweep_upper_;
  std::vector<float> sweep_cross_[4];  ///< lower, upper, lower, upper on the other two axes
  std::vector<uint32_t> sweep_hits_;   ///< one body's overlaps, positions in the order
  int sweep_axis_ = 0;
  // pair sort
  std::vector<uint32_t> pair_start_;
  std::vector<BodyPair> pair_spare_;
};

}  // namespace rwd::sim::d3
