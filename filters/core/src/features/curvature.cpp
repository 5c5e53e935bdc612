// SPDX-License-Identifier: BSD-3-Clause
#include "tc/features/curvature.h"

#include "features/face_geometry.h"
#include "features/height_fit.h"
#include "features/input_checks.h"

#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"
#include "tc/common/parallel.h"

#include <Eigen/Dense>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

// The fit is written by hand rather than with CGAL's Monge_via_jet_fitting: that class takes no
// per-point weights, and both the Gaussian distance weights and the robust reweighting (IRLS)
// of Kalogerakis et al. 2007 need them.

namespace tc
{
namespace
{
using Vec3 = Eigen::Vector3d;
using detail::curvature::monomials;
using detail::curvature::Workspace;

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

// The distance from v of the farthest vertex of its neighbourhood (the first n of ws.ids).
double neighbourhoodRadius(const Workspace& ws, int n, const TriMesh& mesh, const Vec3& pv)
{
  double radius = 0.0;
  for (int i = 0; i < n; ++i)
  {
    const int32_t q = ws.ids[i];
    const Vec3 d = Vec3(mesh.points[3 * q], mesh.points[3 * q + 1], mesh.points[3 * q + 2]) - pv;
    radius = std::max(radius, d.norm());
  }
  return radius;
}

// Offsets of the neighbourhood from v in units of the radius (the estimate is scale covariant)
// and their Gaussian distance weights.
void loadOffsets(Workspace& ws, int n, const TriMesh& mesh, const Vec3& pv, double inv,
  const CurvatureOptions& options)
{
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
}

// The initial normal: the area-weighted one (|sum of face cross products|, ~ twice the one-ring
// area); if the fan is degenerate (zero area or cancelling), the least-variance axis of the
// neighbourhood, oriented like the faces where they say anything.
Vec3 initialNormal(const Workspace& ws, int n, const Vec3& n0, double radius)
{
  const double areaScale = radius * radius;
  if (n0.norm() > 1e-12 * areaScale)
  {
    return n0;
  }
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
  return axis;
}

// The frame of the fit: around the initial normal, or (refit) around the normal of a first,
// plain quadric fit in that frame, where the graph is nearly horizontal at the origin and a
// polynomial represents it best.
Frame fittingFrame(Workspace& ws, int n, const Vec3& normal, const CurvatureOptions& options)
{
  Frame frame = frameAround(normal.normalized());
  double coeffs[10];
  if (options.refit && n >= 9)
  {
    toFrame(ws, n, frame);
    if (detail::curvature::fitPlainQuadric(ws, n, coeffs))
    {
      const Vec3 fitted = frame.n - coeffs[1] * frame.t1 - coeffs[2] * frame.t2;
      frame = frameAround(fitted.normalized());
    }
  }
  return frame;
}

// The estimate from the shape operator of the fit in `frame`, curvatures back in world units.
VertexEstimate principalEstimate(const Shape& shape, const Frame& frame, double inv)
{
  VertexEstimate out;
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

// Zero curvature in the frame around `normal` (or the default +z frame for a zero normal).
VertexEstimate flatEstimate(const Vec3& normal)
{
  VertexEstimate out;
  if (normal.norm() > 0.0)
  {
    out.normal = normal.normalized();
    const Frame f = frameAround(out.normal);
    out.d1 = f.t1;
    out.d2 = f.t2;
  }
  return out;
}

VertexEstimate estimateVertex(Workspace& ws, int32_t v, const TriMesh& mesh, const VertexRing& ring,
  const std::vector<double>& areaNormals, const CurvatureOptions& options)
{
  // 1. The adaptive neighbourhood and its radius.
  const int n = gatherNeighbourhood(ws, v, ring, options);
  ws.reserve(ws.ids.size());
  const Vec3 pv(mesh.points[3 * v], mesh.points[3 * v + 1], mesh.points[3 * v + 2]);
  const double radius = neighbourhoodRadius(ws, n, mesh, pv);
  const Vec3 n0(areaNormals[3 * v], areaNormals[3 * v + 1], areaNormals[3 * v + 2]);
  if (n < 2 || !(radius > 0.0) || !std::isfinite(radius))
  {
    return flatEstimate(n0);
  }
  // 2. Offsets and weights in units of the radius, the fitting frame.
  const double inv = 1.0 / radius;
  loadOffsets(ws, n, mesh, pv, inv, options);
  const Frame frame = fittingFrame(ws, n, initialNormal(ws, n, n0, radius), options);
  // 3. The robust fit in that frame and its shape operator.
  toFrame(ws, n, frame);
  double coeffs[10];
  if (detail::curvature::fitBestModel(ws, n, options, coeffs) == 0)
  {
    VertexEstimate out;
    out.normal = frame.n;
    out.d1 = frame.t1;
    out.d2 = frame.t2;
    return out;
  }
  return principalEstimate(shapeOperator(coeffs), frame, inv);
}

void validate(const TriMesh& mesh, const CurvatureOptions& options)
{
  if (mesh.points.size() % 3 != 0 || mesh.triangles.size() % 3 != 0)
  {
    throw InputError("computeCurvature: points and triangles must hold 3 values per entry");
  }
  detail::requireVertexIds(mesh, "computeCurvature: ");
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

// Area-weighted vertex normals: sums of the (unnormalized) face normals, CCW = outward.
std::vector<double> areaWeightedNormals(
  const TriMesh& mesh, const VertexFaces& vertexFaces, const Progress& progress)
{
  const int64_t nv = mesh.numPoints();
  const std::vector<double> faceNormals = detail::faceCrossProducts(mesh);
  progress.report(0.4);
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
    progress.sub(0.4, 1.0), 4);
  return areaNormals;
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

  // 1. The initial normals.
  const std::vector<double> areaNormals =
    areaWeightedNormals(mesh, vertexFaces, progress.sub(0.05, 0.1));

  // 2. The robust fit at every vertex.
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

  // 3. The mean curvature per face, for the clustering.
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
