// SPDX-License-Identifier: BSD-3-Clause
/// @file pipeline_fixture.h
/// The meshes of the base-complex and path-tracing property tests, each read, given its feature
/// curves and simplified into a base complex once per test run and shared by all tests.
#pragma once

#include "tc/gim/base_complex.h"
#include "tc/common/mesh.h"
#include "tc/common/mesh_topology.h"
#include "tc/io/off_io.h"

#include "test_data.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace tctest
{
/// An OFF file as a triangle mesh (polygons, if any, split into fans).
inline tc::TriMesh loadMesh(const std::string& path)
{
  const tc::PolygonSoup soup = tc::readOFF(path);
  tc::TriMesh mesh;
  mesh.points = soup.points;
  for (int64_t p = 0; p < soup.numPolygons(); ++p)
  {
    const int64_t b = soup.offsets[p], n = soup.offsets[p + 1] - b;
    for (int64_t i = 1; i + 1 < n; ++i)
    {
      mesh.triangles.push_back(static_cast<int32_t>(soup.connectivity[b]));
      mesh.triangles.push_back(static_cast<int32_t>(soup.connectivity[b + i]));
      mesh.triangles.push_back(static_cast<int32_t>(soup.connectivity[b + i + 1]));
    }
  }
  return mesh;
}

inline std::array<double, 3> faceNormal(const tc::TriMesh& m, int64_t f)
{
  const auto a = m.point(m.triangles[3 * f]), b = m.point(m.triangles[3 * f + 1]),
             c = m.point(m.triangles[3 * f + 2]);
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  std::array<double, 3> n = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
    u[0] * v[1] - u[1] * v[0] };
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double& x : n)
  {
    x = len > 0 ? x / len : 0.0;
  }
  return n;
}

/// Stand-in for the feature stage, so these tests do not depend on it: sharp edges (dihedral angle
/// over 45 degrees) are the feature curves, their ends the feature vertices, and the vertices where
/// a number of sharp edges other than 2 meet are corners.
struct Features
{
  std::vector<uint8_t> featureVertex;
  std::vector<uint8_t> cornerVertex;
  std::vector<int32_t> featureEdges;
};

inline Features sharpFeatures(const tc::TriMesh& mesh, double degrees = 45.0)
{
  Features out;
  const tc::EdgeTable et = tc::buildEdgeTable(mesh.triangles);
  const double cosLimit = std::cos(degrees * 3.14159265358979323846 / 180.0);
  std::vector<int> count(mesh.numPoints(), 0);
  for (int64_t e = 0; e < et.numEdges(); ++e)
  {
    if (et.valence(e) != 2)
    {
      continue;
    }
    const auto n0 = faceNormal(mesh, et.edgeFaces[et.faceOffsets[e]]);
    const auto n1 = faceNormal(mesh, et.edgeFaces[et.faceOffsets[e] + 1]);
    if (n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2] < cosLimit)
    {
      out.featureEdges.push_back(et.vertices[2 * e]);
      out.featureEdges.push_back(et.vertices[2 * e + 1]);
      ++count[et.vertices[2 * e]];
      ++count[et.vertices[2 * e + 1]];
    }
  }
  out.featureVertex.resize(mesh.numPoints());
  out.cornerVertex.resize(mesh.numPoints());
  for (int64_t v = 0; v < mesh.numPoints(); ++v)
  {
    out.featureVertex[v] = count[v] > 0;
    out.cornerVertex[v] = count[v] > 0 && count[v] != 2;
  }
  return out;
}

/// One mesh of the property tests, simplified once with default options.
struct PipelineCase
{
  tc::TriMesh mesh;
  Features features;
  tc::BaseComplexResult result;
};

/// The case of the mesh at `path` ("" -> nullptr), built on first use and kept for the run.
inline const PipelineCase* pipelineCase(const std::string& path)
{
  static std::map<std::string, std::unique_ptr<PipelineCase>> cache;
  if (path.empty())
  {
    return nullptr;
  }
  auto& slot = cache[path];
  if (!slot)
  {
    slot = std::make_unique<PipelineCase>();
    slot->mesh = loadMesh(path);
    slot->features = sharpFeatures(slot->mesh);
    slot->result = tc::buildBaseComplex(slot->mesh, slot->features.featureVertex,
      slot->features.cornerVertex, slot->features.featureEdges);
    const auto& r = slot->result;
    std::printf("[ base     ] %s: %lld -> %zu triangles, %lld collapses, max error "
                "%.3g, target %s, %lld snapped\n",
      path.c_str(), static_cast<long long>(slot->mesh.numTriangles()), r.baseTriangles.size() / 3,
      static_cast<long long>(r.collapses), r.maxCollapseError,
      r.reachedTarget ? "reached" : "not reached", static_cast<long long>(r.snappedPoints));
  }
  return slot.get();
}

/// Where the property-test mesh `name` is: bunny_npm, cube and fandisk are bundled with the
/// repository; elephant, cow, homer (static_small), couplingdown and rotor (cad) come from the
/// shared data, "" when it is absent.
/// The closed meshes every stage's property tests run over, by the names pipelineMeshPath takes:
/// organic (bunny_npm, elephant of genus 3, cow, homer) and CAD (cube, fandisk, couplingdown of
/// genus 9). A suite that needs more appends to it; one that cannot take a mesh says why.
inline std::vector<std::string> pipelineMeshes()
{
  return { "bunny_npm", "cube", "fandisk", "elephant", "cow", "homer", "couplingdown" };
}

/// pipelineMeshes() without `name`.
inline std::vector<std::string> pipelineMeshesWithout(const std::string& name)
{
  std::vector<std::string> names = pipelineMeshes();
  names.erase(std::remove(names.begin(), names.end(), name), names.end());
  return names;
}

/// pipelineMeshes() and then `more`.
inline std::vector<std::string> pipelineMeshesAnd(const std::vector<std::string>& more)
{
  std::vector<std::string> names = pipelineMeshes();
  names.insert(names.end(), more.begin(), more.end());
  return names;
}

inline std::string pipelineMeshPath(const std::string& name)
{
  if (name == "fandisk" || name == "bunny_npm" || name == "cube")
  {
    return testingData("meshes/" + name + ".off");
  }
  const std::string folder = name == "couplingdown" || name == "rotor" ? "cad/" : "static_small/";
  return sharedData(folder + name + ".off");
}
} // namespace tctest
