// SPDX-License-Identifier: MIT
#include "d3/angular_momentum.h"

#include <cmath>

namespace rwd::sim::d3 {

// The gyroscopic term. The solver holds the inertia tensor fixed at the
// tick's starting orientation, so its angular velocity belongs to that
// orientation: the world angular momentum is L = I(q0) w. A free body keeps
// L while its inertia turns with it, so the velocity it ends the tick with
// is I(q1)^-1 L: this is what makes a box spun about its intermediate axis
// tumble (the Dzhanibekov effect) instead of spinning forever.
//
// Three things decide how well a tumble keeps time over many ticks:
//
// - Order. The solver turned the body by its starting body-frame rate w0
//   for the whole tick, while the momentum moved through the body and took
//   the rate to w1. Turning it further by (w1 - w0) h / 2 in the body frame
//   turns it by the mean of the two rates, second order instead of first:
//   at 60 Hz the first-order turn puts a flip's period a few per cent off,
//   Heun's method (one pass) about 1% short, the trapezoidal rule (two)
//   within 0.7%.
//
// - The invariants. The gyroscopic term does no work, so the body-frame
//   momentum l is moved along the sphere |l| = const back onto the level
//   set of the tick's start (two Newton steps), and the orientation turned
//   by the same small body-frame rotation, so the world momentum stays L.
//   The second invariant is D = |L|^2 - 2 E I_mid = sum (I_i - I_mid) /
//   I_i l_i^2, not the energy E itself. Both are conserved together, but
//   near the flip orbit's separatrix D is a tiny difference of large
//   numbers (a 1e-5 part of |L|^2 for a box spun 1% off its intermediate
//   axis, and a flip's period goes with its logarithm): recomputing E and
//   |L|^2 in float each tick walks D by their rounding and the flips come
//   ever faster. D has no term in the middle axis, and the other two are
//   evaluated as (a - b)(a + b), which keeps D to a few ulps of itself.
//
// - No bias in the round trip through the stored state. The state keeps w
//   in the world frame, so each tick reads back the body-frame momentum the
//   last one wrote. A quaternion one rounding off unit length turns
//   vectors non-orthogonally, and l * (1/I) * I is l times a fixed
//   1 + eps; either shifts D the same way every tick. Here the turns are
//   divided by |q|^2 and the rate is l / I, so what is read back differs
//   from what was written by rounding that does not pile up.

namespace {

// q v q* / |q|^2: a rotation even when q is a rounding off unit length.
Vec3 turn(Quat q, Vec3 v) {
  const Vec3 u{q.x, q.y, q.z};
  const float n = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
  const Vec3 r = v * (q.w * q.w - dot(u, u)) + u * (2.0f * dot(u, v)) + cross(u, v) * (2.0f * q.w);
  return r * (1.0f / n);
}
Vec3 turn_back(Quat q, Vec3 v) {
  return turn(conjugate(q), v);
}
Vec3 divide_elements(Vec3 a, Vec3 b) {
  return {a.x / b.x, a.y / b.y, a.z / b.z};
}

// D(l) = c_major l_major^2 + c_minor l_minor^2 (c_major >= 0 >= c_minor,
// c_mid = 0) as (a - b)(a + b), a = sqrt(c_major)|l_major|, b likewise.
struct Separatrix {
  Vec3 coefficients;  // c_i = (I_i - I_mid) / I_i
  int major = 0;
  int minor = 0;
  float root_major = 0.0f;  // sqrt(c_major)
  float root_minor = 0.0f;  // sqrt(-c_minor)
  float operator()(Vec3 l) const {
    const float a = root_major * std::fabs(component(l, major));
    const float b = root_minor * std::fabs(component(l, minor));
    return (a - b) * (a + b);
  }
};

Separatrix separatrix(Vec3 inertia) {
  const float moments[3] = {inertia.x, inertia.y, inertia.z};
  int order[3] = {0, 1, 2};  // by moment, largest first; ties keep axis order
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      if (moments[order[j]] > moments[order[i]]) {
        const int t = order[i];
        order[i] = order[j];
        order[j] = t;
      }
    }
  }
  const float mid = moments[order[1]];
  Separatrix s;
  s.coefficients = {(inertia.x - mid) / inertia.x, (inertia.y - mid) / inertia.y,
                    (inertia.z - mid) / inertia.z};
  s.major = order[0];
  s.minor = order[2];
  s.root_major = std::sqrt(component(s.coefficients, s.major));
  s.root_minor = std::sqrt(-component(s.coefficients, s.minor));
  return s;
}

}  // namespace

Spin carry_angular_momentum(const BodyMass& mass, Quat q0, Quat q1, Vec3 w, float tick) {
  const Vec3 inv = mass.inv_inertia_local;
  // Equal principal moments (spheres, cubes): the inertia tensor does not
  // change as the body turns, so neither does w.
  if (inv.x == inv.y && inv.y == inv.z) return {w, q1};
  const Vec3 inertia{1.0f / inv.x, 1.0f / inv.y, 1.0f / inv.z};
  const Vec3 w0 = turn_back(q0, w);
  const Vec3 l0 = mul_elements(inertia, w0);
  const Vec3 l_world = turn(q0, l0);
  const float l_sq = length_squared(l0);
  if (!(l_sq > 0.0f)) return {turn(q1, mul_elements(inv, turn_back(q1, l_world))), q1};
  // The trapezoidal rule: turn by (w1 - w0) h / 2 more, w1 the end rate
  // that turn leaves, found by two passes (the first is Heun's method). w0
  // is also the rate in the frame of q1 (a turn about w0 leaves it be), so
  // the half difference of rates is a body-frame turn at q1.
  Quat q = q1;
  for (int i = 0; i < 2; ++i) {
    const Vec3 w1 = divide_elements(turn_back(q, l_world), inertia);
    const Vec3 half = (w1 - w0) * (0.25f * tick);
    q = normalize(q1 * Quat{half.x, half.y, half.z, 1.0f});
  }
  const Vec3 carried = turn_back(q, l_world);  // body frame at the tick's end
  if (!is_finite(q)) return {turn(q1, mul_elements(inv, turn_back(q1, l_world))), q1};
  const Separatrix d = separatrix(inertia);
  const float d0 = d(l0);
  Vec3 l = carried;
  for (int i = 0; i < 2; ++i) {
    const Vec3 g = mul_elements(d.coefficients, l);  // D has gradient 2g
    const float error = d(l) - d0;
    // The gradient's part tangent to the momentum sphere.
    const Vec3 t = g - l * (dot(g, l) / length_squared(l));
    const float slope = 2.0f * dot(g, t);
    if (!(slope > 1e-12f * l_sq)) break;  // on a principal axis: nothing to correct
    Vec3 next = l - t * (error / slope);
    next = next * std::sqrt(l_sq / length_squared(next));
    if (!is_finite(next)) break;
    l = next;
  }
  // The body-frame rotation r taking l to `carried`: q r maps l to L.
  const Vec3 axis = cross(l, carried);
  const Quat r = normalize(Quat{axis.x, axis.y, axis.z, l_sq + dot(l, carried)});
  const Quat end = normalize(q * r);
  if (!is_finite(end)) return {turn(q, divide_elements(carried, inertia)), q};
  return {turn(end, divide_elements(l, inertia)), end};
}

}  // namespace rwd::sim::d3
