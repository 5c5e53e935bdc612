// SPDX-License-Identifier: BSD-3-Clause
/// @file height_fit.h
/// The robust height-function fit of the curvature estimate (Feng et al. 2010, section 4.2,
/// after Kalogerakis et al. 2007): z = poly(x, y) over a vertex's neighbourhood in a local
/// frame, by weighted least squares re-weighted with Tukey's biweight (IRLS), so that outliers
/// and points across sharp creases lose their influence. Coordinates are in units of the
/// neighbourhood radius.
#pragma once

#include "tc/features/curvature.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
namespace curvature
{
/// Scratch space of one thread, sized once: the hot loop allocates nothing per vertex.
struct Workspace
{
  std::vector<uint32_t> mark; ///< #V visit stamps of the ring search
  uint32_t stamp = 0;
  std::vector<int32_t> ids;     ///< neighbourhood, the vertex itself first
  std::vector<double> offsets;  ///< 3 per point: (p - p_v) / radius in world axes
  std::vector<double> height;   ///< z of each point in the fitting frame
  std::vector<double> mono;     ///< 10 per point: monomials of (x, y) in the fitting frame
  std::vector<double> spatial;  ///< Gaussian distance weights
  std::vector<double> weight;   ///< spatial * robust weights
  std::vector<double> residual; ///< |residuals| (scratch for the median)

  void reserve(size_t n)
  {
    if (n > spatial.size())
    {
      const size_t cap = 2 * n;
      offsets.resize(3 * cap);
      height.resize(cap);
      mono.resize(10 * cap);
      spatial.resize(cap);
      weight.resize(cap);
      residual.resize(cap);
    }
  }
};

/// The monomials [1, x, y, x^2, xy, y^2, x^3, x^2 y, x y^2, y^3] of a point.
inline void monomials(double x, double y, double* m)
{
  m[0] = 1.0;
  m[1] = x;
  m[2] = y;
  m[3] = x * x;
  m[4] = x * y;
  m[5] = y * y;
  m[6] = m[3] * x;
  m[7] = m[3] * y;
  m[8] = x * m[5];
  m[9] = y * m[5];
}

/// A plain (not reweighted) quadric fit with the spatial weights of the first n points of ws.
/// @param[out] coeffs  the 10 monomial coefficients (zero for the unused ones)
/// @return false if the system is singular
bool fitPlainQuadric(Workspace& ws, int n, double coeffs[10]);

/// The most detailed model that the neighbourhood supports, robustly fitted (robustIterations
/// IRLS steps when `robust`): a cubic (degree 3, at least 15 points), a quadric (9 points), or
/// z = a x^2 + b xy + c y^2 (4 points), about 1.5 points per unknown so that the fit
/// approximates the neighbourhood instead of interpolating it.
/// @param[out] coeffs  the 10 monomial coefficients
/// @return the number of terms of the model used (0: none could be fitted)
int fitBestModel(Workspace& ws, int n, const CurvatureOptions& options, double coeffs[10]);
} // namespace curvature
} // namespace detail
} // namespace tc
