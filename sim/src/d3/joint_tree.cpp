// SPDX-License-Identifier: MIT
// Joint trees (joint_tree.h): finding them, factoring them once a tick,
// and the exact solve of their structural rows each pass. Every loop runs
// in an order fixed by body and joint indices.
#include "d3/joint_tree.h"

#include <algorithm>

#include "d3/joint_solver.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

// tree_extra_slot for a slot with no group prepared.
constexpr uint32_t kNoExtraGroup = 0xFFFFFFFFu;

// A pivot below this share of its diagonal: the row depends on others (or
// nothing can move along it) and is left out, taking no impulse.
constexpr float kPivotShare = 1e-3f;

uint32_t find(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

bool movable(const WorldScratch& s, uint32_t body) {
  return body != 0 && s.solver_bodies[body].inv_mass > 0.0f;
}

// The velocity change of one row per unit impulse along another, through
// one body (`side_*`: true when the body is the joint's A, whose rows act
// with the opposite sign and the A lever arms).
float coupling(const JointRow& r, bool r_on_a, const JointRow& s, bool s_on_a,
               const SolverBody& body) {
  const Vec3 ar = r_on_a ? r.angular_a : r.angular_b;
  const Vec3 as = s_on_a ? s.angular_a : s.angular_b;
  const float k = body.inv_mass * dot(r.linear, s.linear) + dot(ar, body.inv_inertia * as);
  return r_on_a == s_on_a ? k : -k;
}

// Dense L D L^T of the symmetric n x n matrix a (row-major, lower part
// read and overwritten by L), pivots into d (0 for a row left out).
void factor_dense(float* a, float* d, uint32_t n) {
  for (uint32_t i = 0; i < n; ++i) {
    const float diag = a[i * n + i];
    float di = diag;
    for (uint32_t k = 0; k < i; ++k) di -= a[i * n + k] * a[i * n + k] * d[k];
    const bool kept = diag > 0.0f && di > kPivotShare * diag;
    d[i] = kept ? di : 0.0f;
    for (uint32_t j = i + 1; j < n; ++j) {
      if (!kept) {
        a[j * n + i] = 0.0f;
        continue;
      }
      float v = a[j * n + i];
      for (uint32_t k = 0; k < i; ++k) v -= a[j * n + k] * a[i * n + k] * d[k];
      a[j * n + i] = v / di;
    }
  }
}

// x = (L D L^T)^-1 b, in place.
void solve_dense(const float* l, const float* d, uint32_t n, float* x) {
  for (uint32_t i = 0; i < n; ++i) {
    float v = x[i];
    for (uint32_t k = 0; k < i; ++k) v -= l[i * n + k] * x[k];
    x[i] = d[i] != 0.0f ? v : 0.0f;
  }
  for (uint32_t i = 0; i < n; ++i) x[i] = d[i] != 0.0f ? x[i] / d[i] : 0.0f;
  for (uint32_t i = n; i-- > 0;) {
    if (d[i] == 0.0f) {
      x[i] = 0.0f;
      continue;
    }
    float v = x[i];
    for (uint32_t k = i + 1; k < n; ++k) v -= l[k * n + i] * x[k];
    x[i] = v;
  }
}

uint32_t rows_of(const WorldScratch& s, uint32_t joint) {
  return static_cast<uint32_t>(s.joint_constraints[joint].block.size());
}

// The solver body of a joint on the other side from `body`.
uint32_t other_body(const JointConstraint& c, uint32_t body) {
  return c.body_a == body ? c.body_b : c.body_a;
}

// Lays out one component's bodies breadth first from `root`; false when a
// front would be too large (the component is then solved row by row).
bool lay_out(WorldScratch& s, uint32_t root, JointTree& tree) {
  tree.body_begin = static_cast<uint32_t>(s.tree_bodies.size());
  JointTreeBody r;
  r.body = root;
  r.parent_joint = kNoParent;
  s.tree_bodies.push_back(r);
  s.tree_seen[root] = 1;
  for (uint32_t q = tree.body_begin; q < s.tree_bodies.size(); ++q) {
    const uint32_t body = s.tree_bodies[q].body;
    const uint32_t parent = s.tree_bodies[q].parent_joint;
    const uint32_t begin = static_cast<uint32_t>(s.tree_children.size());
    uint32_t front = 0;
    for (uint32_t e = s.tree_incidence_start[body]; e < s.tree_incidence_start[body + 1]; ++e) {
      const uint32_t joint = s.tree_incidence[e];
      if (joint == parent) continue;
      s.tree_children.push_back(joint);
      front += s.joint_constraints[joint].capacity;
      const uint32_t other = other_body(s.joint_constraints[joint], body);
      if (movable(s, other) && s.tree_seen[other] == 0) {
        s.tree_seen[other] = 1;
        JointTreeBody child;
        child.body = other;
        child.parent_joint = joint;
        s.tree_bodies.push_back(child);
      }
    }
    JointTreeBody& node = s.tree_bodies[q];
    node.child_begin = begin;
    node.child_end = static_cast<uint32_t>(s.tree_children.size());
    node.front = front;
    if (front > kMaxFrontRows) return false;
  }
  tree.body_end = static_cast<uint32_t>(s.tree_bodies.size());
  return true;
}

// Factors one tree, leaves first: at each body, the front of its child
// joints' rows (their coupling through the body, plus on the diagonal
// their own K and what the subtree below them left) and the coupling to
// the joint above.
void factor_tree(WorldScratch& s, const JointTree& tree) {
  std::vector<float>& arena = s.tree_arena;
  for (uint32_t q = tree.body_end; q-- > tree.body_begin;) {
    JointTreeBody& node = s.tree_bodies[q];
    const SolverBody& body = s.solver_bodies[node.body];
    // The rows the child joints hold now (a limit reached joins them).
    node.front = 0;
    for (uint32_t ci = node.child_begin; ci < node.child_end; ++ci) {
      node.front += rows_of(s, s.tree_children[ci]);
    }
    const uint32_t n = node.front;
    const uint32_t parent_rows = node.parent_joint == kNoParent ? 0 : rows_of(s, node.parent_joint);
    node.factor_at = static_cast<uint32_t>(arena.size());
    arena.resize(arena.size() + n * n + n);
    node.coupling_at = static_cast<uint32_t>(arena.size());
    arena.resize(arena.size() + n * parent_rows);
    float* f = arena.data() + node.factor_at;
    float* d = f + n * n;
    float* y = arena.data() + node.coupling_at;
    // The front: children joints' rows, in child order.
    uint32_t at_i = 0;
    for (uint32_t ci = node.child_begin; ci < node.child_end; ++ci) {
      const JointConstraint& ji = s.joint_constraints[s.tree_children[ci]];
      const bool i_on_a = ji.body_a == node.body;
      const uint32_t mi = static_cast<uint32_t>(ji.block.size());
      uint32_t at_l = 0;
      for (uint32_t cl = node.child_begin; cl <= ci; ++cl) {
        const JointConstraint& jl = s.joint_constraints[s.tree_children[cl]];
        const bool l_on_a = jl.body_a == node.body;
        const uint32_t ml = static_cast<uint32_t>(jl.block.size());
        for (uint32_t r = 0; r < mi; ++r) {
          for (uint32_t c = 0; c < ml; ++c) {
            f[(at_i + r) * n + at_l + c] =
                coupling(ji.block.row(static_cast<int>(r)), i_on_a,
                         jl.block.row(static_cast<int>(c)), l_on_a, body);
          }
        }
        at_l += ml;
      }
      // The diagonal block also has the far side's coupling (the child
      // body below, or nothing for an immovable one) and the subtree's
      // update.
      const uint32_t far = other_body(ji, node.body);
      const SolverBody& far_body = s.solver_bodies[far];
      const float* update = arena.data() + ji.tree_update;
      for (uint32_t r = 0; r < mi; ++r) {
        for (uint32_t c = 0; c <= r; ++c) {
          float v = coupling(ji.block.row(static_cast<int>(r)), !i_on_a,
                             ji.block.row(static_cast<int>(c)), !i_on_a, far_body);
          if (movable(s, far)) v += update[r * mi + c];
          f[(at_i + r) * n + at_i + c] += v;
        }
      }
      at_i += mi;
    }
    // The coupling to the parent joint's rows through this body, before
    // the front is overwritten by its factors.
    if (parent_rows != 0) {
      const JointConstraint& jp = s.joint_constraints[node.parent_joint];
      const bool p_on_a = jp.body_a == node.body;
      uint32_t at = 0;
      for (uint32_t ci = node.child_begin; ci < node.child_end; ++ci) {
        const JointConstraint& ji = s.joint_constraints[s.tree_children[ci]];
        const bool i_on_a = ji.body_a == node.body;
        for (uint32_t r = 0; r < static_cast<uint32_t>(ji.block.size()); ++r) {
          for (uint32_t c = 0; c < parent_rows; ++c) {
            y[(at + r) * parent_rows + c] =
                coupling(ji.block.row(static_cast<int>(r)), i_on_a,
                         jp.block.row(static_cast<int>(c)), p_on_a, body);
          }
        }
        at += static_cast<uint32_t>(ji.block.size());
      }
    }
    // F_cp, kept for the parent's update before Y takes its place.
    float fcp[kMaxFrontRows * 6];
    for (uint32_t i = 0; i < n * parent_rows; ++i) fcp[i] = y[i];
    factor_dense(f, d, n);
    if (parent_rows == 0) continue;
    // Y = F^-1 F_cp, column by column, and the parent's update
    // -F_pc F^-1 F_cp: the rows below, eliminated into the joint above.
    float column[kMaxFrontRows];
    for (uint32_t c = 0; c < parent_rows; ++c) {
      for (uint32_t r = 0; r < n; ++r) column[r] = fcp[r * parent_rows + c];
      solve_dense(f, d, n, column);
      for (uint32_t r = 0; r < n; ++r) y[r * parent_rows + c] = column[r];
    }
    float* update = arena.data() + s.joint_constraints[node.parent_joint].tree_update;
    for (uint32_t p = 0; p < parent_rows; ++p) {
      for (uint32_t c = 0; c < parent_rows; ++c) {
        float v = 0.0f;
        for (uint32_t r = 0; r < n; ++r) v += fcp[r * parent_rows + p] * y[r * parent_rows + c];
        update[p * parent_rows + c] -= v;
      }
    }
  }
}

// lambda = K^-1 rhs over one tree (s.tree_rhs in, s.tree_lambda out;
// s.tree_rhs is consumed): forward from the leaves, backward from the
// root.
void solve_tree_rows(WorldScratch& s, const JointTree& tree) {
  std::vector<JointConstraint>& joints = s.joint_constraints;
  const float* arena = s.tree_arena.data();
  // Forward, leaves first: each front solved for its own right-hand side,
  // and its rows eliminated into the joint above.
  float front[kMaxFrontRows];
  float solved[kMaxFrontRows];
  for (uint32_t q = tree.body_end; q-- > tree.body_begin;) {
    const JointTreeBody& node = s.tree_bodies[q];
    uint32_t at = 0;
    for (uint32_t ci = node.child_begin; ci < node.child_end; ++ci) {
      const JointConstraint& c = joints[s.tree_children[ci]];
      for (int i = 0; i < c.block.size(); ++i) front[at++] = s.tree_rhs[c.tree_row + i];
    }
    const uint32_t n = node.front;
    // A front with nothing to carry (the column of an extra row is zero
    // away from its bodies and their path to the root) solves to zero and
    // eliminates nothing into the joint above.
    bool empty = true;
    for (uint32_t r = 0; r < n; ++r) empty = empty && front[r] == 0.0f;
    if (empty) {
      at = 0;
      for (uint32_t ci = node.child_begin; ci < node.child_end; ++ci) {
        const JointConstraint& c = joints[s.tree_children[ci]];
        for (int i = 0; i < c.block.size(); ++i) s.tree_w[c.tree_row + i] = 0.0f;
      }
      continue;
    }
    for (uint32_t r = 0; r < n; ++r) solved[r] = front[r];
    solve_dense(arena + node.factor_at, arena + node.factor_at + n * n, n, solved);
    at = 0;
    for (uint32_t ci = node.child_begin; ci < node.child_end; ++ci) {
      const JointConstraint& c = joints[s.tree_children[ci]];
      for (int i = 0; i < c.block.size(); ++i) s.tree_w[c.tree_row + i] = solved[at++];
    }
    if (node.parent_joint == kNoParent) continue;
    const JointConstraint& p = joints[node.parent_joint];
    const uint32_t mp = static_cast<uint32_t>(p.block.size());
    const float* y = arena + node.coupling_at;
    for (uint32_t c = 0; c < mp; ++c) {
      float v = 0.0f;
      for (uint32_t r = 0; r < n; ++r) v += y[r * mp + c] * front[r];
      s.tree_rhs[p.tree_row + c] -= v;
    }
  }
  // Backward, root first: each front's rows from the joint above.
  for (uint32_t q = tree.body_begin; q < tree.body_end; ++q) {
    const JointTreeBody& node = s.tree_bodies[q];
    const bool has_parent = node.parent_joint != kNoParent;
    const uint32_t mp =
        has_parent ? static_cast<uint32_t>(joints[node.parent_joint].block.size()) : 0;
    const float* above =
        has_parent ? s.tree_lambda.data() + joints[node.parent_joint].tree_row : nullptr;
    const float* y = arena + node.coupling_at;
    uint32_t at = 0;
    for (uint32_t ci = node.child_begin; ci < node.child_end; ++ci) {
      const JointConstraint& c = joints[s.tree_children[ci]];
      for (int i = 0; i < c.block.size(); ++i, ++at) {
        float v = s.tree_w[c.tree_row + i];
        for (uint32_t col = 0; col < mp; ++col) v -= y[at * mp + col] * above[col];
        s.tree_lambda[c.tree_row + i] = v;
      }
    }
  }
}

}  // namespace

float tree_row_coupling(const JointRow& r, bool r_on_a, const JointRow& s, bool s_on_a,
                        const SolverBody& body) {
  return coupling(r, r_on_a, s, s_on_a, body);
}

void solve_tree(WorldScratch& s, const JointTree& tree) {
  solve_tree_rows(s, tree);
}

void solve_dense_spd(float* a, uint32_t n, float* x) {
  float d[kMaxFrontRows];
  factor_dense(a, d, n);
  solve_dense(a, d, n, x);
}

namespace {

// How many times heavier one of a joint's two moving bodies is than the
// other (1 when either has no mass to compare).
float mass_ratio(const SolverBody& a, const SolverBody& b) {
  if (!(a.inv_mass > 0.0f) || !(b.inv_mass > 0.0f)) return 1.0f;
  return a.inv_mass > b.inv_mass ? a.inv_mass / b.inv_mass : b.inv_mass / a.inv_mass;
}

}  // namespace

void build_joint_trees(WorldScratch& s) {
  s.trees.clear();
  s.tree_bodies.clear();
  s.tree_children.clear();
  s.tree_joints.clear();
  s.tree_arena.clear();
  std::vector<JointConstraint>& joints = s.joint_constraints;
  const uint32_t bodies = static_cast<uint32_t>(s.solver_bodies.size());
  // Components of moving bodies joined by joints with structure; a joint
  // that closes a loop marks its component.
  std::vector<uint32_t>& parent = s.tree_parent;
  parent.resize(bodies);
  for (uint32_t i = 0; i < bodies; ++i) parent[i] = i;
  s.tree_loop.assign(bodies, 0);
  s.tree_count.assign(bodies, 0);
  s.tree_mass_ratio.assign(bodies, 1.0f);
  bool any = false;
  for (JointConstraint& c : joints) {
    c.tree = kNoTree;
    if (c.block.size() == 0) continue;
    const bool ma = movable(s, c.body_a);
    const bool mb = movable(s, c.body_b);
    if (!ma && !mb) continue;
    if (ma && mb) {
      const uint32_t ra = find(parent, c.body_a);
      const uint32_t rb = find(parent, c.body_b);
      const float ratio = mass_ratio(s.solver_bodies[c.body_a], s.solver_bodies[c.body_b]);
      if (ra == rb) {
        s.tree_loop[ra] = 1;
        s.tree_mass_ratio[ra] = std::max(s.tree_mass_ratio[ra], ratio);
      } else {
        const uint32_t root = ra < rb ? ra : rb;
        const uint32_t other = ra < rb ? rb : ra;
        parent[other] = root;
        s.tree_loop[root] |= s.tree_loop[other];
        s.tree_count[root] += s.tree_count[other];
        s.tree_mass_ratio[root] =
            std::max({s.tree_mass_ratio[root], s.tree_mass_ratio[other], ratio});
      }
    }
    ++s.tree_count[find(parent, ma ? c.body_a : c.body_b)];
    any = true;
  }
  if (!any) return;
  // A tree is a loop-free component of two or more such joints (a lone
  // joint is already exact on its own) that the row-by-row passes would
  // let sag: more joints than a load crosses in a few passes, or bodies
  // of very different mass joined.
  auto in_tree = [&](const JointConstraint& c) {
    if (c.block.size() == 0) return false;
    const bool ma = movable(s, c.body_a);
    if (!ma && !movable(s, c.body_b)) return false;
    const uint32_t root = find(parent, ma ? c.body_a : c.body_b);
    return s.tree_loop[root] == 0 && s.tree_count[root] >= 2 &&
           (s.tree_count[root] > kRowByRowTreeJoints ||
            s.tree_mass_ratio[root] > kRowByRowMassRatio);
  };
  // Each moving body's tree joints, in slot order.
  s.tree_incidence_start.assign(bodies + 1, 0);
  for (const JointConstraint& c : joints) {
    if (!in_tree(c)) continue;
    if (movable(s, c.body_a)) ++s.tree_incidence_start[c.body_a + 1];
    if (movable(s, c.body_b)) ++s.tree_incidence_start[c.body_b + 1];
  }
  for (uint32_t i = 0; i < bodies; ++i) s.tree_incidence_start[i + 1] += s.tree_incidence_start[i];
  s.tree_incidence.resize(s.tree_incidence_start[bodies]);
  s.tree_fill.assign(s.tree_incidence_start.begin(), s.tree_incidence_start.end() - 1);
  for (uint32_t k = 0; k < joints.size(); ++k) {
    const JointConstraint& c = joints[k];
    if (!in_tree(c)) continue;
    if (movable(s, c.body_a)) s.tree_incidence[s.tree_fill[c.body_a]++] = k;
    if (movable(s, c.body_b)) s.tree_incidence[s.tree_fill[c.body_b]++] = k;
  }
  // Lay each tree out from its lowest body, and number its rows.
  s.tree_seen.assign(bodies, 0);
  uint32_t rows = 0;
  for (uint32_t body = 1; body < bodies; ++body) {
    if (s.tree_incidence_start[body] == s.tree_incidence_start[body + 1]) continue;
    if (find(parent, body) != body || s.tree_seen[body] != 0) continue;
    JointTree tree;
    const size_t bodies_before = s.tree_bodies.size();
    const size_t children_before = s.tree_children.size();
    if (!lay_out(s, body, tree)) {
      s.tree_bodies.resize(bodies_before);
      s.tree_children.resize(children_before);
      continue;  // its joints stay on their own
    }
    const uint32_t t = static_cast<uint32_t>(s.trees.size());
    tree.joint_begin = static_cast<uint32_t>(s.tree_joints.size());
    for (uint32_t q = tree.body_begin; q < tree.body_end; ++q) {
      const JointTreeBody& node = s.tree_bodies[q];
      for (uint32_t ci = node.child_begin; ci < node.child_end; ++ci) {
        s.tree_joints.push_back(s.tree_children[ci]);
      }
    }
    tree.joint_end = static_cast<uint32_t>(s.tree_joints.size());
    tree.row_begin = rows;
    for (uint32_t k = tree.joint_begin; k < tree.joint_end; ++k) {
      JointConstraint& c = joints[s.tree_joints[k]];
      const uint32_t m = c.capacity;  // room for its limits too
      c.tree = t;
      c.tree_row = rows;
      rows += m;
      c.tree_update = static_cast<uint32_t>(s.tree_arena.size());
      s.tree_arena.resize(s.tree_arena.size() + m * m, 0.0f);
    }
    tree.row_end = rows;
    s.trees.push_back(tree);
  }
  // A joint solved exactly (in a tree, or alone in its component) needs
  // no softness: its structure is rigid, its error closed by the bias and
  // the projection, and nothing sheds its load. (The soft step's spring
  // is what keeps a row-by-row sweep of stiff rows stable; a loop of
  // joints, solved that way, keeps it.)
  for (JointConstraint& c : joints) {
    if (c.block.size() == 0) continue;
    const bool ma = movable(s, c.body_a);
    if (!ma && !movable(s, c.body_b)) continue;
    const uint32_t root = find(parent, ma ? c.body_a : c.body_b);
    if (s.tree_loop[root] != 0) continue;
    c.soft.mass_scale = 1.0f;
    c.soft.impulse_scale = 0.0f;
  }
  s.tree_rhs.resize(rows);
  s.tree_w.resize(rows);
  s.tree_lambda.resize(rows);
  s.tree_acc.resize(rows);
  s.tree_delta.resize(rows);
  s.tree_release.resize(static_cast<size_t>(kMaxReleased) * rows);
  s.tree_factor_base = static_cast<uint32_t>(s.tree_arena.size());
}

void factor_joint_trees(WorldScratch& s) {
  if (s.trees.empty()) return;
  // The subtree updates start over; the fronts are laid out again.
  for (const JointTree& tree : s.trees) {
    for (uint32_t k = tree.joint_begin; k < tree.joint_end; ++k) {
      const JointConstraint& c = s.joint_constraints[s.tree_joints[k]];
      const uint32_t m = c.capacity;
      for (uint32_t i = 0; i < m * m; ++i) s.tree_arena[c.tree_update + i] = 0.0f;
    }
  }
  s.tree_arena.resize(s.tree_factor_base);
  for (const JointTree& tree : s.trees) factor_tree(s, tree);
  // What the extra rows were prepared against is gone.
  s.tree_extra_groups.clear();
  s.tree_extra_used = 0;
  s.tree_extra_slot.assign(s.joint_constraints.size() * kKeptRows, kNoExtraGroup);
}

void solve_joint_tree(const std::vector<JointRecord>& records, WorldScratch& s, uint32_t t,
                      bool use_bias) {
  const JointTree& tree = s.trees[t];
  std::vector<JointConstraint>& joints = s.joint_constraints;
  // Springs, motors and the limits not yet reached first, each against
  // the whole tree's structure held rigid (so a spring turning a knuckle
  // turns the wheel hung from it too), then the exact solve of the
  // structure ends the pass.
  for (uint32_t k = tree.joint_begin; k < tree.joint_end; ++k) {
    JointConstraint& c = joints[s.tree_joints[k]];
    gather_impulses(c, s.tree_acc.data() + c.tree_row);
  }
  for (uint32_t k = tree.joint_begin; k < tree.joint_end; ++k) {
    JointConstraint& c = joints[s.tree_joints[k]];
    const JointRecord& j = records[c.record];
    const JointOps& ops = joint_ops(j.type);
    SolverBody& a = s.solver_bodies[c.body_a];
    SolverBody& b = s.solver_bodies[c.body_b];
    ExtraBase base;
    base.block = &c.block;
    base.block_impulse = s.tree_acc.data() + c.tree_row;
    base.scratch = &s;
    base.tree = t;
    base.joint = s.tree_joints[k];
    base.body_a = c.body_a;
    base.body_b = c.body_b;
    const JointFrames f = joint_frames(c, a, b);
    if (ops.extras != nullptr) ops.extras(j, c, a, b, f, use_bias, base);
    solve_free_limits(j, c, a, b, f, use_bias, base);
  }
  // Then the structure, the whole tree at once: the right-hand side is
  // every structural row's velocity and its bias.
  float bias[kMaxBlockRows];
  for (uint32_t k = tree.joint_begin; k < tree.joint_end; ++k) {
    JointConstraint& c = joints[s.tree_joints[k]];
    const JointRecord& j = records[c.record];
    const SolverBody& a = s.solver_bodies[c.body_a];
    const SolverBody& b = s.solver_bodies[c.body_b];
    const int m = c.block.size();
    if (use_bias) {
      const JointFrames f = joint_frames(c, a, b);
      structural_bias(c, f, joint_ops(j.type).angular_error(j, f), c.soft.bias_rate, bias);
    }
    for (int i = 0; i < m; ++i) {
      s.tree_rhs[c.tree_row + i] = -(c.block.velocity(i, a, b) + (use_bias ? bias[i] : 0.0f));
    }
  }
  solve_tree_rows(s, tree);
  // The impulses, soft while solving, rigid while relaxing.
  const float mass_scale =
      use_bias ? joints[s.tree_joints[tree.joint_begin]].soft.mass_scale : 1.0f;
  const float impulse_scale =
      use_bias ? joints[s.tree_joints[tree.joint_begin]].soft.impulse_scale : 0.0f;
  for (uint32_t k = tree.joint_begin; k < tree.joint_end; ++k) {
    JointConstraint& c = joints[s.tree_joints[k]];
    float* acc = s.tree_acc.data() + c.tree_row;
    float* delta = s.tree_delta.data() + c.tree_row;
    for (int i = 0; i < c.block.size(); ++i) {
      delta[i] = s.tree_lambda[c.tree_row + i] * mass_scale - acc[i] * impulse_scale;
      acc[i] += delta[i];
    }
  }
  // A held limit left pulling (by the solve, or by the extra rows'
  // compensation before it) is released against the whole tree.
  release_tree_limits(s, tree, s.tree_acc.data(), s.tree_delta.data());
  for (uint32_t k = tree.joint_begin; k < tree.joint_end; ++k) {
    JointConstraint& c = joints[s.tree_joints[k]];
    c.block.apply(s.solver_bodies[c.body_a], s.solver_bodies[c.body_b],
                  s.tree_delta.data() + c.tree_row);
    scatter_impulses(c, s.tree_acc.data() + c.tree_row);
  }
}

void project_joint_tree(const std::vector<JointRecord>& records, WorldScratch& s, uint32_t t) {
  const JointTree& tree = s.trees[t];
  std::vector<JointConstraint>& joints = s.joint_constraints;
  float error[kMaxBlockRows];
  for (uint32_t k = tree.joint_begin; k < tree.joint_end; ++k) {
    const JointConstraint& c = joints[s.tree_joints[k]];
    const JointRecord& j = records[c.record];
    const JointFrames f = joint_frames(c, s.solver_bodies[c.body_a], s.solver_bodies[c.body_b]);
    structural_bias(c, f, joint_ops(j.type).angular_error(j, f), 1.0f, error);
    for (int i = 0; i < c.block.size(); ++i) {
      s.tree_rhs[c.tree_row + i] = -clamp_projection(error[i]);
    }
  }
  solve_tree_rows(s, tree);
  for (uint32_t k = tree.joint_begin; k < tree.joint_end; ++k) {
    const JointConstraint& c = joints[s.tree_joints[k]];
    for (int i = 0; i < c.block.size(); ++i) {
      s.tree_delta[c.tree_row + i] = s.tree_lambda[c.tree_row + i];
    }
  }
  // A held limit the displacements would pull shut is released against
  // the whole tree: it stays where it is, the rest still closes.
  release_tree_limits(s, tree, s.tree_delta.data(), nullptr);
  for (uint32_t k = tree.joint_begin; k < tree.joint_end; ++k) {
    const JointConstraint& c = joints[s.tree_joints[k]];
    displace(c.block, s.tree_delta.data() + c.tree_row, s.solver_bodies[c.body_a],
             s.solver_bodies[c.body_b]);
  }
}

}  // namespace rwd::sim::d3
