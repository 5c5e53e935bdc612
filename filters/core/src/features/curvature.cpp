// SPDX-License-Identifier: BSD-3-Clause
#include "tc/features/curvature.h"

#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"
#include "tc/common/parallel.h"

#include <Eigen/Dense>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

// The fit is written by hand on Eigen rather than with CGAL's Monge_via_jet_fitting: that
// class takes no per-point weights, and both the Gaussian distance weights and the robust
// reweighting (IRLS) of Kalogerakis et al. 2007 need them.

namespace tc
{
namespace
{
using Vec3 = Eigen::Vector3d;

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

// Scratch space of one thread, sized once: the hot loop allocates nothing per vertex.
struct Workspace
{
  std::vector<uint32_t> mark; // #V visit stamps of the ring search
  uint32_t stamp = 0;
  std::vector<int32_t> ids;     // neighbourhood, the vertex itself first
  std::vector<double> offsets;  // 3 per point: (p - p_v) / radius in world axes
  std::vector<double> height;   // z of each point in the fitting frame
  std::vector<double> mono;     // 10 per point: monomials of (x, y) in the fitting frame
  std::vector<double> spatial;  // Gaussian distance weights
  std::vector<double> weight;   // spatial * robust weights
  std::vector<double> residual; // |residuals| (scratch for the median)

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

struct Frame
{
  Vec3 t1, t2, n;
};

// A right-handed orthonormal frame around the unit normal n, deterministic in n.
Frame frameAround(const Vec3& n)
{
  Frame f;
  f.n = n;
  const Vec3 axis = std::abs(n.x()) <= std::abs(n.y()) && std::abs(n.x()) <= std::abs(n.z())
    ? Vec3::UnitX()
    : (std::abs(n.y()) <= std::abs(n.z()) ? Vec3::UnitY() : Vec3::UnitZ());
  f.t1 = n.cross(axis).normalized();
  f.t2 = n.cross(f.t1);
  return f;
}

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

// Coordinates of the neighbourhood in `frame` (heights and monomials of the tangent
// coordinates).
void toFrame(Workspace& ws, int n, const Frame& frame)
{
  for (int i = 0; i < n; ++i)
  {
    const Vec3 d(ws.offsets[3 * i], ws.offsets[3 * i + 1], ws.offsets[3 * i + 2]);
    monomials(d.dot(frame.t1), d.dot(frame.t2), &ws.mono[10 * i]);
    ws.height[i] = d.dot(frame.n);
  }
}

// The most detailed model that the neighbourhood supports, robustly fitted in the current
// frame. Returns the number of terms of the model used (0: none could be fitted).
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

struct Shape
{
  double k1 = 0.0, k2 = 0.0;
  Vec3 d1, normal; // in the fitting frame's coordinates
};

// Principal curvatures of the fitted graph z = f(x, y) at the origin, from its first and
// second fundamental forms (the fitted normal is (-fx, -fy, 1) / w, not the frame's z axis).
Shape shapeOperator(const double c[10])
{
  const double fx = c[1], fy = c[2];
  const double fxx = 2.0 * c[3], fxy = c[4], fyy = 2.0 * c[5];
  const double w = std::sqrt(1.0 + fx * fx + fy * fy);
  const Vec3 rx(1.0, 0.0, fx), ry(0.0, 1.0, fy);
  Shape s;
  s.normal = Vec3(-fx, -fy, 1.0) / w;
  // Orthonormal tangent basis (e1, e2) and P, the parameter coordinates of e1 and e2: then
  // P^T II P is the second fundamental form in an orthonormal basis, i.e. the symmetric
  // shape operator (the first fundamental form becomes the identity).
  const Vec3 e1 = rx.normalized();
  const Vec3 e2 = s.normal.cross(e1);
  Eigen::Matrix2d BtJ;
  BtJ << e1.dot(rx), e1.dot(ry), e2.dot(rx), e2.dot(ry);
  const Eigen::Matrix2d P = BtJ.inverse();
  Eigen::Matrix2d II;
  II << fxx / w, fxy / w, fxy / w, fyy / w;
  // Minus: a surface bending away from its normal (f'' < 0 under an outward normal) is convex.
  Eigen::Matrix2d S = -(P.transpose() * II * P);
  const double a = S(0, 0), b = 0.5 * (S(0, 1) + S(1, 0)), d = S(1, 1);
  const double mean = 0.5 * (a + d);
  const double radius = std::hypot(0.5 * (a - d), b);
  s.k1 = mean + radius;
  s.k2 = mean - radius;
  const double theta = 0.5 * std::atan2(2.0 * b, a - d);
  s.d1 = std::cos(theta) * e1 + std::sin(theta) * e2;
  return s;
}

struct VertexEstimate
{
  double k1 = 0.0, k2 = 0.0;
  Vec3 d1 = Vec3::UnitX(), d2 = Vec3::UnitY(), normal = Vec3::UnitZ();
};

// Adaptive neighbourhood: whole rings around v until at least minNeighbors vertices and two
// rings, or maxRings, or no growth. Leaves the ids in ws.ids (v first); returns the count.
int gatherNeighbourhood(
  Workspace& ws, int32_t v, const VertexRing& ring, const CurvatureOptions& options)
{
  if (++ws.stamp == 0)
  {
    std::fill(ws.mark.begin(), ws.mark.end(), 0u);
    ws.stamp = 1;
  }
  ws.ids.clear();
  ws.ids.push_back(v);
  ws.mark[v] = ws.stamp;
  size_t ringBegin = 0;
  for (int rings = 0; rings < options.maxRings; ++rings)
  {
    const size_t ringEnd = ws.ids.size();
    for (size_t k = ringBegin; k < ringEnd; ++k)
    {
      const int32_t u = ws.ids[k];
      for (int64_t j = ring.offsets[u]; j < ring.offsets[u + 1]; ++j)
      {
        const int32_t q = ring.ids[j];
        if (ws.mark[q] != ws.stamp)
        {
          ws.mark[q] = ws.stamp;
          ws.ids.push_back(q);
        }
      }
    }
    ringBegin = ringEnd;
    const bool grew = ws.ids.size() > ringEnd;
    if (!grew || (rings + 1 >= 2 && static_cast<int>(ws.ids.size()) - 1 >= options.minNeighbors))
    {
      break;
    }
  }
  return static_cast<int>(ws.ids.size());
}

VertexEstimate estimateVertex(Workspace& ws, int32_t v, const TriMesh& mesh, const VertexRing& ring,
  const std::vector<double>& areaNormals, const CurvatureOptions& options)
{
  VertexEstimate out;
  const int n = gatherNeighbourhood(ws, v, ring, options);
  ws.reserve(ws.ids.size());
  const Vec3 pv(mesh.points[3 * v], mesh.points[3 * v + 1], mesh.points[3 * v + 2]);
  double radius = 0.0;
  for (int i = 0; i < n; ++i)
  {
    const int32_t q = ws.ids[i];
    const Vec3 d = Vec3(mesh.points[3 * q], mesh.points[3 * q + 1], mesh.points[3 * q + 2]) - pv;
    radius = std::max(radius, d.norm());
  }
  Vec3 n0(areaNormals[3 * v], areaNormals[3 * v + 1], areaNormals[3 * v + 2]);
  if (n < 2 || !(radius > 0.0) || !std::isfinite(radius))
  {
    if (n0.norm() > 0.0)
    {
      out.normal = n0.normalized();
      const Frame f = frameAround(out.normal);
      out.d1 = f.t1;
      out.d2 = f.t2;
    }
    return out;
  }
  // Everything below is in units of the neighbourhood radius: the estimate is scale covariant.
  const double inv = 1.0 / radius;
  const double twoSigma2 = 2.0 * options.weightSigma * options.weightSigma;
  for (int i = 0; i < n; ++i)
  {
    const int32_t q = ws.ids[i];
    for (int c = 0; c < 3; ++c)
    {
      ws.offsets[3 * i + c] = (mesh.points[3 * q + c] - pv[c]) * inv;
    }
    const double r2 = ws.offsets[3 * i] * ws.offsets[3 * i] +
      ws.offsets[3 * i + 1] * ws.offsets[3 * i + 1] + ws.offsets[3 * i + 2] * ws.offsets[3 * i + 2];
    ws.spatial[i] = std::exp(-r2 / twoSigma2);
  }
  // The area-weighted normal (|sum of face cross products|, ~ twice the one-ring area) is the
  // initial frame; if the fan is degenerate (zero area or cancelling), the least-variance axis
  // of the neighbourhood replaces it, oriented like the faces where they say anything.
  const double areaScale = radius * radius;
  if (!(n0.norm() > 1e-12 * areaScale))
  {
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    Vec3 mean = Vec3::Zero();
    for (int i = 0; i < n; ++i)
    {
      mean += Vec3(ws.offsets[3 * i], ws.offsets[3 * i + 1], ws.offsets[3 * i + 2]);
    }
    mean /= n;
    for (int i = 0; i < n; ++i)
    {
      const Vec3 d = Vec3(ws.offsets[3 * i], ws.offsets[3 * i + 1], ws.offsets[3 * i + 2]) - mean;
      cov += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(cov);
    Vec3 axis = eig.eigenvectors().col(0);
    if (axis.dot(n0) < 0.0)
    {
      axis = -axis;
    }
    n0 = axis;
  }
  Frame frame = frameAround(n0.normalized());
  double coeffs[10];
  if (options.refit && n >= 9)
  {
    // A first, plain quadric fit refines the normal; the real fit then happens in that frame,
    // where the graph is nearly horizontal at the origin and a polynomial represents it best.
    toFrame(ws, n, frame);
    std::copy(ws.spatial.begin(), ws.spatial.begin() + n, ws.weight.begin());
    if (fitModel(ws, n, kQuadricTerms, coeffs))
    {
      const Vec3 fitted = frame.n - coeffs[1] * frame.t1 - coeffs[2] * frame.t2;
      frame = frameAround(fitted.normalized());
    }
  }
  toFrame(ws, n, frame);
  const int terms = fitBestModel(ws, n, options, coeffs);
  if (terms == 0)
  {
    out.normal = frame.n;
    out.d1 = frame.t1;
    out.d2 = frame.t2;
    return out;
  }
  const Shape shape = shapeOperator(coeffs);
  const auto toWorld = [&frame](const Vec3& l)
  { return Vec3(l.x() * frame.t1 + l.y() * frame.t2 + l.z() * frame.n); };
  out.normal = toWorld(shape.normal).normalized();
  Vec3 d1 = toWorld(shape.d1);
  d1 = (d1 - d1.dot(out.normal) * out.normal).normalized();
  // Deterministic sign (a principal direction is an axis): d1 points to the side of a fixed
  // generic direction, whose components are unrelated irrationals so that no symmetric mesh
  // puts a direction exactly orthogonal to it (where rounding could flip the choice).
  if (d1.dot(Vec3(0.3183098861837907, 0.5772156649015329, 0.7548776662466927)) < 0.0)
  {
    d1 = -d1;
  }
  out.d1 = d1;
  out.d2 = out.normal.cross(d1);
  out.k1 = shape.k1 * inv;
  out.k2 = shape.k2 * inv;
  return out;
}

void validate(const TriMesh& mesh, const CurvatureOptions& options)
{
  if (mesh.points.size() % 3 != 0 || mesh.triangles.size() % 3 != 0)
  {
    throw InputError("computeCurvature: points and triangles must hold 3 values per entry");
  }
  const int64_t nv = mesh.numPoints();
  for (int32_t id : mesh.triangles)
  {
    if (id < 0 || id >= nv)
    {
      throw InputError("computeCurvature: a triangle references vertex " + std::to_string(id) +
        " of a mesh with " + std::to_string(nv) + " vertices; fix the connectivity");
    }
  }
  if (options.degree != 2 && options.degree != 3)
  {
    throw InputError(
      "computeCurvature: degree must be 2 or 3, not " + std::to_string(options.degree));
  }
  if (options.maxRings < 1 || options.minNeighbors < 0 || options.robustIterations < 0 ||
    !(options.weightSigma > 0.0))
  {
    throw InputError("computeCurvature: maxRings >= 1, minNeighbors >= 0, robustIterations >= 0 "
                     "and weightSigma > 0 are required");
  }
}
} // namespace

CurvatureResult computeCurvature(
  const TriMesh& mesh, const CurvatureOptions& options, const Progress& progress)
{
  validate(mesh, options);
  const int64_t nv = mesh.numPoints();
  const int64_t nf = mesh.numTriangles();
  const EdgeTable edges = buildEdgeTable(mesh.triangles);
  const VertexRing ring = buildVertexRing(edges, nv);
  const VertexFaces vertexFaces = buildVertexFaces(mesh.triangles, nv);
  progress.report(0.05);

  // Area-weighted vertex normals: sum of the (unnormalized) face normals, CCW = outward.
  std::vector<double> faceNormals(3 * nf);
  parallel_for(
    nf,
    [&](int64_t f)
    {
      const int32_t* t = &mesh.triangles[3 * f];
      const Vec3 a(mesh.points[3 * t[0]], mesh.points[3 * t[0] + 1], mesh.points[3 * t[0] + 2]);
      const Vec3 b(mesh.points[3 * t[1]], mesh.points[3 * t[1] + 1], mesh.points[3 * t[1] + 2]);
      const Vec3 c(mesh.points[3 * t[2]], mesh.points[3 * t[2] + 1], mesh.points[3 * t[2] + 2]);
      const Vec3 n = (b - a).cross(c - a);
      std::copy(n.data(), n.data() + 3, &faceNormals[3 * f]);
    },
    progress.sub(0.05, 0.07), 4);
  std::vector<double> areaNormals(3 * nv, 0.0);
  parallel_for(
    nv,
    [&](int64_t v)
    {
      for (int64_t k = vertexFaces.offsets[v]; k < vertexFaces.offsets[v + 1]; ++k)
      {
        for (int c = 0; c < 3; ++c)
        {
          areaNormals[3 * v + c] += faceNormals[3 * vertexFaces.faceIds[k] + c];
        }
      }
    },
    progress.sub(0.07, 0.1), 4);

  CurvatureResult result;
  result.k1.resize(nv);
  result.k2.resize(nv);
  result.d1.resize(3 * nv);
  result.d2.resize(3 * nv);
  result.normals.resize(3 * nv);
  result.mean.resize(nv);
  result.gaussian.resize(nv);
  tbb::enumerable_thread_specific<Workspace> workspaces;
  parallel_for(
    nv,
    [&](int64_t v)
    {
      Workspace& ws = workspaces.local();
      if (ws.mark.size() != static_cast<size_t>(nv))
      {
        ws.mark.assign(nv, 0u);
        ws.stamp = 0;
      }
      const VertexEstimate e =
        estimateVertex(ws, static_cast<int32_t>(v), mesh, ring, areaNormals, options);
      result.k1[v] = e.k1;
      result.k2[v] = e.k2;
      result.mean[v] = 0.5 * (e.k1 + e.k2);
      result.gaussian[v] = e.k1 * e.k2;
      for (int c = 0; c < 3; ++c)
      {
        result.d1[3 * v + c] = e.d1[c];
        result.d2[3 * v + c] = e.d2[c];
        result.normals[3 * v + c] = e.normal[c];
      }
    },
    progress.sub(0.1, 0.98));

  result.faceMean.resize(nf);
  for (int64_t f = 0; f < nf; ++f)
  {
    const int32_t* t = &mesh.triangles[3 * f];
    result.faceMean[f] = (result.mean[t[0]] + result.mean[t[1]] + result.mean[t[2]]) / 3.0;
  }
  progress.report(1.0);
  return result;
}
} // namespace tc
