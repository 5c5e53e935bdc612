// SPDX-License-Identifier: BSD-3-Clause
#include "gim/geometry_images_input.h"

#include "tc/skinning/skin.h"

#include "tc/common/errors.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tc::detail::geometry_images
{
namespace
{
/// The patch mesh: sizes, finite points, triangles with three distinct corners in range, and
/// one inputPointId per point, one patchId and inputTriangle per triangle.
void checkPatchMesh(const PatchMesh& pm, Layout& L)
{
  const TriMesh& mesh = pm.mesh;
  if (mesh.points.size() % 3 != 0 || mesh.triangles.size() % 3 != 0)
  {
    throw InputError(kWhere + "the patch mesh has " + num(mesh.points.size()) +
      " coordinates and " + num(mesh.triangles.size()) +
      " triangle indices; both must be multiples of 3");
  }
  L.numPoints = mesh.numPoints();
  const int64_t nv = L.numPoints;
  const int64_t nf = mesh.numTriangles();
  if (nf == 0)
  {
    throw InputError(
      kWhere + "the patch mesh has no triangle: trace the paths of a non-empty mesh");
  }
  if (nv > std::numeric_limits<int32_t>::max() / 2)
  {
    throw InputError(kWhere + "the patch mesh has " + num(nv) + " points, more than supported");
  }
  for (double x : mesh.points)
  {
    if (!std::isfinite(x))
    {
      throw InputError(kWhere + "the patch mesh has a non-finite coordinate; clean the input mesh");
    }
  }
  for (int64_t t = 0; t < nf; ++t)
  {
    const int32_t* c = &mesh.triangles[3 * t];
    for (int k = 0; k < 3; ++k)
    {
      if (c[k] < 0 || c[k] >= nv)
      {
        throw InputError(kWhere + "triangle " + num(t) + " of the patch mesh has corner " +
          num(c[k]) + ", outside 0 .. " + num(nv - 1));
      }
    }
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0])
    {
      throw InputError(kWhere + "triangle " + num(t) + " of the patch mesh repeats a corner");
    }
  }
  if (static_cast<int64_t>(pm.inputPointId.size()) != nv)
  {
    throw InputError(kWhere + "inputPointId has " + num(pm.inputPointId.size()) + " entries for " +
      num(nv) + " points");
  }
  if (static_cast<int64_t>(pm.patchId.size()) != nf ||
    static_cast<int64_t>(pm.inputTriangle.size()) != nf)
  {
    throw InputError(kWhere + "patchId and inputTriangle need one entry per triangle (" + num(nf) +
      "), they have " + num(pm.patchId.size()) + " and " + num(pm.inputTriangle.size()));
  }
}

/// The base complex: triangles whose corners are base vertices, base vertices that are input
/// points, and per-side arrays (features, faceEdges) of the right size.
void checkBaseComplex(const PatchMesh& pm, const BaseComplexResult& base, Layout& L)
{
  const int64_t nv = L.numPoints;
  const size_t nb = base.baseTriangles.size();
  if (nb == 0 || nb % 3 != 0)
  {
    throw InputError(kWhere + "the base complex has " + num(nb) +
      " triangle indices; it needs at least one triangle (a multiple of 3)");
  }
  L.numCharts = static_cast<int32_t>(nb / 3);
  const int64_t nvb = static_cast<int64_t>(base.baseVertices.size());
  for (size_t b = 0; b < base.baseVertices.size(); ++b)
  {
    const int32_t v = base.baseVertices[b];
    if (v < 0 || v >= nv || pm.inputPointId[v] < 0)
    {
      throw InputError(kWhere + "base vertex " + num(b) + " is point " + num(v) +
        ", not an input point of the patch mesh");
    }
  }
  for (size_t i = 0; i < nb; ++i)
  {
    if (base.baseTriangles[i] < 0 || base.baseTriangles[i] >= nvb)
    {
      throw InputError(kWhere + "base triangle " + num(i / 3) + " has corner " +
        num(base.baseTriangles[i]) + ", outside 0 .. " + num(nvb - 1));
    }
  }
  if (!base.baseEdgeIsFeature.empty() && base.baseEdgeIsFeature.size() != nb)
  {
    throw InputError(kWhere + "baseEdgeIsFeature has " + num(base.baseEdgeIsFeature.size()) +
      " entries; it needs 3 per base triangle (" + num(nb) + ") or none");
  }
  if (pm.faceEdges.size() != nb)
  {
    throw InputError(kWhere + "faceEdges has " + num(pm.faceEdges.size()) +
      " entries; it needs 3 per base triangle (" + num(nb) + ")");
  }
  if (pm.baseEdges.size() % 2 != 0)
  {
    throw InputError(kWhere + "baseEdges has an odd number of entries");
  }
  L.numEdges = static_cast<int32_t>(pm.baseEdges.size() / 2);
}

/// Every base edge's path: at least 2 points of the patch mesh, from the point of its lower
/// base vertex to that of its higher one.
void checkPaths(const PatchMesh& pm, const BaseComplexResult& base, const Layout& L)
{
  const int64_t nv = L.numPoints;
  const int64_t nvb = static_cast<int64_t>(base.baseVertices.size());
  const int32_t ne = L.numEdges;
  if (static_cast<int64_t>(pm.pathOffsets.size()) != ne + 1 || pm.pathOffsets[0] != 0 ||
    pm.pathOffsets.back() != static_cast<int64_t>(pm.pathPoints.size()))
  {
    throw InputError(kWhere + "pathOffsets must have #base edges + 1 (" + num(ne + 1) +
      ") entries from 0 to the size of pathPoints (" + num(pm.pathPoints.size()) + ")");
  }
  for (int32_t e = 0; e < ne; ++e)
  {
    const int32_t a = pm.baseEdges[2 * e], b = pm.baseEdges[2 * e + 1];
    if (a < 0 || b >= nvb || a >= b)
    {
      throw InputError(kWhere + "base edge " + num(e) + " joins base vertices " + num(a) + " and " +
        num(b) + "; they must be in 0 .. " + num(nvb - 1) + ", lower first");
    }
    const int64_t p0 = pm.pathOffsets[e], p1 = pm.pathOffsets[e + 1];
    if (p1 - p0 < 2)
    {
      throw InputError(kWhere + "the path of base edge " + num(e) + " has fewer than 2 points");
    }
    for (int64_t i = p0; i < p1; ++i)
    {
      if (pm.pathPoints[i] < 0 || pm.pathPoints[i] >= nv)
      {
        throw InputError(kWhere + "the path of base edge " + num(e) + " has point " +
          num(pm.pathPoints[i]) + ", not a point of the patch mesh");
      }
    }
    if (pm.pathPoints[p0] != base.baseVertices[a] || pm.pathPoints[p1 - 1] != base.baseVertices[b])
    {
      throw InputError(kWhere + "the path of base edge " + num(e) +
        " must run from the point of base vertex " + num(a) + " to that of " + num(b));
    }
  }
}

/// The two (face, side) pairs of every base edge, which must run it in opposite directions: the
/// base complex is a closed oriented manifold.
void pairBaseEdges(const PatchMesh& pm, const BaseComplexResult& base, Layout& L)
{
  const int32_t ne = L.numEdges;
  L.edgeChart.assign(2 * static_cast<size_t>(ne), -1);
  L.edgeSide.assign(2 * static_cast<size_t>(ne), -1);
  L.edgeFeature.assign(ne, 0);
  for (int32_t f = 0; f < L.numCharts; ++f)
  {
    const int32_t* tri = &base.baseTriangles[3 * f];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0])
    {
      throw InputError(kWhere + "base triangle " + num(f) + " repeats a corner");
    }
    for (int k = 0; k < 3; ++k)
    {
      const int32_t e = pm.faceEdges[3 * f + k];
      if (e < 0 || e >= ne)
      {
        throw InputError(kWhere + "side " + num(k) + " of base face " + num(f) + " is base edge " +
          num(e) + ", outside 0 .. " + num(ne - 1));
      }
      const int32_t a = tri[k], b = tri[(k + 1) % 3];
      if (std::min(a, b) != pm.baseEdges[2 * e] || std::max(a, b) != pm.baseEdges[2 * e + 1])
      {
        throw InputError(kWhere + "side " + num(k) + " of base face " + num(f) + " joins base " +
          "vertices " + num(a) + " and " + num(b) + " but faceEdges names base edge " + num(e));
      }
      const int slot = L.edgeChart[2 * e] < 0 ? 0 : 1;
      if (slot == 1 && L.edgeChart[2 * e + 1] >= 0)
      {
        throw InputError(kWhere + "base edge " + num(e) +
          " borders more than two base faces; the base complex must be a closed manifold");
      }
      if (slot == 1 && base.baseTriangles[3 * L.edgeChart[2 * e] + L.edgeSide[2 * e]] != b)
      {
        throw InputError(kWhere + "base faces " + num(L.edgeChart[2 * e]) + " and " + num(f) +
          " run base edge " + num(e) + " the same way; the base complex must be oriented");
      }
      L.edgeChart[2 * e + slot] = f;
      L.edgeSide[2 * e + slot] = k;
      if (!base.baseEdgeIsFeature.empty() && base.baseEdgeIsFeature[3 * f + k] != 0)
      {
        L.edgeFeature[e] = 1;
      }
    }
  }
  for (int32_t e = 0; e < ne; ++e)
  {
    if (L.edgeChart[2 * e + 1] < 0)
    {
      throw InputError(kWhere + "base edge " + num(e) +
        " borders fewer than two base faces; the base complex must be closed");
    }
  }
}

/// The triangles of every patch, in ascending order (a counting sort by patchId); every patch
/// must have one.
void groupTrianglesByPatch(const PatchMesh& pm, Layout& L)
{
  const int64_t nf = pm.mesh.numTriangles();
  L.patchOffsets.assign(static_cast<size_t>(L.numCharts) + 1, 0);
  for (int64_t t = 0; t < nf; ++t)
  {
    const int32_t p = pm.patchId[t];
    if (p < 0 || p >= L.numCharts)
    {
      throw InputError(kWhere + "triangle " + num(t) + " has patch " + num(p) + ", outside 0 .. " +
        num(L.numCharts - 1));
    }
    ++L.patchOffsets[p + 1];
  }
  for (int32_t c = 0; c < L.numCharts; ++c)
  {
    if (L.patchOffsets[c + 1] == 0)
    {
      throw InputError(kWhere + "patch " + num(c) + " has no triangle");
    }
    L.patchOffsets[c + 1] += L.patchOffsets[c];
  }
  L.patchTriangles.resize(nf);
  std::vector<int64_t> fill(L.patchOffsets.begin(), L.patchOffsets.end() - 1);
  for (int64_t t = 0; t < nf; ++t)
  {
    L.patchTriangles[fill[pm.patchId[t]]++] = static_cast<int32_t>(t);
  }
}
} // namespace

void checkOptions(const GeometryImageOptions& options)
{
  if (options.minLevel < 0 || options.maxLevel > kMaxLevelLimit ||
    options.minLevel > options.maxLevel)
  {
    throw InputError(kWhere +
      "levels must satisfy 0 <= minLevel <= maxLevel <= " + num(kMaxLevelLimit) + " (got " +
      num(options.minLevel) + " and " + num(options.maxLevel) + ")");
  }
  if (!(options.curvatureWeight >= 0.0) || !std::isfinite(options.curvatureWeight))
  {
    throw InputError(kWhere + "curvatureWeight must be finite and >= 0");
  }
  if (options.levelRule != LevelRule::Area && options.levelRule != LevelRule::Error)
  {
    throw InputError(kWhere +
      "levelRule must be LevelRule::Area (0) or LevelRule::Error (1), not " +
      num(static_cast<int32_t>(options.levelRule)));
  }
  if (options.stretchIterations < 0 || options.stretchIterations > kMaxStretchIterations)
  {
    throw InputError(kWhere + "stretchIterations must be 0 .. " + num(kMaxStretchIterations) +
      " (0: Floater's mean-value map alone), not " + num(options.stretchIterations));
  }
  if (options.sampleBudget < 0)
  {
    throw InputError(kWhere +
      "sampleBudget must be >= 0 (0: as many samples as the errorTarget needs, or with no "
      "target as the input has points)");
  }
  if (!(options.errorTarget >= 0.0 && options.errorTarget < 1.0))
  {
    throw InputError(kWhere +
      "errorTarget must be a fraction of the diagonal in [0, 1) (0: the "
      "budget alone), not " +
      std::to_string(options.errorTarget));
  }
}

Layout checkInput(const PatchMesh& pm, const BaseComplexResult& base)
{
  Layout L;
  checkPatchMesh(pm, L);
  checkBaseComplex(pm, base, L);
  checkPaths(pm, base, L);
  pairBaseEdges(pm, base, L);
  groupTrianglesByPatch(pm, L);
  return L;
}

void checkPointArrays(
  const Layout& L, const std::vector<double>& normals, const std::vector<double>& meanCurvature)
{
  const int64_t nv = L.numPoints;
  if (!normals.empty() && static_cast<int64_t>(normals.size()) != 3 * nv)
  {
    throw InputError(kWhere + "normals has " + num(normals.size()) + " values; it needs 3 per " +
      "point of the patch mesh (" + num(3 * nv) + ") or none");
  }
  if (!meanCurvature.empty() && static_cast<int64_t>(meanCurvature.size()) != nv)
  {
    throw InputError(kWhere + "meanCurvature has " + num(meanCurvature.size()) +
      " values; it needs one per point of the patch mesh (" + num(nv) + ") or none");
  }
  for (const std::vector<double>* a : { &normals, &meanCurvature })
  {
    if (!std::all_of(a->begin(), a->end(), [](double x) { return std::isfinite(x); }))
    {
      throw InputError(kWhere + "normals and meanCurvature must be finite");
    }
  }
}

void checkExtraAttributes(
  const std::vector<GeometryImageAttribute>& extra, int64_t numPoints, int64_t numTriangles)
{
  for (size_t a = 0; a < extra.size(); ++a)
  {
    const GeometryImageAttribute& x = extra[a];
    if (x.name.empty() || x.name == kAtlasPosition || x.name == kAtlasNormal)
    {
      throw InputError(kWhere + "extra attribute " + num(a) + " needs a name other than \"" +
        kAtlasPosition + "\" and \"" + kAtlasNormal + "\"");
    }
    for (size_t b = 0; b < a; ++b)
    {
      if (extra[b].name == x.name)
      {
        throw InputError(kWhere + "two extra attributes are named \"" + x.name + "\"");
      }
    }
    if (x.components < 1 || x.components > kMaxComponents ||
      static_cast<int64_t>(x.values.size()) != numPoints * x.components)
    {
      throw InputError(kWhere + "extra attribute \"" + x.name + "\" needs 1 .. " +
        num(kMaxComponents) + " components and #points x components (" + num(numPoints) + " x " +
        num(x.components) + ") values; it has " + num(x.values.size()));
    }
    if (x.influences && (x.components != kSkinValues || !x.cornerValues.empty()))
    {
      throw InputError(kWhere + "the influences \"" + x.name + "\" need " + num(kSkinValues) +
        " components (4 joints, 4 weights) and no corner values");
    }
    if (!x.cornerValues.empty() &&
      static_cast<int64_t>(x.cornerValues.size()) != 3 * numTriangles * x.components)
    {
      throw InputError(kWhere + "the corner values of extra attribute \"" + x.name +
        "\" need 3 x #triangles x components (" + num(numTriangles) + " triangles) values or none");
    }
    auto finite = [](double v) { return std::isfinite(v); };
    if (!std::all_of(x.values.begin(), x.values.end(), finite) ||
      !std::all_of(x.cornerValues.begin(), x.cornerValues.end(), finite))
    {
      throw InputError(kWhere + "extra attribute \"" + x.name + "\" has a non-finite value");
    }
  }
}

std::vector<int32_t> sidePath(
  const PatchMesh& pm, const BaseComplexResult& base, int32_t c, int32_t k)
{
  const int32_t e = pm.faceEdges[3 * c + k];
  std::vector<int32_t> path(
    pm.pathPoints.begin() + pm.pathOffsets[e], pm.pathPoints.begin() + pm.pathOffsets[e + 1]);
  if (!sideRunsForward(pm, base, c, k))
  {
    std::reverse(path.begin(), path.end());
  }
  return path;
}

std::vector<uint8_t> featureVertices(const PatchMesh& pm, const Layout& L, size_t numBaseVertices)
{
  std::vector<uint8_t> featureVertex(numBaseVertices, 0);
  for (int32_t e = 0; e < L.numEdges; ++e)
  {
    if (L.edgeFeature[e])
    {
      featureVertex[pm.baseEdges[2 * e]] = 1;
      featureVertex[pm.baseEdges[2 * e + 1]] = 1;
    }
  }
  return featureVertex;
}

std::vector<AtlasChart> chartTable(
  const PatchMesh& pm, const BaseComplexResult& base, const Layout& L)
{
  std::vector<AtlasChart> charts(L.numCharts);
  for (int32_t c = 0; c < L.numCharts; ++c)
  {
    AtlasChart& ch = charts[c];
    for (int k = 0; k < 3; ++k)
    {
      ch.cornerVertex[k] = pm.inputPointId[base.baseVertices[base.baseTriangles[3 * c + k]]];
      const int32_t e = pm.faceEdges[3 * c + k];
      const int slot = L.edgeChart[2 * e] == c && L.edgeSide[2 * e] == k ? 1 : 0;
      ch.neighborChart[k] = L.edgeChart[2 * e + slot];
      ch.neighborSide[k] = L.edgeSide[2 * e + slot];
      ch.featureSide[k] = L.edgeFeature[e];
    }
  }
  return charts;
}
} // namespace tc::detail::geometry_images
