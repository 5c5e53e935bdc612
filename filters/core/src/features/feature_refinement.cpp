// SPDX-License-Identifier: BSD-3-Clause
#include "tc/features/feature_refinement.h"

#include "detail/geometry2d.h"
#include "features/boundary_straightening.h"
#include "features/corners.h"
#include "features/crease_lines.h"
#include "features/face_adjacency.h"
#include "features/face_geometry.h"
#include "features/feature_lines.h"
#include "features/graph_cut.h"
#include "features/refinement_band.h"

#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace tc
{
namespace
{
using namespace detail::refinement;
using detail::kPi;

void validate(const TriMesh& mesh, const std::vector<int32_t>& clusterId,
  const std::vector<double>& meanCurvature, const std::vector<double>& faceMeanCurvature,
  const std::vector<uint8_t>& crestVertex, const FeatureRefinementOptions& options)
{
  const std::vector<uint8_t>& seamSides = options.seamSides;
  const size_t nv = static_cast<size_t>(mesh.numPoints());
  const size_t nf = static_cast<size_t>(mesh.numTriangles());
  auto mismatch = [](const char* what, size_t got, size_t want, const char* of)
  {
    throw InputError(std::string("refineFeatures: ") + what + " has " + std::to_string(got) +
      " entries but the mesh has " + std::to_string(want) + " " + of +
      "; pass arrays computed on this mesh");
  };
  if (mesh.points.size() % 3 != 0 || mesh.triangles.size() % 3 != 0)
  {
    throw InputError("refineFeatures: points and triangles must hold 3 values per element");
  }
  if (clusterId.size() != nf)
  {
    mismatch("clusterId", clusterId.size(), nf, "triangles");
  }
  if (faceMeanCurvature.size() != nf)
  {
    mismatch("faceMeanCurvature", faceMeanCurvature.size(), nf, "triangles");
  }
  if (meanCurvature.size() != nv)
  {
    mismatch("meanCurvature", meanCurvature.size(), nv, "vertices");
  }
  if (!seamSides.empty() && seamSides.size() != nf)
  {
    mismatch("seamSides", seamSides.size(), nf, "triangles (or none)");
  }
  if (!options.skinRegions.empty() && options.skinRegions.size() != nf)
  {
    mismatch("skinRegions", options.skinRegions.size(), nf, "triangles (or none)");
  }
  if (!crestVertex.empty() && crestVertex.size() != nv)
  {
    mismatch("crestVertex", crestVertex.size(), nv, "vertices (or none)");
  }
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
  {
    const int32_t v = mesh.triangles[i];
    if (v < 0 || static_cast<size_t>(v) >= nv)
    {
      throw InputError("refineFeatures: triangle " + std::to_string(i / 3) + " references vertex " +
        std::to_string(v) + " of a mesh with " + std::to_string(nv) +
        " vertices; fix the connectivity");
    }
    if (v == mesh.triangles[3 * (i / 3) + (i + 1) % 3])
    {
      throw InputError("refineFeatures: triangle " + std::to_string(i / 3) +
        " repeats a vertex; clean the mesh with prepareMesh() first");
    }
  }
  for (size_t f = 0; f < nf; ++f)
  {
    if (clusterId[f] < 0)
    {
      throw InputError("refineFeatures: triangle " + std::to_string(f) + " has cluster id " +
        std::to_string(clusterId[f]) + "; every triangle needs a cluster (ids >= 0)");
    }
    if (!std::isfinite(faceMeanCurvature[f]))
    {
      throw InputError(
        "refineFeatures: faceMeanCurvature of triangle " + std::to_string(f) + " is not finite");
    }
  }
  for (size_t v = 0; v < nv; ++v)
  {
    if (!std::isfinite(meanCurvature[v]))
    {
      throw InputError(
        "refineFeatures: meanCurvature of vertex " + std::to_string(v) + " is not finite");
    }
  }
}

// Cluster ids made compact, 0 .. #clusters - 1, for flat per-cluster arrays.
// @param[out] ids  the input id of every compact one, ascending
std::vector<int32_t> compactLabels(const std::vector<int32_t>& clusterId, std::vector<int32_t>& ids)
{
  ids = clusterId;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::vector<int32_t> label(clusterId.size());
  for (size_t f = 0; f < clusterId.size(); ++f)
  {
    label[f] =
      static_cast<int32_t>(std::lower_bound(ids.begin(), ids.end(), clusterId[f]) - ids.begin());
  }
  return label;
}

// The band and its minimum cuts (eq. 4), repeated on the new boundaries while they move (see
// cutPasses), later passes inside the first band; then the straightening.
void refineBoundaries(const TriMesh& mesh, const EdgeTable& edges,
  const std::vector<double>& faceMeanCurvature, const std::vector<uint8_t>& crestVertex,
  const std::vector<double>& dihedral, const FeatureRefinementOptions& options,
  const ClusterPairs& pairs, std::vector<int32_t>& label, FeatureRefinementResult& result,
  const Progress& progress)
{
  const detail::FaceAdjacency dual = detail::buildFaceAdjacency(edges, mesh.numTriangles());
  const std::vector<double> centroids = detail::faceCentroids(mesh);
  const std::vector<double> capacity = dualCapacity(
    mesh, edges, dual, faceMeanCurvature, crestVertex, dihedral, options, progress.sub(0.05, 0.1));
  const int passes = std::max(1, options.cutPasses);
  Band first;
  for (int pass = 0; pass < passes; ++pass)
  {
    const Progress step = progress.sub(0.1 + 0.5 * pass / passes, 0.1 + 0.5 * (pass + 1) / passes);
    const BandExtent extent{ options.bandFraction, pass == 0 ? options.bandRings : 0,
      pass == 0 ? nullptr : &first };
    Band band = buildBand(edges, dual, centroids, label, pairs, boundaryEdges(edges, label), extent,
      step.sub(0.0, 0.3));
    const int64_t changed = cutBand(dual, capacity, band, pairs, label, step.sub(0.3, 1.0));
    if (pass == 0)
    {
      result.bandFaces = band.size;
      first = std::move(band);
    }
    if (changed == 0)
    {
      break;
    }
  }
  if (options.straightenLines)
  {
    result.straightenedFaces = straightenBoundaries(
      mesh, edges, dihedral, options.creaseAngle * kPi / 180.0, pairs.numClusters, label);
  }
}

// The vertices that triangles use, by |H| descending, ties by id.
std::vector<int32_t> rankByCurvature(const TriMesh& mesh, const std::vector<double>& meanCurvature)
{
  const int64_t nv = mesh.numPoints();
  std::vector<uint8_t> used(nv, 0);
  for (int32_t v : mesh.triangles)
  {
    used[v] = 1;
  }
  std::vector<int32_t> byCurvature;
  byCurvature.reserve(nv);
  for (int64_t v = 0; v < nv; ++v)
  {
    if (used[v])
    {
      byCurvature.push_back(static_cast<int32_t>(v));
    }
  }
  std::sort(byCurvature.begin(), byCurvature.end(),
    [&](int32_t a, int32_t b)
    {
      const double ha = std::abs(meanCurvature[a]), hb = std::abs(meanCurvature[b]);
      return ha > hb || (ha == hb && a < b);
    });
  return byCurvature;
}

// The mean of the top curvatureTopFraction of |H| over the vertices that triangles use,
// scaled, and at least the noise floor minCurvatureTimesSize / (bounding-box diagonal of those
// vertices).
double curvatureThreshold(const TriMesh& mesh, const std::vector<double>& meanCurvature,
  const std::vector<int32_t>& byCurvature, const FeatureRefinementOptions& options)
{
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const int64_t numUsed = static_cast<int64_t>(byCurvature.size());
  const int64_t numTop = std::clamp<int64_t>(
    static_cast<int64_t>(std::ceil(options.curvatureTopFraction * static_cast<double>(numUsed))), 1,
    numUsed);
  double topSum = 0.0;
  for (int64_t i = 0; i < numTop; ++i)
  {
    topSum += std::abs(meanCurvature[byCurvature[i]]);
  }
  double lo[3] = { kInf, kInf, kInf }, hi[3] = { -kInf, -kInf, -kInf };
  for (int32_t v : byCurvature)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], mesh.points[3 * v + c]);
      hi[c] = std::max(hi[c], mesh.points[3 * v + c]);
    }
  }
  const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) +
    (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const double floor = diagonal > 0.0 ? options.minCurvatureTimesSize / diagonal : 0.0;
  return std::max(options.curvatureThresholdScale * topSum / static_cast<double>(numTop), floor);
}
} // namespace

FeatureRefinementResult refineFeatures(const TriMesh& mesh, const std::vector<int32_t>& clusterId,
  const std::vector<double>& meanCurvature, const std::vector<double>& faceMeanCurvature,
  const std::vector<uint8_t>& crestVertex, const FeatureRefinementOptions& options,
  const Progress& progress)
{
  validate(mesh, clusterId, meanCurvature, faceMeanCurvature, crestVertex, options);
  const int64_t nv = mesh.numPoints();
  const int64_t nf = mesh.numTriangles();
  FeatureRefinementResult result;
  result.clusterId = clusterId;
  result.featureVertex.assign(nv, 0);
  result.cornerVertex.assign(nv, 0);
  if (nf == 0)
  {
    progress.report(1.0);
    return result;
  }

  // 1. Topology, and cluster ids made compact.
  const EdgeTable edges = buildEdgeTable(mesh.triangles);
  std::vector<int32_t> ids;
  std::vector<int32_t> label = compactLabels(clusterId, ids);
  const ClusterPairs pairs{ static_cast<int64_t>(ids.size()) };
  // Edge dihedral angles: eq. 4's crease factor, the straightening and the crease chains.
  const std::vector<double> dihedral =
    options.dihedralWeight > 0.0 || options.straightenLines || options.creaseLineAngle > 0.0
    ? detail::edgeDihedrals(mesh, edges)
    : std::vector<double>();
  progress.report(0.05);

  // 2. The cuts in the band, then the straightening.
  const std::vector<int32_t> inputLabel = label;
  refineBoundaries(
    mesh, edges, faceMeanCurvature, crestVertex, dihedral, options, pairs, label, result, progress);
  for (int64_t f = 0; f < nf; ++f)
  {
    result.relabeledFaces += label[f] != inputLabel[f] ? 1 : 0;
    result.clusterId[f] = ids[label[f]];
  }

  // 3. The curvature threshold of the segments and corners.
  const std::vector<int32_t> byCurvature = rankByCurvature(mesh, meanCurvature);
  result.curvatureThreshold = curvatureThreshold(mesh, meanCurvature, byCurvature, options);
  progress.report(0.65);

  // 4. Segments of the refined boundaries, kept above the threshold.
  const detail::Polylines segments = boundarySegments(edges, boundaryEdges(edges, label), nv);
  result.candidateSegments = static_cast<int64_t>(segments.offsets.size()) - 1;
  keepFeatureSegments(mesh, segments, meanCurvature, result);
  addCreaseLines(mesh, edges, dihedral, meanCurvature, options, result);
  addSeamLines(mesh, edges, meanCurvature, options, result);
  addSkinLines(mesh, edges, meanCurvature, options, result);
  progress.report(0.75);

  // 5. Corners.
  findCorners(edges, byCurvature, meanCurvature, options, result, progress.sub(0.75, 0.95));
  progress.report(1.0);
  return result;
}
} // namespace tc
