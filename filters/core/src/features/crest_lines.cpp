// SPDX-License-Identifier: BSD-3-Clause
#include "tc/features/crest_lines.h"

#include "features/input_checks.h"
#include "features/polyline_chains.h"

#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"
#include "tc/common/parallel.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

// Not CGAL's Ridges_3: it needs the third-order jet coefficients of every vertex in property
// maps (a second, separate jet fit); the extremality coefficient here is instead the one-ring
// gradient of the principal curvature that computeCurvature() already produced.

namespace tc
{
namespace
{
using Vec3 = Eigen::Vector3d;

constexpr int kRidge = 0;
constexpr int kValley = 1;
// |e| below this fraction of (largest |k| of the one-ring) / (mean one-ring edge length) is
// rounding noise: e is snapped to zero.
constexpr double kZeroExtremality = 1e-9;

inline Vec3 row(const std::vector<double>& a, int64_t i)
{
  return Vec3(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
}

// +1 or -1: the factor that orients direction b like direction a (ties count as alike, the
// same rule everywhere so that an edge and both its triangles agree).
inline double alike(const Vec3& a, const Vec3& b)
{
  return a.dot(b) >= 0.0 ? 1.0 : -1.0;
}

void validate(const TriMesh& mesh, const CurvatureResult& c)
{
  const size_t nv = static_cast<size_t>(mesh.numPoints());
  if (c.k1.size() != nv || c.k2.size() != nv || c.d1.size() != 3 * nv || c.d2.size() != 3 * nv)
  {
    throw InputError("extractCrestLines: the curvature has " + std::to_string(c.k1.size()) +
      " vertices but the mesh " + std::to_string(nv) +
      "; pass computeCurvature() of the same mesh");
  }
  detail::requireVertexIds(mesh, "extractCrestLines: ");
}

// Extremality coefficients e1 = grad(k1) . d1 and e2 = grad(k2) . d2 (Ohtake et al. 2004) of
// vertex v, the gradients fitted in the tangent plane spanned by (d1, d2) over the one-ring by
// least squares of the differences k(q) - k(v); each neighbour is weighted by 1 / |q - v|^2 so
// that every direction counts as one directional derivative. Both stay 0 where the one-ring is
// collinear.
void vertexExtremality(const TriMesh& mesh, const CurvatureResult& curvature,
  const VertexRing& ring, int64_t v, double* e)
{
  const std::vector<double>& k1 = curvature.k1;
  const std::vector<double>& k2 = curvature.k2;
  const Vec3 p = row(mesh.points, v);
  const Vec3 d1 = row(curvature.d1, v), d2 = row(curvature.d2, v);
  double a11 = 0.0, a12 = 0.0, a22 = 0.0, r1 = 0.0, r2 = 0.0, v1 = 0.0, v2 = 0.0;
  double kMax = std::max(std::abs(k1[v]), std::abs(k2[v])), lengthSum = 0.0;
  int count = 0;
  for (int64_t j = ring.offsets[v]; j < ring.offsets[v + 1]; ++j)
  {
    const int32_t q = ring.ids[j];
    const Vec3 d = row(mesh.points, q) - p;
    const double x = d.dot(d1), y = d.dot(d2);
    const double len2 = x * x + y * y;
    if (!(len2 > 0.0))
    {
      continue;
    }
    kMax = std::max(kMax, std::max(std::abs(k1[q]), std::abs(k2[q])));
    lengthSum += d.norm();
    ++count;
    const double w = 1.0 / len2;
    a11 += w * x * x;
    a12 += w * x * y;
    a22 += w * y * y;
    r1 += w * x * (k1[q] - k1[v]);
    r2 += w * y * (k1[q] - k1[v]);
    v1 += w * x * (k2[q] - k2[v]);
    v2 += w * y * (k2[q] - k2[v]);
  }
  const double det = a11 * a22 - a12 * a12;
  // The weighted Gram matrix is dimensionless; a collinear one-ring leaves the gradient
  // undefined (no crest can be placed there).
  if (!(det > 1e-12 * (a11 + a22) * (a11 + a22)))
  {
    return;
  }
  // On a symmetric mesh a vertex can lie exactly on a crest, where e is zero up to rounding and
  // its sign (so the line's path) would follow the rounding noise; such e are snapped to an
  // exact zero, which the crossing test treats consistently.
  const double zero = kZeroExtremality * kMax * count / lengthSum;
  const double e1 = (a22 * r1 - a12 * r2) / det;
  const double e2 = (a11 * v2 - a12 * v1) / det;
  e[kRidge] = std::abs(e1) > zero ? e1 : 0.0;
  e[kValley] = std::abs(e2) > zero ? e2 : 0.0;
}

// Salience threshold, relative to the mesh's own curvature and size (scale invariant): the
// larger of minRelativeCurvature times the area-weighted mean of max(|k1|, |k2|) and
// minCurvatureTimesSize / (bounding-box diagonal).
double salienceThreshold(
  const TriMesh& mesh, const CurvatureResult& curvature, const CrestLineOptions& options)
{
  const int64_t nv = mesh.numPoints();
  const int64_t nf = mesh.numTriangles();
  const std::vector<double>& k1 = curvature.k1;
  const std::vector<double>& k2 = curvature.k2;
  double areaSum = 0.0, curvatureSum = 0.0;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max()), hi = -lo;
  for (int64_t v = 0; v < nv; ++v)
  {
    lo = lo.cwiseMin(row(mesh.points, v));
    hi = hi.cwiseMax(row(mesh.points, v));
  }
  for (int64_t f = 0; f < nf; ++f)
  {
    const int32_t* t = &mesh.triangles[3 * f];
    const Vec3 a = row(mesh.points, t[0]);
    const double area = 0.5 * (row(mesh.points, t[1]) - a).cross(row(mesh.points, t[2]) - a).norm();
    double k = 0.0;
    for (int i = 0; i < 3; ++i)
    {
      k += std::max(std::abs(k1[t[i]]), std::abs(k2[t[i]]));
    }
    areaSum += area;
    curvatureSum += area * k / 3.0;
  }
  const double diagonal = nv > 0 ? (hi - lo).norm() : 0.0;
  const double typical = areaSum > 0.0 ? curvatureSum / areaSum : 0.0;
  return std::max(options.minRelativeCurvature * typical,
    diagonal > 0.0 ? options.minCurvatureTimesSize / diagonal : 0.0);
}

// A crest point is keyed by its mesh edge and crest type, so that both triangles of an edge
// share it.
inline int64_t crestKey(int64_t edge, int type)
{
  return 2 * edge + type;
}
inline int64_t keyEdge(int64_t key)
{
  return key / 2;
}
inline int keyType(int64_t key)
{
  return static_cast<int>(key % 2);
}

// Crest points, per crestKey: t is the linear interpolation parameter from the smaller vertex
// id (-1: none), k the |k| of the crest there.
struct CrestPoints
{
  std::vector<double> t;
  std::vector<double> k;
};

// Where e changes sign between the two ends of an edge once the second end's direction is
// oriented like the first's, and the crest there is dominant (Ohtake et al.: k_max > |k_min| on
// ridges, k_min < -|k_max| on valleys) and salient.
CrestPoints findCrestPoints(const EdgeTable& edges, const CurvatureResult& curvature,
  const std::vector<double>& extremality, double minCurvature, const CrestLineOptions& options,
  const Progress& progress)
{
  const int64_t ne = edges.numEdges();
  const std::vector<double>& k1 = curvature.k1;
  const std::vector<double>& k2 = curvature.k2;
  const bool wanted[2] = { options.ridges, options.valleys };
  CrestPoints points{ std::vector<double>(2 * ne, -1.0), std::vector<double>(2 * ne, 0.0) };
  parallel_for(
    ne,
    [&](int64_t e)
    {
      const int32_t a = edges.vertices[2 * e], b = edges.vertices[2 * e + 1];
      for (int type = 0; type < 2; ++type)
      {
        if (!wanted[type])
        {
          continue;
        }
        const std::vector<double>& dir = type == kRidge ? curvature.d1 : curvature.d2;
        const double s = alike(row(dir, a), row(dir, b));
        const double ea = extremality[2 * a + type];
        const double eb = extremality[2 * b + type];
        // A zero e counts as positive in its own vertex's orientation (a symbolic perturbation:
        // the crest then passes through that vertex, t = 0 or 1, and the line stays connected
        // around it through zero-length segments). Two zero ends are not a crossing: the crest
        // runs along the edge and is found on the edges beside it.
        if ((ea >= 0.0) == ((eb >= 0.0) == (s > 0.0)) || (ea == 0.0 && eb == 0.0))
        {
          continue;
        }
        const double t = std::clamp(ea / (ea - s * eb), 0.0, 1.0);
        const double c1 = (1.0 - t) * k1[a] + t * k1[b];
        const double c2 = (1.0 - t) * k2[a] + t * k2[b];
        const double k = type == kRidge ? c1 : -c2;
        const double other = type == kRidge ? std::abs(c2) : std::abs(c1);
        if (k > other && k >= minCurvature)
        {
          points.t[crestKey(e, type)] = t;
          points.k[crestKey(e, type)] = k;
        }
      }
    },
    progress, 8);
  return points;
}

// The segment of one face and crest type: its two crossed sides, or false. The triangle's
// three directions must orient consistently (no singularity of the direction field inside)
// and the linear interpolation of the oriented e must decrease along d (a maximum: ridge) or
// increase (a minimum: valley).
bool faceSegment(const TriMesh& mesh, const EdgeTable& edges, const CurvatureResult& curvature,
  const std::vector<double>& extremality, const CrestPoints& points, int64_t f, int type,
  int32_t crossed[2])
{
  const int32_t* c = &mesh.triangles[3 * f];
  const int32_t* fe = &edges.faceEdges[3 * f];
  int count = 0;
  for (int i = 0; i < 3; ++i)
  {
    if (points.t[crestKey(fe[i], type)] >= 0.0)
    {
      if (count < 2)
      {
        crossed[count] = fe[i];
      }
      ++count;
    }
  }
  if (count != 2)
  {
    return false;
  }
  const std::vector<double>& dir = type == kRidge ? curvature.d1 : curvature.d2;
  const Vec3 d0 = row(dir, c[0]), d1 = row(dir, c[1]), d2 = row(dir, c[2]);
  const double s1 = alike(d0, d1), s2 = alike(d0, d2);
  if (alike(d1, d2) != s1 * s2)
  {
    return false;
  }
  const double e0 = extremality[2 * c[0] + type];
  const double de1 = s1 * extremality[2 * c[1] + type] - e0;
  const double de2 = s2 * extremality[2 * c[2] + type] - e0;
  const Vec3 d = d0 + s1 * d1 + s2 * d2;
  // grad(e) = alpha u + beta w with grad(e) . u = de1 and grad(e) . w = de2.
  const Vec3 p0 = row(mesh.points, c[0]);
  const Vec3 u = row(mesh.points, c[1]) - p0, w = row(mesh.points, c[2]) - p0;
  const double uu = u.dot(u), uw = u.dot(w), ww = w.dot(w);
  const double det = uu * ww - uw * uw;
  if (!(det > 0.0))
  {
    return false;
  }
  const double alpha = (ww * de1 - uw * de2) / det;
  const double beta = (uu * de2 - uw * de1) / det;
  const double slope = alpha * u.dot(d) + beta * w.dot(d);
  return (type == kRidge && slope < 0.0) || (type == kValley && slope > 0.0);
}

// The segments of every face with crest points on exactly two sides, as pairs of crestKey()s,
// in face then type order.
std::vector<int64_t> crestSegments(const TriMesh& mesh, const EdgeTable& edges,
  const CurvatureResult& curvature, const std::vector<double>& extremality,
  const CrestPoints& points, const Progress& progress)
{
  const int64_t nf = mesh.numTriangles();
  std::vector<int32_t> segment(4 * nf, -1); // two edges per face and type
  parallel_for(
    nf,
    [&](int64_t f)
    {
      for (int type = 0; type < 2; ++type)
      {
        int32_t crossed[2];
        if (faceSegment(mesh, edges, curvature, extremality, points, f, type, crossed))
        {
          segment[4 * f + 2 * type] = crossed[0];
          segment[4 * f + 2 * type + 1] = crossed[1];
        }
      }
    },
    progress, 8);
  std::vector<int64_t> segmentNodes;
  for (int64_t f = 0; f < nf; ++f)
  {
    for (int type = 0; type < 2; ++type)
    {
      if (segment[4 * f + 2 * type] >= 0)
      {
        segmentNodes.push_back(crestKey(segment[4 * f + 2 * type], type));
        segmentNodes.push_back(crestKey(segment[4 * f + 2 * type + 1], type));
      }
    }
  }
  return segmentNodes;
}

// The lines that pass the filters, with their strength (sum over segments of length times the
// mean |k| at its ends: dimensionless) and points shared between lines that meet.
CrestLines filterLines(const TriMesh& mesh, const EdgeTable& edges, const CrestPoints& points,
  const detail::Polylines& chains, const CrestLineOptions& options)
{
  const auto nodePoint = [&](int64_t key)
  {
    const int64_t e = keyEdge(key);
    const double t = points.t[key];
    return Vec3((1.0 - t) * row(mesh.points, edges.vertices[2 * e]) +
      t * row(mesh.points, edges.vertices[2 * e + 1]));
  };
  CrestLines out;
  std::vector<int64_t> pointOf(2 * edges.numEdges(), -1);
  std::vector<int64_t> kept; // nodes of one line without the zero-length links
  const int64_t numLines = static_cast<int64_t>(chains.offsets.size()) - 1;
  for (int64_t l = 0; l < numLines; ++l)
  {
    // Consecutive nodes at the same position are the zero-length links around a vertex that
    // the crest passes through: one point is enough.
    kept.clear();
    double strength = 0.0;
    for (int64_t i = chains.offsets[l]; i < chains.offsets[l + 1]; ++i)
    {
      const int64_t key = chains.nodes[i];
      if (!kept.empty())
      {
        const double length = (nodePoint(key) - nodePoint(kept.back())).norm();
        if (length == 0.0)
        {
          continue;
        }
        strength += length * 0.5 * (points.k[key] + points.k[kept.back()]);
      }
      kept.push_back(key);
    }
    if (static_cast<int64_t>(kept.size()) - 1 < std::max(options.minSegments, 1) ||
      strength < options.minStrength)
    {
      continue;
    }
    for (int64_t key : kept)
    {
      if (pointOf[key] < 0)
      {
        pointOf[key] = static_cast<int64_t>(out.points.size() / 3);
        const Vec3 p = nodePoint(key);
        out.points.insert(out.points.end(), { p.x(), p.y(), p.z() });
        out.pointEdge.push_back(static_cast<int32_t>(keyEdge(key)));
      }
      out.connectivity.push_back(pointOf[key]);
    }
    out.offsets.push_back(static_cast<int64_t>(out.connectivity.size()));
    out.strength.push_back(strength);
    out.type.push_back(static_cast<int8_t>(keyType(kept.front())));
  }
  return out;
}
} // namespace

CrestLines extractCrestLines(const TriMesh& mesh, const CurvatureResult& curvature,
  const CrestLineOptions& options, const Progress& progress)
{
  validate(mesh, curvature);
  const int64_t nv = mesh.numPoints();
  const EdgeTable edges = buildEdgeTable(mesh.triangles);
  const VertexRing ring = buildVertexRing(edges, nv);
  progress.report(0.1);

  // 1. Extremality coefficients e = grad(k) . d per vertex, ridge then valley.
  std::vector<double> extremality(2 * nv, 0.0);
  parallel_for(
    nv, [&](int64_t v) { vertexExtremality(mesh, curvature, ring, v, &extremality[2 * v]); },
    progress.sub(0.1, 0.4), 8);

  // 2. Salience threshold.
  const double minCurvature = salienceThreshold(mesh, curvature, options);

  // 3. Crest points on edges.
  const CrestPoints points =
    findCrestPoints(edges, curvature, extremality, minCurvature, options, progress.sub(0.4, 0.55));

  // 4. Segments across faces.
  const std::vector<int64_t> segmentNodes =
    crestSegments(mesh, edges, curvature, extremality, points, progress.sub(0.55, 0.75));

  // 5. Segments chained into polylines (sequential, in face order: deterministic).
  const detail::Polylines chains = detail::chainSegments(segmentNodes, 2 * edges.numEdges());
  progress.report(0.9);

  // 6. Strength, the filters, and the output.
  CrestLines out = filterLines(mesh, edges, points, chains, options);
  progress.report(1.0);
  return out;
}

std::vector<uint8_t> crestVertices(const TriMesh& mesh, const CrestLines& lines)
{
  std::vector<uint8_t> marked(mesh.numPoints(), 0);
  if (lines.pointEdge.empty())
  {
    return marked;
  }
  const EdgeTable edges = buildEdgeTable(mesh.triangles);
  const int64_t np = static_cast<int64_t>(lines.pointEdge.size());
  for (int64_t p = 0; p < np; ++p)
  {
    const int32_t e = lines.pointEdge[p];
    if (e < 0 || e >= edges.numEdges())
    {
      throw InputError("crest point " + std::to_string(p) + " names edge " + std::to_string(e) +
        ", which the mesh does not have: the crest lines belong to another mesh");
    }
    const int32_t a = edges.vertices[2 * e];
    const int32_t b = edges.vertices[2 * e + 1];
    double da = 0.0;
    double db = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      const double x = lines.points[3 * p + c];
      da += (x - mesh.points[3 * a + c]) * (x - mesh.points[3 * a + c]);
      db += (x - mesh.points[3 * b + c]) * (x - mesh.points[3 * b + c]);
    }
    marked[da <= db ? a : b] = 1;
  }
  return marked;
}
} // namespace tc
