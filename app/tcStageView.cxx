// SPDX-License-Identifier: BSD-3-Clause
#include "tcStageView.h"

#include "tcColorMaps.h"
#include "tcStage.h"
#include "tcStagePipeline.h"

#include "tc/common/array_names.h"
#include "tc/gim/atlas.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkImageActor.h>
#include <vtkImageData.h>
#include <vtkImageMapper3D.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkLookupTable.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSphereSource.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>

namespace
{
/// Trackball camera, except that the left button pans the flat atlas picture instead of turning
/// it out of its plane.
class tcViewerInteractorStyle : public vtkInteractorStyleTrackballCamera
{
public:
  static tcViewerInteractorStyle* New();
  vtkTypeMacro(tcViewerInteractorStyle, vtkInteractorStyleTrackballCamera);

  vtkRenderer* Flat = nullptr;

  void OnLeftButtonDown() override
  {
    const int* xy = this->Interactor->GetEventPosition();
    this->FindPokedRenderer(xy[0], xy[1]);
    if (this->CurrentRenderer && this->CurrentRenderer == this->Flat)
    {
      this->GrabFocus(this->EventCallbackCommand);
      this->StartPan();
      return;
    }
    this->Superclass::OnLeftButtonDown();
  }
};
vtkStandardNewMacro(tcViewerInteractorStyle);
}

tcStageView::tcStageView(vtkRenderWindow* window, vtkRenderer* renderer)
  : Window(window)
  , Renderer(renderer)
{
  this->SurfaceActor->SetMapper(this->SurfaceMapper);
  this->LineActor->SetMapper(this->LineMapper);
  this->LineMapper->ScalarVisibilityOff();
  this->LineMapper->SetResolveCoincidentTopologyToPolygonOffset();
  this->LineActor->GetProperty()->SetColor(0.05, 0.05, 0.05);
  this->LineActor->GetProperty()->SetLineWidth(2.0);
  vtkNew<vtkGlyph3DMapper> glyphs;
  this->CornerSphere->SetThetaResolution(12);
  this->CornerSphere->SetPhiResolution(8);
  glyphs->SetSourceConnection(this->CornerSphere->GetOutputPort());
  glyphs->ScalingOff();
  glyphs->ScalarVisibilityOff();
  this->CornerActor->SetMapper(glyphs);
  this->CornerActor->GetProperty()->SetColor(0.85, 0.1, 0.1);
  this->Renderer->AddActor(this->SurfaceActor);
  this->Renderer->AddActor(this->LineActor);
  this->Renderer->AddActor(this->CornerActor);
  this->CornerActor->VisibilityOff();
  this->Legend->SetNumberOfLabels(5);
  this->Legend->SetWidth(0.08);
  this->Legend->SetHeight(0.5);
  // Fixed sizes, not ones scaled to the bar's (7-pixel labels in a 750-pixel window).
  this->Legend->UnconstrainedFontSizeOn();
  this->Legend->GetTitleTextProperty()->SetFontSize(14);
  this->Legend->GetLabelTextProperty()->SetFontSize(13);
  this->Renderer->AddActor2D(this->Legend);
  this->SurfaceActor->VisibilityOff();
  this->LineActor->VisibilityOff();
  this->Legend->VisibilityOff();

  this->AtlasRenderer->SetBackground(0.1, 0.1, 0.1);
  this->AtlasRenderer->SetViewport(0.0, 0.0, 0.5, 1.0);
  this->AtlasRenderer->GetActiveCamera()->ParallelProjectionOn();
  this->AtlasPicture->InterpolateOff(); // one texel, one square: the samples stay visible
  this->AtlasRenderer->AddActor(this->AtlasPicture);
  this->AtlasCaption->SetInput("Atlas, finest mip step: normal (x, y, z) as (R, G, B)");
  this->AtlasCaption->GetTextProperty()->SetFontSize(14);
  this->AtlasCaption->GetTextProperty()->SetColor(0.9, 0.9, 0.9);
  this->AtlasCaption->SetPosition(10, 10);
  this->AtlasRenderer->AddActor2D(this->AtlasCaption);
}

tcStageView::~tcStageView() = default;

void tcStageView::UseInteractor(vtkRenderWindowInteractor* interactor)
{
  vtkNew<tcViewerInteractorStyle> style;
  style->Flat = this->AtlasRenderer;
  interactor->SetInteractorStyle(style);
}

void tcStageView::Show(int stage, const tcStageOutput& output)
{
  this->Stage = stage;
  // Feature-like lines stand out; the many edges of a reconstruction (every grid triangle's)
  // must not hide its colours: thin and faint.
  const bool grid = stage == tcStage::Reconstruction;
  this->LineActor->GetProperty()->SetLineWidth(grid ? 1.0 : 2.0);
  this->LineActor->GetProperty()->SetOpacity(grid ? 0.25 : 1.0);
  this->SurfaceActor->GetProperty()->SetOpacity(stage == tcStage::Base ? 0.6 : 1.0);
  const bool split = this->Window->HasRenderer(this->AtlasRenderer);
  if (stage == tcStage::Atlas)
  {
    this->ShowAtlasPicture(output.Atlas);
  }
  else
  {
    this->HideAtlasPicture();
  }
  this->ShowSurface(output.Surface);
  this->ShowLines(output.Lines);
  this->ShowCorners(output.Corners, output.Surface->GetLength());
  if (!split && this->Window->HasRenderer(this->AtlasRenderer))
  {
    this->Renderer->ResetCamera(); // half the width now: fit the mesh again
  }
}

void tcStageView::Hide()
{
  this->SurfaceActor->VisibilityOff();
  this->LineActor->VisibilityOff();
  this->CornerActor->VisibilityOff();
  this->Legend->VisibilityOff();
  this->HideAtlasPicture();
  this->HasLines = false;
}

void tcStageView::Forget()
{
  this->Shown = nullptr;
  this->Stage = tcStage::LOD;
}

void tcStageView::ShowSurface(vtkPolyData* surface)
{
  this->Shown = vtkSmartPointer<vtkPolyData>::New();
  this->Shown->ShallowCopy(surface);
  if (this->Stage >= tcStage::Curvature && this->Stage <= tcStage::Patches &&
    surface->GetPointData()->GetNormals() && surface->GetNumberOfPolys() > 0)
  {
    // Normals split where faces meet at 45 degrees or more (the crease angle of the geometry
    // images' error); see the class comment.
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(this->Shown);
    normals->SetFeatureAngle(45.0);
    normals->SplittingOn();
    normals->ConsistencyOff();
    normals->AutoOrientNormalsOff();
    normals->ComputeCellNormalsOff();
    normals->Update();
    this->SurfaceMapper->SetInputData(normals->GetOutput());
  }
  else
  {
    this->SurfaceMapper->SetInputData(this->Shown);
  }
  this->SurfaceActor->VisibilityOn();
}

void tcStageView::ShowLines(vtkPolyData* lines)
{
  this->HasLines = lines != nullptr;
  if (lines)
  {
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    copy->ShallowCopy(lines);
    this->LineMapper->SetInputData(copy);
  }
  this->LineActor->SetVisibility(lines != nullptr && this->LinesOn);
}

void tcStageView::ShowCorners(vtkPolyData* corners, double diagonal)
{
  if (corners)
  {
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    copy->ShallowCopy(corners);
    auto* glyphs = static_cast<vtkGlyph3DMapper*>(this->CornerActor->GetMapper());
    glyphs->SetInputData(copy);
    this->CornerSphere->SetRadius(0.008 * diagonal);
  }
  this->CornerActor->SetVisibility(corners != nullptr && this->CornersOn);
}

void tcStageView::ShowAtlasPicture(vtkMultiBlockDataSet* atlas)
{
  auto* images = atlas ? vtkMultiBlockDataSet::SafeDownCast(atlas->GetBlock(1)) : nullptr;
  auto* finest = images ? vtkImageData::SafeDownCast(images->GetBlock(0)) : nullptr;
  vtkDataArray* normals = finest ? finest->GetPointData()->GetArray(tc::kAtlasNormal) : nullptr;
  if (!normals || normals->GetNumberOfComponents() != 3)
  {
    this->HideAtlasPicture();
    return;
  }
  auto picture = vtkSmartPointer<vtkImageData>::New();
  picture->SetDimensions(finest->GetDimensions());
  vtkNew<vtkUnsignedCharArray> colors;
  tcColorMaps::NormalColors(normals, colors);
  picture->GetPointData()->SetScalars(colors);
  this->AtlasPicture->GetMapper()->SetInputData(picture);
  if (!this->Window->HasRenderer(this->AtlasRenderer))
  {
    this->Window->AddRenderer(this->AtlasRenderer);
    this->Renderer->SetViewport(0.5, 0.0, 1.0, 1.0);
  }
  this->AtlasRenderer->ResetCamera();
}

void tcStageView::HideAtlasPicture()
{
  if (this->Window->HasRenderer(this->AtlasRenderer))
  {
    this->Window->RemoveRenderer(this->AtlasRenderer);
    this->Renderer->SetViewport(0.0, 0.0, 1.0, 1.0);
  }
}

namespace
{
/// The colour choice that draws the surface's base-colour texture.
const char* const kTextureChoice = "Texture";

/// The base-colour texture `surface` carries (the reader's field arrays, which every stage and
/// the rebuilt mesh keep) and the coordinates to draw it with; null when it has not both.
vtkSmartPointer<vtkTexture> SurfaceTexture(vtkPolyData* surface)
{
  vtkFieldData* fd = surface ? surface->GetFieldData() : nullptr;
  vtkDataArray* rgba = fd ? fd->GetArray(tc::kBaseColorTexture) : nullptr;
  vtkDataArray* size = fd ? fd->GetArray(tc::kBaseColorTextureSize) : nullptr;
  vtkDataArray* uv = surface ? surface->GetPointData()->GetArray(tc::kTextureCoordinates) : nullptr;
  if (!rgba || !size || !uv || rgba->GetNumberOfComponents() != 4 ||
    size->GetNumberOfComponents() != 2 ||
    rgba->GetNumberOfTuples() !=
      static_cast<vtkIdType>(size->GetComponent(0, 0)) *
        static_cast<vtkIdType>(size->GetComponent(0, 1)))
  {
    return nullptr;
  }
  vtkNew<vtkImageData> image;
  image->SetDimensions(
    static_cast<int>(size->GetComponent(0, 0)), static_cast<int>(size->GetComponent(0, 1)), 1);
  image->GetPointData()->SetScalars(rgba);
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetInputData(image);
  texture->InterpolateOn();
  texture->MipmapOn();
  texture->RepeatOn();
  return texture;
}
} // namespace

QStringList tcStageView::ColorChoices() const
{
  QStringList choices("Solid");
  vtkPolyData* surface = this->Shown;
  if (!surface)
  {
    return choices;
  }
  if (SurfaceTexture(surface))
  {
    choices << kTextureChoice;
  }
  for (int i = 0; i < surface->GetPointData()->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* a = surface->GetPointData()->GetArray(i);
    if (a && a->GetName() && a != surface->GetPointData()->GetNormals())
    {
      choices << a->GetName();
    }
  }
  for (int i = 0; i < surface->GetCellData()->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* a = surface->GetCellData()->GetArray(i);
    if (a && a->GetName())
    {
      choices << QString("cell:") + a->GetName();
    }
  }
  return choices;
}

QString tcStageView::DefaultColor(int stage, const QStringList& choices, const QString& previous)
{
  const QString clusters = QString("cell:") + tc::kClusterId;
  const QString charts = QString("cell:") + tc::kChartId;
  if (stage == tcStage::Input && choices.contains(kTextureChoice))
  {
    return kTextureChoice;
  }
  if (stage == tcStage::Base)
  {
    return tc::kBaseFaceId;
  }
  if (stage == tcStage::Patches)
  {
    return QString("cell:") + tc::kPatchId;
  }
  if (stage == tcStage::Atlas)
  {
    return charts;
  }
  if (stage == tcStage::Reconstruction)
  {
    return choices.contains(tc::kDistance) ? QString(tc::kDistance) : charts;
  }
  if (choices.contains(clusters))
  {
    return clusters;
  }
  if (choices.contains(tc::kMeanCurvature))
  {
    return tc::kMeanCurvature;
  }
  return choices.contains(previous) ? previous : QString("Solid");
}

void tcStageView::ColorBy(const QString& name)
{
  const bool cell = name.startsWith("cell:");
  const QString arrayName = cell ? name.mid(5) : name;
  vtkDataArray* values = !this->Shown ? nullptr
    : cell ? this->Shown->GetCellData()->GetArray(arrayName.toStdString().c_str())
           : this->Shown->GetPointData()->GetArray(arrayName.toStdString().c_str());
  const vtkSmartPointer<vtkTexture> texture =
    name == kTextureChoice ? SurfaceTexture(this->Shown) : nullptr;
  this->SurfaceActor->SetTexture(texture);
  if (texture)
  {
    // The texture's colours as they are: white under it, as vtkTexture multiplies.
    for (vtkPolyData* surface : { this->Shown.Get(), this->SurfaceMapper->GetInput() })
    {
      surface->GetPointData()->SetActiveTCoords(tc::kTextureCoordinates);
    }
    this->SurfaceMapper->ScalarVisibilityOff();
    this->SurfaceActor->GetProperty()->SetColor(1.0, 1.0, 1.0);
    this->Legend->VisibilityOff();
    return;
  }
  if (!values)
  {
    this->SurfaceMapper->ScalarVisibilityOff();
    this->SurfaceActor->GetProperty()->SetColor(0.85, 0.85, 0.85);
    this->Legend->VisibilityOff();
    return;
  }
  vtkNew<vtkLookupTable> lut;
  const bool curvature = arrayName.contains("Curvature");
  const bool labels = arrayName.endsWith("Id");
  if (curvature)
  {
    tcColorMaps::DivergingColors(lut, values, 0);
  }
  else if (labels)
  {
    tcColorMaps::LabelColors(lut, values);
  }
  else
  {
    tcColorMaps::RangeColors(lut, values, 0);
  }
  lut->SetVectorModeToComponent();
  lut->SetVectorComponent(0);
  this->SurfaceMapper->ScalarVisibilityOn();
  if (cell)
  {
    this->SurfaceMapper->SetScalarModeToUseCellFieldData();
  }
  else
  {
    this->SurfaceMapper->SetScalarModeToUsePointFieldData();
  }
  this->SurfaceMapper->SelectColorArray(arrayName.toStdString().c_str());
  this->SurfaceMapper->SetLookupTable(lut);
  this->SurfaceMapper->UseLookupTableScalarRangeOn();
  this->Legend->SetLookupTable(lut);
  this->Legend->SetTitle(arrayName.toStdString().c_str());
  this->Legend->SetVisibility(!labels && this->Stage != tcStage::LOD);
}

void tcStageView::SetLinesVisible(bool on)
{
  this->LinesOn = on;
  this->LineActor->SetVisibility(on && this->HasLines);
}

void tcStageView::SetCornersVisible(bool on)
{
  this->CornersOn = on;
  this->CornerActor->SetVisibility(on && this->Stage == tcStage::Features);
}

void tcStageView::SetEdgesVisible(bool on)
{
  this->SurfaceActor->GetProperty()->SetEdgeVisibility(on);
}
