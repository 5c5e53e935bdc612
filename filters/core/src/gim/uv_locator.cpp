// SPDX-License-Identifier: BSD-3-Clause
#include "gim/uv_locator.h"

#include "gim/patch_parameterization.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tc::detail::geometry_images
{
namespace
{
// Barycentric tolerance of the 2-D point location (points on a shared uv edge).
constexpr double kInsideTolerance = 1e-12;
} // namespace

UvLocator::UvLocator(const PatchParameterization& p)
  : P_(p)
{
  const int64_t nt = static_cast<int64_t>(p.triangles.size() / 3);
  G_ = static_cast<int32_t>(std::clamp<double>(std::ceil(std::sqrt(double(nt))), 1.0, 1024.0));
  Offsets_.assign(static_cast<size_t>(G_) * G_ + 1, 0);
  // Two passes over the triangles of non-zero uv area: count per cell, then fill.
  for (int pass = 0; pass < 2; ++pass)
  {
    std::vector<int64_t> fill;
    if (pass == 1)
    {
      for (size_t i = 1; i < Offsets_.size(); ++i)
      {
        Offsets_[i] += Offsets_[i - 1];
      }
      Ids_.resize(static_cast<size_t>(Offsets_.back()));
      fill.assign(Offsets_.begin(), Offsets_.end() - 1);
    }
    for (int64_t t = 0; t < nt; ++t)
    {
      if (uvArea2(p, t) == 0.0)
      {
        continue;
      }
      const double* a = &p.uv[2 * p.triangles[3 * t]];
      const double* b = &p.uv[2 * p.triangles[3 * t + 1]];
      const double* q = &p.uv[2 * p.triangles[3 * t + 2]];
      const int32_t x0 = cell(std::min({ a[0], b[0], q[0] }));
      const int32_t x1 = cell(std::max({ a[0], b[0], q[0] }));
      const int32_t y0 = cell(std::min({ a[1], b[1], q[1] }));
      const int32_t y1 = cell(std::max({ a[1], b[1], q[1] }));
      for (int32_t y = y0; y <= y1; ++y)
      {
        for (int32_t x = x0; x <= x1; ++x)
        {
          const size_t id = static_cast<size_t>(y) * G_ + x;
          if (pass == 0)
          {
            ++Offsets_[id + 1];
          }
          else
          {
            Ids_[fill[id]++] = static_cast<int32_t>(t);
          }
        }
      }
    }
  }
}

UvLocator::Hit UvLocator::locate(double u, double v) const
{
  Hit best;
  double bestMin = -std::numeric_limits<double>::infinity();
  const int32_t cx = cell(u), cy = cell(v);
  for (int32_t ring = 0; ring <= G_; ++ring)
  {
    for (int32_t y = cy - ring; y <= cy + ring; ++y)
    {
      for (int32_t x = cx - ring; x <= cx + ring; ++x)
      {
        const bool onRing = std::abs(x - cx) == ring || std::abs(y - cy) == ring;
        if (!onRing || x < 0 || y < 0 || x >= G_ || y >= G_)
        {
          continue;
        }
        const size_t id = static_cast<size_t>(y) * G_ + x;
        for (int64_t s = Offsets_[id]; s < Offsets_[id + 1]; ++s)
        {
          const int32_t t = Ids_[s];
          double w[3];
          barycentric(t, u, v, w);
          const double m = std::min({ w[0], w[1], w[2] });
          if (m > bestMin)
          {
            bestMin = m;
            best.triangle = t;
            std::copy(w, w + 3, best.w);
          }
        }
      }
    }
    if (bestMin >= -kInsideTolerance)
    {
      break;
    }
  }
  if (best.triangle >= 0)
  {
    double sum = 0.0;
    for (double& x : best.w)
    {
      x = std::max(x, 0.0);
      sum += x;
    }
    for (double& x : best.w)
    {
      x = sum > 0.0 ? x / sum : 1.0 / 3.0;
    }
  }
  return best;
}

int32_t UvLocator::cell(double x) const
{
  return static_cast<int32_t>(std::clamp(std::floor(x * G_), 0.0, double(G_ - 1)));
}

void UvLocator::barycentric(int32_t t, double u, double v, double (&w)[3]) const
{
  const double* a = &P_.uv[2 * P_.triangles[3 * t]];
  const double* b = &P_.uv[2 * P_.triangles[3 * t + 1]];
  const double* q = &P_.uv[2 * P_.triangles[3 * t + 2]];
  const double area2 = uvArea2(P_, t);
  w[0] = ((b[0] - u) * (q[1] - v) - (q[0] - u) * (b[1] - v)) / area2;
  w[1] = ((q[0] - u) * (a[1] - v) - (a[0] - u) * (q[1] - v)) / area2;
  w[2] = 1.0 - w[0] - w[1];
}
} // namespace tc::detail::geometry_images
