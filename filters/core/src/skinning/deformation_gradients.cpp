// SPDX-License-Identifier: BSD-3-Clause
#include "skinning/deformation_gradients.h"

#include "tc/common/parallel.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace tc
{
namespace detail
{
namespace deformation
{
namespace
{
// A rest face counts as degenerate when |e1 x e2| is below this fraction of its longest
// squared edge (the sine of its largest angle): float positions cannot resolve a thinner one,
// and its gradient would be rounding noise.
constexpr double kDegenerateSine = 1e-6;

// V = [e1 e2 e3] of the face (a, b, c) in `points`, e3 = n / sqrt(|n|) (Sumner et al. 2005:
// the fourth vertex v4 = v1 + e3 gives the face a thickness that scales with its size). A face
// without area gets e3 = 0. `sine` receives |n| / max |e|^2.
Eigen::Matrix3d edgeMatrix(
  const std::vector<float>& points, int32_t a, int32_t b, int32_t c, double* sine = nullptr)
{
  const Eigen::Vector3d p(points[3 * a], points[3 * a + 1], points[3 * a + 2]);
  const Eigen::Vector3d e1 =
    Eigen::Vector3d(points[3 * b], points[3 * b + 1], points[3 * b + 2]) - p;
  const Eigen::Vector3d e2 =
    Eigen::Vector3d(points[3 * c], points[3 * c + 1], points[3 * c + 2]) - p;
  const Eigen::Vector3d n = e1.cross(e2);
  const double area2 = n.norm();
  Eigen::Matrix3d v;
  v.col(0) = e1;
  v.col(1) = e2;
  v.col(2) = area2 > 0.0 ? Eigen::Vector3d(n / std::sqrt(area2)) : Eigen::Vector3d::Zero();
  if (sine != nullptr)
  {
    const double longest =
      std::max({ e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm() });
    *sine = longest > 0.0 ? area2 / longest : 0.0;
  }
  return v;
}

// ||a - b||_F of two row-major 3 x 3 matrices.
double frobeniusDistance(const double* a, const double* b)
{
  double d2 = 0.0;
  for (int c = 0; c < 9; ++c)
  {
    d2 += (a[c] - b[c]) * (a[c] - b[c]);
  }
  return std::sqrt(d2);
}

// Sums for sigma_Gamma over faces and frames, added in face order (deterministic).
struct GradientMoments
{
  double sum[9] = {};
  double squares = 0.0;
  double count = 0.0;

  void add(const double* g)
  {
    for (int c = 0; c < 9; ++c)
    {
      sum[c] += g[c];
      squares += g[c] * g[c];
    }
    count += 1.0;
  }

  void add(const std::vector<double>& gamma, const std::vector<uint8_t>& degenerate)
  {
    for (size_t f = 0; f < degenerate.size(); ++f)
    {
      if (!degenerate[f])
      {
        add(&gamma[9 * f]);
      }
    }
  }

  // sqrt(mean ||Gamma||^2 - ||mean Gamma||^2), 0 without a value.
  double standardDeviation() const
  {
    if (count == 0.0)
    {
      return 0.0;
    }
    double meanSquared = 0.0;
    for (double s : sum)
    {
      meanSquared += (s / count) * (s / count);
    }
    return std::sqrt(std::max(0.0, squares / count - meanSquared));
  }
};
} // namespace

RestInverses restInverses(const std::vector<int32_t>& triangles, const std::vector<float>& rest)
{
  const int64_t nf = static_cast<int64_t>(triangles.size() / 3);
  RestInverses out;
  out.inverse.assign(9 * nf, 0.0);
  out.degenerate.assign(nf, 0);
  parallel_for(nf,
    [&](int64_t f)
    {
      double sine = 0.0;
      const Eigen::Matrix3d v =
        edgeMatrix(rest, triangles[3 * f], triangles[3 * f + 1], triangles[3 * f + 2], &sine);
      if (!(sine > kDegenerateSine))
      {
        out.degenerate[f] = 1;
        return;
      }
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(&out.inverse[9 * f]) = v.inverse();
    });
  return out;
}

void frameGradients(const std::vector<int32_t>& triangles, const RestInverses& rest,
  const std::vector<float>& deformed, std::vector<double>& gamma)
{
  const int64_t nf = static_cast<int64_t>(triangles.size() / 3);
  gamma.assign(9 * nf, 0.0);
  parallel_for(nf,
    [&](int64_t f)
    {
      if (rest.degenerate[f])
      {
        return;
      }
      using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
      const Eigen::Map<const RowMajor3> inverse(&rest.inverse[9 * f]);
      Eigen::Map<RowMajor3> out(&gamma[9 * f]);
      out = edgeMatrix(deformed, triangles[3 * f], triangles[3 * f + 1], triangles[3 * f + 2]) *
        inverse;
    });
}

GradientDifferences gradientDifferences(const std::vector<int32_t>& triangles,
  const std::vector<std::vector<float>>& frames, const spectral::DualGraph& graph,
  const Progress& progress)
{
  const int64_t rows = graph.offsets.empty() ? 0 : static_cast<int64_t>(graph.offsets.size()) - 1;
  const RestInverses rest = restInverses(triangles, frames[0]);
  GradientDifferences out;
  out.meanDifference.assign(graph.ids.size(), 0.0);
  GradientMoments moments;
  std::vector<double> gamma;
  const int64_t numFrames = static_cast<int64_t>(frames.size());
  for (int64_t k = 1; k < numFrames; ++k)
  {
    frameGradients(triangles, rest, frames[k], gamma);
    moments.add(gamma, rest.degenerate);
    parallel_for(rows,
      [&](int64_t f)
      {
        for (int64_t e = graph.offsets[f]; e < graph.offsets[f + 1]; ++e)
        {
          const int32_t g = graph.ids[e];
          if (!rest.degenerate[f] && !rest.degenerate[g])
          {
            out.meanDifference[e] += frobeniusDistance(&gamma[9 * f], &gamma[9 * g]);
          }
        }
      });
    progress.report(static_cast<double>(k) / static_cast<double>(numFrames));
  }
  out.sigma = moments.standardDeviation();
  for (double& d : out.meanDifference)
  {
    d /= static_cast<double>(std::max<int64_t>(1, numFrames - 1));
  }
  progress.report(1.0);
  return out;
}
} // namespace deformation
} // namespace detail
} // namespace tc
