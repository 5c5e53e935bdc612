// SPDX-License-Identifier: BSD-3-Clause
/// @file view_matrices.h
/// OpenGL-style camera matrices, row-major, for the LOD selection's tests and benchmark
/// (tc::LodView::worldToClip takes a row-major world-to-clip matrix).
#pragma once

#include <array>
#include <cmath>

namespace tctest
{
using Matrix = std::array<double, 16>;

/// a * b.
inline Matrix multiply(const Matrix& a, const Matrix& b)
{
  Matrix c{};
  for (int r = 0; r < 4; ++r)
  {
    for (int k = 0; k < 4; ++k)
    {
      for (int j = 0; j < 4; ++j)
      {
        c[4 * r + k] += a[4 * r + j] * b[4 * j + k];
      }
    }
  }
  return c;
}

/// glOrtho(left, right, bottom, top, near, far).
inline Matrix ortho(double l, double r, double b, double t, double n, double f)
{
  return { 2 / (r - l), 0, 0, -(r + l) / (r - l), 0, 2 / (t - b), 0, -(t + b) / (t - b), 0, 0,
    -2 / (f - n), -(f + n) / (f - n), 0, 0, 0, 1 };
}

/// gluPerspective(fovy, aspect, near, far): the eye at the origin looking down -z.
inline Matrix perspective(double fovyDegrees, double aspect, double n, double f)
{
  const double t = 1.0 / std::tan(fovyDegrees * 3.14159265358979323846 / 360.0);
  return { t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (f + n) / (n - f), 2 * f * n / (n - f), 0, 0, -1,
    0 };
}

/// gluLookAt(eye, target) with +y up.
inline Matrix lookAt(const std::array<double, 3>& eye, const std::array<double, 3>& target)
{
  std::array<double, 3> f{ target[0] - eye[0], target[1] - eye[1], target[2] - eye[2] };
  const double fl = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  for (double& v : f)
  {
    v /= fl;
  }
  // s = f x (0, 1, 0), u = s x f.
  std::array<double, 3> s{ -f[2], 0.0, f[0] };
  const double sl = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  for (double& v : s)
  {
    v /= sl;
  }
  const std::array<double, 3> u{ s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2],
    s[0] * f[1] - s[1] * f[0] };
  return { s[0], s[1], s[2], -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]), u[0], u[1], u[2],
    -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]), -f[0], -f[1], -f[2],
    f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2], 0, 0, 0, 1 };
}
} // namespace tctest
