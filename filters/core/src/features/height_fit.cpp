// SPDX-License-Identifier: BSD-3-Clause
#include "features/height_fit.h"

#include <algorithm>
#include <cmath>

namespace tc
{
namespace detail
{
namespace curvature
{
namespace
{
// Below this residual scale (relative to the neighbourhood radius) a fit counts as exact:
// the robust weights of an exact fit (a plane, a quadric) stay ~1 instead of amplifying
// rounding noise.
constexpr double kResidualScaleFloor = 1e-3;
// Tukey's biweight constant (95% efficiency under Gaussian noise) and the MAD-to-sigma factor.
constexpr double kTukey = 4.685;
constexpr double kMadToSigma = 1.4826;
// A model is rejected (the next simpler one is tried) when a pivot of its normal equations
// falls below this fraction of the diagonal entry, i.e. when a monomial is explained by the
// previous ones to within 1e-10 on this neighbourhood (1 - R^2 of that regression).
constexpr double kMinRelativePivot = 1e-10;

// The polynomial models of the height function, by their monomials of
// [1, x, y, x^2, xy, y^2, x^3, x^2 y, x y^2, y^3].
constexpr int kCubicTerms[10] = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9 };
constexpr int kQuadricTerms[6] = { 0, 1, 2, 3, 4, 5 };
// The last resort for tiny neighbourhoods (a lone triangle fan): z = a x^2 + b xy + c y^2, the
// frame's normal kept as the surface normal.
constexpr int kOsculatingTerms[3] = { 3, 4, 5 };

// Solves the symmetric positive definite N x N system A x = b (lower triangle of A used) by
// an unpivoted LDL^T factorization, fully unrolled for the small fixed N. False when a relative
// pivot says the monomials are (nearly) dependent on this neighbourhood.
template <int N>
bool solveSymmetric(const double (&A)[N][N], const double (&b)[N], double (&x)[N])
{
  double L[N][N];
  double d[N];
  for (int j = 0; j < N; ++j)
  {
    double v = A[j][j];
    for (int k = 0; k < j; ++k)
    {
      v -= L[j][k] * L[j][k] * d[k];
    }
    if (!(v > kMinRelativePivot * A[j][j]) || !(A[j][j] > 1e-14 * A[0][0]))
    {
      return false;
    }
    d[j] = v;
    const double inv = 1.0 / v;
    for (int i = j + 1; i < N; ++i)
    {
      double s = A[i][j];
      for (int k = 0; k < j; ++k)
      {
        s -= L[i][k] * L[j][k] * d[k];
      }
      L[i][j] = s * inv;
    }
  }
  for (int i = 0; i < N; ++i)
  {
    double s = b[i];
    for (int k = 0; k < i; ++k)
    {
      s -= L[i][k] * x[k];
    }
    x[i] = s;
  }
  for (int i = N - 1; i >= 0; --i)
  {
    double s = x[i] / d[i];
    for (int k = i + 1; k < N; ++k)
    {
      s -= L[k][i] * x[k];
    }
    x[i] = s;
  }
  for (int i = 0; i < N; ++i)
  {
    if (!std::isfinite(x[i]))
    {
      return false;
    }
  }
  return true;
}

// Weighted least squares of z over the monomials `terms`, in normalized local coordinates.
// Writes the 10 coefficients (zero for unused monomials); false if the system is singular.
template <int N>
bool fitModel(const Workspace& ws, int n, const int (&terms)[N], double coeffs[10])
{
  double A[N][N] = {};
  double b[N] = {};
  for (int i = 0; i < n; ++i)
  {
    const double w = ws.weight[i];
    const double* m = &ws.mono[10 * i];
    double v[N];
    for (int k = 0; k < N; ++k)
    {
      v[k] = m[terms[k]];
    }
    const double wz = w * ws.height[i];
    for (int r = 0; r < N; ++r)
    {
      const double wv = w * v[r];
      b[r] += wz * v[r];
      for (int c = 0; c <= r; ++c)
      {
        A[r][c] += wv * v[c];
      }
    }
  }
  double x[N];
  if (!solveSymmetric(A, b, x))
  {
    return false;
  }
  std::fill(coeffs, coeffs + 10, 0.0);
  for (int k = 0; k < N; ++k)
  {
    coeffs[terms[k]] = x[k];
  }
  return true;
}

inline double evaluate(const double* m, const double coeffs[10])
{
  double f = 0.0;
  for (int k = 0; k < 10; ++k)
  {
    f += coeffs[k] * m[k];
  }
  return f;
}

// Median of the absolute residuals of the fit over the neighbourhood.
double medianAbsResidual(Workspace& ws, int n, const double coeffs[10])
{
  for (int i = 0; i < n; ++i)
  {
    ws.residual[i] = std::abs(ws.height[i] - evaluate(&ws.mono[10 * i], coeffs));
  }
  std::nth_element(ws.residual.begin(), ws.residual.begin() + n / 2, ws.residual.begin() + n);
  return ws.residual[n / 2];
}

// One model: a weighted fit with the Gaussian distance weights, then `robustIterations` IRLS
// steps with Tukey's biweight on a MAD scale of the residuals (the M-estimation of
// Kalogerakis et al. 2007, applied to the height-function fit). Keeps the last
// successful fit if a reweighted system becomes singular.
template <int N>
bool robustFit(Workspace& ws, int n, const int (&terms)[N], int iterations, double coeffs[10])
{
  std::copy(ws.spatial.begin(), ws.spatial.begin() + n, ws.weight.begin());
  if (!fitModel(ws, n, terms, coeffs))
  {
    return false;
  }
  double trial[10];
  for (int it = 0; it < iterations; ++it)
  {
    const double scale =
      std::max(kMadToSigma * medianAbsResidual(ws, n, coeffs), kResidualScaleFloor);
    const double c = 1.0 / (kTukey * scale);
    int inliers = 0;
    for (int i = 0; i < n; ++i)
    {
      const double u = (ws.height[i] - evaluate(&ws.mono[10 * i], coeffs)) * c;
      const double t = u * u < 1.0 ? (1.0 - u * u) * (1.0 - u * u) : 0.0;
      ws.weight[i] = ws.spatial[i] * t;
      inliers += t > 0.0 ? 1 : 0;
    }
    if (inliers < N + N / 2 || !fitModel(ws, n, terms, trial))
    {
      break;
    }
    std::copy(trial, trial + 10, coeffs);
  }
  return true;
}
} // namespace

bool fitPlainQuadric(Workspace& ws, int n, double coeffs[10])
{
  std::copy(ws.spatial.begin(), ws.spatial.begin() + n, ws.weight.begin());
  return fitModel(ws, n, kQuadricTerms, coeffs);
}

int fitBestModel(Workspace& ws, int n, const CurvatureOptions& options, double coeffs[10])
{
  const int iterations = options.robust ? options.robustIterations : 0;
  // About 1.5 points per unknown before a model is tried, so that the fit approximates the
  // neighbourhood instead of interpolating it (the last resort makes do with 4 for 3).
  if (options.degree >= 3 && n >= 15 && robustFit(ws, n, kCubicTerms, iterations, coeffs))
  {
    return 10;
  }
  if (n >= 9 && robustFit(ws, n, kQuadricTerms, iterations, coeffs))
  {
    return 6;
  }
  if (n >= 4 && robustFit(ws, n, kOsculatingTerms, iterations, coeffs))
  {
    return 3;
  }
  return 0;
}
} // namespace curvature
} // namespace detail
} // namespace tc
