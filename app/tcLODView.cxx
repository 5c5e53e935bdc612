// SPDX-License-Identifier: BSD-3-Clause
#include "tcLODView.h"

#include "tcColorMaps.h"
#include "tcLODMapper.h"

#include "tc/common/array_names.h"

#include <QStringList>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkCoordinate.h>
#include <vtkDataObject.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPlaneSource.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <utility>

tcLODView::tcLODView(vtkRenderWindow* window, vtkRenderer* renderer)
  : Window(window)
  , Renderer(renderer)
{
  // The statistics go in a second layer drawn after the 3-D one (see the class comment). The
  // overlay takes no interaction: the 3-D view does.
  this->Actor->SetMapper(this->Mapper);
  this->Actor->GetProperty()->SetColor(0.85, 0.85, 0.85);
  this->Actor->VisibilityOff();
  this->Renderer->AddActor(this->Actor);
  this->GroundMapper->SetInputConnection(this->Ground->GetOutputPort());
  this->GroundActor->SetMapper(this->GroundMapper);
  this->GroundActor->GetProperty()->SetColor(0.42, 0.45, 0.40);
  this->GroundActor->GetProperty()->SetSpecular(0.0);
  this->GroundActor->VisibilityOff();
  this->Renderer->AddActor(this->GroundActor);
  this->Window->SetNumberOfLayers(2);
  this->OverlayRenderer->SetLayer(1);
  this->OverlayRenderer->InteractiveOff();
  vtkTextProperty* text = this->Overlay->GetTextProperty();
  text->SetFontSize(14);
  text->SetFontFamilyToCourier();
  text->SetColor(1.0, 1.0, 1.0);
  text->SetBackgroundColor(0.0, 0.0, 0.0);
  text->SetBackgroundOpacity(0.5);
  text->SetVerticalJustificationToTop();
  this->Overlay->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  this->Overlay->SetPosition(0.01, 0.985);
  this->OverlayRenderer->AddActor2D(this->Overlay);
  this->BuildLevelLegend();
  this->RenderedTag =
    this->Renderer->AddObserver(vtkCommand::EndEvent, this, &tcLODView::OnRendered);
}

tcLODView::~tcLODView()
{
  this->Renderer->RemoveObserver(this->RenderedTag);
}

void tcLODView::BuildLevelLegend()
{
  this->LevelColors->IndexedLookupOn();
  this->LevelLegend->SetLookupTable(this->LevelColors);
  this->LevelLegend->SetTitle("level");
  this->LevelLegend->UnconstrainedFontSizeOn();
  this->LevelLegend->GetTitleTextProperty()->SetFontSize(14);
  this->LevelLegend->GetAnnotationTextProperty()->SetFontSize(14);
  this->LevelLegend->GetAnnotationTextProperty()->SetColor(1.0, 1.0, 1.0);
  this->LevelLegend->SetWidth(0.06);
  this->LevelLegend->SetHeight(0.45);
  this->LevelLegend->SetPosition(0.92, 0.05);
  this->LevelLegend->VisibilityOff();
  this->OverlayRenderer->AddActor2D(this->LevelLegend);
}

/// The legend's colours: level d is drawn in label colour d + 1 (the shaders' tcLabelColor of
/// tcLevel + 1, which tcColorMaps::LabelColors gives on the CPU).
void tcLODView::UpdateLevelLegend(vtkDataObject* atlas)
{
  auto* blocks = vtkMultiBlockDataSet::SafeDownCast(atlas);
  auto* charts = blocks ? vtkTable::SafeDownCast(blocks->GetBlock(0)) : nullptr;
  vtkDataArray* levels =
    charts ? vtkArrayDownCast<vtkDataArray>(charts->GetColumnByName(tc::kMaxLevel)) : nullptr;
  const int finest = levels ? static_cast<int>(levels->GetRange()[1]) : 0;
  vtkNew<vtkIntArray> labels;
  labels->InsertNextValue(finest + 1);
  vtkNew<vtkLookupTable> palette;
  tcColorMaps::LabelColors(palette, labels);
  this->LevelColors->ResetAnnotations();
  this->LevelColors->SetNumberOfTableValues(finest + 1);
  for (int d = 0; d <= finest; ++d)
  {
    this->LevelColors->SetTableValue(d, palette->GetTableValue(d + 1));
    this->LevelColors->SetAnnotation(vtkVariant(d), std::to_string(d));
  }
  this->LevelColors->Build();
  this->LevelLegend->SetVisibility(this->Mapper->GetColorMode() == tcLODMapper::ColorByLevel);
}

void tcLODView::SetFrameCallback(std::function<void(const tcLODFrame&)> callback)
{
  this->FrameDrawn = std::move(callback);
}

void tcLODView::Show(vtkDataObject* atlas, bool entering)
{
  if (atlas != this->AtlasSource || atlas->GetMTime() != this->AtlasTime)
  {
    auto copy = vtkSmartPointer<vtkMultiBlockDataSet>::New();
    copy->DeepCopy(atlas);
    this->Mapper->SetInputData(copy);
    this->AtlasSource = atlas;
    this->AtlasTime = atlas->GetMTime();
    this->UpdateLevelLegend(atlas);
    // The crowd is laid out from the bounds of one instance.
    this->Mapper->SetInstanceMatrices(nullptr);
    this->Mapper->GetBounds(this->Bounds);
  }
  this->UpdateCrowd();
  this->Actor->VisibilityOn();
  if (!this->Window->HasRenderer(this->OverlayRenderer))
  {
    this->Window->AddRenderer(this->OverlayRenderer);
  }
  if (this->Renderer->GetActiveCamera() != this->Camera)
  {
    this->StageCamera = this->Renderer->GetActiveCamera();
    this->Renderer->SetActiveCamera(this->Camera);
  }
  if (entering)
  {
    this->Frame();
  }
}

void tcLODView::Hide()
{
  this->Actor->VisibilityOff();
  this->GroundActor->VisibilityOff();
  if (this->Window->HasRenderer(this->OverlayRenderer))
  {
    this->Window->RemoveRenderer(this->OverlayRenderer);
  }
  if (this->StageCamera && this->Renderer->GetActiveCamera() == this->Camera)
  {
    this->Renderer->SetActiveCamera(this->StageCamera);
  }
}

bool tcLODView::IsShown() const
{
  return this->Actor->GetVisibility();
}

void tcLODView::UpdateCrowd()
{
  const int n = this->Instances;
  const double* b = this->Bounds;
  if (!vtkMath::AreBoundsInitialized(b))
  {
    return;
  }
  // A square grid on the plane through the bottom of the atlas's box (+Y up), 1.6 times its
  // largest side apart: a copy turned about the vertical axis keeps within its diagonal, less
  // than that. Each copy turns about its own vertical axis by the golden angle times its index,
  // so that no two neighbours look the same way; the first one is not turned.
  const double size = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  const double spacing = 1.6 * size;
  const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  const int rows = (n + columns - 1) / columns;
  const double cx = 0.5 * (b[0] + b[1]), cz = 0.5 * (b[4] + b[5]);
  const double goldenAngle = vtkMath::Pi() * (3.0 - std::sqrt(5.0));
  vtkNew<vtkDoubleArray> matrices;
  matrices->SetNumberOfComponents(16);
  matrices->SetNumberOfTuples(n);
  for (int k = 0; k < n; ++k)
  {
    const double x = cx + (k % columns - 0.5 * (columns - 1)) * spacing;
    const double z = cz + (k / columns - 0.5 * (rows - 1)) * spacing;
    const double c = std::cos(k * goldenAngle), s = std::sin(k * goldenAngle);
    // Row-major: move the box's centre to the origin, turn about +Y, move it to its grid cell.
    const double m[16] = { c, 0, s, x - (c * cx + s * cz), 0, 1, 0, 0, -s, 0, c,
      z - (-s * cx + c * cz), 0, 0, 0, 1 };
    matrices->SetTuple(k, m);
  }
  this->Mapper->SetInstanceMatrices(matrices);
  // The ground: the grid's extent plus half a cell around it, just below the feet.
  const double x0 = cx - 0.5 * columns * spacing, x1 = cx + 0.5 * columns * spacing;
  const double z0 = cz - 0.5 * rows * spacing, z1 = cz + 0.5 * rows * spacing;
  const double y = b[2] - 1e-3 * size;
  this->Ground->SetOrigin(x0, y, z1);
  this->Ground->SetPoint1(x1, y, z1);
  this->Ground->SetPoint2(x0, y, z0);
  this->GroundActor->SetVisibility(n > 1);
}

void tcLODView::Frame()
{
  // From the front (+Z), 35 degrees up and 30 to the side: the rows of a crowd stand out behind
  // one another instead of hiding each other.
  vtkCamera* camera = this->Camera;
  const double up = vtkMath::RadiansFromDegrees(35.0), side = vtkMath::RadiansFromDegrees(30.0);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetPosition(std::cos(up) * std::sin(side), std::sin(up), std::cos(up) * std::cos(side));
  camera->SetViewUp(0.0, 1.0, 0.0);
  this->Renderer->ResetCamera();
}

void tcLODView::Render()
{
  if (this->IsShown())
  {
    this->Window->Render();
  }
}

void tcLODView::SetLODBias(double bias)
{
  this->Mapper->SetLODBias(bias);
  this->Render();
}

void tcLODView::SetErrorTarget(double pixels)
{
  this->Mapper->SetErrorTarget(pixels);
  this->Render();
}

void tcLODView::SetFreezeLOD(bool freeze)
{
  this->Mapper->SetFreezeLOD(freeze);
  this->Render();
}

void tcLODView::SetColorMode(int mode)
{
  this->Mapper->SetColorMode(mode);
  this->LevelLegend->SetVisibility(mode == tcLODMapper::ColorByLevel);
  this->Render();
}

void tcLODView::SetWireframe(bool wireframe)
{
  this->Actor->GetProperty()->SetRepresentation(wireframe ? VTK_WIREFRAME : VTK_SURFACE);
  this->Render();
}

void tcLODView::SetInstances(int instances)
{
  this->Instances = instances;
  if (this->IsShown())
  {
    this->UpdateCrowd();
    this->Frame();
    this->Render();
  }
}

double tcLODView::GetSelectionMilliseconds() const
{
  return 1e3 * this->Mapper->GetSelectionSeconds();
}

double tcLODView::GetRenderMilliseconds() const
{
  return 1e3 * this->Renderer->GetLastRenderTimeInSeconds();
}

tcLODFrame tcLODView::Statistics() const
{
  // The frame rate is the last whole render's (this one is not finished). Timings vary from run
  // to run: batch pictures show "-" in their place (the window prints them).
  const tcLODMapper* m = this->Mapper;
  const double seconds = this->Renderer->GetLastRenderTimeInSeconds();
  tcLODFrame frame;
  frame.Fps = this->Batch || seconds <= 0 ? QString("-") : QString::number(1.0 / seconds, 'f', 1);
  frame.Selection =
    this->Batch ? QString("-") : QString::number(1e3 * m->GetSelectionSeconds(), 'f', 2);
  int finest = 0;
  for (int level = 0; level < 16; ++level)
  {
    finest = m->GetChartsAtLevel(level) > 0 ? level : finest;
  }
  QStringList perLevel;
  for (int level = 0; level <= finest; ++level)
  {
    perLevel << QString("L%1 %2").arg(level).arg(m->GetChartsAtLevel(level));
  }
  frame.PerLevel = perLevel.join(" | ");
  frame.Charts = m->GetNumberOfCharts();
  frame.TrianglesDrawn = m->GetTrianglesDrawn();
  frame.ChartsDrawn = m->GetChartsDrawn();
  frame.Instances = m->GetNumberOfInstances();
  return frame;
}

void tcLODView::OnRendered(vtkObject*, unsigned long, void*)
{
  if (!this->IsShown())
  {
    return;
  }
  // The 3-D layer is drawn and the overlay layer is next: these are this frame's figures.
  const tcLODFrame frame = this->Statistics();
  this->Overlay->SetInput(QString("fps %1\n%2 triangles drawn\n%3 charts drawn\n%4\n"
                                  "LOD selection %5 ms\n%6 instance%7")
                            .arg(frame.Fps)
                            .arg(frame.TrianglesDrawn)
                            .arg(frame.ChartsDrawn)
                            .arg(frame.PerLevel)
                            .arg(frame.Selection)
                            .arg(frame.Instances)
                            .arg(frame.Instances == 1 ? "" : "s")
                            .toStdString()
                            .c_str());
  if (this->FrameDrawn)
  {
    this->FrameDrawn(frame);
  }
}
