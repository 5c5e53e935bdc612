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
#include <cmath>
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

/// The indices i with mask[i] set (all of them for an empty mask) of 0 .. n - 1.
std::vector<int32_t> selected(int32_t n, const std::vector<uint8_t>& mask)
{
  std::vector<int32_t> out;
  for (int32_t i = 0; i < n; ++i)
  {
    if (mask.empty() || mask[static_cast<size_t>(i)])
    {
      out.push_back(i);
    }
  }
  return out;
}

/// Step 4: the grids of the charts in `which` at their sampled level and their levelError at
/// every level up to it, in parallel; also their creases (once), which the errors are measured
/// along.
void sampleCharts(const SamplingInput& in, const std::vector<PatchParameterization>& param,
  const std::vector<int32_t>& sampled, const std::vector<PathSamples>& paths,
  const std::vector<int32_t>& which, std::vector<AtlasChart>& charts, std::vector<ChartGrid>& grids,
  std::vector<Creases>& creases, const Progress& progress)
{
  const int32_t nc = in.L.numCharts;
  const TriMesh& mesh = in.patches.mesh;
  grids.resize(nc);
  // The first call samples every chart: its creases are found then, in the same loop.
  const bool first = creases.empty();
  creases.resize(nc);
  const int64_t n = static_cast<int64_t>(which.size());
  parallel_for(
    n,
    [&](int64_t k)
    {
      const int32_t c = which[static_cast<size_t>(k)];
      if (first)
      {
        creases[c] = patchCreases(mesh, param[c]);
      }
      grids[c] = sampleChartGrid(in, param[c], charts[c], c, sampled[c], paths);
      charts[c].levelError = chartLevelErrors(mesh, param[c], grids[c], creases[c], sampled[c]);
    },
    progress, blockSteps(n));
}

/// Step 3: the paths in `which` sampled at the finer sampled level of their two charts, in
/// parallel.
void samplePaths(const SamplingInput& in, const std::vector<int32_t>& sampled,
  const std::vector<int32_t>& which, std::vector<PathSamples>& paths, const Progress& progress)
{
  const Layout& L = in.L;
  paths.resize(L.numEdges);
  const int64_t n = static_cast<int64_t>(which.size());
  parallel_for(
    n,
    [&](int64_t k)
    {
      const int32_t e = which[static_cast<size_t>(k)];
      const int32_t level = std::max(sampled[L.edgeChart[2 * e]], sampled[L.edgeChart[2 * e + 1]]);
      paths[e] = samplePath(in, e, level);
    },
    progress, blockSteps(n));
}

/// Steps 3 and 4 again for the charts in `raised` (their sampled level raised), their paths,
/// and the charts across those paths (whose sides are copied from them); false when none.
bool resampleRaised(const SamplingInput& in, const std::vector<PatchParameterization>& param,
  const std::vector<uint8_t>& raised, const std::vector<int32_t>& sampled,
  std::vector<PathSamples>& paths, std::vector<AtlasChart>& charts, std::vector<ChartGrid>& grids,
  std::vector<Creases>& creases, const Progress& progress)
{
  const Layout& L = in.L;
  std::vector<uint8_t> edge(L.numEdges, 0), chart(L.numCharts, 0);
  for (int32_t e = 0; e < L.numEdges; ++e)
  {
    if (raised[L.edgeChart[2 * e]] || raised[L.edgeChart[2 * e + 1]])
    {
      edge[e] = chart[L.edgeChart[2 * e]] = chart[L.edgeChart[2 * e + 1]] = 1;
    }
  }
  const std::vector<int32_t> which = selected(L.numCharts, chart);
  if (which.empty())
  {
    return false;
  }
  samplePaths(in, sampled, selected(L.numEdges, edge), paths, progress.sub(0.0, 0.1));
  sampleCharts(in, param, sampled, paths, which, charts, grids, creases, progress.sub(0.1, 1.0));
  return true;
}

/// Steps 3 and 4 for every chart, then, while an errorTarget is set, again for the charts whose
/// error at their sampled level is above it (raised one level, within the measured budget).
void sampleAndMeasure(const SamplingInput& in, const std::vector<PatchParameterization>& param,
  const GeometryImageOptions& o, const SampleBudgets& budgets, double diagonal,
  std::vector<int32_t>& sampled, std::vector<PathSamples>& paths, std::vector<AtlasChart>& charts,
  std::vector<ChartGrid>& grids, std::vector<Creases>& creases, const Progress& progress)
{
  const Layout& L = in.L;
  samplePaths(in, sampled, selected(L.numEdges, {}), paths, progress.sub(0.0, 0.05));
  sampleCharts(in, param, sampled, paths, selected(L.numCharts, {}), charts, grids, creases,
    progress.sub(0.05, 0.6));
  if (!stopsOnTarget(o))
  {
    return;
  }
  // Rounds shrink fast (a chart rises only while above the target), so each gets half of what
  // is left of the range.
  for (int32_t round = 0; round < o.maxLevel; ++round)
  {
    const std::vector<uint8_t> raised =
      raiseMeasured(charts, sampled, o, budgets.measured, o.errorTarget * diagonal);
    const double a = 1.0 - 0.4 * std::pow(0.5, round), b = 1.0 - 0.4 * std::pow(0.5, round + 1);
    if (!resampleRaised(
          in, param, raised, sampled, paths, charts, grids, creases, progress.sub(a, b)))
    {
      break;
    }
  }
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
  checkExtraAttributes(extra, L.numPoints, patches.mesh.numTriangles());
  const SampleLayout S = sampleLayout(extra);
  Atlas atlas = emptyAtlas(patches, extra);
  const std::vector<double> shared = sharedNormals(patches.mesh, L, normals);
  progress.report(0.02);

  // 1. Parameterize every patch and measure its curvature-weighted area.
  std::vector<PatchParameterization> param;
  std::vector<double> weightedArea;
  parameterizePatches(patches, base, L, meanCurvature, options, atlas.inputDiagonal, param,
    weightedArea, progress.sub(0.02, 0.45));

  // 2. The budgets; the level every chart is sampled at first (the area rule's d_max, raised
  // for the error rule to the levels it measures); the chart table's neighbours.
  const SampleBudgets budgets = sampleBudgets(options, L.numCharts, atlas.inputPoints);
  std::vector<int32_t> sampled = sampledLevels(weightedArea, options, budgets.area);
  atlas.charts = chartTable(patches, base, L);

  // 3-4. Corners and paths, sampled once in float and copied into every chart that shares them;
  // every chart's grid at its sampled level and its error at each level; the charts above the
  // error target measured higher.
  const std::vector<uint8_t> featureVertex = featureVertices(patches, L, base.baseVertices.size());
  const SamplingInput in{ patches, base, L, S, extra, shared, featureVertex };
  std::vector<PathSamples> paths;
  std::vector<ChartGrid> grids;
  std::vector<Creases> creases;
  sampleAndMeasure(in, param, options, budgets, atlas.inputDiagonal, sampled, paths, atlas.charts,
    grids, creases, progress.sub(0.45, 0.85));

  // 5. d_max of every chart under the budget and the target; level d of a chart is its sampled
  // grid at stride 2^(sampled - d), whatever d_max is chosen.
  const std::vector<int32_t> level =
    chartLevels(atlas.charts, sampled, patches.mesh, atlas.inputDiagonal, options, budgets);

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
