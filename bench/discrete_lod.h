// SPDX-License-Identifier: BSD-3-Clause
// What a game engine draws instead of per-chart LOD: a discrete LOD chain per object (the mesh,
// then meshopt_simplify at 1/2, 1/4, ... of its triangles, as gltfpack makes one), each
// instance drawn at the coarsest level whose measured error projects to at most the target in
// pixels at the instance's bounding sphere, instances outside the view not drawn.
#pragma once

#include "tcMeshConversion.h"

#include "tc/metrics/qem_peer.h"
#include "tc/metrics/surface_distance.h"

#include <vtkCamera.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace tcbench
{
struct DiscreteLod
{
  std::vector<vtkSmartPointer<vtkPolyDataMapper>> mappers; ///< level 0: the mesh itself
  std::vector<double> triangles;                           ///< per level
  std::vector<double> error; ///< per level: symmetric Hausdorff to the mesh, mesh units
};

/// The chain down to about `minTriangles`; a level that simplification cannot bring below 3/4
/// of the previous one ends it. Errors are measured, not estimated: tc::surfaceDistance, the
/// measure the atlas's levels are judged by.
inline DiscreteLod BuildChain(const tc::TriMesh& mesh, int64_t minTriangles)
{
  DiscreteLod chain;
  tc::SurfaceDistanceOptions options;
  options.perPointDistance = false;
  tc::TriMesh level = mesh;
  for (;;)
  {
    vtkNew<vtkPolyData> data;
    tcvtk::FromTriMesh(level, data);
    auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
    mapper->SetInputData(data);
    mapper->StaticOn();
    chain.mappers.push_back(mapper);
    chain.triangles.push_back(static_cast<double>(level.numTriangles()));
    chain.error.push_back(
      chain.error.empty() ? 0.0 : tc::surfaceDistance(level, mesh, options).hausdorff);
    const int64_t target = level.numTriangles() / 2;
    if (target < minTriangles)
    {
      return chain;
    }
    tc::TriMesh next = tc::simplifyQem(mesh, target);
    if (4 * next.numTriangles() > 3 * level.numTriangles())
    {
      return chain;
    }
    level = std::move(next);
  }
}

/// An instance's bounding sphere in world coordinates.
struct Sphere
{
  double center[3] = { 0, 0, 0 };
  double radius = 0;
};

/// True unless the sphere lies wholly outside one of the camera's frustum planes.
inline bool InFrustum(vtkCamera* camera, double aspect, const Sphere& s)
{
  double planes[24];
  camera->GetFrustumPlanes(aspect, planes);
  for (int p = 0; p < 6; ++p)
  {
    const double* n = planes + 4 * p; // inward normals
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if ((vtkMath::Dot(n, s.center) + n[3]) / length < -s.radius)
    {
      return false;
    }
  }
  return true;
}

/// The coarsest level whose error, seen at the nearest point of the sphere, is at most
/// `pixels` on a viewport `height` pixels high (perspective camera).
inline size_t ChooseLevel(
  const DiscreteLod& chain, vtkCamera* camera, double height, const Sphere& s, double pixels)
{
  const double distance =
    std::max(std::sqrt(vtkMath::Distance2BetweenPoints(camera->GetPosition(), s.center)) - s.radius,
      camera->GetClippingRange()[0]);
  const double perUnit =
    0.5 * height / (std::tan(vtkMath::RadiansFromDegrees(0.5 * camera->GetViewAngle())) * distance);
  size_t level = 0;
  while (level + 1 < chain.error.size() && chain.error[level + 1] * perUnit <= pixels)
  {
    ++level;
  }
  return level;
}
} // namespace tcbench
