// SPDX-License-Identifier: BSD-3-Clause
#include "tc/features/crest_lines.h"

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
  for (int32_t id : mesh.triangles)
  {
    if (id < 0 || static_cast<size_t>(id) >= nv)
    {
      throw InputError("extractCrestLines: a triangle references vertex " + std::to_string(id) +
        " of a mesh with " + std::to_string(nv) + " vertices; fix the connectivity");
    }
  }
}
} // namespace

CrestLines extractCrestLines(const TriMesh& mesh, const CurvatureResult& curvature,
  const CrestLineOptions& options, const Progress& progress)
{
  validate(mesh, curvature);
  const int64_t nv = mesh.numPoints();
  const int64_t nf = mesh.numTriangles();
  const EdgeTable edges = buildEdgeTable(mesh.triangles);
  const VertexRing ring = buildVertexRing(edges, nv);
  const int64_t ne = edges.numEdges();
  const std::vector<double>& k1 = curvature.k1;
  const std::vector<double>& k2 = curvature.k2;
  progress.report(0.1);

  // 1. Extremality coefficients e1 = grad(k1) . d1 and e2 = grad(k2) . d2 (Ohtake et al. 2004),
  //    the gradients fitted in the tangent plane spanned by (d1, d2) over the one-ring
  //    by least squares of the differences k(q) - k(v); each neighbour is weighted by
  //    1 / |q - v|^2 so that every direction counts as one directional derivative.
  std::vector<double> extremality(2 * nv, 0.0);
  parallel_for(
    nv,
    [&](int64_t v)
    {
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
      // On a symmetric mesh a vertex can lie exactly on a crest, where e is zero up to
      // rounding and its sign (so the line's path) would follow the rounding noise; such e are
      // snapped to an exact zero, which the crossing test treats consistently.
      const double zero = kZeroExtremality * kMax * count / lengthSum;
      const double e1 = (a22 * r1 - a12 * r2) / det;
      const double e2 = (a11 * v2 - a12 * v1) / det;
      extremality[2 * v + kRidge] = std::abs(e1) > zero ? e1 : 0.0;
      extremality[2 * v + kValley] = std::abs(e2) > zero ? e2 : 0.0;
    },
    progress.sub(0.1, 0.4), 8);

  // 2. Salience threshold, relative to the mesh's own curvature and size (scale invariant).
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
  const double minCurvature = std::max(options.minRelativeCurvature * typical,
    diagonal > 0.0 ? options.minCurvatureTimesSize / diagonal : 0.0);

  // 3. Crest points: per edge and crest type, where e changes sign between the two ends once
  //    the second end's direction is oriented like the first's; t is the linear interpolation
  //    parameter from the smaller vertex id (-1: none), edgeK the |k| of the crest there.
  const bool wanted[2] = { options.ridges, options.valleys };
  std::vector<double> edgeT(2 * ne, -1.0), edgeK(2 * ne, 0.0);
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
        // Dominance (Ohtake et al.: k_max > |k_min| on ridges, k_min < -|k_max| on valleys)
        // and salience.
        const double k = type == kRidge ? c1 : -c2;
        const double other = type == kRidge ? std::abs(c2) : std::abs(c1);
        if (k > other && k >= minCurvature)
        {
          edgeT[2 * e + type] = t;
          edgeK[2 * e + type] = k;
        }
      }
    },
    progress.sub(0.4, 0.55), 8);

  // 4. Segments: a triangle whose three directions orient consistently (no singularity of the
  //    direction field inside) and that has crest points on exactly two sides joins them when
  //    the linear interpolation of the oriented e decreases along d (a maximum: ridge) or
  //    increases (a minimum: valley). faceSegment holds the two edges per face and type.
  std::vector<int32_t> faceSegment(4 * nf, -1);
  parallel_for(
    nf,
    [&](int64_t f)
    {
      const int32_t* c = &mesh.triangles[3 * f];
      const int32_t* fe = &edges.faceEdges[3 * f];
      const Vec3 p0 = row(mesh.points, c[0]);
      const Vec3 u = row(mesh.points, c[1]) - p0, w = row(mesh.points, c[2]) - p0;
      for (int type = 0; type < 2; ++type)
      {
        int crossed[3];
        int count = 0;
        for (int i = 0; i < 3; ++i)
        {
          if (edgeT[2 * fe[i] + type] >= 0.0)
          {
            crossed[count++] = fe[i];
          }
        }
        if (count != 2)
        {
          continue;
        }
        const std::vector<double>& dir = type == kRidge ? curvature.d1 : curvature.d2;
        const Vec3 d0 = row(dir, c[0]), d1 = row(dir, c[1]), d2 = row(dir, c[2]);
        const double s1 = alike(d0, d1), s2 = alike(d0, d2);
        if (alike(d1, d2) != s1 * s2)
        {
          continue;
        }
        const double e0 = extremality[2 * c[0] + type];
        const double de1 = s1 * extremality[2 * c[1] + type] - e0;
        const double de2 = s2 * extremality[2 * c[2] + type] - e0;
        const Vec3 d = d0 + s1 * d1 + s2 * d2;
        // grad(e) = alpha u + beta w with grad(e) . u = de1 and grad(e) . w = de2.
        const double uu = u.dot(u), uw = u.dot(w), ww = w.dot(w);
        const double det = uu * ww - uw * uw;
        if (!(det > 0.0))
        {
          continue;
        }
        const double alpha = (ww * de1 - uw * de2) / det;
        const double beta = (uu * de2 - uw * de1) / det;
        const double slope = alpha * u.dot(d) + beta * w.dot(d);
        if ((type == kRidge && slope < 0.0) || (type == kValley && slope > 0.0))
        {
          faceSegment[4 * f + 2 * type] = crossed[0];
          faceSegment[4 * f + 2 * type + 1] = crossed[1];
        }
      }
    },
    progress.sub(0.55, 0.75), 8);

  // 5. Chain the segments into polylines (sequential, in face order: deterministic). Nodes are
  //    crest points, keyed 2 * edge + type, so both triangles of an edge share them.
  std::vector<int64_t> segNode; // 2 per segment
  for (int64_t f = 0; f < nf; ++f)
  {
    for (int type = 0; type < 2; ++type)
    {
      if (faceSegment[4 * f + 2 * type] >= 0)
      {
        segNode.push_back(2 * static_cast<int64_t>(faceSegment[4 * f + 2 * type]) + type);
        segNode.push_back(2 * static_cast<int64_t>(faceSegment[4 * f + 2 * type + 1]) + type);
      }
    }
  }
  const int64_t numSegments = static_cast<int64_t>(segNode.size() / 2);
  std::vector<int64_t> nodeOffsets(2 * ne + 1, 0);
  for (int64_t key : segNode)
  {
    ++nodeOffsets[key + 1];
  }
  for (int64_t k = 0; k < 2 * ne; ++k)
  {
    nodeOffsets[k + 1] += nodeOffsets[k];
  }
  std::vector<int64_t> nodeSegments(segNode.size());
  {
    std::vector<int64_t> fill(nodeOffsets.begin(), nodeOffsets.end() - 1);
    for (int64_t s = 0; s < 2 * numSegments; ++s)
    {
      nodeSegments[fill[segNode[s]]++] = s / 2;
    }
  }
  const auto degree = [&](int64_t key) { return nodeOffsets[key + 1] - nodeOffsets[key]; };
  std::vector<char> used(numSegments, 0);
  std::vector<int64_t> lineNodes;
  std::vector<int64_t> lineOffsets{ 0 };
  const auto walk = [&](int64_t start, int64_t seg)
  {
    int64_t node = start;
    lineNodes.push_back(start);
    while (true)
    {
      used[seg] = 1;
      node = segNode[2 * seg] == node ? segNode[2 * seg + 1] : segNode[2 * seg];
      lineNodes.push_back(node);
      if (degree(node) != 2)
      {
        break;
      }
      int64_t next = -1;
      for (int64_t j = nodeOffsets[node]; j < nodeOffsets[node + 1]; ++j)
      {
        if (!used[nodeSegments[j]])
        {
          next = nodeSegments[j];
        }
      }
      if (next < 0)
      {
        break; // back at the start of a closed line
      }
      seg = next;
    }
    lineOffsets.push_back(static_cast<int64_t>(lineNodes.size()));
  };
  // Open lines run from ends and branchings; what remains are closed loops.
  for (int64_t key = 0; key < 2 * ne; ++key)
  {
    if (degree(key) == 0 || degree(key) == 2)
    {
      continue;
    }
    for (int64_t j = nodeOffsets[key]; j < nodeOffsets[key + 1]; ++j)
    {
      if (!used[nodeSegments[j]])
      {
        walk(key, nodeSegments[j]);
      }
    }
  }
  for (int64_t s = 0; s < numSegments; ++s)
  {
    if (!used[s])
    {
      walk(segNode[2 * s], s);
    }
  }
  progress.report(0.9);

  // 6. Strength (sum over segments of length times mean |k| at its ends: dimensionless), the
  //    filters, and the output with points shared between lines that meet.
  const auto nodePoint = [&](int64_t key)
  {
    const int64_t e = key / 2;
    const double t = edgeT[key];
    return Vec3((1.0 - t) * row(mesh.points, edges.vertices[2 * e]) +
      t * row(mesh.points, edges.vertices[2 * e + 1]));
  };
  CrestLines out;
  std::vector<int64_t> pointOf(2 * ne, -1);
  std::vector<int64_t> kept; // nodes of one line without the zero-length links
  const int64_t numLines = static_cast<int64_t>(lineOffsets.size()) - 1;
  for (int64_t l = 0; l < numLines; ++l)
  {
    // Consecutive nodes at the same position are the zero-length links around a vertex that
    // the crest passes through: one point is enough.
    kept.clear();
    double strength = 0.0;
    for (int64_t i = lineOffsets[l]; i < lineOffsets[l + 1]; ++i)
    {
      const int64_t key = lineNodes[i];
      if (!kept.empty())
      {
        const double length = (nodePoint(key) - nodePoint(kept.back())).norm();
        if (length == 0.0)
        {
          continue;
        }
        strength += length * 0.5 * (edgeK[key] + edgeK[kept.back()]);
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
        out.pointEdge.push_back(static_cast<int32_t>(key / 2));
      }
      out.connectivity.push_back(pointOf[key]);
    }
    out.offsets.push_back(static_cast<int64_t>(out.connectivity.size()));
    out.strength.push_back(strength);
    out.type.push_back(static_cast<int8_t>(kept.front() % 2));
  }
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
