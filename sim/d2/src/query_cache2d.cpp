// SPDX-License-Identifier: MIT
#include "query_cache2d.h"

#include <algorithm>

#include "body_math2d.h"

namespace rwd::sim2d {

using namespace detail;

namespace {

// Leaves hold a few bodies: an exact bounds test is cheaper than a node.
constexpr uint32_t kLeafSize = 4;
// Refits before a full rebuild: the splits were chosen for where the bodies
// were then, and a few seconds of motion make the boxes overlap more.
constexpr uint32_t kMaxRefits = 30;

}  // namespace

bool World2D::QueryCache::refit(const World2DState& state) {
  // The same bodies: as many live, enabled ones as items, each item's still
  // live and enabled (item indices are distinct, so the sets are equal).
  size_t live = 0;
  for (const BodyRecord2D& b : state.bodies) {
    if ((b.flags & kBodyLive) && (b.flags & kBodyEnabled)) ++live;
  }
  if (live != items_.size()) return false;
  for (const Item& item : items_) {
    if (item.index >= state.bodies.size()) return false;
    const BodyRecord2D& b = state.bodies[item.index];
    if (!(b.flags & kBodyLive) || !(b.flags & kBodyEnabled)) return false;
  }
  for (Item& item : items_) {
    const BodyRecord2D& b = state.bodies[item.index];
    item.box = shape_bounds(b.shape, origin_transform(b));
  }
  // Nodes were made parent first, so children come after their parent:
  // walking backwards unites children before their parent needs them.
  for (size_t n = nodes_.size(); n-- > 0;) {
    Node& node = nodes_[n];
    if (node.count > 0) {
      Box2W box = items_[node.first].box;
      for (uint32_t i = node.first + 1; i < node.first + node.count; ++i) {
        box.lower = vmin(box.lower, items_[i].box.lower);
        box.upper = vmax(box.upper, items_[i].box.upper);
      }
      node.box = box;
    } else {
      const Box2W& l = nodes_[static_cast<size_t>(node.left)].box;
      const Box2W& r = nodes_[static_cast<size_t>(node.right)].box;
      node.box = {vmin(l.lower, r.lower), vmax(l.upper, r.upper)};
    }
  }
  return true;
}

void World2D::QueryCache::build(const World2DState& state, uint64_t edits) {
  step_count_ = state.step_count;
  edits_ = edits;
  if (built_ && refits_ < kMaxRefits && refit(state)) {
    ++refits_;
    return;
  }
  refits_ = 0;
  items_.clear();
  nodes_.clear();
  for (uint32_t i = 0; i < state.bodies.size(); ++i) {
    const BodyRecord2D& b = state.bodies[i];
    if (!(b.flags & kBodyLive) || !(b.flags & kBodyEnabled)) continue;
    items_.push_back({shape_bounds(b.shape, origin_transform(b)), i});
  }
  if (!items_.empty()) {
    nodes_.reserve(2 * items_.size());
    build_range(0, static_cast<uint32_t>(items_.size()));
  }
  built_ = true;
}

int32_t World2D::QueryCache::build_range(uint32_t first, uint32_t count) {
  const auto id = static_cast<int32_t>(nodes_.size());
  nodes_.emplace_back();
  Box2W box = items_[first].box;
  // Box centres doubled (lower + upper), to split on without a division.
  V2 lo = items_[first].box.lower + items_[first].box.upper;
  V2 hi = lo;
  for (uint32_t i = first; i < first + count; ++i) {
    box.lower = vmin(box.lower, items_[i].box.lower);
    box.upper = vmax(box.upper, items_[i].box.upper);
    const V2 c = items_[i].box.lower + items_[i].box.upper;
    lo = vmin(lo, c);
    hi = vmax(hi, c);
  }
  nodes_[static_cast<size_t>(id)].box = box;
  if (count <= kLeafSize) {
    nodes_[static_cast<size_t>(id)].first = first;
    nodes_[static_cast<size_t>(id)].count = count;
    return id;
  }
  // Split at the median centre along the wider spread; (centre, index) is
  // a strict order, so the split is the same on every run.
  const bool by_x = hi.x - lo.x >= hi.y - lo.y;
  const auto begin = items_.begin() + first;
  const auto mid = begin + count / 2;
  std::nth_element(begin, mid, begin + count, [by_x](const Item& a, const Item& b) {
    const W ca = by_x ? a.box.lower.x + a.box.upper.x : a.box.lower.y + a.box.upper.y;
    const W cb = by_x ? b.box.lower.x + b.box.upper.x : b.box.lower.y + b.box.upper.y;
    return ca != cb ? ca < cb : a.index < b.index;
  });
  const int32_t left = build_range(first, count / 2);
  const int32_t right = build_range(first + count / 2, count - count / 2);
  nodes_[static_cast<size_t>(id)].left = left;
  nodes_[static_cast<size_t>(id)].right = right;
  nodes_[static_cast<size_t>(id)].split_y = by_x ? 0 : 1;
  return id;
}

const World2D::QueryCache& World2D::query_cache() const {
  if (!query_cache_) query_cache_ = std::make_shared<QueryCache>();
  if (!query_cache_->fresh(state_.step_count, body_edits_)) {
    query_cache_->build(state_, body_edits_);
  }
  return *query_cache_;
}

}  // namespace rwd::sim2d
