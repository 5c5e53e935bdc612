// SPDX-License-Identifier: BSD-3-Clause
// tcMeshReader on a terrain raster (a crop of the shared USGS DEM with its JSON side file): the
// grid's counts, its cell size in metres, the Elevation array and VerticalScale, the
// georeference kept apart; then the terrain, heights times 3, coloured by Elevation and seen
// from the south-west, compared with its baseline.
#include "tcMeshReader.h"
#include "tcTestUtilities.h"

#include "tc/common/array_names.h"

#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cmath>

namespace
{
vtkSmartPointer<vtkPolyData> ReadTerrain(const std::string& path, double verticalScale)
{
  vtkNew<tcMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetVerticalScale(verticalScale);
  reader->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(reader->GetOutput());
  return mesh;
}
} // namespace

int TestHeightFieldReader(int argc, char* argv[])
{
  tctest::Checker check;
  const std::string path = tctest::Arg(argc, argv, "-D") + "/terrain/jacksboro_crop_96x80.pgm";
  vtkSmartPointer<vtkPolyData> terrain = ReadTerrain(path, 1.0);
  TC_CHECK(check, terrain->GetNumberOfPoints() == 96 * 80);
  TC_CHECK(check, terrain->GetNumberOfPolys() == 2 * 95 * 79);
  // 3 arc-seconds at latitude 36.6: 74.6 m east-west, 92.5 m north-south (rows run south).
  double p0[3], p1[3], pRow[3];
  terrain->GetPoint(0, p0);
  terrain->GetPoint(1, p1);
  terrain->GetPoint(96, pRow);
  TC_CHECK(check, std::abs(p1[0] - p0[0] - 74.6) < 0.1 && std::abs(p1[1] - p0[1]) < 1e-9);
  TC_CHECK(check, std::abs(pRow[1] - p0[1] + 92.5) < 0.1);
  vtkDataArray* elevation = terrain->GetPointData()->GetArray(tc::kElevation);
  TC_CHECK(check, elevation != nullptr);
  const double* bounds = terrain->GetBounds();
  TC_CHECK(check,
    elevation && elevation->GetRange()[0] == bounds[4] && elevation->GetRange()[1] == bounds[5] &&
      bounds[5] - bounds[4] > 100.0);
  vtkDataArray* origin = terrain->GetFieldData()->GetArray(tc::kGeoOrigin);
  TC_CHECK(
    check, origin && std::abs(origin->GetComponent(0, 0) - (-84.41375 + 150.5 / 1200)) < 1e-9);

  vtkSmartPointer<vtkPolyData> raised = ReadTerrain(path, 3.0);
  const double* r = raised->GetBounds();
  TC_CHECK(check, std::abs((r[5] - r[4]) - 3.0 * (bounds[5] - bounds[4])) < 1e-6);

  vtkNew<vtkLookupTable> lut;
  lut->SetHueRange(0.66, 0.0);
  lut->SetTableRange(elevation ? elevation->GetRange() : bounds + 4);
  lut->Build();
  const double whole[4] = { 0.0, 0.0, 1.0, 1.0 };
  vtkSmartPointer<vtkRenderer> renderer =
    tctest::ArrayRenderer(raised, tc::kElevation, false, lut, whole);
  vtkCamera* camera = renderer->GetActiveCamera();
  const double centre[3] = { 0.5 * (r[0] + r[1]), 0.5 * (r[2] + r[3]), 0.5 * (r[4] + r[5]) };
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0] - 0.6 * (r[1] - r[0]), centre[1] - 1.0 * (r[3] - r[2]),
    centre[2] + 0.8 * (r[3] - r[2]));
  camera->SetViewUp(0.0, 0.0, 1.0);
  renderer->ResetCamera();
  renderer->ResetCameraClippingRange();
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(400, 400);
  window->AddRenderer(renderer);
  window->Render();
  TC_CHECK(check, tctest::MatchesBaseline(argc, argv, window));
  return check.failures == 0 ? 0 : 1;
}
