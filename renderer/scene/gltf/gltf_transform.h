// A node's transform as glTF gives it (a column-major 4x4 matrix, or
// translation, rotation quaternion and scale), in double precision: the
// affine part only (glTF's node matrices MUST be affine: its last row is
// ignored, as the specification's TRS decomposition implies).
#pragma once

#include <cmath>

#include "core/vec3.h"

namespace kappa {

struct Affine {
  double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};  ///< rows; column 3 the translation

  /// From glTF's column-major 16 numbers.
  static Affine from_column_major(const double* c) {
    Affine a;
    for (int r = 0; r < 3; ++r)
      for (int col = 0; col < 4; ++col) a.m[r][col] = c[col * 4 + r];
    return a;
  }
  /// T * R * S, the quaternion (x, y, z, w) of unit length.
  static Affine from_trs(const double t[3], const double q[4], const double s[3]) {
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    Affine a;
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 3; ++col) a.m[row][col] = r[row][col] * s[col];
      a.m[row][3] = t[row];
    }
    return a;
  }

  Affine operator*(const Affine& b) const {
    Affine c;
    for (int r = 0; r < 3; ++r) {
      for (int col = 0; col < 4; ++col) {
        double v = col == 3 ? m[r][3] : 0.0;
        for (int k = 0; k < 3; ++k) v += m[r][k] * b.m[k][col];
        c.m[r][col] = v;
      }
    }
    return c;
  }

  bool identity() const {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        if (m[r][c] != (r == c ? 1.0 : 0.0)) return false;
    return true;
  }
  double determinant() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }
  Vec3d point(const Vec3d& p) const {
    return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
            m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
            m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
  }
  Vec3d vector(const Vec3d& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  /// A normal's transform: the inverse transpose of the linear part, up to
  /// scale (its cofactor matrix; the caller normalises).
  Vec3d normal(const Vec3d& n) const {
    const double c[3][3] = {{m[1][1] * m[2][2] - m[1][2] * m[2][1], m[1][2] * m[2][0] - m[1][0] * m[2][2],
                             m[1][0] * m[2][1] - m[1][1] * m[2][0]},
                            {m[0][2] * m[2][1] - m[0][1] * m[2][2], m[0][0] * m[2][2] - m[0][2] * m[2][0],
                             m[0][1] * m[2][0] - m[0][0] * m[2][1]},
                            {m[0][1] * m[1][2] - m[0][2] * m[1][1], m[0][2] * m[1][0] - m[0][0] * m[1][2],
                             m[0][0] * m[1][1] - m[0][1] * m[1][0]}};
    const double sign = determinant() < 0 ? -1.0 : 1.0;
    return Vec3d{c[0][0] * n.x + c[0][1] * n.y + c[0][2] * n.z, c[1][0] * n.x + c[1][1] * n.y + c[1][2] * n.z,
                 c[2][0] * n.x + c[2][1] * n.y + c[2][2] * n.z} *
           sign;
  }
};

}  // namespace kappa
