// SPDX-License-Identifier: BSD-3-Clause
#include "tc/prep/mesh_preparation.h"

#include "prep/component_selection.h"
#include "prep/ear_clipping.h"
#include "prep/first_equal.h"
#include "prep/non_manifold.h"
#include "prep/orientation.h"
#include "prep/point_merging.h"
#include "prep/points.h"
#include "prep/report_text.h"
#include "prep/surface_repair.h"

#include "detail/splitmix.h"
#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

// Written by hand rather than with CGAL's repair_polygon_soup / orient_polygon_soup: those do
// not say which element they changed and always split non-manifold vertices, while this stage
// must return per-element flags (NonManifoldEdge, NonManifoldVertex, InputPointId, ...) and
// split only when the user asks for it.

namespace tc
{
namespace
{
using namespace detail;

constexpr int64_t kMaxIndex = std::numeric_limits<int32_t>::max();

/// Triangles with less area than this fraction of diagonal^2 are degenerate: relative to the
/// size of the mesh so that scaling the input does not change what is dropped.
constexpr double kDegenerateArea = 1e-12;

// ---------------------------------------------------------------------------------------------
// 1. Validation

/// Sizes, counts, offsets and point ids.
void validateArrays(const PolygonSoup& soup)
{
  const int64_t nv = soup.numPoints();
  const int64_t np = soup.numPolygons();
  if (soup.points.size() % 3 != 0)
  {
    throw InputError("mesh preparation: the point array has " + std::to_string(soup.points.size()) +
      " values, not a multiple of 3 (x y z per point)");
  }
  if (nv == 0)
  {
    throw InputError("mesh preparation: the input has no points; give a surface mesh");
  }
  if (nv > kMaxIndex)
  {
    throw InputError("mesh preparation: the input has " + std::to_string(nv) +
      " points, more than the 2^31 - 1 this stage supports; split the mesh into parts");
  }
  if (np <= 0)
  {
    throw InputError("mesh preparation: the input has points but no polygons; give a surface "
                     "mesh with faces, not a point cloud");
  }
  if (soup.offsets.front() != 0 ||
    soup.offsets.back() != static_cast<int64_t>(soup.connectivity.size()))
  {
    throw InputError("mesh preparation: malformed polygon offsets: the first must be 0 and the "
                     "last the connectivity size " +
      std::to_string(soup.connectivity.size()));
  }
  for (int64_t p = 0; p < np; ++p)
  {
    if (soup.offsets[p + 1] < soup.offsets[p])
    {
      throw InputError("mesh preparation: malformed polygon offsets: polygon " + std::to_string(p) +
        " ends before it starts");
    }
    for (int64_t k = soup.offsets[p]; k < soup.offsets[p + 1]; ++k)
    {
      const int64_t id = soup.connectivity[k];
      if (id < 0 || id >= nv)
      {
        throw InputError("mesh preparation: polygon " + std::to_string(p) + " refers to point id " +
          std::to_string(id) + ", out of range: the input has " + std::to_string(nv) +
          " points (ids 0 to " + std::to_string(nv - 1) + "); fix the connectivity");
      }
    }
  }
}

/// Finite coordinates, and polygons that are not all points or segments.
void validateGeometry(const PolygonSoup& soup)
{
  const int64_t nv = soup.numPoints();
  int64_t firstBad = -1;
  int64_t numBad = 0;
  for (int64_t v = 0; v < nv; ++v)
  {
    if (!std::isfinite(soup.points[3 * v]) || !std::isfinite(soup.points[3 * v + 1]) ||
      !std::isfinite(soup.points[3 * v + 2]))
    {
      firstBad = numBad == 0 ? v : firstBad;
      ++numBad;
    }
  }
  if (numBad > 0)
  {
    throw InputError("mesh preparation: point " + std::to_string(firstBad) +
      " has a NaN or infinite coordinate (" + counted(numBad, { "point has", "points have" }) +
      " one); remove or repair these points before preparing the mesh");
  }
  // Sum of fan-triangle areas: zero only if every polygon is a point or a segment.
  double area = 0.0;
  const double* points = soup.points.data();
  for (int64_t p = 0; p < soup.numPolygons() && area == 0.0; ++p)
  {
    const int64_t* ids = soup.connectivity.data() + soup.offsets[p];
    const int64_t n = soup.offsets[p + 1] - soup.offsets[p];
    for (int64_t k = 1; k + 1 < n; ++k)
    {
      area += doubleArea(points, ids[0], ids[k], ids[k + 1]);
    }
  }
  if (area == 0.0)
  {
    throw InputError("mesh preparation: the polygons have zero total area (all their points "
                     "coincide or lie on a line); give a surface mesh");
  }
}

/// A component floor of 0 or more; sliver thresholds in range, when slivers are to be removed.
void validateOptions(const PreparationOptions& options)
{
  if (options.minComponentTriangles < 0)
  {
    throw InputError("mesh preparation: minComponentTriangles must be 0 (off) or more (got " +
      std::to_string(options.minComponentTriangles) + ")");
  }
  if (!options.removeSlivers ||
    (options.sliverAngle >= kMinSliverAngle && options.sliverAngle <= 180.0 &&
      options.sliverEdgeRatio >= kMinSliverEdgeRatio))
  {
    return;
  }
  // Lower thresholds would count ordinary triangles as slivers and collapse the mesh away.
  auto g = [](double x)
  {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", x);
    return std::string(text);
  };
  throw InputError("mesh preparation: sliverAngle must be " + g(kMinSliverAngle) +
    " .. 180 degrees and sliverEdgeRatio at least " + g(kMinSliverEdgeRatio) + " (got " +
    g(options.sliverAngle) + " and " + g(options.sliverEdgeRatio) + ")");
}

/// The points the polygons use, and their bounding box.
struct UsedPoints
{
  std::vector<uint8_t> used; ///< #V: 1 if a polygon uses the point
  std::array<double, 3> low; ///< lowest corner of their bounding box
  double diagonal = 0.0;     ///< its diagonal
};

UsedPoints usedPoints(const PolygonSoup& soup)
{
  const int64_t nv = soup.numPoints();
  const double* points = soup.points.data();
  UsedPoints out;
  out.used.assign(nv, 0);
  for (int64_t id : soup.connectivity)
  {
    out.used[id] = 1;
  }
  std::array<double, 3> low = { std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity() };
  std::array<double, 3> high = { -low[0], -low[1], -low[2] };
  for (int64_t v = 0; v < nv; ++v)
  {
    if (out.used[v])
    {
      for (int c = 0; c < 3; ++c)
      {
        low[c] = std::min(low[c], points[3 * v + c]);
        high[c] = std::max(high[c], points[3 * v + c]);
      }
    }
  }
  out.low = low;
  out.diagonal = norm(sub({ high[0], high[1], high[2] }, { low[0], low[1], low[2] }));
  return out;
}

// ---------------------------------------------------------------------------------------------
// 3. Triangulation and degenerate triangles

/// Triangles before duplicate removal, with the polygon each came from.
struct Candidates
{
  std::vector<int32_t> triangles; ///< #T x 3 representative point ids
  std::vector<int64_t> cell;      ///< #T input polygon
};

/// The merged corners of polygon p (of more or fewer than 3 corners), without repeats of
/// consecutive corners: merging can make them equal, and they would only give empty ears.
void polygonCorners(const PolygonSoup& soup, int64_t p, const std::vector<int32_t>& representative,
  std::vector<int32_t>& corners)
{
  corners.clear();
  for (int64_t k = soup.offsets[p]; k < soup.offsets[p + 1]; ++k)
  {
    const int32_t id = representative[soup.connectivity[k]];
    if (corners.empty() || corners.back() != id)
    {
      corners.push_back(id);
    }
  }
  while (corners.size() > 1 && corners.back() == corners.front())
  {
    corners.pop_back();
  }
}

/// Keeps the triangles of polygon p (those from `first` on) that have 3 distinct corners and
/// twice their area at least `minDoubleArea`; counts the others as degenerate.
void dropDegenerate(const double* points, size_t first, double minDoubleArea, int64_t p,
  Candidates& out, PreparationReport& report)
{
  std::vector<int32_t>& triangles = out.triangles;
  size_t kept = first;
  for (size_t t = first; t < triangles.size(); t += 3)
  {
    const int32_t a = triangles[t];
    const int32_t b = triangles[t + 1];
    const int32_t c = triangles[t + 2];
    if (a == b || b == c || c == a || doubleArea(points, a, b, c) < minDoubleArea)
    {
      ++report.degenerateFaces;
      continue;
    }
    triangles[kept] = a;
    triangles[kept + 1] = b;
    triangles[kept + 2] = c;
    kept += 3;
    out.cell.push_back(p);
  }
  triangles.resize(kept);
}

/// Every polygon over the merged points as triangles (ear clipping for more than 3 corners),
/// dropping the degenerate ones.
Candidates triangulate(const PolygonSoup& soup, const std::vector<int32_t>& representative,
  double diagonal, PreparationReport& report)
{
  const int64_t np = soup.numPolygons();
  const double* points = soup.points.data();
  Candidates out;
  int64_t estimate = 0;
  for (int64_t p = 0; p < np; ++p)
  {
    estimate += std::max<int64_t>(1, soup.offsets[p + 1] - soup.offsets[p] - 2);
  }
  out.triangles.reserve(3 * estimate);
  out.cell.reserve(estimate);
  const double minDoubleArea = 2.0 * kDegenerateArea * diagonal * diagonal;
  EarScratch scratch;
  std::vector<int32_t> corners;
  for (int64_t p = 0; p < np; ++p)
  {
    const int64_t begin = soup.offsets[p];
    const int64_t n = soup.offsets[p + 1] - begin;
    const size_t first = out.triangles.size();
    if (n == 3)
    {
      for (int64_t k = 0; k < 3; ++k)
      {
        out.triangles.push_back(representative[soup.connectivity[begin + k]]);
      }
    }
    else
    {
      report.polygonsTriangulated += n > 3 ? 1 : 0;
      polygonCorners(soup, p, representative, corners);
      const int32_t m = static_cast<int32_t>(corners.size());
      if (m < 3)
      {
        ++report.degenerateFaces;
        continue;
      }
      if (m == 3)
      {
        out.triangles.insert(out.triangles.end(), corners.begin(), corners.end());
      }
      else
      {
        earClip(points, corners.data(), m, scratch, out.triangles);
      }
    }
    dropDegenerate(points, first, minDoubleArea, p, out, report);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// 4, 5. Duplicate triangles, compaction

/// 1 for every candidate to keep: the first of each set of triangles with the same three points
/// (in any order).
std::vector<uint8_t> firstOfDuplicates(const Candidates& candidates, PreparationReport& report)
{
  const int64_t numCandidates = static_cast<int64_t>(candidates.cell.size());
  if (3 * numCandidates > kMaxIndex)
  {
    throw InputError("mesh preparation: " + std::to_string(numCandidates) +
      " triangles are more than this stage supports (2^31 / 3); split the mesh into parts");
  }
  std::vector<std::array<int32_t, 3>> keys(numCandidates);
  for (int64_t t = 0; t < numCandidates; ++t)
  {
    const int32_t* corners = &candidates.triangles[3 * t];
    keys[t] = { corners[0], corners[1], corners[2] };
    std::sort(keys[t].begin(), keys[t].end());
  }
  const std::vector<int32_t> first = firstEqual(
    numCandidates,
    [&keys](int32_t t)
    {
      const auto& k = keys[t];
      return mix64(static_cast<uint64_t>(k[0]) << 32 ^
        mix64(static_cast<uint64_t>(k[1]) << 32 ^ static_cast<uint64_t>(k[2])));
    },
    [&keys](int32_t a, int32_t b) { return keys[a] == keys[b]; });
  std::vector<uint8_t> keep(numCandidates, 1);
  for (int64_t t = 0; t < numCandidates; ++t)
  {
    if (first[t] != t)
    {
      keep[t] = 0;
      ++report.duplicateFaces;
    }
  }
  if (numCandidates == report.duplicateFaces)
  {
    throw InputError("mesh preparation: no triangles with non-zero area are left after cleaning (" +
      counted(report.degenerateFaces, kDegenerateFace) +
      " dropped); give a surface mesh with non-degenerate faces");
  }
  return keep;
}

/// The kept candidates as result.mesh.triangles over the used points numbered in input order
/// (result.inputPointId, inputCellId); returns the number of points.
int32_t compact(const Candidates& candidates, const std::vector<uint8_t>& keep, int64_t nv,
  PreparationResult& result)
{
  const int64_t numCandidates = static_cast<int64_t>(keep.size());
  const int64_t numKept = std::count(keep.begin(), keep.end(), uint8_t(1));
  std::vector<int32_t> newId(nv, -1);
  std::vector<int32_t>& tri = result.mesh.triangles;
  tri.resize(3 * numKept);
  result.inputCellId.resize(numKept);
  int64_t f = 0;
  for (int64_t t = 0; t < numCandidates; ++t)
  {
    if (keep[t])
    {
      for (int c = 0; c < 3; ++c)
      {
        newId[candidates.triangles[3 * t + c]] = 0;
      }
      result.inputCellId[f] = candidates.cell[t];
      ++f;
    }
  }
  int32_t numVertices = 0;
  for (int64_t v = 0; v < nv; ++v)
  {
    if (newId[v] == 0)
    {
      newId[v] = numVertices++;
      result.inputPointId.push_back(v);
    }
  }
  f = 0;
  for (int64_t t = 0; t < numCandidates; ++t)
  {
    if (keep[t])
    {
      for (int c = 0; c < 3; ++c)
      {
        tri[3 * f + c] = newId[candidates.triangles[3 * t + c]];
      }
      ++f;
    }
  }
  return numVertices;
}

// ---------------------------------------------------------------------------------------------
// 8 - 11. Output points, boundary, repairs

/// The prepared mesh between steps: its edge table, sizes and what its components are.
struct MeshState
{
  EdgeTable edges;
  int32_t numVertices = 0;
  int64_t numTriangles = 0;
  ComponentKinds kinds;
};

/// The output points: the input point of each (result.inputPointId).
void copyPoints(const PolygonSoup& soup, int32_t numVertices, PreparationResult& result)
{
  result.mesh.points.resize(3 * static_cast<size_t>(numVertices));
  for (int32_t v = 0; v < numVertices; ++v)
  {
    for (int c = 0; c < 3; ++c)
    {
      result.mesh.points[3 * v + c] = soup.points[3 * result.inputPointId[v] + c];
    }
  }
}

/// Counts the boundary edges (one triangle) and flags their vertices.
void markBoundary(const EdgeTable& edges, int32_t numVertices, PreparationResult& result)
{
  result.report.boundaryEdges = 0;
  result.boundaryVertex.assign(numVertices, 0);
  for (int32_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) == 1)
    {
      ++result.report.boundaryEdges;
      result.boundaryVertex[edges.vertices[2 * e]] = 1;
      result.boundaryVertex[edges.vertices[2 * e + 1]] = 1;
    }
  }
}

/// Components, orientation and boundary over state.edges.
void settle(bool orient, MeshState& state, PreparationResult& result)
{
  state.kinds = orientComponents(orient, state.edges, result);
  describeComponents(result.componentId, state.kinds, result.report);
  markBoundary(state.edges, state.numVertices, result);
}

/// After a repair changed the triangles: edges, components, orientation and boundary again.
void relink(bool orient, MeshState& state, PreparationResult& result)
{
  state.edges = buildEdgeTable(result.mesh.triangles);
  settle(orient, state, result);
}

/// values[i] = values[kept[i]] for the kept (ascending) entries; the rest dropped.
template <typename Values>
void keepEntries(Values& values, const std::vector<int32_t>& kept)
{
  for (size_t i = 0; i < kept.size(); ++i)
  {
    values[i] = values[kept[i]];
  }
  values.resize(kept.size());
}

/// After a repair kept some points and triangles (old ids, ascending): the per-element arrays
/// follow them, and the edges, components, orientation and boundary are found again.
void follow(const std::vector<int32_t>& keptPoints, const std::vector<int32_t>& keptTriangles,
  bool orient, MeshState& state, PreparationResult& result)
{
  keepEntries(result.inputPointId, keptPoints);
  keepEntries(result.nonManifoldVertex, keptPoints);
  keepEntries(result.inputCellId, keptTriangles);
  keepEntries(result.nonManifoldEdge, keptTriangles);
  state.numVertices = static_cast<int32_t>(keptPoints.size());
  state.numTriangles = static_cast<int64_t>(keptTriangles.size());
  relink(orient, state, result);
}

/// What the report says about each repair.
void record(const HoleFilling& filled, PreparationReport& report)
{
  report.filledHoles = filled.filledHoles;
  report.holeTriangles = filled.addedTriangles;
  report.holePoints = filled.addedPoints;
  report.unfairedHoles = filled.unfairedHoles;
  report.openHoles = filled.skippedHoles;
}

void record(const SliverRemoval& removed, PreparationReport& report)
{
  report.slivers = removed.slivers;
  report.sliverPoints = removed.collapsedPoints;
  report.reshapedTriangles = removed.reshapedTriangles;
  report.remainingSlivers = removed.remainingSlivers;
}

/// The outcome of a CGAL repair (`repair`, turned on by `option`), recorded in the report;
/// throws notManifoldError when the repair refused the mesh as not manifold.
template <typename Outcome>
Outcome recorded(Outcome outcome, const PreparationOptions& options, PreparationReport& report,
  const char* repair, const char* option)
{
  if (outcome.nonManifold)
  {
    throw notManifoldError(report, options, repair, option);
  }
  record(outcome, report);
  return outcome;
}

/// Drops the components whose `keep` is 0 (their points too); the per-element arrays follow.
void dropComponents(
  const std::vector<uint8_t>& keep, bool orient, MeshState& state, PreparationResult& result)
{
  const ComponentRemoval removal = keepComponents(result.mesh, result.componentId, keep);
  result.report.droppedComponentPoints += removal.droppedPoints;
  follow(removal.keptPoints, removal.keptTriangles, orient, state, result);
}

/// Step 9: drops the components the options name (non-orientable, small, all but the largest).
void selectAndDropComponents(
  const PreparationOptions& options, MeshState& state, PreparationResult& result)
{
  PreparationReport& report = result.report;
  const std::vector<uint8_t> keep =
    selectComponents(result.componentId, state.kinds, options, report);
  if (report.droppedNonOrientable + report.droppedSmallComponents + report.droppedMinorComponents >
    0)
  {
    dropComponents(keep, options.orient, state, result);
  }
}

/// Step 10: fills the holes (CGAL), then drops the components of fewer than 4 triangles: once
/// filled, no closed surface (a lone triangle becomes a flat two-sided pair, around whose
/// corners no base complex fits).
void closeHoles(const PreparationOptions& options, const Progress& progress, MeshState& state,
  PreparationResult& result)
{
  PreparationReport& report = result.report;
  if (report.boundaryEdges > 0)
  {
    const HoleFilling filled = recorded(fillHoles(result.mesh, options.maxHoleEdges, progress),
      options, report, "fill holes", "FillHoles");
    // The patches' points and triangles come from no input element.
    state.numVertices += static_cast<int32_t>(filled.addedPoints);
    state.numTriangles += filled.addedTriangles;
    result.inputPointId.resize(state.numVertices, -1);
    result.inputCellId.resize(state.numTriangles, -1);
    result.nonManifoldVertex.resize(state.numVertices, 0);
    result.nonManifoldEdge.resize(state.numTriangles, 0);
    if (filled.addedTriangles > 0)
    {
      relink(options.orient, state, result);
    }
  }
  const std::vector<int64_t> triangles = componentTriangles(result.componentId, report.components);
  std::vector<uint8_t> keep(triangles.size(), 1);
  for (size_t k = 0; k < triangles.size(); ++k)
  {
    keep[k] = triangles[k] >= 4 ? 1 : 0;
    report.droppedFragments += 1 - keep[k];
  }
  if (report.droppedFragments > 0)
  {
    dropComponents(keep, options.orient, state, result);
  }
}

/// Step 11: removes the slivers (CGAL). Only drops points and triangles and changes corners:
/// the per-element arrays follow the kept ones.
void removeSliverTriangles(const PreparationOptions& options, const Progress& progress,
  MeshState& state, PreparationResult& result)
{
  const SliverRemoval removed =
    recorded(removeSlivers(result.mesh, options.sliverAngle, options.sliverEdgeRatio, progress),
      options, result.report, "remove slivers", "RemoveSlivers");
  if (removed.collapsedPoints > 0 || removed.reshapedTriangles > 0)
  {
    follow(removed.keptPoints, removed.keptTriangles, options.orient, state, result);
  }
}
} // namespace

PreparationResult prepareMesh(
  const PolygonSoup& soup, const PreparationOptions& options, const Progress& progress)
{
  progress.report(0.0);
  PreparationResult result;
  PreparationReport& report = result.report;
  report.inputPoints = soup.numPoints();
  report.inputPolygons = soup.numPolygons();

  // 1. Validate: every later step may assume ids in range and finite coordinates.
  validateArrays(soup);
  validateGeometry(soup);
  validateOptions(options);
  const UsedPoints used = usedPoints(soup);
  progress.report(0.05);

  // 2. Merge duplicate points (before triangulating, so that polygons see merged corners).
  const std::vector<int32_t> representative = mergePoints(soup, used.used, used.low, used.diagonal,
    std::max(0.0, options.mergeTolerance) * used.diagonal);
  for (int64_t v = 0; v < soup.numPoints(); ++v)
  {
    report.mergedPoints += (used.used[v] && representative[v] != v) ? 1 : 0;
  }
  progress.report(0.2);

  // 3. Triangulate polygons and drop degenerate triangles.
  Candidates candidates = triangulate(soup, representative, used.diagonal, report);
  progress.report(0.35);

  // 4. Drop repeated triangles (same three points in any order); the first one stays.
  const std::vector<uint8_t> keep = firstOfDuplicates(candidates, report);

  // 5. Number the used points in input order; compact the triangles.
  MeshState state;
  state.numVertices = compact(candidates, keep, soup.numPoints(), result);
  state.numTriangles = result.mesh.numTriangles();
  report.unusedPoints = soup.numPoints() - report.mergedPoints - state.numVertices;
  candidates = Candidates();
  progress.report(0.45);

  // 6. Non-manifold edges and vertices, flagged before any splitting.
  state.edges = buildEdgeTable(result.mesh.triangles);
  findNonManifold(result.mesh.triangles, state.edges, state.numVertices, result);
  progress.report(0.6);

  // 7. Split (opt-in).
  if (options.splitNonManifold && (report.nonManifoldEdges > 0 || report.nonManifoldVertices > 0))
  {
    const int32_t before = state.numVertices;
    state.numVertices =
      splitNonManifold(result.mesh.triangles, state.edges, state.numVertices, result);
    report.splitVertices = state.numVertices - before;
  }
  progress.report(0.7);

  // 8. Output points, components, orientation and boundary.
  copyPoints(soup, state.numVertices, result);
  settle(options.orient, state, result);
  progress.report(0.8);

  // 9. Components (opt-in): before the repairs, which refuse a non-orientable component and
  // would only fill the holes of parts about to be dropped.
  selectAndDropComponents(options, state, result);

  // 10. Holes (opt-in), on the oriented mesh; then the closed components face outward too.
  if (options.fillHoles)
  {
    closeHoles(options, progress.sub(0.8, 0.9), state, result);
  }
  progress.report(0.9);

  // 11. Slivers (opt-in), last, so that hole patches are repaired too.
  if (options.removeSlivers)
  {
    removeSliverTriangles(options, progress.sub(0.9, 1.0), state, result);
  }

  // 12. Counts.
  report.outputPoints = state.numVertices;
  report.outputTriangles = state.numTriangles;
  progress.report(1.0);
  return result;
}
} // namespace tc
