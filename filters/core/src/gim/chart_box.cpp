// SPDX-License-Identifier: BSD-3-Clause
#include "gim/chart_box.h"

#include "gim/geometry_images_vec3.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

// Oriented boxes along principal axes, written by hand rather than with
// CGAL::oriented_bounding_box: CGAL's optimal-box search is costly for every chart whatever its
// size, and a detailed mesh has a thousand charts, while the box only feeds the projected-area
// LOD estimate of eq. 6, for which principal axes are close enough.

namespace tc::detail::geometry_images
{
namespace
{
struct Box
{
  std::array<double, 12> corners{};
};

/// The axis-aligned box of `points` in the frame of the rotation R (rows = axes), as c0 and its
/// three neighbours along the axes, back in world coordinates.
Box boxInFrame(const std::vector<Vec3>& points, const Eigen::Matrix3d& R)
{
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& q : points)
  {
    const Vec3 r = R * q;
    lo = lo.cwiseMin(r);
    hi = hi.cwiseMax(r);
  }
  Box b;
  const Vec3 c[4] = { lo, Vec3(hi.x(), lo.y(), lo.z()), Vec3(lo.x(), hi.y(), lo.z()),
    Vec3(lo.x(), lo.y(), hi.z()) };
  for (int i = 0; i < 4; ++i)
  {
    const Vec3 w = R.transpose() * c[i];
    for (int x = 0; x < 3; ++x)
    {
      b.corners[3 * i + x] = w[x];
    }
  }
  return b;
}

/// The box with every corner rounded by storageRounded after each axis of non-zero length grew
/// at both ends by more than that rounding can move a corner (3 x 5e-8 of the largest
/// coordinate), so it still holds every point. A flat box (a planar chart) stays flat: its points
/// may then lie off its rounded plane by the rounding, 5e-8 of the largest coordinate.
std::array<double, 12> storableBox(const std::array<double, 12>& corners)
{
  double largest = 0.0;
  for (double x : corners)
  {
    largest = std::max(largest, std::abs(x));
  }
  const double grow = 2e-7 * largest;
  std::array<double, 12> out = corners;
  Vec3 c0(corners[0], corners[1], corners[2]);
  Vec3 shift = Vec3::Zero();
  for (int k = 0; k < 3; ++k)
  {
    const Vec3 axis = Vec3(corners[3 + 3 * k], corners[4 + 3 * k], corners[5 + 3 * k]) - c0;
    const double length = axis.norm();
    const Vec3 unit = length > 0.0 ? Vec3(axis / length) : Vec3::Zero();
    shift -= grow * unit;
    for (int x = 0; x < 3; ++x)
    {
      out[3 + 3 * k + x] += 2.0 * grow * unit[x];
    }
  }
  for (int x = 0; x < 3; ++x)
  {
    out[x] += shift[x];
    for (int k = 0; k < 3; ++k)
    {
      out[3 + 3 * k + x] += shift[x];
    }
  }
  for (double& x : out)
  {
    x = storageRounded(x);
  }
  return out;
}

/// Oriented bounding box along the principal axes of `points`. With `also`: points the box
/// must hold as well, which do not set its axes (fitted samples).
Box orientedBox(const std::vector<Vec3>& points, const std::vector<Vec3>* also = nullptr)
{
  Vec3 mean = Vec3::Zero();
  for (const Vec3& q : points)
  {
    mean += q;
  }
  mean /= static_cast<double>(std::max<size_t>(points.size(), 1));
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& q : points)
  {
    cov += (q - mean) * (q - mean).transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Eigen::Matrix3d R = eig.eigenvectors().transpose();
  if (!R.allFinite() || (R * R.transpose() - Eigen::Matrix3d::Identity()).norm() > 1e-6)
  {
    R = Eigen::Matrix3d::Identity();
  }
  if (!also)
  {
    return boxInFrame(points, R);
  }
  std::vector<Vec3> all(points);
  all.insert(all.end(), also->begin(), also->end());
  return boxInFrame(all, R);
}
} // namespace

double inputDiagonal(const PatchMesh& patches)
{
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  bool any = false;
  for (int64_t v = 0; v < patches.mesh.numPoints(); ++v)
  {
    if (patches.inputPointId[v] >= 0)
    {
      lo = lo.cwiseMin(pointOf(patches.mesh, v));
      hi = hi.cwiseMax(pointOf(patches.mesh, v));
      any = true;
    }
  }
  return any ? (hi - lo).norm() : 0.0;
}

double storageRounded(double x)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.8g", x);
  return std::strtod(text, nullptr);
}

std::array<double, 12> chartBox(
  const TriMesh& mesh, const PatchParameterization& p, const ChartGrid* fitted, int32_t level)
{
  std::vector<Vec3> pts(p.points.size());
  for (size_t v = 0; v < pts.size(); ++v)
  {
    pts[v] = pointOf(mesh, p.points[v]);
  }
  if (!fitted)
  {
    return storableBox(orientedBox(pts).corners);
  }
  const int64_t n = int64_t(1) << level;
  std::vector<Vec3> samples;
  for (int64_t j = 0; j <= n; ++j)
  {
    for (int64_t i = 0; i + j <= n; ++i)
    {
      const float* q = fitted->at(level, i, j);
      samples.emplace_back(q[0], q[1], q[2]);
    }
  }
  return storableBox(orientedBox(pts, &samples).corners);
}
} // namespace tc::detail::geometry_images
