// SPDX-License-Identifier: BSD-3-Clause
#include "gim/atlas_quantization.h"

#include "gim/chart_box.h"
#include "gim/geometry_images_vec3.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tc::detail
{
namespace
{
/// Beyond this many steps from 0 a coordinate's code no longer fits the double decode exactly
/// (2^53) with room for the origin's sum; the frame refuses it.
constexpr double kMaxSteps = 4503599627370496.0; // 2^52

/// Every chart sample's Position in every image: f(const float* p).
template <class F>
void forEachPosition(const Atlas& atlas, F&& f)
{
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    const float* data = atlas.images[k].data[0].data();
    forEachImageSample(
      atlas, k, [&](int32_t, int32_t, int32_t, int32_t, size_t texel) { f(data + 3 * texel); });
  }
}

double signNotZero(double x)
{
  return x >= 0.0 ? 1.0 : -1.0;
}

using geometry_images::storageRounded;
using geometry_images::Vec3;

/// `x` rounded by storageRounded to no less than x (8 significant digits round by at most
/// 5e-8 of x).
double storedUpperBound(double x)
{
  return storageRounded(x * (1.0 + 1e-7));
}

/// The chart box grown along its axes by `margin` at both ends, and by what storageRounded can
/// move a corner (as chart_box.cpp's storableBox), so that it holds every sample the snap moved
/// by at most `margin`. A flat box's missing axis is its normal: the snap can move samples off
/// its plane.
std::array<double, 12> grownBox(const std::array<double, 12>& box, double margin)
{
  double largest = 0.0;
  for (double x : box)
  {
    largest = std::max(largest, std::abs(x));
  }
  const double grow = margin + 2e-7 * largest;
  const Vec3 c0(box[0], box[1], box[2]);
  std::array<Vec3, 3> unit;
  for (int k = 0; k < 3; ++k)
  {
    const Vec3 axis = Vec3(box[3 + 3 * k], box[4 + 3 * k], box[5 + 3 * k]) - c0;
    unit[k] = axis.norm() > 0.0 ? Vec3(axis.normalized()) : Vec3::Zero();
  }
  for (int k = 0; k < 3; ++k)
  {
    const Vec3 normal = unit[(k + 1) % 3].cross(unit[(k + 2) % 3]);
    if (unit[k].isZero() && normal.norm() > 0.0)
    {
      unit[k] = normal.normalized();
    }
  }
  std::array<double, 12> out = box;
  const Vec3 shift = -grow * (unit[0] + unit[1] + unit[2]);
  for (int k = 0; k < 4; ++k)
  {
    const Vec3 extra = k == 0 ? Vec3::Zero() : Vec3(2.0 * grow * unit[k - 1]);
    for (int x = 0; x < 3; ++x)
    {
      out[3 * k + x] = storageRounded(box[3 * k + x] + shift[x] + extra[x]);
    }
  }
  return out;
}

/// Keeps the chart table's promises after the snap moved chart c's samples by at most
/// `moved`: its box holds them, its level errors bound their distance to the input.
void widenChart(AtlasChart& chart, double moved)
{
  if (moved <= 0.0)
  {
    return;
  }
  chart.box = grownBox(chart.box, moved);
  for (double& e : chart.levelError)
  {
    e = storedUpperBound(e + moved);
  }
}
} // namespace

std::optional<PositionFrame> positionFrame(const Atlas& atlas)
{
  const double diagonal = atlas.inputDiagonal;
  if (!(diagonal > 0.0) || !std::isfinite(diagonal) || atlas.attributes.empty() ||
    atlas.attributes[0].components != 3)
  {
    return std::nullopt;
  }
  // diagonal = f * 2^x with f in [0.5, 1): the largest power of two <= diagonal is 2^(x - 1).
  int x = 0;
  std::frexp(diagonal, &x);
  PositionFrame frame;
  frame.stepExponent = x - 1 - kPositionStepBits;
  std::array<double, 3> low{ HUGE_VAL, HUGE_VAL, HUGE_VAL };
  std::array<double, 3> high{ -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  bool finite = true;
  forEachPosition(atlas,
    [&](const float* p)
    {
      for (int a = 0; a < 3; ++a)
      {
        finite = finite && std::isfinite(p[a]);
        low[a] = std::min(low[a], static_cast<double>(p[a]));
        high[a] = std::max(high[a], static_cast<double>(p[a]));
      }
    });
  if (!finite || low[0] > high[0])
  {
    return std::nullopt;
  }
  for (int a = 0; a < 3; ++a)
  {
    const double first = std::floor(std::ldexp(low[a], -frame.stepExponent));
    const double last = std::ceil(std::ldexp(high[a], -frame.stepExponent));
    if (std::abs(first) > kMaxSteps || std::abs(last) > kMaxSteps ||
      last - first > static_cast<double>(kMaxPositionExtent))
    {
      return std::nullopt;
    }
    frame.origin[a] = static_cast<int64_t>(first);
    frame.extent[a] = static_cast<int64_t>(last - first);
  }
  return frame;
}

float decodeCoordinate(const PositionFrame& frame, int axis, int64_t q)
{
  return static_cast<float>(
    std::ldexp(static_cast<double>(frame.origin[axis] + q), frame.stepExponent));
}

bool encodePosition(const PositionFrame& frame, const float* p, std::array<int64_t, 3>& q)
{
  std::array<int64_t, 3> codes{};
  for (int a = 0; a < 3; ++a)
  {
    const double steps = std::ldexp(static_cast<double>(p[a]), -frame.stepExponent);
    if (!(std::abs(steps) <= kMaxSteps))
    {
      return false;
    }
    codes[a] = std::llround(steps) - frame.origin[a];
    if (codes[a] < 0 || codes[a] > frame.extent[a])
    {
      return false;
    }
  }
  q = codes;
  return true;
}

void decodeNormal(int32_t bits, int32_t u, int32_t v, float* n)
{
  const double limit = normalLimit(bits);
  double x = u / limit;
  double y = v / limit;
  const double z = 1.0 - std::abs(x) - std::abs(y);
  if (z < 0.0)
  {
    // The lower hemisphere, folded over the square's corners.
    const double fx = (1.0 - std::abs(y)) * signNotZero(x);
    y = (1.0 - std::abs(x)) * signNotZero(y);
    x = fx;
  }
  const double length = std::sqrt(x * x + y * y + z * z);
  // + 0.0f turns -0.0 into +0.0 (signNotZero(-0.0) is +1, so -0.0 would encode like +0.0 but
  // not decode back to it).
  n[0] = static_cast<float>(x / length) + 0.0f;
  n[1] = static_cast<float>(y / length) + 0.0f;
  n[2] = static_cast<float>(z / length) + 0.0f;
}

bool encodeNormal(int32_t bits, const float* n, std::array<int32_t, 2>& uv)
{
  const double x = n[0];
  const double y = n[1];
  const double z = n[2];
  const double l1 = std::abs(x) + std::abs(y) + std::abs(z);
  if (!(l1 > 0.0) || !std::isfinite(l1))
  {
    return false;
  }
  double px = x / l1;
  double py = y / l1;
  if (z < 0.0)
  {
    const double fx = (1.0 - std::abs(py)) * signNotZero(px);
    py = (1.0 - std::abs(px)) * signNotZero(py);
    px = fx;
  }
  // Of the four codes around the projection, the one whose normal is closest: at 12 bits its
  // angle is at most about 0.041 degrees (0.0406 on the bunny), the nearest code's 0.059.
  const int32_t limit = normalLimit(bits);
  const double u0 = std::floor(px * limit);
  const double v0 = std::floor(py * limit);
  double best = -HUGE_VAL;
  for (int du = 0; du < 2; ++du)
  {
    for (int dv = 0; dv < 2; ++dv)
    {
      const int32_t u = std::clamp(static_cast<int32_t>(u0) + du, -limit, limit);
      const int32_t v = std::clamp(static_cast<int32_t>(v0) + dv, -limit, limit);
      float m[3];
      decodeNormal(bits, u, v, m);
      const double cosine = (x * m[0] + y * m[1] + z * m[2]) / std::sqrt(x * x + y * y + z * z);
      if (cosine > best)
      {
        best = cosine;
        uv = { u, v };
      }
    }
  }
  return true;
}

void snapToLattice(Atlas& atlas)
{
  const std::optional<PositionFrame> frame = positionFrame(atlas);
  const bool normals = atlas.attributes.size() > 1 && atlas.attributes[1].components == 3;
  // Per chart: the farthest its finest level's samples (every level's) moved.
  std::vector<double> moved(atlas.charts.size(), 0.0);
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    float* positions = atlas.images[k].data[0].data();
    float* normal = normals ? atlas.images[k].data[1].data() : nullptr;
    forEachImageSample(atlas, k,
      [&](int32_t c, int32_t d, int32_t, int32_t, size_t texel)
      {
        std::array<int64_t, 3> q{};
        float* p = positions + 3 * texel;
        if (frame && encodePosition(*frame, p, q))
        {
          Vec3 offset;
          for (int a = 0; a < 3; ++a)
          {
            const float snapped = decodeCoordinate(*frame, a, q[a]);
            offset[a] = static_cast<double>(snapped) - p[a];
            p[a] = snapped;
          }
          if (d == atlas.charts[static_cast<size_t>(c)].maxLevel)
          {
            moved[static_cast<size_t>(c)] = std::max(moved[static_cast<size_t>(c)], offset.norm());
          }
        }
        std::array<int32_t, 2> uv{};
        if (normal && encodeNormal(kNormalBits, normal + 3 * texel, uv))
        {
          decodeNormal(kNormalBits, uv[0], uv[1], normal + 3 * texel);
        }
      });
  }
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    widenChart(atlas.charts[c], moved[c]);
  }
}
} // namespace tc::detail
