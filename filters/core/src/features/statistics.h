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
/// |k_f| / sigma_k per face, the curvature term of eq. 3. All 0 when sigma_k = 0 (a plane, a
/// sphere): the factor is then the same for every pair and cancels in D^-1/2 W D^-1/2 (no 0/0).
/// @return #F
inline std::vector<double> curvatureExponents(const std::vector<double>& faceMeanCurvature)
{
  const double sigmaK = curvatureSpread(faceMeanCurvature);
  std::vector<double> curvExp(faceMeanCurvature.size(), 0.0);
  if (sigmaK > 0.0)
  {
    for (size_t f = 0; f < faceMeanCurvature.size(); ++f)
    {
      curvExp[f] = std::abs(faceMeanCurvature[f]) / sigmaK;
    }
  }
  return curvExp;
}
} // namespace detail
} // namespace tc
