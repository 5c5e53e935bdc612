// SPDX-License-Identifier: BSD-3-Clause
/// @file statistics.h
/// The spreads that scale the exponents of eq. 3 and 4 of Feng et al. 2010 (sigma_k, sigma_d,
/// sigma_theta): population standard deviations, one formula for every stage.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
/// Population standard deviation from a sum, a sum of squares and a count; 0 for fewer than
/// two values (and never the root of a negative rounding residue).
inline double standardDeviation(double sum, double sumSquares, double count)
{
  if (count < 2.0)
  {
    return 0.0;
  }
  const double mean = sum / count;
  return std::sqrt(std::max(0.0, sumSquares / count - mean * mean));
}

/// sigma_k of eq. 3 and 4: the standard deviation of |kappa| over all faces.
/// @param[in] faceMeanCurvature  #F mean curvature per face
inline double curvatureSpread(const std::vector<double>& faceMeanCurvature)
{
  double sum = 0.0, squares = 0.0;
  for (double k : faceMeanCurvature)
  {
    sum += std::abs(k);
    squares += k * k;
  }
  return standardDeviation(sum, squares, static_cast<double>(faceMeanCurvature.size()));
}
} // namespace detail
} // namespace tc
