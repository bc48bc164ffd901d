// SPDX-License-Identifier: MIT
// Mass properties of a hull and its principal frame. Only + - * / and sqrt:
// the C library's trigonometry differs between platforms, and the axes
// found here become part of every body's state.
#include <cmath>

#include "d3/hull_build_steps.h"

namespace rwd::sim::d3::hull_steps {

// Tetrahedra from a point inside (the vertices' mean) over each face's
// fan. For a tetrahedron with corners 0, w1, w2, w3 and det = w1 . (w2 x w3)
// (six times its signed volume), the second moment is
//   integral x x^T dV = det / 120 * (sum_i w_i w_i^T + s s^T),  s = w1 + w2 + w3,
// and its first moment det / 24 * s.
MassProperties polyhedron_mass(std::span<const DVec3> points,
                               const std::vector<std::vector<uint32_t>>& loops) {
  DVec3 ref;
  for (const DVec3& p : points) ref = ref + p;
  ref = ref * (1.0 / static_cast<double>(points.size()));

  double det_sum = 0.0;
  DVec3 first;
  double second[3][3]{};
  for (const std::vector<uint32_t>& loop : loops) {
    const DVec3 w1 = points[loop[0]] - ref;
    for (size_t k = 1; k + 1 < loop.size(); ++k) {
      const DVec3 w2 = points[loop[k]] - ref;
      const DVec3 w3 = points[loop[k + 1]] - ref;
      const double det = dot(w1, cross(w2, w3));
      const DVec3 s = w1 + w2 + w3;
      det_sum += det;
      first = first + s * det;
      const double w[4][3] = {
          {w1.x, w1.y, w1.z}, {w2.x, w2.y, w2.z}, {w3.x, w3.y, w3.z}, {s.x, s.y, s.z}};
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          const double sum =
              w[0][i] * w[0][j] + w[1][i] * w[1][j] + w[2][i] * w[2][j] + w[3][i] * w[3][j];
          second[i][j] += det * sum;
        }
      }
    }
  }
  MassProperties m;
  m.volume = det_sum / 6.0;
  const DVec3 shift = first * (1.0 / (4.0 * det_sum));  // centre of mass from ref
  m.center = ref + shift;
  // Covariance per unit volume about the centre, then inertia per unit mass.
  const double sh[3] = {shift.x, shift.y, shift.z};
  double cov[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) cov[i][j] = second[i][j] / (20.0 * det_sum) - sh[i] * sh[j];
  }
  const double trace = cov[0][0] + cov[1][1] + cov[2][2];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m.inertia[i][j] = (i == j ? trace : 0.0) - cov[i][j];
  }
  return m;
}

namespace {

constexpr double kOffDiagonalIgnored = 1e-6;  // of the trace
constexpr int kMaxSweeps = 50;

// Columns of `v`: eigenvectors; diagonal of `a`: eigenvalues.
void jacobi(double a[3][3], double v[3][3]) {
  const double threshold =
      kOffDiagonalIgnored * (std::fabs(a[0][0]) + std::fabs(a[1][1]) + std::fabs(a[2][2]));
  static constexpr int kPairs[3][3] = {{0, 1, 2}, {0, 2, 1}, {1, 2, 0}};  // p, q, the other
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    bool turned = false;
    for (const auto& pair : kPairs) {
      const int p = pair[0];
      const int q = pair[1];
      const int r = pair[2];
      const double apq = a[p][q];
      if (!(std::fabs(apq) > threshold)) continue;
      // The rotation that zeroes a[p][q] (Numerical Recipes, section 11.1):
      // t is the tangent of the rotation angle: the smaller root of
      // t^2 + 2 t theta - 1 = 0.
      const double theta = (a[q][q] - a[p][p]) / (2.0 * apq);
      double t = 1.0 / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
      if (theta < 0.0) t = -t;
      const double c = 1.0 / std::sqrt(t * t + 1.0);
      const double s = t * c;
      const double arp = a[r][p];
      const double arq = a[r][q];
      a[p][p] -= t * apq;
      a[q][q] += t * apq;
      a[p][q] = a[q][p] = 0.0;
      a[r][p] = a[p][r] = c * arp - s * arq;
      a[r][q] = a[q][r] = s * arp + c * arq;
      for (int k = 0; k < 3; ++k) {
        const double vkp = v[k][p];
        const double vkq = v[k][q];
        v[k][p] = c * vkp - s * vkq;
        v[k][q] = s * vkp + c * vkq;
      }
      turned = true;
    }
    if (!turned) break;
  }
}

DVec3 column(const double v[3][3], int j) {
  return {v[0][j], v[1][j], v[2][j]};
}

double component(DVec3 a, int i) {
  return i == 0 ? a.x : (i == 1 ? a.y : a.z);
}

}  // namespace

PrincipalAxes principal_axes(const double tensor[3][3]) {
  double a[3][3];
  double v[3][3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) a[i][j] = tensor[i][j];
  }
  jacobi(a, v);

  // Order and sign the eigenvectors so the frame lies closest to the
  // identity (largest trace; ties to the earlier permutation): an
  // axis-aligned hull keeps its own axes and a slightly turned one a
  // slightly turned frame, instead of axes shuffled by moment size.
  static constexpr int kPermutations[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                              {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  PrincipalAxes best;
  double best_trace = -10.0;
  for (const auto& perm : kPermutations) {
    DVec3 axes[3];
    double diagonal[3];
    for (int k = 0; k < 3; ++k) {
      axes[k] = column(v, perm[k]);
      if (component(axes[k], k) < 0.0) axes[k] = axes[k] * -1.0;
      diagonal[k] = component(axes[k], k);
    }
    if (dot(axes[0], cross(axes[1], axes[2])) < 0.0) {
      int flip = 0;  // the column that costs the trace least
      for (int k = 1; k < 3; ++k) {
        if (diagonal[k] < diagonal[flip]) flip = k;
      }
      axes[flip] = axes[flip] * -1.0;
      diagonal[flip] = -diagonal[flip];
    }
    const double trace = diagonal[0] + diagonal[1] + diagonal[2];
    if (trace > best_trace) {
      best_trace = trace;
      for (int k = 0; k < 3; ++k) {
        best.axes[k] = axes[k];
        best.moments[k] = a[perm[k]][perm[k]];
      }
    }
  }
  return best;
}

Quat quat_from_axes(const DVec3 axes[3]) {
  // m[i][j]: row i of the rotation whose columns are the axes.
  double m[3][3];
  for (int j = 0; j < 3; ++j) {
    m[0][j] = axes[j].x;
    m[1][j] = axes[j].y;
    m[2][j] = axes[j].z;
  }
  // Shepperd: solve for the largest of |w|, |x|, |y|, |z| first, so the
  // square root and the division never see a small number.
  const double trace = m[0][0] + m[1][1] + m[2][2];
  double x;
  double y;
  double z;
  double w;
  if (trace >= m[0][0] && trace >= m[1][1] && trace >= m[2][2]) {
    w = 0.5 * std::sqrt(1.0 + trace);
    const double k = 0.25 / w;
    x = (m[2][1] - m[1][2]) * k;
    y = (m[0][2] - m[2][0]) * k;
    z = (m[1][0] - m[0][1]) * k;
  } else if (m[0][0] >= m[1][1] && m[0][0] >= m[2][2]) {
    x = 0.5 * std::sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]);
    const double k = 0.25 / x;
    w = (m[2][1] - m[1][2]) * k;
    y = (m[0][1] + m[1][0]) * k;
    z = (m[0][2] + m[2][0]) * k;
  } else if (m[1][1] >= m[2][2]) {
    y = 0.5 * std::sqrt(1.0 - m[0][0] + m[1][1] - m[2][2]);
    const double k = 0.25 / y;
    w = (m[0][2] - m[2][0]) * k;
    x = (m[0][1] + m[1][0]) * k;
    z = (m[1][2] + m[2][1]) * k;
  } else {
    z = 0.5 * std::sqrt(1.0 - m[0][0] - m[1][1] + m[2][2]);
    const double k = 0.25 / z;
    w = (m[1][0] - m[0][1]) * k;
    x = (m[0][2] + m[2][0]) * k;
    y = (m[1][2] + m[2][1]) * k;
  }
  const double sign = w < 0.0 ? -1.0 : 1.0;  // q and -q are one rotation: keep w >= 0
  const double inv = sign / std::sqrt(x * x + y * y + z * z + w * w);
  return {static_cast<float>(x * inv), static_cast<float>(y * inv), static_cast<float>(z * inv),
          static_cast<float>(w * inv)};
}

}  // namespace rwd::sim::d3::hull_steps
