// SPDX-License-Identifier: BSD-3-Clause
#include "tcLODView.h"

#include "tcAtlasConversion.h"
#include "tcColorMaps.h"
#include "tcLODMapper.h"

#include "tc/common/array_names.h"
#include "tc/common/errors.h"
#include "tc/gim/atlas.h"

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
#include <cstdint>
#include <string>
#include <utility>

namespace
{
/// Instance k's phase as a fraction of the animation: 0 for the first (a crowd of one is at the
/// time asked for), for the others a fixed hash of k (splitmix64's finalizer). Not an even
/// spread by index: the instances stand in rows, and phases that grow along a row would run
/// across the crowd as a wave. A hash of the index alone keeps each instance's phase when the
/// crowd grows, and the same on every machine (for the baselines).
double PhaseFraction(int k)
{
  if (k == 0)
  {
    return 0.0;
  }
  uint64_t z = static_cast<uint64_t>(k) * 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}
}

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

bool tcLODView::Show(vtkDataObject* atlas, bool entering)
{
  const bool fresh = atlas != this->AtlasSource || atlas->GetMTime() != this->AtlasTime;
  if (fresh)
  {
    auto copy = vtkSmartPointer<vtkMultiBlockDataSet>::New();
    copy->DeepCopy(atlas);
    this->Mapper->SetInputData(copy);
    this->AtlasSource = atlas;
    this->AtlasTime = atlas->GetMTime();
    this->UpdateLevelLegend(atlas);
    // The crowd is laid out from the bounds of one instance, in the pose shown.
    this->ReadAnimations(atlas);
    this->Mapper->SetInstanceMatrices(nullptr);
    this->UpdatePoses();
    this->Mapper->GetBounds(this->Bounds);
  }
  this->UpdateCrowd();
  this->UpdatePoses();
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
  return fresh;
}

void tcLODView::ReadAnimations(vtkDataObject* atlas)
{
  // What poses an atlas for the mapper (tcLODSkinning): a rig and a Skin attribute. An atlas
  // that does not convert has none; the mapper reports why when it draws.
  tc::Atlas converted;
  std::string error;
  std::vector<tc::Animation> animations;
  if (tcvtk::ToAtlas(atlas, converted, error) && !converted.rig.empty() &&
    tc::findAttribute(converted, tc::kAtlasSkin) >= 0)
  {
    animations = std::move(converted.rig.animations);
  }
  // The same animations (a pipeline run that changed a parameter, not the file) keep the pose.
  const auto same = [](const tc::Animation& a, const tc::Animation& b)
  { return a.name == b.name && a.duration == b.duration; };
  if (!std::equal(animations.begin(), animations.end(), this->Animations.begin(),
        this->Animations.end(), same))
  {
    this->AnimationIndex = animations.empty() ? -1 : 0;
    this->Time = 0.0;
  }
  this->Animations = std::move(animations);
}

QStringList tcLODView::GetAnimationNames() const
{
  QStringList names;
  for (const tc::Animation& animation : this->Animations)
  {
    names << QString::fromStdString(animation.name);
  }
  return names;
}

double tcLODView::GetAnimationDuration() const
{
  return this->AnimationIndex < 0
    ? 0.0
    : this->Animations[static_cast<size_t>(this->AnimationIndex)].duration;
}

int tcLODView::FindAnimation(const QString& choice, QString& error) const
{
  try
  {
    const int index = tc::findAnimation(this->Animations, choice.toStdString());
    if (index < 0)
    {
      error = "the atlas has no animation: it is not skinned, or its rig has none";
    }
    return index;
  }
  catch (const tc::InputError& e)
  {
    error = e.what();
    return -1;
  }
}

void tcLODView::SetAnimation(int index)
{
  if (index < 0 || index >= static_cast<int>(this->Animations.size()))
  {
    return;
  }
  this->AnimationIndex = index;
  this->Time = this->Time <= this->GetAnimationDuration() ? this->Time : 0.0;
  this->UpdatePoses();
  this->Render();
}

void tcLODView::SetAnimationTime(double seconds)
{
  this->Time = std::min(std::max(seconds, 0.0), this->GetAnimationDuration());
  this->UpdatePoses();
  this->Render();
}

void tcLODView::SetPhased(bool phased)
{
  this->Phased = phased;
  this->UpdatePoses();
  this->Render();
}

void tcLODView::UpdatePoses()
{
  if (this->AnimationIndex < 0)
  {
    this->Mapper->SetInstanceAnimations(nullptr);
    this->Mapper->SetInstanceTimes(nullptr);
    return;
  }
  // The animation by index, for every instance: a name may be another animation's too, or
  // another's index as digits (the mapper's Animation takes either).
  vtkNew<vtkIntArray> animations;
  animations->SetNumberOfTuples(this->Instances);
  animations->FillValue(this->AnimationIndex);
  this->Mapper->SetInstanceAnimations(animations);
  this->Mapper->SetAnimationTime(this->Time);
  const double duration = this->GetAnimationDuration();
  if (!this->Phased || this->Instances == 1 || duration <= 0.0)
  {
    this->Mapper->SetInstanceTimes(nullptr);
    return;
  }
  vtkNew<vtkDoubleArray> times;
  times->SetNumberOfTuples(this->Instances);
  for (int k = 0; k < this->Instances; ++k)
  {
    // Time and phase are each in [0, duration]: one turn of the loop wraps their sum back.
    const double t = this->Time + duration * PhaseFraction(k);
    times->SetValue(k, t > duration ? t - duration : t);
  }
  this->Mapper->SetInstanceTimes(times);
}

QString tcLODView::PoseText() const
{
  if (this->AnimationIndex < 0 || !this->Mapper->GetSkinned())
  {
    return QString();
  }
  // One pass of arg: a name holding "%2" stays as it is.
  return QString("animation '%1' at %2 s of %3 s%4")
    .arg(this->GetAnimationNames()[this->AnimationIndex], QString::number(this->Time, 'f', 2),
      QString::number(this->GetAnimationDuration(), 'f', 2),
      this->Instances > 1 ? (this->Phased ? ", own phases" : ", in step") : "");
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
    this->UpdatePoses();
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
  frame.Animation = this->PoseText();
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
                                  "LOD selection %5 ms\n%6 instance%7%8")
                            .arg(frame.Fps)
                            .arg(frame.TrianglesDrawn)
                            .arg(frame.ChartsDrawn)
                            .arg(frame.PerLevel)
                            .arg(frame.Selection)
                            .arg(frame.Instances)
                            .arg(frame.Instances == 1 ? "" : "s")
                            .arg(frame.Animation.isEmpty() ? QString() : "\n" + frame.Animation)
                            .toStdString()
                            .c_str());
  if (this->FrameDrawn)
  {
    this->FrameDrawn(frame);
  }
}
