// SPDX-License-Identifier: BSD-3-Clause
#include "tc/gim/geometry_images.h"

#include "gim/atlas_packing.h"
#include "gim/atlas_quantization.h"
#include "gim/chart_box.h"
#include "gim/chart_grid.h"
#include "gim/geometry_images_input.h"
#include "gim/level_error.h"
#include "gim/level_rule.h"
#include "gim/patch_parameterization.h"
#include "gim/resampling.h"
#include "gim/sample_fit.h"
#include "tc/common/errors.h"
#include "tc/common/parallel.h"

#include <algorithm>
#include <string>
#include <vector>

// The steps of buildGeometryImages, each in the file of its concept: input checks
// (geometry_images_input), patch parameterization, level rule, resampling (paths once, then
// chart grids), level errors, sample fit, boxes (chart_box) and packing (atlas_packing).

namespace tc::detail::geometry_images
{
namespace
{
/// Progress steps of a parallel loop over n patches, paths or charts: parallel_for runs its
/// steps one after the other, so each must hold several items for both cores to work.
int blockSteps(int64_t n)
{
  return static_cast<int>(std::clamp<int64_t>(n / 4, 1, 32));
}

/// The atlas's attributes (Position, Normal, then `extra`) and what it says of its input: the
/// input points (inputPointId >= 0), their bounding-box diagonal, and largest inputTriangle + 1.
Atlas emptyAtlas(const PatchMesh& patches, const std::vector<GeometryImageAttribute>& extra)
{
  Atlas atlas;
  atlas.attributes.push_back({ kAtlasPosition, 3 });
  atlas.attributes.push_back({ kAtlasNormal, 3 });
  for (const GeometryImageAttribute& x : extra)
  {
    atlas.attributes.push_back({ x.name, x.components });
  }
  for (int32_t id : patches.inputPointId)
  {
    atlas.inputPoints += id >= 0 ? 1 : 0;
  }
  atlas.inputDiagonal = inputDiagonal(patches);
  int32_t maxTriangle = -1;
  for (int32_t t : patches.inputTriangle)
  {
    maxTriangle = std::max(maxTriangle, t);
  }
  atlas.inputTriangles = int64_t(maxTriangle) + 1;
  return atlas;
}

/// Step 1: every patch parameterized, in parallel, with its curvature-weighted area; the first
/// failure in patch order is thrown once all have run.
void parameterizePatches(const PatchMesh& patches, const BaseComplexResult& base, const Layout& L,
  const std::vector<double>& meanCurvature, const GeometryImageOptions& options, double diagonal,
  std::vector<PatchParameterization>& param, std::vector<double>& weightedArea,
  const Progress& progress)
{
  const int32_t nc = L.numCharts;
  param.assign(nc, {});
  weightedArea.assign(nc, 0.0);
  std::vector<std::string> failure(nc);
  parallel_for(
    nc,
    [&](int64_t c)
    {
      try
      {
        param[c] =
          parameterize(patches, base, L, static_cast<int32_t>(c), options.stretchIterations);
      }
      catch (const InputError& e)
      {
        failure[c] = e.what();
        return;
      }
      weightedArea[c] = curvatureWeightedArea(
        patches.mesh, L, static_cast<int32_t>(c), meanCurvature, options.curvatureWeight, diagonal);
    },
    progress, blockSteps(nc));
  for (const std::string& f : failure)
  {
    if (!f.empty())
    {
      throw InputError(f);
    }
  }
}

/// Step 4: every chart's grid at its sampled level and its levelError at every level up to it,
/// in parallel; also the creases of every patch, which the errors are measured along.
void sampleCharts(const SamplingInput& in, const std::vector<PatchParameterization>& param,
  const std::vector<int32_t>& sampled, const std::vector<PathSamples>& paths,
  std::vector<AtlasChart>& charts, std::vector<ChartGrid>& grids, std::vector<Creases>& creases,
  const Progress& progress)
{
  const int32_t nc = in.L.numCharts;
  const TriMesh& mesh = in.patches.mesh;
  grids.assign(nc, {});
  creases.assign(nc, {});
  parallel_for(
    nc,
    [&](int64_t c)
    {
      creases[c] = patchCreases(mesh, param[c]);
      grids[c] =
        sampleChartGrid(in, param[c], charts[c], static_cast<int32_t>(c), sampled[c], paths);
      charts[c].levelError = chartLevelErrors(mesh, param[c], grids[c], creases[c], sampled[c]);
    },
    progress, blockSteps(nc));
}

/// Step 3: every path sampled at the finer sampled level of its two charts, in parallel.
std::vector<PathSamples> samplePaths(
  const SamplingInput& in, const std::vector<int32_t>& sampled, const Progress& progress)
{
  const Layout& L = in.L;
  std::vector<PathSamples> paths(L.numEdges);
  parallel_for(
    L.numEdges,
    [&](int64_t e)
    {
      const int32_t level = std::max(sampled[L.edgeChart[2 * e]], sampled[L.edgeChart[2 * e + 1]]);
      paths[e] = samplePath(in, static_cast<int32_t>(e), level);
    },
    progress, blockSteps(L.numEdges));
  return paths;
}

/// Step 6, sides: every path that follows no feature curve fitted, in parallel.
void fitSides(const SamplingInput& in, const std::vector<int32_t>& level,
  const std::vector<PathSamples>& paths, std::vector<ChartGrid>& grids, const Progress& progress)
{
  parallel_for(
    in.L.numEdges,
    [&](int64_t e)
    {
      if (!in.L.edgeFeature[e])
      {
        fitSide(in, static_cast<int32_t>(e), level, paths, grids);
      }
    },
    progress, blockSteps(in.L.numEdges));
}

/// Step 6, per chart: d_max, the interior fit (then the errors measured again, on the fitted
/// samples), the box, and the chart table's doubles rounded for storage. In parallel.
void finishCharts(const TriMesh& mesh, const std::vector<PatchParameterization>& param,
  const std::vector<int32_t>& level, const std::vector<Creases>& creases, bool fitSamples,
  std::vector<ChartGrid>& grids, std::vector<AtlasChart>& charts, const Progress& progress)
{
  const int32_t nc = static_cast<int32_t>(charts.size());
  parallel_for(
    nc,
    [&](int64_t c)
    {
      AtlasChart& ch = charts[c];
      ch.maxLevel = level[c];
      if (fitSamples)
      {
        // ch.levelError is still the interpolated grid's (step 4): the bound of the fit.
        fitInterior(
          mesh, param[c], grids[c], level[c], ch.levelError[static_cast<size_t>(level[c])]);
        ch.levelError = chartLevelErrors(mesh, param[c], grids[c], creases[c], level[c]);
        ch.box = chartBox(mesh, param[c], &grids[c], level[c]);
      }
      else
      {
        ch.box = chartBox(mesh, param[c], nullptr, level[c]);
      }
      ch.levelError.resize(static_cast<size_t>(level[c]) + 1);
      for (double& e : ch.levelError)
      {
        e = storageRounded(e);
      }
    },
    progress, blockSteps(nc));
}
/// Step 7, texels: every level of every chart copied into its images, in parallel.
void writeImages(const std::vector<ChartGrid>& grids, const SampleLayout& S, Atlas& atlas,
  const Progress& progress)
{
  const int32_t nc = static_cast<int32_t>(atlas.charts.size());
  parallel_for(
    nc, [&](int64_t c) { writeChartImages(grids[c], S, static_cast<int32_t>(c), atlas); }, progress,
    blockSteps(nc));
}
} // namespace
} // namespace tc::detail::geometry_images

namespace tc
{
Atlas buildGeometryImages(const PatchMesh& patches, const BaseComplexResult& base,
  const std::vector<double>& normals, const std::vector<double>& meanCurvature,
  const std::vector<GeometryImageAttribute>& extra, const GeometryImageOptions& options,
  const Progress& progress)
{
  using namespace detail::geometry_images;
  // 0. The checked input; the float values of a sample; the atlas's attributes and input
  // figures; the shared (two-sided) unit normal of every point.
  checkOptions(options);
  const Layout L = checkInput(patches, base);
  checkPointArrays(L, normals, meanCurvature);
  checkExtraAttributes(extra, L.numPoints);
  const SampleLayout S = sampleLayout(extra);
  Atlas atlas = emptyAtlas(patches, extra);
  const std::vector<double> shared = sharedNormals(patches.mesh, L, normals);
  progress.report(0.02);

  // 1. Parameterize every patch and measure its curvature-weighted area.
  std::vector<PatchParameterization> param;
  std::vector<double> weightedArea;
  parameterizePatches(patches, base, L, meanCurvature, options, atlas.inputDiagonal, param,
    weightedArea, progress.sub(0.02, 0.45));

  // 2. The budget; the level every chart is sampled at (the area rule's d_max, raised for the
  // error rule to the levels it measures); the chart table's neighbours.
  const int64_t budget = sampleBudget(options, L.numCharts, atlas.inputPoints);
  const std::vector<int32_t> sampled = sampledLevels(weightedArea, options, budget);
  atlas.charts = chartTable(patches, base, L);

  // 3. Corners and paths: sampled once, in float, and copied into every chart that shares them.
  const std::vector<uint8_t> featureVertex = featureVertices(patches, L, base.baseVertices.size());
  const SamplingInput in{ patches, base, L, S, extra, shared, featureVertex };
  const std::vector<PathSamples> paths = samplePaths(in, sampled, progress.sub(0.45, 0.5));

  // 4. Every chart's grid at its sampled level and its error at each level.
  std::vector<ChartGrid> grids;
  std::vector<Creases> creases;
  sampleCharts(in, param, sampled, paths, atlas.charts, grids, creases, progress.sub(0.5, 0.85));

  // 5. d_max of every chart under the budget; level d of a chart is its sampled grid at stride
  // 2^(sampled - d), whatever d_max is chosen.
  const std::vector<int32_t> level =
    chartLevels(atlas.charts, sampled, patches.mesh, atlas.inputDiagonal, options, budget);

  // 6. The fit of the sides, then of every chart's interior; boxes and rounded errors.
  if (options.fitSamples)
  {
    fitSides(in, level, paths, grids, progress.sub(0.85, 0.87));
  }
  finishCharts(patches.mesh, param, level, creases, options.fitSamples, grids, atlas.charts,
    progress.sub(0.87, 0.9));

  // 7. Packing (paper 5.2): charts paired by d_max, one shelf-packed image per mip step; then
  // every level of every chart copied into its texels.
  packAtlas(level, S, atlas);
  writeImages(grids, S, atlas, progress.sub(0.9, 1.0));

  // 8. Positions and normals onto the lattice the atlas file stores exactly (one frame for all
  // charts, so shared samples stay bit-identical).
  detail::snapToLattice(atlas);
  progress.report(1.0);
  return atlas;
}
} // namespace tc
