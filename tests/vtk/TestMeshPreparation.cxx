// SPDX-License-Identifier: BSD-3-Clause
// tcMeshPreparation at the VTK level: polygons become triangles, flags and provenance arrays
// are written, input arrays pass through, the report lands in field data, non-manifold
// splitting yields a manifold, and bad input is an error rather than a crash. Then a UV sphere
// without its polar caps, open (left) and with the holes filled by faired patches and its
// slivers removed (right, the new triangles in their own colour), compared with its baseline.
#include "tcMeshPreparation.h"
#include "tcTestUtilities.h"

#include "tc/common/array_names.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFeatureEdges.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkCamera.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>

#include <cmath>
#include <limits>

namespace
{
void CountErrors(vtkObject*, unsigned long, void* clientData, void*)
{
  ++*static_cast<int*>(clientData);
}

vtkIdType CountNonManifoldEdges(vtkPolyData* mesh)
{
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(mesh);
  edges->BoundaryEdgesOff();
  edges->FeatureEdgesOff();
  edges->ManifoldEdgesOff();
  edges->NonManifoldEdgesOn();
  edges->Update();
  return edges->GetOutput()->GetNumberOfLines();
}

/// A quad (0 1 2 3), a fan of three triangles on edge (1, 2) making it non-manifold, a
/// duplicate of point 0 (point 6) used by a triangle, and a degenerate triangle.
vtkSmartPointer<vtkPolyData> MessyMesh(double badCoordinate = 0.0)
{
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(0, 0, 0);             // 0
  pts->InsertNextPoint(1, 0, 0);             // 1
  pts->InsertNextPoint(1, 1, badCoordinate); // 2
  pts->InsertNextPoint(0, 1, 0);             // 3
  pts->InsertNextPoint(2, 0.5, 0);           // 4
  pts->InsertNextPoint(1.5, 0.5, 1);         // 5
  pts->InsertNextPoint(0, 0, 0);             // 6 = duplicate of 0
  pts->InsertNextPoint(-1, 0.5, 0);          // 7
  vtkNew<vtkCellArray> polys;
  const vtkIdType quad[4] = { 0, 1, 2, 3 };
  polys->InsertNextCell(4, quad);
  const vtkIdType t1[3] = { 1, 4, 2 };
  polys->InsertNextCell(3, t1);
  const vtkIdType t2[3] = { 2, 5, 1 };
  polys->InsertNextCell(3, t2);
  const vtkIdType t3[3] = { 6, 3, 7 };
  polys->InsertNextCell(3, t3);
  const vtkIdType degenerate[3] = { 3, 3, 7 };
  polys->InsertNextCell(3, degenerate);
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(pts);
  mesh->SetPolys(polys);
  vtkNew<vtkDoubleArray> temperature;
  temperature->SetName("Temperature");
  for (vtkIdType i = 0; i < 8; ++i)
  {
    temperature->InsertNextValue(10.0 * i);
  }
  mesh->GetPointData()->AddArray(temperature);
  return mesh;
}
}

int TestMeshPreparation(int argc, char* argv[])
{
  tctest::Checker check;

  // A messy mesh is cleaned, flagged and reported.
  {
    vtkNew<tcMeshPreparation> prep;
    prep->SetInputData(MessyMesh());
    prep->Update();
    vtkPolyData* out = prep->GetOutput();
    TC_CHECK(check, out->GetNumberOfPolys() == 5); // quad -> 2, plus 3 triangles
    TC_CHECK(check, out->GetPolys()->GetNumberOfConnectivityIds() == 15);
    TC_CHECK(check, out->GetNumberOfPoints() == 7); // duplicate merged
    auto* nme = out->GetCellData()->GetArray(tc::kNonManifoldEdge);
    auto* nmv = out->GetPointData()->GetArray(tc::kNonManifoldVertex);
    auto* inputIds = out->GetPointData()->GetArray(tc::kInputPointId);
    auto* temperature = out->GetPointData()->GetArray("Temperature");
    TC_CHECK(check, nme && nmv && inputIds && temperature);
    TC_CHECK(check, out->GetCellData()->GetArray(tc::kInputCellId) != nullptr);
    TC_CHECK(check, out->GetCellData()->GetArray(tc::kComponentId) != nullptr);
    if (nme && inputIds && temperature)
    {
      int flagged = 0;
      for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
      {
        flagged += nme->GetTuple1(c) != 0.0;
      }
      TC_CHECK(check, flagged == 3); // one half of the quad and the two fins on edge (1, 2)
      for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
      {
        // Carried arrays follow InputPointId.
        TC_CHECK(check, temperature->GetTuple1(p) == 10.0 * inputIds->GetTuple1(p));
      }
    }
    const std::string report = prep->GetReport();
    TC_CHECK(check, prep->GetChanged());
    TC_CHECK(check, report.find("merged") != std::string::npos);
    TC_CHECK(check, report.find("degenerate") != std::string::npos);
    TC_CHECK(check, out->GetFieldData()->GetAbstractArray(tc::kPreparationReport) != nullptr);
    TC_CHECK(check, CountNonManifoldEdges(out) == 1);

    prep->SplitNonManifoldOn();
    prep->Update();
    TC_CHECK(check, CountNonManifoldEdges(prep->GetOutput()) == 0);
    TC_CHECK(check, prep->GetOutput()->GetNumberOfPolys() == 5);
  }

  // A clean closed mesh passes unchanged.
  {
    vtkSmartPointer<vtkPolyData> bunny =
      tctest::Read(tctest::Arg(argc, argv, "-D") + "/meshes/bunny_npm.off");
    TC_CHECK(check, bunny != nullptr);
    if (bunny)
    {
      vtkNew<tcMeshPreparation> prep;
      prep->SetInputData(bunny);
      prep->Update();
      TC_CHECK(check, !prep->GetChanged());
      TC_CHECK(check, prep->GetOutput()->GetNumberOfPolys() == 3674);
      TC_CHECK(check, prep->GetOutput()->GetNumberOfPoints() == 1839);
    }
  }

  // NaN coordinates and empty input are errors, not crashes.
  for (int bad = 0; bad < 2; ++bad)
  {
    vtkNew<tcMeshPreparation> prep;
    int errors = 0;
    vtkNew<vtkCallbackCommand> cb;
    cb->SetCallback(CountErrors);
    cb->SetClientData(&errors);
    prep->AddObserver(vtkCommand::ErrorEvent, cb);
    if (bad == 0)
    {
      prep->SetInputData(MessyMesh(std::numeric_limits<double>::quiet_NaN()));
    }
    else
    {
      vtkNew<vtkPolyData> empty;
      prep->SetInputData(empty);
    }
    prep->Update();
    TC_CHECK(check, errors == 1);
    TC_CHECK(check, prep->GetOutput()->GetNumberOfPolys() == 0);
  }

  // Holes and slivers: a UV sphere (its pole triangles are needles) without the cells of
  // |z| > 0.2 (of radius 0.5).
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(64);
  source->SetPhiResolution(24);
  source->Update();
  vtkPolyData* sphere = source->GetOutput();
  vtkNew<vtkPolyData> open;
  open->SetPoints(sphere->GetPoints());
  open->AllocateExact(sphere->GetNumberOfCells(), 3 * sphere->GetNumberOfCells());
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < sphere->GetNumberOfCells(); ++c)
  {
    sphere->GetCellPoints(c, ids);
    double z = 0.0;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      z += sphere->GetPoint(ids->GetId(k))[2] / ids->GetNumberOfIds();
    }
    if (std::abs(z) < 0.2)
    {
      open->InsertNextCell(sphere->GetCellType(c), ids);
    }
  }
  vtkNew<tcMeshPreparation> plain;
  plain->SetInputData(open);
  plain->Update();
  vtkNew<tcMeshPreparation> repaired;
  repaired->SetInputData(open);
  repaired->FillHolesOn();
  repaired->RemoveSliversOn();
  repaired->Update();
  vtkPolyData* closed = repaired->GetOutput();
  TC_CHECK(check, tctest::OpenOrNonManifoldEdges(plain->GetOutput()) > 0);
  TC_CHECK(check, tctest::OpenOrNonManifoldEdges(closed) == 0);
  TC_CHECK(check, tctest::Euler(closed) == 2);
  const std::string report = repaired->GetReport();
  TC_CHECK(check, report.find("filled 2 holes") != std::string::npos);
  // Colour: 1 for a hole-filling triangle (InputCellId -1), 0 for a kept one.
  vtkDataArray* from = closed->GetCellData()->GetArray(tc::kInputCellId);
  vtkNew<vtkIntArray> added;
  added->SetName("Added");
  vtkIdType newCells = 0;
  for (vtkIdType c = 0; c < closed->GetNumberOfCells(); ++c)
  {
    const int isNew = from->GetTuple1(c) < 0 ? 1 : 0;
    added->InsertNextValue(isNew);
    newCells += isNew;
  }
  closed->GetCellData()->AddArray(added);
  TC_CHECK(check, newCells > 0);
  vtkNew<vtkIntArray> none;
  none->SetName("Added");
  none->SetNumberOfTuples(plain->GetOutput()->GetNumberOfCells());
  none->FillValue(0);
  plain->GetOutput()->GetCellData()->AddArray(none);
  const double left[4] = { 0.0, 0.0, 0.5, 1.0 };
  const double right[4] = { 0.5, 0.0, 1.0, 1.0 };
  vtkSmartPointer<vtkRenderer> a =
    tctest::LabelRenderer(plain->GetOutput(), "Added", nullptr, nullptr, left);
  vtkSmartPointer<vtkRenderer> b = tctest::LabelRenderer(closed, "Added", nullptr, nullptr, right);
  for (vtkRenderer* r : { a.Get(), b.Get() })
  {
    r->ResetCamera();
    r->GetActiveCamera()->Elevation(35.0);
    r->ResetCameraClippingRange();
  }
  vtkSmartPointer<vtkRenderWindow> window = tctest::SideBySide(a, b);
  TC_CHECK(check, tctest::MatchesBaseline(argc, argv, window));
  return check.failures == 0 ? 0 : 1;
}
