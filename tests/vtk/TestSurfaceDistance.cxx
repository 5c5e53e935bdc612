// SPDX-License-Identifier: BSD-3-Clause
// tcSurfaceDistance on surfaces with known answers: a square against the same square moved by
// 0.1 along its normal (every distance 0.1), a sphere against itself (0), a coarse sphere
// against a fine one (the largest gap is the depth of the deepest coarse face below the
// sphere); then the bundled bunny measured against its rebuilt atlas at level 2 and at the
// finest level, both coloured on one distance scale, against the baseline.
#include "tcGeometryImageMesh.h"
#include "tcGeometryImages.h"
#include "tcSurfaceDistance.h"
#include "tcTestUtilities.h"

#include "tc/common/array_names.h"

#include <vtkDataArray.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSphereSource.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace
{
vtkSmartPointer<vtkPolyData> Triangles(vtkAlgorithm* source)
{
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(source->GetOutputPort());
  triangles->Update();
  return triangles->GetOutput();
}

vtkSmartPointer<vtkPolyData> Sphere(int resolution)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(resolution);
  sphere->SetPhiResolution(resolution);
  return Triangles(sphere);
}

/// The largest depth of a face of `mesh` (inscribed in the unit sphere) below the sphere:
/// 1 - the distance from the centre to the face's plane.
double DeepestFace(vtkPolyData* mesh)
{
  double deepest = 0.0;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    mesh->GetCellPoints(c, n, ids);
    double p[3][3];
    for (int k = 0; k < 3; ++k)
    {
      mesh->GetPoint(ids[k], p[k]);
    }
    double u[3], v[3];
    for (int x = 0; x < 3; ++x)
    {
      u[x] = p[1][x] - p[0][x];
      v[x] = p[2][x] - p[0][x];
    }
    const double nrm[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
      u[0] * v[1] - u[1] * v[0] };
    const double l = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    if (l > 0.0)
    {
      const double d = std::abs(nrm[0] * p[0][0] + nrm[1] * p[0][1] + nrm[2] * p[0][2]) / l;
      deepest = std::max(deepest, 1.0 - d);
    }
  }
  return deepest;
}

/// `surface` coloured by its Distance array from blue (0) to red (`top`).
vtkSmartPointer<vtkRenderer> DistanceRenderer(
  vtkPolyData* surface, double top, const double viewport[4], bool bar)
{
  vtkNew<vtkLookupTable> lut;
  lut->SetHueRange(0.667, 0.0);
  lut->SetTableRange(0.0, top);
  lut->Build();
  vtkSmartPointer<vtkRenderer> renderer =
    tctest::ArrayRenderer(surface, tc::kDistance, false, lut, viewport);
  if (bar)
  {
    vtkNew<vtkScalarBarActor> scale;
    scale->SetLookupTable(lut);
    scale->SetNumberOfLabels(3);
    scale->SetPosition(0.82, 0.1);
    scale->SetWidth(0.12);
    scale->SetHeight(0.8);
    renderer->AddViewProp(scale);
  }
  renderer->ResetCamera();
  return renderer;
}
} // namespace

int TestSurfaceDistance(int argc, char* argv[])
{
  tctest::Checker check;

  // 1. A square and the same square 0.1 above it: every distance is 0.1 (as a float: the
  // sources' points are float, 0.1f = 0.100000001490).
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(10, 10);
  vtkSmartPointer<vtkPolyData> square = Triangles(plane);
  vtkNew<vtkTransform> up;
  up->Translate(0.0, 0.0, 0.1);
  vtkNew<vtkTransformPolyDataFilter> lift;
  lift->SetInputData(square);
  lift->SetTransform(up);
  lift->Update();
  vtkNew<tcSurfaceDistance> distance;
  distance->SetInputData(0, lift->GetOutput());
  distance->SetReferenceData(square);
  distance->Update();
  std::printf("square moved by 0.1: Hausdorff %.12f, mean %.12f, RMS %.12f, diagonal %.6f\n",
    distance->GetHausdorff(), distance->GetMeanDistance(), distance->GetRmsDistance(),
    distance->GetDiagonal());
  TC_CHECK(check, std::abs(distance->GetHausdorff() - 0.1) < 1e-8);
  TC_CHECK(check, std::abs(distance->GetMeanDistance() - 0.1) < 1e-8);
  TC_CHECK(check, std::abs(distance->GetRmsDistance() - 0.1) < 1e-8);
  TC_CHECK(check, std::abs(distance->GetDiagonal() - std::sqrt(2.0)) < 1e-7);
  vtkDataArray* values = distance->GetOutput()->GetPointData()->GetArray(tc::kDistance);
  if (TC_CHECK(check, values != nullptr))
  {
    double range[2];
    values->GetRange(range);
    TC_CHECK(check, std::abs(range[0] - 0.1) < 1e-8 && std::abs(range[1] - 0.1) < 1e-8);
  }

  // 2. A sphere against itself.
  vtkSmartPointer<vtkPolyData> fine = Sphere(96);
  distance->SetInputData(0, fine);
  distance->SetReferenceData(fine);
  distance->Update();
  TC_CHECK(check, distance->GetHausdorff() < 1e-12);

  // 3. A coarse sphere against a fine one: its vertices lie on the sphere, the deepest point is
  // below the centre of its deepest face (less the fine sphere's own depth, 0.0005 here).
  vtkSmartPointer<vtkPolyData> coarse = Sphere(8);
  const double deepest = DeepestFace(coarse);
  distance->SetInputData(0, coarse);
  distance->SetReferenceData(fine);
  distance->Update();
  std::printf("sphere 8 x 8 against 96 x 96: Hausdorff %.5f, deepest coarse face %.5f, fine "
              "sphere's own depth %.5f\n",
    distance->GetHausdorff(), deepest, DeepestFace(fine));
  TC_CHECK(check, distance->GetHausdorff() <= deepest + 1e-9);
  TC_CHECK(check, distance->GetHausdorff() >= 0.9 * (deepest - DeepestFace(fine)));
  TC_CHECK(check, distance->GetMeanDistance() < distance->GetRmsDistance());
  TC_CHECK(check, distance->GetRmsDistance() < distance->GetHausdorff());

  // 4. The bunny against its atlas rebuilt at level 2 and at the finest level.
  const std::string data = tctest::Arg(argc, argv, "-D");
  vtkSmartPointer<vtkPolyData> mesh = tctest::ReadPrepared(data + "/meshes/bunny_npm.off");
  if (!TC_CHECK(check, mesh != nullptr))
  {
    return 1;
  }
  vtkSmartPointer<tcGeometryImages> images = tctest::AtlasStages(mesh);
  vtkNew<tcGeometryImageMesh> rebuild;
  rebuild->SetInputConnection(images->GetOutputPort());
  vtkSmartPointer<vtkPolyData> measured[2];
  double relative[2] = { 0.0, 0.0 };
  const int levels[2] = { 2, -1 };
  for (int i = 0; i < 2; ++i)
  {
    rebuild->SetLevel(levels[i]);
    rebuild->Update();
    vtkNew<tcSurfaceDistance> toAtlas;
    toAtlas->SetInputData(0, mesh);
    toAtlas->SetReferenceConnection(rebuild->GetOutputPort());
    toAtlas->Update();
    measured[i] = vtkSmartPointer<vtkPolyData>::New();
    measured[i]->DeepCopy(toAtlas->GetOutput());
    relative[i] = toAtlas->GetRmsDistance() / toAtlas->GetDiagonal();
    std::printf("bunny against its atlas at level %d: Hausdorff %.4f%%, RMS %.4f%% of the "
                "diagonal\n",
      levels[i], 100.0 * toAtlas->GetHausdorff() / toAtlas->GetDiagonal(), 100.0 * relative[i]);
    TC_CHECK(check, measured[i]->GetPointData()->GetArray(tc::kDistance) != nullptr);
    TC_CHECK(check, measured[i]->GetNumberOfPoints() == mesh->GetNumberOfPoints());
  }
  TC_CHECK(check, relative[1] < relative[0]);

  // Picture: one scale for both, up to the largest distance at level 2.
  double range[2];
  measured[0]->GetPointData()->GetArray(tc::kDistance)->GetRange(range);
  const double left[4] = { 0.0, 0.0, 0.5, 1.0 }, right[4] = { 0.5, 0.0, 1.0, 1.0 };
  vtkSmartPointer<vtkRenderWindow> window =
    tctest::SideBySide(DistanceRenderer(measured[0], range[1], left, false),
      DistanceRenderer(measured[1], range[1], right, true));
  TC_CHECK(check, tctest::MatchesBaseline(argc, argv, window));
  return check.failures == 0 ? 0 : 1;
}
