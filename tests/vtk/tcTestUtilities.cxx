// SPDX-License-Identifier: BSD-3-Clause
#include "tcTestUtilities.h"

#include "tcBaseComplex.h"
#include "tcColorMaps.h"
#include "tcCurvature.h"
#include "tcFeatureRefinement.h"
#include "tcGeometryImages.h"
#include "tcMeshPreparation.h"
#include "tcMeshReader.h"
#include "tcPathTracing.h"
#include "tcSpectralClustering.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkExtractEdges.h>
#include <vtkFeatureEdges.h>
#include <vtkGlyph3DMapper.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRegressionTestImage.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarsToColors.h>
#include <vtkSphereSource.h>

#include <fstream>

namespace tctest
{
namespace
{
/// Draws `lines` (if any) in black over the surface.
void AddLines(vtkRenderer* renderer, vtkPolyData* lines, double width)
{
  if (!lines || lines->GetNumberOfCells() == 0)
  {
    return;
  }
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(lines);
  mapper->ScalarVisibilityOff();
  mapper->SetResolveCoincidentTopologyToPolygonOffset();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.05, 0.05, 0.05);
  actor->GetProperty()->SetLineWidth(width);
  renderer->AddActor(actor);
}
}

std::string Arg(int argc, char* argv[], const char* flag)
{
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::string(argv[i]) == flag)
    {
      return argv[i + 1];
    }
  }
  return std::string();
}

std::string SharedFile(int argc, char* argv[], const std::string& relative)
{
  const std::string path = Arg(argc, argv, "-S") + "/" + relative;
  if (!std::ifstream(path).good())
  {
    std::cout << "skipped: " << path << " is absent (../shared/data not beside the checkout)\n";
    return std::string();
  }
  return path;
}

vtkSmartPointer<vtkPolyData> Read(const std::string& path)
{
  vtkNew<tcMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  auto* out = reader->GetOutput();
  if (!out || out->GetNumberOfPolys() == 0)
  {
    std::cerr << "cannot read " << path << "\n";
    return nullptr;
  }
  vtkSmartPointer<vtkPolyData> copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(out);
  return copy;
}

vtkSmartPointer<vtkPolyData> ReadPrepared(const std::string& path)
{
  vtkSmartPointer<vtkPolyData> mesh = Read(path);
  if (!mesh)
  {
    return nullptr;
  }
  vtkNew<tcMeshPreparation> prep;
  prep->SetInputData(mesh);
  prep->Update();
  vtkSmartPointer<vtkPolyData> copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(prep->GetOutput());
  return copy;
}

vtkSmartPointer<vtkPolyData> Curvature(vtkPolyData* prepared)
{
  vtkNew<tcCurvature> curvature;
  curvature->SetInputData(prepared);
  curvature->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(curvature->GetOutput());
  return out;
}

vtkSmartPointer<tcFeatureRefinement> FeatureStages(vtkPolyData* prepared)
{
  vtkNew<tcSpectralClustering> clustering;
  clustering->SetInputData(Curvature(prepared));
  auto refinement = vtkSmartPointer<tcFeatureRefinement>::New();
  refinement->SetInputConnection(clustering->GetOutputPort());
  refinement->Update();
  return refinement;
}

vtkSmartPointer<vtkRenderWindow> CurvatureScene(
  vtkPolyData* surface, const char* array, vtkPolyData* lines)
{
  vtkDataArray* values = surface->GetPointData()->GetArray(array);
  vtkNew<vtkLookupTable> lut;
  tcColorMaps::DivergingColors(lut, values);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(surface);
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray(array);
  mapper->SetLookupTable(lut);
  mapper->UseLookupTableScalarRangeOn();
  mapper->SetScalarVisibility(values != nullptr);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.32, 0.34, 0.43);
  renderer->AddActor(actor);
  AddLines(renderer, lines, 2.0);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(30);
  renderer->GetActiveCamera()->Elevation(20);
  renderer->ResetCamera();
  vtkSmartPointer<vtkRenderWindow> window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetSize(400, 400);
  window->SetMultiSamples(0);
  window->OffScreenRenderingOn();
  window->AddRenderer(renderer);
  return window;
}

vtkSmartPointer<vtkRenderer> ArrayRenderer(vtkPolyData* surface, const char* array, bool cells,
  vtkScalarsToColors* lut, const double viewport[4])
{
  vtkDataArray* values =
    cells ? surface->GetCellData()->GetArray(array) : surface->GetPointData()->GetArray(array);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(surface);
  if (cells)
  {
    mapper->SetScalarModeToUseCellFieldData();
  }
  else
  {
    mapper->SetScalarModeToUsePointFieldData();
  }
  mapper->SelectColorArray(array);
  mapper->SetLookupTable(lut);
  mapper->UseLookupTableScalarRangeOn();
  mapper->SetScalarVisibility(values != nullptr);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  renderer->SetBackground(0.32, 0.34, 0.43);
  renderer->AddActor(actor);
  return renderer;
}

vtkSmartPointer<vtkRenderer> LabelRenderer(vtkPolyData* surface, const char* labels,
  vtkPolyData* lines, vtkPolyData* points, const double viewport[4])
{
  // Labels are looked up in cell data first, then in point data.
  vtkDataArray* cellValues = surface->GetCellData()->GetArray(labels);
  vtkDataArray* values = cellValues ? cellValues : surface->GetPointData()->GetArray(labels);
  vtkNew<vtkLookupTable> lut;
  tcColorMaps::LabelColors(lut, values);
  vtkSmartPointer<vtkRenderer> renderer =
    ArrayRenderer(surface, labels, cellValues != nullptr, lut, viewport);
  AddLines(renderer, lines, 3.0);
  if (points && points->GetNumberOfPoints() > 0)
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetRadius(0.01 * surface->GetLength());
    vtkNew<vtkGlyph3DMapper> glyphs;
    glyphs->SetInputData(points);
    glyphs->SetSourceConnection(sphere->GetOutputPort());
    glyphs->ScalingOff();
    glyphs->ScalarVisibilityOff();
    vtkNew<vtkActor> pointActor;
    pointActor->SetMapper(glyphs);
    pointActor->GetProperty()->SetColor(0.85, 0.1, 0.1);
    renderer->AddActor(pointActor);
  }
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(30);
  renderer->GetActiveCamera()->Elevation(20);
  renderer->ResetCamera();
  return renderer;
}

vtkSmartPointer<vtkRenderWindow> SideBySide(vtkRenderer* left, vtkRenderer* right)
{
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetSize(800, 400);
  window->SetMultiSamples(0);
  window->OffScreenRenderingOn();
  window->AddRenderer(left);
  window->AddRenderer(right);
  return window;
}

bool MatchesBaseline(int argc, char* argv[], vtkRenderWindow* window, double threshold)
{
  window->Render();
  const int result = vtkRegressionTester::Test(argc, argv, window, threshold);
  return result == vtkRegressionTester::PASSED;
}
long long Euler(vtkPolyData* mesh)
{
  vtkNew<vtkExtractEdges> edges;
  edges->SetInputData(mesh);
  edges->Update();
  return mesh->GetNumberOfPoints() - edges->GetOutput()->GetNumberOfLines() +
    mesh->GetNumberOfPolys();
}

vtkIdType OpenOrNonManifoldEdges(vtkPolyData* mesh)
{
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(mesh);
  edges->BoundaryEdgesOn();
  edges->NonManifoldEdgesOn();
  edges->FeatureEdgesOff();
  edges->ManifoldEdgesOff();
  edges->Update();
  return edges->GetOutput()->GetNumberOfLines();
}

vtkSmartPointer<tcGeometryImages> AtlasStages(vtkPolyData* prepared, vtkIdType sampleBudget)
{
  vtkSmartPointer<tcFeatureRefinement> refinement = FeatureStages(prepared);
  vtkNew<tcBaseComplex> base;
  base->SetInputConnection(refinement->GetOutputPort());
  vtkNew<tcPathTracing> tracing;
  tracing->SetInputConnection(base->GetOutputPort(1));
  auto images = vtkSmartPointer<tcGeometryImages>::New();
  images->SetInputConnection(tracing->GetOutputPort());
  if (sampleBudget > 0)
  {
    images->SetSampleBudget(sampleBudget);
  }
  images->Update();
  return images;
}
} // namespace tctest
