// SPDX-License-Identifier: BSD-3-Clause
// How well the feature stage (Feng et al. 2010, 4.1-4.2: curvature and crest lines, spectral
// clustering, feature refinement, with the defaults that `trichart build` uses) finds the
// creases of CAD parts: recall and precision of the feature-line edges against the mesh edges
// whose faces meet at more than 45 degrees (issue 18's goal: recall >= 0.90, precision >= 0.85),
// with the mesh's genus and components and the counts of clusters, lines and corners.
//
//   tc_bench_feature_lines [--fill-holes] [--crease-lines DEG] [mesh ...]
//       default meshes: the CAD meshes of ../shared/data/cad; --crease-lines: the
//       FeatureRefinementOptions::creaseLineAngle (default: the option's default)
// --fill-holes closes holes in the preparation as `trichart build --fill-holes` does (blade is
// open); without it an open mesh is measured on its own edges.
#include "bench_common.h"

#include "tcMeshConversion.h"

#include "tc/common/mesh.h"
#include "tc/common/mesh_topology.h"
#include "tc/features/crest_lines.h"
#include "tc/features/curvature.h"
#include "tc/features/feature_refinement.h"
#include "tc/features/spectral_clustering.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <iomanip>
#include <iostream>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace
{
constexpr double kGoalRecall = 0.90;
constexpr double kGoalPrecision = 0.85;
constexpr double kSharpDegrees = 45.0;

using Edge = std::pair<int32_t, int32_t>;

Edge key(int32_t a, int32_t b)
{
  return { std::min(a, b), std::max(a, b) };
}

/// Unit normal of face f (zero for a degenerate face).
std::array<double, 3> normalOf(const tc::TriMesh& mesh, int64_t f)
{
  const auto a = mesh.point(mesh.triangles[3 * f]);
  const auto b = mesh.point(mesh.triangles[3 * f + 1]);
  const auto c = mesh.point(mesh.triangles[3 * f + 2]);
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  std::array<double, 3> n = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
    u[0] * v[1] - u[1] * v[0] };
  const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double& x : n)
  {
    x = l > 0.0 ? x / l : 0.0;
  }
  return n;
}

/// Interior (two-face) edges whose faces meet at more than `degrees`.
std::set<Edge> sharpEdges(const tc::TriMesh& mesh, const tc::EdgeTable& edges, double degrees)
{
  const double limit = std::cos(degrees * 3.14159265358979323846 / 180.0);
  std::set<Edge> sharp;
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) != 2)
    {
      continue;
    }
    const auto n0 = normalOf(mesh, edges.edgeFaces[edges.faceOffsets[e]]);
    const auto n1 = normalOf(mesh, edges.edgeFaces[edges.faceOffsets[e] + 1]);
    if (n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2] < limit)
    {
      sharp.insert(key(edges.vertices[2 * e], edges.vertices[2 * e + 1]));
    }
  }
  return sharp;
}

std::set<Edge> lineEdges(const tc::FeatureRefinementResult& r)
{
  std::set<Edge> out;
  for (int64_t l = 0; l < r.numLines(); ++l)
  {
    for (int64_t i = r.lineOffsets[l]; i + 1 < r.lineOffsets[l + 1]; ++i)
    {
      out.insert(key(r.lineVertices[i], r.lineVertices[i + 1]));
    }
  }
  return out;
}

/// Edge-connected components and the genus summed over them (from V - E + F = 2 - 2g - b per
/// component, b its boundary loops), with the mesh's boundary edges.
struct Topology
{
  int64_t components = 0;
  int64_t genus = 0;
  int64_t boundaryEdges = 0;
};

Topology topologyOf(const tc::TriMesh& mesh, const tc::EdgeTable& edges)
{
  const int64_t nv = mesh.numPoints();
  std::vector<int64_t> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int64_t v)
  {
    while (parent[v] != v)
    {
      v = parent[v] = parent[parent[v]];
    }
    return v;
  };
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    parent[find(edges.vertices[2 * e])] = find(edges.vertices[2 * e + 1]);
  }
  Topology t;
  std::vector<uint8_t> used(nv, 0);
  for (int32_t v : mesh.triangles)
  {
    used[v] = 1;
  }
  int64_t vertices = 0, roots = 0;
  std::vector<uint8_t> onBoundary(nv, 0);
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) == 1)
    {
      ++t.boundaryEdges;
      onBoundary[edges.vertices[2 * e]] = onBoundary[edges.vertices[2 * e + 1]] = 1;
    }
  }
  for (int64_t v = 0; v < nv; ++v)
  {
    vertices += used[v];
    roots += used[v] && find(v) == v ? 1 : 0;
  }
  t.components = roots;
  // Boundary loops: the components of the graph of border edges.
  std::vector<int64_t> loopParent(nv);
  std::iota(loopParent.begin(), loopParent.end(), 0);
  auto findLoop = [&](int64_t v)
  {
    while (loopParent[v] != v)
    {
      v = loopParent[v] = loopParent[loopParent[v]];
    }
    return v;
  };
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) == 1)
    {
      loopParent[findLoop(edges.vertices[2 * e])] = findLoop(edges.vertices[2 * e + 1]);
    }
  }
  int64_t loops = 0;
  for (int64_t v = 0; v < nv; ++v)
  {
    loops += onBoundary[v] && findLoop(v) == v ? 1 : 0;
  }
  const int64_t euler = vertices - edges.numEdges() + mesh.numTriangles();
  t.genus = (2 * roots - loops - euler) / 2;
  return t;
}

struct Row
{
  std::string name;
  int64_t triangles = 0;
  Topology topology;
  int64_t sharp = 0;
  int32_t clusters = 0;
  int64_t lines = 0;
  int64_t lineEdges = 0;
  int64_t corners = 0;
  double recall = 0.0;
  double precision = 0.0;
  double seconds = 0.0;
};

/// The mesh in `file`, read and prepared with the default options (and hole filling if asked).
vtkSmartPointer<vtkPolyData> prepared(const std::string& file, bool fillHoles)
{
  vtkNew<tcMeshReader> reader;
  reader->SetFileName(file.c_str());
  vtkNew<tcMeshPreparation> prep;
  prep->SetInputConnection(reader->GetOutputPort());
  prep->SetFillHoles(fillHoles);
  prep->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(prep->GetOutput());
  return mesh;
}

/// The feature stage on one prepared mesh with the defaults of `trichart build`.
Row measure(const std::string& file, bool fillHoles, double creaseLineAngle)
{
  Row row;
  row.name = tcbench::BaseName(file);
  tc::TriMesh mesh;
  std::string error;
  if (!tcvtk::ToTriMesh(prepared(file, fillHoles), mesh, error))
  {
    throw std::runtime_error(error);
  }
  const tc::EdgeTable edges = tc::buildEdgeTable(mesh.triangles);
  row.triangles = mesh.numTriangles();
  row.topology = topologyOf(mesh, edges);
  const std::set<Edge> sharp = sharpEdges(mesh, edges, kSharpDegrees);
  row.sharp = static_cast<int64_t>(sharp.size());

  const auto start = std::chrono::steady_clock::now();
  const tc::CurvatureResult curvature = tc::computeCurvature(mesh);
  const std::vector<uint8_t> crest =
    tc::crestVertices(mesh, tc::extractCrestLines(mesh, curvature));
  const tc::SpectralClusteringResult clusters =
    tc::spectralClustering(mesh, curvature.faceMean, crest);
  tc::FeatureRefinementOptions fo;
  fo.creaseLineAngle = creaseLineAngle;
  const tc::FeatureRefinementResult features =
    tc::refineFeatures(mesh, clusters.clusterId, curvature.mean, curvature.faceMean, crest, fo);
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const std::set<Edge> found = lineEdges(features);
  int64_t hits = 0;
  for (const Edge& e : found)
  {
    hits += sharp.count(e) ? 1 : 0;
  }
  row.clusters = clusters.numClusters;
  row.lines = features.numLines();
  row.lineEdges = static_cast<int64_t>(found.size());
  row.corners = static_cast<int64_t>(features.corners.size());
  row.recall = sharp.empty() ? 1.0 : static_cast<double>(hits) / static_cast<double>(sharp.size());
  row.precision =
    found.empty() ? 0.0 : static_cast<double>(hits) / static_cast<double>(found.size());
  return row;
}

void printRow(const Row& r)
{
  const bool ok = r.recall >= kGoalRecall && r.precision >= kGoalPrecision;
  std::cout << std::left << std::setw(20) << r.name << std::right << std::setw(8) << r.triangles
            << std::setw(6) << r.topology.genus << std::setw(6) << r.topology.components
            << std::setw(8) << r.topology.boundaryEdges << std::setw(8) << r.sharp << std::setw(9)
            << r.clusters << std::setw(7) << r.lines << std::setw(8) << r.lineEdges << std::setw(8)
            << r.corners << std::fixed << std::setprecision(3) << std::setw(9) << r.recall
            << std::setw(10) << r.precision << std::setprecision(2) << std::setw(8) << r.seconds
            << "  " << (ok ? "ok" : "MISSED") << "\n";
  std::cout.unsetf(std::ios::fixed);
}
} // namespace

int main(int argc, char* argv[])
{
  bool fillHoles = false;
  double creaseLineAngle = tc::FeatureRefinementOptions{}.creaseLineAngle;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--fill-holes")
    {
      fillHoles = true;
    }
    else if (arg == "--crease-lines" && i + 1 < argc)
    {
      creaseLineAngle = std::strtod(argv[++i], nullptr);
    }
    else
    {
      files.push_back(arg);
    }
  }
  if (files.empty())
  {
    const std::string cad = std::string(TC_SHARED_DATA_DIR) + "/cad/";
    for (const char* name :
      { "fandisk", "fandisk_large", "couplingdown", "rotor", "pinion", "anchor", "joint", "blade" })
    {
      files.push_back(cad + name + ".off");
    }
  }
  std::cout << "feature lines against the edges over " << kSharpDegrees
            << " degrees (defaults of trichart build" << (fillHoles ? ", --fill-holes" : "")
            << ", crease lines from " << creaseLineAngle << " degrees (0: none)"
            << "); goal recall >= " << kGoalRecall << ", precision >= " << kGoalPrecision << "\n";
  std::cout << std::left << std::setw(20) << "mesh" << std::right << std::setw(8) << "tris"
            << std::setw(6) << "genus" << std::setw(6) << "comp" << std::setw(8) << "border"
            << std::setw(8) << "sharp" << std::setw(9) << "clusters" << std::setw(7) << "lines"
            << std::setw(8) << "l.edges" << std::setw(8) << "corners" << std::setw(9) << "recall"
            << std::setw(10) << "precision" << std::setw(8) << "s"
            << "\n";
  int missed = 0;
  for (const std::string& file : tcbench::Present(files))
  {
    try
    {
      const Row row = measure(file, fillHoles, creaseLineAngle);
      printRow(row);
      missed += row.recall >= kGoalRecall && row.precision >= kGoalPrecision ? 0 : 1;
    }
    catch (const std::exception& e)
    {
      std::cout << tcbench::BaseName(file) << ": failed: " << e.what() << "\n";
      ++missed;
    }
  }
  std::cout << "meshes below the goal: " << missed << "\n";
  return 0;
}
