// SPDX-License-Identifier: BSD-3-Clause
#include "tcTestUtilities.h"

#include "tcMeshPreparation.h"
#include "tcMeshReader.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRegressionTestImage.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

namespace tctest
{
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

vtkSmartPointer<vtkRenderWindow> CurvatureScene(
  vtkPolyData* surface, const char* array, vtkPolyData* lines)
{
  // Symmetric range holding 95% of the values, so that a few extreme vertices do not wash
  // out the picture.
  vtkDataArray* values = surface->GetPointData()->GetArray(array);
  std::vector<double> magnitudes(values ? values->GetNumberOfTuples() : 0);
  for (size_t i = 0; i < magnitudes.size(); ++i)
  {
    magnitudes[i] = std::abs(values->GetComponent(static_cast<vtkIdType>(i), 0));
  }
  double limit = 1.0;
  if (!magnitudes.empty())
  {
    const size_t k = std::min(magnitudes.size() - 1, magnitudes.size() * 95 / 100);
    std::nth_element(magnitudes.begin(), magnitudes.begin() + k, magnitudes.end());
    limit = magnitudes[k] > 0.0 ? magnitudes[k] : 1.0;
  }
  vtkNew<vtkLookupTable> lut;
  lut->SetNumberOfTableValues(256);
  lut->SetTableRange(-limit, limit);
  for (int i = 0; i < 256; ++i)
  {
    const double t = i / 255.0;
    const double s = t < 0.5 ? t / 0.5 : (t - 0.5) / 0.5;
    if (t < 0.5)
    {
      lut->SetTableValue(i, 0.23 + 0.77 * s, 0.30 + 0.70 * s, 0.75 + 0.25 * s, 1.0);
    }
    else
    {
      lut->SetTableValue(i, 1.0 - 0.29 * s, 1.0 - 0.98 * s, 1.0 - 0.85 * s, 1.0);
    }
  }
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
  if (lines && lines->GetNumberOfCells() > 0)
  {
    vtkNew<vtkPolyDataMapper> lineMapper;
    lineMapper->SetInputData(lines);
    lineMapper->ScalarVisibilityOff();
    lineMapper->SetResolveCoincidentTopologyToPolygonOffset();
    vtkNew<vtkActor> lineActor;
    lineActor->SetMapper(lineMapper);
    lineActor->GetProperty()->SetColor(0.05, 0.05, 0.05);
    lineActor->GetProperty()->SetLineWidth(2.0);
    renderer->AddActor(lineActor);
  }
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

bool MatchesBaseline(int argc, char* argv[], vtkRenderWindow* window, double threshold)
{
  window->Render();
  const int result = vtkRegressionTester::Test(argc, argv, window, threshold);
  return result == vtkRegressionTester::PASSED;
}
} // namespace tctest
