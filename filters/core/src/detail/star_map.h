// SPDX-License-Identifier: BSD-3-Clause
/// @file star_map.h
/// The star of a vertex flattened by the conformal map z^a of MAPS (Lee et al. 1998, section
/// 3.2), as the base complex's bijection check and the path tracer both draw it.
#pragma once

#include "detail/geometry2d.h"
#include "detail/vec3.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tc
{
namespace detail
{
/// Flattens the star of a vertex at `centre` whose ring (counter-clockwise, n >= 3 vertices)
/// has positions ringPos(0) .. ringPos(n - 1): the 3D angles at the centre are scaled by
/// a = 2 pi / (their sum) and the radii, relative to the first, raised to the power a. Where
/// that map does not embed the ring (one scaled angle would reach pi, a degenerate ring, a zero
/// first radius), the ring is put on the unit circle at equal angles instead. Appends the n
/// positions to z, the centre at the origin; theta and radius are scratch (resized to n).
template <class RingPosition>
void flattenStar(const V3& centre, size_t n, RingPosition ringPos, std::vector<double>& theta,
  std::vector<double>& radius, std::vector<P2>& z)
{
  theta.assign(n, 0.0);
  radius.assign(n, 0.0);
  double total = 0.0;
  for (size_t i = 0; i < n; ++i)
  {
    const V3 u = sub(ringPos(i), centre);
    const V3 v = sub(ringPos((i + 1) % n), centre);
    theta[i] = std::atan2(norm(cross(u, v)), dot(u, v));
    radius[i] = norm(u);
    total += theta[i];
  }
  const double power = 2.0 * kPi / total;
  const bool embeds = std::isfinite(power) && radius[0] > 0 &&
    std::all_of(theta.begin(), theta.end(), [&](double t) { return power * t < kPi; });
  double phi = 0.0;
  for (size_t i = 0; i < n; ++i)
  {
    const double angle = embeds ? power * phi : 2.0 * kPi * static_cast<double>(i) / n;
    const double rho = embeds ? std::pow(radius[i] / radius[0], power) : 1.0;
    z.push_back({ rho * std::cos(angle), rho * std::sin(angle) });
    phi += theta[i];
  }
}
} // namespace detail
} // namespace tc
