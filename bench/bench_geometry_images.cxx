// SPDX-License-Identifier: BSD-3-Clause
// The static pipeline end to end through the core functions (Feng et al. 2010, sections 4, 5.1,
// 5.2, 6.3 and 7), timed stage by stage on prepared meshes: curvature and crest lines, spectral
// clustering, feature refinement, base complex, path tracing, geometry images, atlas file. The
// atlas is rebuilt at every uniform level and measured against the prepared input with the
// Metro-style surfaceDistance; in the same run, meshoptimizer's QEM simplification to the same
// triangle count is measured the same way, and the whole chain is run again without feature
// constraints (the ablation of the paper's Fig. 10). Prints the figures and the goals of
// issue 5 next to them.
//
//   tc_bench_geometry_images [--error-target F] [mesh ...]
//       default meshes: bunny_glmark2 (70K), armadillo, fandisk_large, refined_elephant;
//       --error-target: GeometryImageOptions::errorTarget (default: the option's default)
#include "bench_common.h"
#include "tc/metrics/qem_peer.h"

#include "tcMeshConversion.h"

#include "tc/common/mesh.h"
#include "tc/features/crest_lines.h"
#include "tc/features/curvature.h"
#include "tc/features/feature_refinement.h"
#include "tc/features/spectral_clustering.h"
#include "tc/gim/atlas.h"
#include "tc/gim/base_complex.h"
#include "tc/gim/geometry_image_mesh.h"
#include "tc/gim/geometry_images.h"
#include "tc/gim/path_tracing.h"
#include "tc/io/atlas_io.h"
#include "tc/metrics/surface_distance.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
// Goals of issues 5 and 18.
constexpr double kMaxErrorRatio = 2.0;        // error <= 2x QEM at every level
constexpr double kMaxFinestError = 0.001;     // <= 0.1% of the diagonal at the finest level
constexpr double kMaxBunnySeconds = 10.0;     // full pipeline on the 70K bunny
constexpr double kMaxBytesPerTriangle = 14.0; // atlas file size per input triangle
constexpr const char* kGoalMesh = "bunny_glmark2.obj";

/// The stages run so far with their wall-clock seconds; `current` names the one running, so
/// that an exception can say where it came from.
struct Stages
{
  std::string current;
  std::vector<std::pair<std::string, double>> seconds;

  void run(const std::string& name, const std::function<void()>& work)
  {
    current = name;
    const auto start = std::chrono::steady_clock::now();
    work();
    seconds.emplace_back(
      name, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
};

const char* mark(bool ok)
{
  return ok ? "ok" : "MISSED";
}

/// A value as a percentage of the diagonal, e.g. "0.1234%".
std::string percent(double fraction)
{
  std::ostringstream s;
  s << std::setprecision(4) << 100.0 * fraction << "%";
  return s.str();
}

std::string fixed(double value, int digits)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << value;
  return s.str();
}

/// A value per Steiner point interpolated along the input edge it lies on, so that arrays over
/// the input points become arrays over PatchMesh::mesh's points (input points first).
std::vector<double> overPatchPoints(const tc::PatchMesh& patches, const std::vector<double>& input)
{
  std::vector<double> out(input);
  const size_t steiner = patches.steinerParameter.size();
  for (size_t s = 0; s < steiner; ++s)
  {
    const double t = patches.steinerParameter[s];
    out.push_back((1.0 - t) * input[static_cast<size_t>(patches.steinerEdge[2 * s])] +
      t * input[static_cast<size_t>(patches.steinerEdge[2 * s + 1])]);
  }
  return out;
}

/// The atlas of `mesh` from a base complex: traced paths, then geometry images. The mean
/// curvature weights the sample budget towards curved charts (GeometryImageOptions).
tc::Atlas atlasOf(const tc::TriMesh& mesh, const tc::BaseComplexResult& base,
  const std::vector<double>& meanCurvature, const std::string& source,
  const tc::GeometryImageOptions& options, Stages& stages)
{
  tc::PatchMesh patches;
  stages.run("path tracing", [&] { patches = tc::tracePaths(mesh, base); });
  tc::Atlas atlas;
  stages.run("geometry images",
    [&]
    {
      atlas = tc::buildGeometryImages(
        patches, base, {}, overPatchPoints(patches, meanCurvature), {}, options);
    });
  atlas.source = source;
  return atlas;
}

struct LevelError
{
  int64_t vertices = 0;
  int64_t triangles = 0;
  double hausdorff = 0.0; ///< fraction of the diagonal
  double rms = 0.0;       ///< fraction of the diagonal
};

LevelError errorOf(const tc::TriMesh& mesh, const tc::TriMesh& reference)
{
  tc::SurfaceDistanceOptions options;
  options.perPointDistance = false;
  const tc::SurfaceDistanceResult d = tc::surfaceDistance(mesh, reference, options);
  return { mesh.numPoints(), mesh.numTriangles(), d.hausdorff / d.diagonal,
    d.rmsDistance / d.diagonal };
}

/// The rebuilt mesh at every uniform level 0 .. maxLevel, measured against `reference`.
std::vector<LevelError> levelErrors(const tc::Atlas& atlas, const tc::TriMesh& reference)
{
  std::vector<LevelError> levels;
  for (int32_t d = 0; d <= atlas.maxLevel(); ++d)
  {
    levels.push_back(errorOf(tc::rebuildMesh(atlas, d).mesh, reference));
  }
  return levels;
}

/// The levels the renderer's error rule gives for a threshold `tau` (tc::selectLevels in error
/// mode at a fixed scale): each chart at the coarsest level whose levelError is at most tau, or
/// at its finest level.
std::vector<int32_t> levelsWithin(const tc::Atlas& atlas, double tau)
{
  std::vector<int32_t> levels;
  for (const tc::AtlasChart& chart : atlas.charts)
  {
    int32_t d = 0;
    while (d < chart.maxLevel && chart.levelError[static_cast<size_t>(d)] > tau)
    {
      ++d;
    }
    levels.push_back(d);
  }
  return levels;
}

int64_t trianglesOf(const std::vector<int32_t>& levels)
{
  int64_t sum = 0;
  for (int32_t d : levels)
  {
    sum += int64_t(1) << (2 * d);
  }
  return sum;
}

/// The renderer's adaptive rule at the largest triangle count that does not exceed
/// `maxTriangles`: the smallest threshold (among the charts' levelError values) that fits.
std::vector<int32_t> adaptiveLevels(const tc::Atlas& atlas, int64_t maxTriangles)
{
  std::vector<double> taus{ 0.0 };
  for (const tc::AtlasChart& chart : atlas.charts)
  {
    for (int32_t d = 0; d <= chart.maxLevel; ++d)
    {
      taus.push_back(chart.levelError[static_cast<size_t>(d)]);
    }
  }
  std::sort(taus.begin(), taus.end());
  taus.erase(std::unique(taus.begin(), taus.end()), taus.end());
  // Triangles fall as tau rises: the first tau that fits.
  size_t lo = 0, hi = taus.size() - 1;
  while (lo < hi)
  {
    const size_t mid = (lo + hi) / 2;
    if (trianglesOf(levelsWithin(atlas, taus[mid])) <= maxTriangles)
    {
      hi = mid;
    }
    else
    {
      lo = mid + 1;
    }
  }
  return levelsWithin(atlas, taus[lo]);
}

/// Prints one line per stage run and returns their total.
double printSeconds(const Stages& stages)
{
  double total = 0.0;
  for (const auto& s : stages.seconds)
  {
    std::cout << "  " << std::left << std::setw(26) << s.first << std::right << fixed(s.second, 3)
              << "\n";
    total += s.second;
  }
  return total;
}

/// Prints what a base complex came to (before path tracing, which needs it to be a bijection).
void printBase(const tc::BaseComplexResult& base)
{
  std::cout << "base complex: " << base.baseTriangles.size() / 3 << " faces, "
            << (base.reachedTarget ? "target reached" : "target not reached") << ", "
            << base.invalidTriangles << " invalid triangles, " << base.snappedPoints
            << " snapped points\n";
}

/// Prints the charts and levels of an atlas, and its finest samples per input point.
void printAtlas(const tc::Atlas& atlas)
{
  int64_t samples = 0;
  for (const tc::AtlasChart& c : atlas.charts)
  {
    samples += tc::gridVertexCount(c.maxLevel);
  }
  int32_t minChartLevel = atlas.maxLevel();
  for (const tc::AtlasChart& c : atlas.charts)
  {
    minChartLevel = std::min(minChartLevel, c.maxLevel);
  }
  std::cout << "charts: " << atlas.charts.size() << ", max level: " << atlas.maxLevel()
            << " (chart levels " << minChartLevel << " .. " << atlas.maxLevel() << "), "
            << atlas.images.size() << " images, finest " << atlas.images[0].width << " x "
            << atlas.images[0].height << "; " << samples << " finest samples, "
            << fixed(static_cast<double>(samples) / static_cast<double>(atlas.inputPoints), 2)
            << " per input point\n";
}

/// The pipeline on one mesh; a stage that throws is reported and ends that part of the run.
void benchmark(const std::string& file, const tc::GeometryImageOptions& options)
{
  const std::string name = tcbench::BaseName(file);
  std::cout << "\n== " << name << "\n";
  Stages stages;

  // Read and prepare (VTK filters), then the core mesh. Section 4: curvature and crest lines,
  // spectral clustering, feature refinement, chained as the VTK filters (tcCurvature,
  // tcSpectralClustering, tcFeatureRefinement) chain them.
  tc::TriMesh mesh;
  tc::CurvatureResult curvature;
  tc::FeatureRefinementResult features;
  std::vector<int32_t> featureEdges;
  try
  {
    stages.run("read + preparation",
      [&]
      {
        std::string error;
        if (!tcvtk::ToTriMesh(tcbench::Prepared(file), mesh, error))
        {
          throw std::runtime_error(error);
        }
      });
    std::cout << "input: " << mesh.numPoints() << " points, " << mesh.numTriangles()
              << " triangles (prepared)\n";
    std::vector<uint8_t> crest;
    stages.run("curvature + crest lines",
      [&]
      {
        curvature = tc::computeCurvature(mesh);
        crest = tc::crestVertices(mesh, tc::extractCrestLines(mesh, curvature));
      });
    tc::SpectralClusteringResult clusters;
    stages.run("spectral clustering",
      [&] { clusters = tc::spectralClustering(mesh, curvature.faceMean, crest); });
    stages.run("feature refinement",
      [&]
      {
        features =
          tc::refineFeatures(mesh, clusters.clusterId, curvature.mean, curvature.faceMean, crest);
      });
    // The feature edges: consecutive vertices of every feature line (as tcFeatureRefinement
    // hands them to tcBaseComplex).
    for (int64_t k = 0; k < features.numLines(); ++k)
    {
      for (int64_t i = features.lineOffsets[k]; i + 1 < features.lineOffsets[k + 1]; ++i)
      {
        featureEdges.push_back(features.lineVertices[i]);
        featureEdges.push_back(features.lineVertices[i + 1]);
      }
    }
    std::cout << "features: " << clusters.numClusters << " clusters, " << features.numLines()
              << " feature lines (" << featureEdges.size() / 2 << " edges), "
              << features.corners.size() << " corners\n";
  }
  catch (const std::exception& e)
  {
    std::cout << name << ": " << stages.current << " failed: " << e.what() << "\n";
    std::cout << "seconds of the stages before\n";
    printSeconds(stages);
    std::cout << "peak memory so far: " << fixed(tcbench::PeakMegabytes(), 1) << " MB\n";
    return;
  }

  // Section 5: base complex, traced paths, geometry images; the atlas file. Section 7: the
  // rebuilt mesh at every uniform level, and QEM at the same triangle count.
  std::vector<LevelError> ours;
  double bytes = -1.0;
  try
  {
    tc::BaseComplexResult base;
    stages.run("base complex",
      [&]
      {
        base =
          tc::buildBaseComplex(mesh, features.featureVertex, features.cornerVertex, featureEdges);
      });
    printBase(base);
    const tc::Atlas atlas = atlasOf(mesh, base, curvature.mean, name, options, stages);
    printAtlas(atlas);
    const std::filesystem::path atlasFile = std::filesystem::temp_directory_path() /
      ("tc_bench_geometry_images_" + std::to_string(getpid()) + ".exr");
    stages.run("write atlas", [&] { tc::writeAtlas(atlas, atlasFile.string()); });
    bytes = static_cast<double>(std::filesystem::file_size(atlasFile));
    std::filesystem::remove(atlasFile);

    stages.current = "error measurement";
    ours = levelErrors(atlas, mesh);
    std::cout << "\nerror against the prepared input (Hausdorff and RMS / bounding-box diagonal); "
                 "QEM = meshopt_simplify to the same triangle count\n";
    std::cout << std::left << std::setw(6) << "level" << std::setw(9) << "verts" << std::setw(9)
              << "tris" << std::setw(11) << "H" << std::setw(11) << "RMS" << std::setw(9)
              << "QEM vert" << std::setw(9) << "QEM tris" << std::setw(11) << "QEM H"
              << std::setw(11) << "QEM RMS" << std::setw(8) << "H/QEM" << std::setw(8) << "RMS/QEM"
              << "goal <= 2x QEM (H, RMS)\n";
    bool withinRatio = true;
    for (size_t d = 0; d < ours.size(); ++d)
    {
      const LevelError qem = errorOf(tc::simplifyQem(mesh, ours[d].triangles), mesh);
      const double hRatio = ours[d].hausdorff / qem.hausdorff;
      const double rmsRatio = ours[d].rms / qem.rms;
      const bool hOk = hRatio <= kMaxErrorRatio, rmsOk = rmsRatio <= kMaxErrorRatio;
      withinRatio = withinRatio && hOk && rmsOk;
      std::cout << std::setw(6) << d << std::setw(9) << ours[d].vertices << std::setw(9)
                << ours[d].triangles << std::setw(11) << percent(ours[d].hausdorff) << std::setw(11)
                << percent(ours[d].rms) << std::setw(9) << qem.vertices << std::setw(9)
                << qem.triangles << std::setw(11) << percent(qem.hausdorff) << std::setw(11)
                << percent(qem.rms) << std::setw(8) << fixed(hRatio, 2) << std::setw(8)
                << fixed(rmsRatio, 2) << mark(hOk) << ", " << mark(rmsOk) << "\n";
    }
    std::cout << std::right;

    // What the renderer draws is not a uniform level: its error rule puts each chart at the
    // coarsest level within one error threshold. The same triangle counts that way.
    std::cout << "\nadaptive levels (the renderer's error rule: each chart at the coarsest level "
                 "whose levelError is within one threshold), at most the triangles of each "
                 "uniform level\n";
    std::cout << std::left << std::setw(6) << "as" << std::setw(9) << "verts" << std::setw(9)
              << "tris" << std::setw(11) << "H" << std::setw(11) << "RMS" << std::setw(11)
              << "QEM H" << std::setw(11) << "QEM RMS" << std::setw(8) << "H/QEM"
              << "RMS/QEM\n";
    for (size_t d = 0; d < ours.size(); ++d)
    {
      const LevelError adaptive =
        errorOf(tc::rebuildMesh(atlas, adaptiveLevels(atlas, ours[d].triangles)).mesh, mesh);
      const LevelError qem = errorOf(tc::simplifyQem(mesh, adaptive.triangles), mesh);
      std::cout << std::setw(6) << d << std::setw(9) << adaptive.vertices << std::setw(9)
                << adaptive.triangles << std::setw(11) << percent(adaptive.hausdorff)
                << std::setw(11) << percent(adaptive.rms) << std::setw(11) << percent(qem.hausdorff)
                << std::setw(11) << percent(qem.rms) << std::setw(8)
                << fixed(adaptive.hausdorff / qem.hausdorff, 2) << fixed(adaptive.rms / qem.rms, 2)
                << "\n";
    }
    std::cout << std::right;
    const LevelError& finest = ours.back();
    std::cout << "goal error <= 2x QEM at every level (H and RMS): " << mark(withinRatio) << "\n";
    std::cout << "goal finest level (" << ours.size() - 1 << ") <= 0.1% of the diagonal: Hausdorff "
              << percent(finest.hausdorff) << " " << mark(finest.hausdorff <= kMaxFinestError)
              << ", RMS " << percent(finest.rms) << " " << mark(finest.rms <= kMaxFinestError)
              << "\n";
  }
  catch (const std::exception& e)
  {
    std::cout << name << ": " << stages.current << " failed: " << e.what() << "\n";
  }

  // The ablation of Fig. 10: the same chain with no feature constraint on the base complex
  // (run whether or not the constrained one got through; not part of the timed pipeline).
  Stages ablation;
  try
  {
    std::cout << "\nwithout feature constraints (Fig. 10 ablation)\n";
    tc::BaseComplexResult plainBase;
    ablation.run("base complex", [&] { plainBase = tc::buildBaseComplex(mesh, {}, {}, {}); });
    printBase(plainBase);
    const tc::Atlas plain = atlasOf(mesh, plainBase, curvature.mean, name, options, ablation);
    printAtlas(plain);
    ablation.current = "error measurement";
    const std::vector<LevelError> plainErrors = levelErrors(plain, mesh);
    std::cout << std::left << std::setw(6) << "level" << std::setw(9) << "verts" << std::setw(9)
              << "tris" << std::setw(11) << "H" << std::setw(11) << "RMS"
              << "with features / without (H, RMS)\n";
    for (size_t d = 0; d < plainErrors.size(); ++d)
    {
      std::cout << std::setw(6) << d << std::setw(9) << plainErrors[d].vertices << std::setw(9)
                << plainErrors[d].triangles << std::setw(11) << percent(plainErrors[d].hausdorff)
                << std::setw(11) << percent(plainErrors[d].rms);
      if (d < ours.size())
      {
        std::cout << fixed(ours[d].hausdorff / plainErrors[d].hausdorff, 2) << ", "
                  << fixed(ours[d].rms / plainErrors[d].rms, 2);
      }
      std::cout << "\n";
    }
    std::cout << std::right;
  }
  catch (const std::exception& e)
  {
    std::cout << name << ": ablation (no features): " << ablation.current << " failed: " << e.what()
              << "\n";
  }

  // Stage times and size of the feature-constrained pipeline.
  const bool complete = bytes >= 0.0;
  std::cout << "\nseconds per stage" << (complete ? "" : " (of the stages that ran)") << "\n";
  const double total = printSeconds(stages);
  if (complete)
  {
    std::cout << "  " << std::left << std::setw(26) << "total" << std::right << fixed(total, 3);
    if (name == kGoalMesh)
    {
      std::cout << "   goal <= 10 s on the 70K bunny: " << mark(total <= kMaxBunnySeconds);
    }
    std::cout << "\n";
    const double perTriangle = bytes / static_cast<double>(mesh.numTriangles());
    std::cout << "atlas file: " << fixed(bytes / (1024.0 * 1024.0), 3) << " MB ("
              << static_cast<int64_t>(bytes) << " bytes), " << fixed(perTriangle, 2)
              << " bytes per input triangle   goal <= 14: "
              << mark(perTriangle <= kMaxBytesPerTriangle) << "\n";
  }
  std::cout << "peak memory so far: " << fixed(tcbench::PeakMegabytes(), 1) << " MB\n";
}
} // namespace

int main(int argc, char* argv[])
{
  std::vector<std::string> files(argv + 1, argv + argc);
  tc::GeometryImageOptions options;
  if (files.size() >= 2 && files[0] == "--error-target")
  {
    options.errorTarget = std::strtod(files[1].c_str(), nullptr);
    files.erase(files.begin(), files.begin() + 2);
  }
  std::cout << "error target: " << options.errorTarget << " of the diagonal"
            << (options.errorTarget > 0.0 ? "" : " (none: the budget alone)") << "\n";
  if (files.empty())
  {
    const std::string data = TC_SHARED_DATA_DIR;
    files = { data + "/static_medium/bunny_glmark2.obj", data + "/static_medium/armadillo.off",
      data + "/cad/fandisk_large.off", data + "/static_medium/refined_elephant.off" };
  }
  for (const std::string& file : tcbench::Present(files))
  {
    benchmark(file, options);
  }
  return 0;
}
