// SPDX-License-Identifier: BSD-3-Clause
#include "gim/sample_fit.h"

#include "gim/geometry_images_vec3.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>

namespace tc::detail::geometry_images
{
namespace
{
/// Membrane weight on sample offsets, relative to the mean data weight per sample (see
/// fitInterior), and the definiteness term. A weaker membrane overshoots at creases, a stronger
/// one fits less closely.
constexpr double kFitMembrane = 0.02;
constexpr double kFitDefinite = 1e-3;

/// Solves the symmetric positive definite system of a fit (entries summed, 3 right-hand sides);
/// an empty matrix if it fails.
Eigen::MatrixX3d solveOffsets(
  int32_t n, const std::vector<Eigen::Triplet<double>>& entries, const Eigen::MatrixX3d& rhs)
{
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  if (ldlt.info() != Eigen::Success)
  {
    return {};
  }
  Eigen::MatrixX3d x = ldlt.solve(rhs);
  if (ldlt.info() != Eigen::Success || !x.allFinite())
  {
    return {};
  }
  return x;
}

/// Adds data point P with weight w at the place of barycentrics b[] of samples id[] (-1: fixed)
/// whose current positions are x[] to the normal equations of a fit of the sample offsets.
template <int K>
void addFitData(const int32_t (&id)[K], const double (&b)[K], const Vec3 (&x)[K], const Vec3& P,
  double w, std::vector<Eigen::Triplet<double>>& entries, Eigen::MatrixX3d& rhs)
{
  Vec3 r = -P;
  for (int k = 0; k < K; ++k)
  {
    r += b[k] * x[k];
  }
  for (int a = 0; a < K; ++a)
  {
    if (id[a] < 0)
    {
      continue;
    }
    rhs.row(id[a]) -= w * b[a] * r.transpose();
    for (int c = 0; c < K; ++c)
    {
      if (id[c] >= 0)
      {
        entries.emplace_back(id[a], id[c], w * b[a] * b[c]);
      }
    }
  }
}

/// The side samples of a path at level d (m = 2^d segments) fitted to the path by least squares,
/// as fitInterior fits a chart's interior: the path's points and its edges' midpoints, placed
/// by arc length on the chords between samples (weights a quarter and a half of the edge
/// lengths), a membrane on the offsets of consecutive samples and the ends fixed. `drawn` holds
/// the m + 1 interpolated positions; returns the m + 1 fitted ones (empty: keep them).
std::vector<Vec3> fitPath(const TriMesh& mesh, const int32_t* path, int64_t count, int32_t d,
  const std::vector<Vec3>& drawn)
{
  const int64_t m = int64_t(1) << d;
  if (m < 2 || count < 2)
  {
    return {};
  }
  const std::vector<double> arc = arcLengths(mesh, path, count);
  const double length = arc.back();
  if (!(length > 0.0))
  {
    return {};
  }
  const int32_t nu = static_cast<int32_t>(m - 1);
  std::vector<Vec3> x = drawn;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(nu, 3);
  auto addData = [&](double s, const Vec3& P, double w)
  {
    const double t = std::clamp(s / length, 0.0, 1.0) * m;
    const int64_t q = std::clamp<int64_t>(static_cast<int64_t>(std::floor(t)), 0, m - 1);
    const int32_t id[2] = { q == 0 ? -1 : static_cast<int32_t>(q - 1),
      q + 1 == m ? -1 : static_cast<int32_t>(q) };
    const double b[2] = { 1.0 - (t - q), t - q };
    const Vec3 xs[2] = { x[q], x[q + 1] };
    addFitData(id, b, xs, P, w, entries, rhs);
  };
  for (int64_t i = 0; i + 1 < count; ++i)
  {
    const double l = arc[i + 1] - arc[i];
    const Vec3 a = pointOf(mesh, path[i]), b = pointOf(mesh, path[i + 1]);
    addData(arc[i], a, 0.25 * l);
    addData(arc[i + 1], b, 0.25 * l);
    addData(0.5 * (arc[i] + arc[i + 1]), 0.5 * (a + b), 0.5 * l);
  }
  const double mean = length / nu;
  const double mu = kFitMembrane * mean;
  for (int32_t a = 0; a < nu; ++a)
  {
    entries.emplace_back(a, a, kFitDefinite * mean + 2.0 * mu);
    if (a + 1 < nu)
    {
      entries.emplace_back(a, a + 1, -mu);
      entries.emplace_back(a + 1, a, -mu);
    }
  }
  const Eigen::MatrixX3d delta = solveOffsets(nu, entries, rhs);
  if (delta.rows() == 0)
  {
    return {};
  }
  for (int32_t a = 0; a < nu; ++a)
  {
    x[a + 1] += delta.row(a).transpose();
  }
  return x;
}

/// The normal equations of the fit of a chart's interior at level d (n = 2^d per side): one
/// unknown offset per interior sample, numbered row by row; side samples are fixed (-1).
struct InteriorFit
{
  int32_t d = 0;
  int64_t nd = 0;
  std::vector<int32_t> unknown; ///< per sample of level d: its unknown, -1 on the sides
  int32_t nu = 0;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX3d rhs;
  double total = 0.0; ///< of the data weights

  explicit InteriorFit(int32_t level)
    : d(level)
    , nd(int64_t(1) << level)
    , unknown(static_cast<size_t>(gridVertexCount(level)), -1)
  {
    for (int64_t j = 1; j < nd; ++j)
    {
      for (int64_t i = 1; i + j < nd; ++i)
      {
        unknown[index(i, j)] = nu++;
      }
    }
    rhs = Eigen::MatrixX3d::Zero(nu, 3);
  }

  int64_t index(int64_t i, int64_t j) const
  {
    return gridVertexIndex(d, static_cast<int32_t>(i), static_cast<int32_t>(j));
  }

  /// Data point P with weight w at parameter (u, v), against the current samples of g.
  void addData(const ChartGrid& g, double u, double v, const Vec3& P, double w)
  {
    if (!(w > 0.0))
    {
      return;
    }
    total += w;
    const GridHit h = gridHit(u, v, nd);
    int32_t id[3];
    Vec3 x[3];
    for (int k = 0; k < 3; ++k)
    {
      id[k] = unknown[index(h.i[k], h.j[k])];
      const float* q = g.at(d, h.i[k], h.j[k]);
      x[k] = Vec3(q[0], q[1], q[2]);
    }
    addFitData(id, h.w, x, P, w, entries, rhs);
  }

  /// The patch's data: its triangles' centroids (weight half the area) and its points (a sixth
  /// of the area of each of their triangles).
  void addPatch(const TriMesh& mesh, const PatchParameterization& p, const ChartGrid& g)
  {
    const int64_t nt = static_cast<int64_t>(p.triangles.size() / 3);
    std::vector<double> pointWeight(p.points.size(), 0.0);
    for (int64_t t = 0; t < nt; ++t)
    {
      const int32_t* c = &p.triangles[3 * t];
      const Vec3 a = pointOf(mesh, p.points[c[0]]), b = pointOf(mesh, p.points[c[1]]),
                 e = pointOf(mesh, p.points[c[2]]);
      const double area = 0.5 * (b - a).cross(e - a).norm();
      for (int k = 0; k < 3; ++k)
      {
        pointWeight[c[k]] += area / 6.0;
      }
      addData(g, (p.uv[2 * c[0]] + p.uv[2 * c[1]] + p.uv[2 * c[2]]) / 3.0,
        (p.uv[2 * c[0] + 1] + p.uv[2 * c[1] + 1] + p.uv[2 * c[2] + 1]) / 3.0, (a + b + e) / 3.0,
        area / 2.0);
    }
    for (size_t v = 0; v < p.points.size(); ++v)
    {
      addData(g, p.uv[2 * v], p.uv[2 * v + 1], pointOf(mesh, p.points[v]), pointWeight[v]);
    }
  }

  /// The membrane over the grid edges (each once: right, up and up-left neighbours) and the
  /// definiteness term; offsets of side samples are 0.
  void addMembrane()
  {
    const double mean = total / nu;
    const double mu = kFitMembrane * mean;
    for (int64_t j = 0; j <= nd; ++j)
    {
      for (int64_t i = 0; i + j <= nd; ++i)
      {
        const int32_t a = unknown[index(i, j)];
        if (a >= 0)
        {
          entries.emplace_back(a, a, kFitDefinite * mean);
        }
        const int64_t ni[3] = { i + 1, i, i - 1 }, nj[3] = { j, j + 1, j + 1 };
        for (int k = 0; k < 3; ++k)
        {
          if (ni[k] < 0 || ni[k] + nj[k] > nd)
          {
            continue;
          }
          const int32_t b = unknown[index(ni[k], nj[k])];
          if (a >= 0)
          {
            entries.emplace_back(a, a, mu);
          }
          if (b >= 0)
          {
            entries.emplace_back(b, b, mu);
          }
          if (a >= 0 && b >= 0)
          {
            entries.emplace_back(a, b, -mu);
            entries.emplace_back(b, a, -mu);
          }
        }
      }
    }
  }
};

/// The m + 1 = 2^d + 1 samples of path e at level d, as interpolated (lower base vertex first).
std::vector<Vec3> drawnPathSamples(const PathSamples& ps, int32_t d, int32_t size)
{
  std::vector<Vec3> drawn((size_t(1) << d) + 1);
  for (size_t q = 0; q < drawn.size(); ++q)
  {
    const float* v = &ps.values[(static_cast<int64_t>(q) << (ps.level - d)) * size];
    drawn[q] = Vec3(v[0], v[1], v[2]);
  }
  return drawn;
}

/// Writes the fitted samples of a path at level d (`fitted`, lower base vertex first) into the
/// side of the chart in `slot` of its base edge e, at that chart's level: drawn sample q, or
/// the straight line between q and q + 1 for the samples in between.
void writeFittedSide(const SamplingInput& in, int32_t e, int slot, int32_t d,
  const std::vector<Vec3>& fitted, const std::vector<int32_t>& level, std::vector<ChartGrid>& grids)
{
  const int32_t c = in.L.edgeChart[2 * e + slot], k = in.L.edgeSide[2 * e + slot];
  const bool forward = sideRunsForward(in.patches, in.base, c, k);
  const int32_t shift = level[c] - d;
  const int64_t n = int64_t(1) << level[c];
  for (int64_t t = 1; t < n; ++t)
  {
    const int64_t r = forward ? t : n - t;
    const int64_t q = r >> shift;
    const int64_t rest = r - (q << shift);
    Vec3 value = fitted[q];
    if (rest != 0)
    {
      const double w = static_cast<double>(rest) / static_cast<double>(int64_t(1) << shift);
      value = (1.0 - w) * fitted[q] + w * fitted[q + 1];
    }
    const std::array<int32_t, 2> ij =
      sidePoint(k, static_cast<int32_t>(t), static_cast<int32_t>(n));
    float* out = grids[c].at(level[c], ij[0], ij[1]);
    for (int x = 0; x < 3; ++x)
    {
      out[x] = static_cast<float>(value[x]);
    }
  }
}

} // namespace

void fitSide(const SamplingInput& in, int32_t e, const std::vector<int32_t>& level,
  const std::vector<PathSamples>& paths, std::vector<ChartGrid>& grids)
{
  const Layout& L = in.L;
  const int32_t d = std::min(level[L.edgeChart[2 * e]], level[L.edgeChart[2 * e + 1]]);
  const int32_t finer = std::max(level[L.edgeChart[2 * e]], level[L.edgeChart[2 * e + 1]]);
  const std::vector<Vec3> drawn = drawnPathSamples(paths[e], d, in.S.size);
  const int64_t p0 = in.patches.pathOffsets[e], p1 = in.patches.pathOffsets[e + 1];
  std::vector<Vec3> fitted =
    fitPath(in.patches.mesh, &in.patches.pathPoints[p0], p1 - p0, d, drawn);
  if (fitted.empty())
  {
    if (finer == d)
    {
      return;
    }
    // Not fitted (a level below 1): the drawn samples stay, the finer chart's others still go
    // onto the straight lines between them.
    fitted = drawn;
  }
  for (int slot = 0; slot < 2; ++slot)
  {
    writeFittedSide(in, e, slot, d, fitted, level, grids);
  }
}

// The offsets delta minimize
//   sum over data points q of w_q |sum_k b_qk (X0_k + delta_k) - P_q|^2
//   + mu sum over grid edges (a, b) of |delta_a - delta_b|^2 + lambda sum_a |delta_a|^2,
// the data being the patch's points and its triangles' centroids at their (u, v), b_qk the
// barycentrics of q's grid triangle, X0 the interpolated samples: an offset of about a third of
// a chord's sagitta halves the largest deviation on both sides of it. Side and corner samples
// (shared with the neighbours) keep delta = 0; mu (a membrane on the offsets, relative to the
// mean data weight per sample) keeps the offsets smooth where a sample has little data, lambda
// keeps the system definite.
void fitInterior(
  const TriMesh& mesh, const PatchParameterization& p, ChartGrid& g, int32_t d, double maxOffset)
{
  InteriorFit fit(d);
  if (fit.nu == 0)
  {
    return;
  }
  fit.addPatch(mesh, p, g);
  if (!(fit.total > 0.0))
  {
    return;
  }
  fit.addMembrane();
  const Eigen::MatrixX3d delta = solveOffsets(fit.nu, fit.entries, fit.rhs);
  if (delta.rows() == 0)
  {
    return; // keep the interpolated samples
  }
  for (int64_t j = 1; j < fit.nd; ++j)
  {
    for (int64_t i = 1; i + j < fit.nd; ++i)
    {
      float* s = g.at(d, i, j);
      const int32_t a = fit.unknown[fit.index(i, j)];
      const double length = delta.row(a).norm();
      const double scale = maxOffset > 0.0 && length > maxOffset ? maxOffset / length : 1.0;
      for (int x = 0; x < 3; ++x)
      {
        s[x] = static_cast<float>(s[x] + scale * delta(a, x));
      }
    }
  }
}
} // namespace tc::detail::geometry_images
