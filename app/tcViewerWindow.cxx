// SPDX-License-Identifier: BSD-3-Clause
#include "tcViewerWindow.h"

#include "tcAtlasReader.h"
#include "tcAtlasWriter.h"
#include "tcBaseComplex.h"
#include "tcColorMaps.h"
#include "tcCurvature.h"
#include "tcFeatureRefinement.h"
#include "tcGeometryImageMesh.h"
#include "tcGeometryImages.h"
#include "tcLODMapper.h"
#include "tcMeshPreparation.h"
#include "tcMeshReader.h"
#include "tcPathTracing.h"
#include "tcSpectralClustering.h"
#include "tcSurfaceDistance.h"

#include "tc/common/array_names.h"
#include "tc/gim/atlas.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QColor>
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QLabel>
#include <QListWidget>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSettings>
#include <QSpinBox>
#include <QStackedWidget>
#include <QStatusBar>
#include <QTextDocumentFragment>
#include <QVBoxLayout>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkExtractEdges.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkGlyph3DMapper.h>
#include <vtkImageActor.h>
#include <vtkImageData.h>
#include <vtkImageMapper3D.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkLinearSubdivisionFilter.h>
#include <vtkLookupTable.h>
#include <vtkMath.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSphereSource.h>
#include <vtkTable.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

namespace
{
const char* const kStageNames[] = { "input", "preparation", "curvature", "clusters", "features",
  "base", "patches", "atlas", "reconstruction", "lod" };
const char* const kStageLabels[] = { "Input mesh", "Preparation", "Curvature", "Spectral clusters",
  "Feature lines and corners", "Base complex (MAPS)", "Triangle patches and paths",
  "Geometry-image atlas", "Reconstruction and its error", "Level of detail (GPU)" };
static_assert(
  sizeof(kStageNames) / sizeof(*kStageNames) == tcViewerWindow::StageCount, "one name per stage");
static_assert(sizeof(kStageLabels) / sizeof(*kStageLabels) == tcViewerWindow::StageCount,
  "one label per stage");

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

tcViewerWindow::tcViewerWindow()
{
  this->Preparation->SetInputConnection(this->Reader->GetOutputPort());
  this->Curvature->SetInputConnection(this->Preparation->GetOutputPort());
  this->Clustering->SetInputConnection(this->Curvature->GetOutputPort());
  this->Refinement->SetInputConnection(this->Clustering->GetOutputPort());
  this->BaseComplex->SetInputConnection(this->Refinement->GetOutputPort());
  this->BaseEdges->SetInputConnection(this->BaseComplex->GetOutputPort(0));
  this->PathTracing->SetInputConnection(this->BaseComplex->GetOutputPort(1));
  this->GeometryImages->SetInputConnection(this->PathTracing->GetOutputPort(0));
  this->AtlasMesh->SetInputConnection(this->GeometryImages->GetOutputPort());
  this->AtlasMesh->SetLevel(-1);
  this->Reconstruction->SetInputConnection(this->GeometryImages->GetOutputPort());
  // The error is measured against the prepared mesh: the surface the charts were cut from, on
  // the reconstruction with its triangles split (see the class comment).
  this->Subdivision->SetInputConnection(this->Reconstruction->GetOutputPort());
  this->Subdivision->SetNumberOfSubdivisions(2);
  this->Distance->SetInputConnection(0, this->Subdivision->GetOutputPort());
  this->Distance->SetReferenceConnection(this->Preparation->GetOutputPort());
  this->RebuiltEdges->SetInputConnection(this->Reconstruction->GetOutputPort());
  for (vtkAlgorithm* a : this->Filters())
  {
    a->AddObserver(vtkCommand::ProgressEvent, this, &tcViewerWindow::OnProgress);
    a->AddObserver(vtkCommand::ErrorEvent, this, &tcViewerWindow::OnError);
  }
  this->BuildUi();
  this->setAcceptDrops(true);
}

tcViewerWindow::~tcViewerWindow() = default;

std::vector<vtkAlgorithm*> tcViewerWindow::Filters() const
{
  return { this->Reader, this->Preparation, this->Curvature, this->Clustering, this->Refinement,
    this->BaseComplex, this->PathTracing, this->GeometryImages, this->AtlasReader, this->AtlasMesh,
    this->Reconstruction, this->Subdivision, this->Distance, this->AtlasWriter };
}

vtkAlgorithm* tcViewerWindow::StageAlgorithm(int stage) const
{
  // The filter whose update runs the stage: the atlas stage shows the atlas and the mesh
  // rebuilt from it, the reconstruction its distance to the prepared mesh (none for an atlas
  // file, which has no input mesh), the LOD stage the atlas itself.
  vtkAlgorithm* reconstruction = this->AtlasFile ? static_cast<vtkAlgorithm*>(this->Reconstruction)
                                                 : static_cast<vtkAlgorithm*>(this->Distance);
  vtkAlgorithm* algorithms[] = { this->Reader, this->Preparation, this->Curvature, this->Clustering,
    this->Refinement, this->BaseComplex, this->PathTracing, this->AtlasMesh, reconstruction,
    this->AtlasSource() };
  static_assert(sizeof(algorithms) / sizeof(*algorithms) == StageCount, "one filter per stage");
  return algorithms[stage];
}

vtkAlgorithm* tcViewerWindow::AtlasSource() const
{
  return this->AtlasFile ? static_cast<vtkAlgorithm*>(this->AtlasReader)
                         : static_cast<vtkAlgorithm*>(this->GeometryImages);
}

bool tcViewerWindow::StageAvailable(int stage) const
{
  return stage >= 0 && stage < StageCount && (!this->AtlasFile || stage >= AtlasStage);
}

void tcViewerWindow::UpdateStageAvailability()
{
  for (int s = 0; s < StageCount; ++s)
  {
    QListWidgetItem* item = this->Stages->item(s);
    const bool available = this->StageAvailable(s);
    item->setFlags(
      available ? item->flags() | Qt::ItemIsEnabled : item->flags() & ~Qt::ItemIsEnabled);
    item->setToolTip(available ? QString() : "Needs an input mesh: an atlas file is open");
  }
  // An opened atlas is shown as it is: its geometry-image parameters cannot change.
  QWidget* geometryImages = this->Panels->widget(AtlasStage);
  geometryImages->setEnabled(!this->AtlasFile);
  geometryImages->setToolTip(
    this->AtlasFile ? "The atlas comes from a file: open a mesh to build a new one" : QString());
}

QStringList tcViewerWindow::StageNames()
{
  QStringList names;
  for (const char* name : kStageNames)
  {
    names << name;
  }
  return names;
}

QString tcViewerWindow::ClosedManifoldHint() const
{
  return "<b>Not a closed, oriented manifold</b>: the base complex will refuse it: " +
    QString::fromUtf8(this->Preparation->GetClosedManifoldRepairs()) +
    ". Check the box in the Preparation panel, then Apply.";
}

bool tcViewerWindow::IsAtlasFile(const QString& path)
{
  // By extension first, so that a damaged .exr is reported by the atlas reader (which says what
  // is wrong with it) rather than refused by the mesh reader as an unknown format.
  return path.endsWith(".exr", Qt::CaseInsensitive) ||
    tcAtlasReader::CanReadFile(path.toStdString().c_str());
}

int tcViewerWindow::StageFromName(const QString& name)
{
  for (int s = 0; s < StageCount; ++s)
  {
    if (name.compare(kStageNames[s], Qt::CaseInsensitive) == 0)
    {
      return s;
    }
  }
  return -1;
}

void tcViewerWindow::BuildUi()
{
  this->setWindowTitle("TriChart Viewer");
  this->resize(1100, 750);

  // 3-D view.
  this->View = new QVTKOpenGLNativeWidget(this);
  this->View->setRenderWindow(this->RenderWindow);
  this->RenderWindow->AddRenderer(this->Renderer);
  this->Renderer->SetBackground(0.32, 0.34, 0.43);
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
  this->Legend->GetTitleTextProperty()->SetFontSize(12);
  this->Renderer->AddActor2D(this->Legend);
  this->SurfaceActor->VisibilityOff();
  this->LineActor->VisibilityOff();
  this->Legend->VisibilityOff();
  this->setCentralWidget(this->View);

  // The atlas picture: a second renderer, added to the window only for the atlas stage.
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

  // The LOD stage: the atlas through tcLODMapper, its statistics in a second layer drawn after
  // the 3-D one (see the class comment). The overlay takes no interaction: the 3-D view does.
  this->LODActor->SetMapper(this->LODMapper);
  this->LODActor->GetProperty()->SetColor(0.85, 0.85, 0.85);
  this->LODActor->VisibilityOff();
  this->Renderer->AddActor(this->LODActor);
  this->GroundMapper->SetInputConnection(this->Ground->GetOutputPort());
  this->GroundActor->SetMapper(this->GroundMapper);
  this->GroundActor->GetProperty()->SetColor(0.42, 0.45, 0.40);
  this->GroundActor->GetProperty()->SetSpecular(0.0);
  this->GroundActor->VisibilityOff();
  this->Renderer->AddActor(this->GroundActor);
  this->RenderWindow->SetNumberOfLayers(2);
  this->OverlayRenderer->SetLayer(1);
  this->OverlayRenderer->InteractiveOff();
  this->LODStatistics->GetTextProperty()->SetFontSize(14);
  this->LODStatistics->GetTextProperty()->SetFontFamilyToCourier();
  this->LODStatistics->GetTextProperty()->SetColor(1.0, 1.0, 1.0);
  this->LODStatistics->GetTextProperty()->SetBackgroundColor(0.0, 0.0, 0.0);
  this->LODStatistics->GetTextProperty()->SetBackgroundOpacity(0.5);
  this->LODStatistics->GetTextProperty()->SetVerticalJustificationToTop();
  this->LODStatistics->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  this->LODStatistics->SetPosition(0.01, 0.985);
  this->OverlayRenderer->AddActor2D(this->LODStatistics);
  this->Renderer->AddObserver(vtkCommand::EndEvent, this, &tcViewerWindow::OnRendered);

  vtkNew<tcViewerInteractorStyle> style;
  style->Flat = this->AtlasRenderer;
  this->View->interactor()->SetInteractorStyle(style);

  // Pipeline panel: stages, their parameters, apply, display options.
  auto* dock = new QDockWidget("Pipeline", this);
  dock->setObjectName("PipelineDock");
  dock->setFeatures(QDockWidget::NoDockWidgetFeatures);
  auto* panel = new QWidget(dock);
  auto* layout = new QVBoxLayout(panel);
  this->Stages = new QListWidget(panel);
  for (const char* label : kStageLabels)
  {
    this->Stages->addItem(label);
  }
  // Every stage in view without scrolling; the parameter panel below takes what is left.
  this->Stages->setFixedHeight(
    this->Stages->sizeHintForRow(0) * this->Stages->count() + 2 * this->Stages->frameWidth() + 2);
  layout->addWidget(new QLabel("<b>Stages</b>", panel));
  layout->addWidget(this->Stages);
  this->Panels = new QStackedWidget(panel);
  this->Panels->addWidget(
    new QLabel("Reads .ply, .ply.gz, .obj, .stl,\n.off, .vtp and .vtk files, and the\nsurfaces "
               "of scene files in their\nrest pose: .glb, .gltf, .fbx, .x\nand .md2.",
      panel));
  this->Panels->addWidget(this->BuildPreparationPanel());
  this->Panels->addWidget(this->BuildCurvaturePanel());
  this->Panels->addWidget(this->BuildClusteringPanel());
  this->Panels->addWidget(this->BuildRefinementPanel());
  this->Panels->addWidget(this->BuildBaseComplexPanel());
  this->Panels->addWidget(new QLabel(
    "No parameters: each base edge is traced\nonto the mesh, which is cut into one\ntriangle "
    "patch per base face.",
    panel));
  this->Panels->addWidget(this->BuildGeometryImagesPanel());
  this->Panels->addWidget(this->BuildReconstructionPanel());
  this->Panels->addWidget(this->BuildLODPanel());
  layout->addWidget(this->Panels);
  auto* apply = new QPushButton("Apply", panel);
  layout->addWidget(apply);

  layout->addWidget(new QLabel("<b>Display</b>", panel));
  auto* form = new QFormLayout();
  this->ColorBy = new QComboBox(panel);
  form->addRow("Colour by", this->ColorBy);
  this->ShowLines = new QCheckBox("Lines (crests, boundaries, paths, edges)", panel);
  this->ShowLines->setChecked(true);
  form->addRow(this->ShowLines);
  this->ShowCorners = new QCheckBox("Corners", panel);
  this->ShowCorners->setChecked(true);
  form->addRow(this->ShowCorners);
  this->ShowEdges = new QCheckBox("Mesh edges", panel);
  form->addRow(this->ShowEdges);
  layout->addLayout(form);
  // The summary scrolls rather than grow the window: screenshots keep one size.
  auto* scroll = new QScrollArea(panel);
  scroll->setFrameShape(QFrame::NoFrame);
  scroll->setWidgetResizable(true);
  scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  scroll->viewport()->setAutoFillBackground(false);
  this->Info = new QLabel(scroll);
  this->Info->setWordWrap(true);
  this->Info->setAlignment(Qt::AlignLeft | Qt::AlignTop);
  this->Info->setTextInteractionFlags(Qt::TextSelectableByMouse);
  this->Info->setAutoFillBackground(false);
  scroll->setWidget(this->Info);
  // Three lines at least, not the taller default of a scroll area: with every stage listed and
  // the tallest parameter panel shown, the window keeps its size.
  scroll->setMinimumHeight(3 * this->Info->fontMetrics().lineSpacing());
  layout->addWidget(scroll, 1);
  dock->setWidget(panel);
  dock->setMinimumWidth(260);
  this->addDockWidget(Qt::LeftDockWidgetArea, dock);

  // The panel stack is as tall as the shown panel, not as the tallest one, so that the summary
  // below it has room.
  connect(this->Panels, &QStackedWidget::currentChanged, this,
    [this](int index)
    {
      for (int i = 0; i < this->Panels->count(); ++i)
      {
        const auto policy = i == index ? QSizePolicy::Preferred : QSizePolicy::Ignored;
        this->Panels->widget(i)->setSizePolicy(policy, policy);
      }
      this->Panels->adjustSize();
    });
  emit this->Panels->currentChanged(this->Panels->currentIndex());
  connect(this->Stages, &QListWidget::currentRowChanged, this,
    [this](int row)
    {
      this->Panels->setCurrentIndex(std::max(0, row));
      if (!this->Running && this->StageAvailable(row) && row != this->CurrentStage &&
        !this->FileName.isEmpty())
      {
        this->ShowStage(row);
      }
    });
  connect(apply, &QPushButton::clicked, this, [this]() { this->ShowStage(this->CurrentStage); });
  connect(this->ColorBy, &QComboBox::currentTextChanged, this,
    [this](const QString& name)
    {
      if (!this->Running)
      {
        this->SetColorArray(name);
        this->RenderWindow->Render();
      }
    });
  connect(this->ShowLines, &QCheckBox::toggled, this,
    [this](bool on)
    {
      this->LineActor->SetVisibility(on && this->HasLines);
      this->RenderWindow->Render();
    });
  connect(this->ShowCorners, &QCheckBox::toggled, this,
    [this](bool on)
    {
      this->CornerActor->SetVisibility(on && this->CurrentStage == FeaturesStage);
      this->RenderWindow->Render();
    });
  connect(this->ShowEdges, &QCheckBox::toggled, this,
    [this](bool on)
    {
      this->SurfaceActor->GetProperty()->SetEdgeVisibility(on);
      this->RenderWindow->Render();
    });

  // Progress with cancel.
  this->Progress = new QProgressBar(this);
  this->Progress->setRange(0, 100);
  this->Progress->setMaximumWidth(250);
  this->Cancel = new QPushButton("Cancel", this);
  this->Cancel->setEnabled(false);
  this->statusBar()->addPermanentWidget(this->Progress);
  this->statusBar()->addPermanentWidget(this->Cancel);
  connect(this->Cancel, &QPushButton::clicked, this,
    [this]()
    {
      for (vtkAlgorithm* a : this->Filters())
      {
        a->AbortExecuteOn();
      }
    });

  // Menus.
  QMenu* file = this->menuBar()->addMenu("&File");
  QAction* open = file->addAction("&Open...");
  open->setShortcut(QKeySequence::Open);
  connect(open, &QAction::triggered, this,
    [this]()
    {
      QString meshes = "*.gz";
      for (const QString& ext : QString(tcMeshReader::GetSupportedExtensions()).split(' '))
      {
        meshes += " *." + ext;
      }
      const QString path = QFileDialog::getOpenFileName(this, "Open mesh or atlas", QString(),
        "Meshes and atlases (" + meshes + " *.exr);;Meshes (" + meshes +
          ");;Atlases (*.exr);;All files (*)");
      if (!path.isEmpty())
      {
        this->OpenFile(path, std::max(0, this->CurrentStage));
      }
    });
  this->RecentMenu = file->addMenu("Open &Recent");
  this->UpdateRecentMenu();
  QAction* exportStage = file->addAction("&Export stage as VTP...");
  connect(exportStage, &QAction::triggered, this,
    [this]()
    {
      if (this->CurrentStage == LODStage)
      {
        this->ReportError("The LOD stage draws the atlas on the GPU and builds no mesh: export "
                          "the reconstruction stage, or save the atlas.");
        return;
      }
      if (!this->Shown)
      {
        return;
      }
      const QString path = QFileDialog::getSaveFileName(
        this, "Export stage", QString(kStageNames[this->CurrentStage]) + ".vtp", "VTP (*.vtp)");
      if (!path.isEmpty())
      {
        vtkNew<vtkXMLPolyDataWriter> writer;
        writer->SetInputData(this->Shown);
        writer->SetFileName(path.toStdString().c_str());
        if (writer->Write() != 1)
        {
          this->ReportError("Cannot write " + path);
        }
      }
    });
  QAction* saveAtlas = file->addAction("Save &atlas...");
  connect(saveAtlas, &QAction::triggered, this,
    [this]()
    {
      if (this->FileName.isEmpty())
      {
        this->ReportError("Open a mesh or an atlas first: there is no atlas to save.");
        return;
      }
      const QString path = QFileDialog::getSaveFileName(this, "Save atlas",
        QFileInfo(this->FileName).completeBaseName() + ".exr", "Atlases (*.exr)");
      if (!path.isEmpty())
      {
        this->SaveAtlas(path);
      }
    });
  QAction* shot = file->addAction("Save &screenshot...");
  connect(shot, &QAction::triggered, this,
    [this]()
    {
      const QString path =
        QFileDialog::getSaveFileName(this, "Save screenshot", "trichart.png", "PNG (*.png)");
      if (!path.isEmpty() && !this->SaveScreenshot(path))
      {
        this->ReportError("Cannot write " + path);
      }
    });
  file->addSeparator();
  QAction* quit = file->addAction("&Quit");
  quit->setShortcut(QKeySequence::Quit);
  connect(quit, &QAction::triggered, qApp, &QApplication::quit);
}

QWidget* tcViewerWindow::BuildPreparationPanel()
{
  auto* w = new QWidget(this);
  auto* form = new QFormLayout(w);
  this->MergeTolerance = new QDoubleSpinBox(w);
  this->MergeTolerance->setDecimals(5);
  this->MergeTolerance->setRange(0.0, 0.1);
  this->MergeTolerance->setSingleStep(0.0001);
  this->MergeTolerance->setValue(this->Preparation->GetMergeTolerance());
  this->MergeTolerance->setToolTip("Merge points closer than this fraction of the diagonal");
  form->addRow("MergeTolerance", this->MergeTolerance);
  this->Orient = new QCheckBox(w);
  this->Orient->setChecked(this->Preparation->GetOrient());
  form->addRow("Orient", this->Orient);
  this->SplitNonManifold = new QCheckBox(w);
  this->SplitNonManifold->setChecked(this->Preparation->GetSplitNonManifold());
  form->addRow("SplitNonManifold", this->SplitNonManifold);
  this->FillHoles = new QCheckBox(w);
  this->FillHoles->setChecked(this->Preparation->GetFillHoles());
  form->addRow("FillHoles", this->FillHoles);
  this->MaxHoleEdges = new QSpinBox(w);
  this->MaxHoleEdges->setRange(0, 10000000);
  this->MaxHoleEdges->setSpecialValueText("any size"); // 0
  this->MaxHoleEdges->setValue(static_cast<int>(this->Preparation->GetMaxHoleEdges()));
  this->MaxHoleEdges->setToolTip("The largest hole FillHoles closes, in boundary edges");
  form->addRow("MaxHoleEdges", this->MaxHoleEdges);
  this->RemoveSlivers = new QCheckBox(w);
  this->RemoveSlivers->setChecked(this->Preparation->GetRemoveSlivers());
  this->RemoveSlivers->setToolTip("Collapse needles and flip caps (a scan's slivers)");
  form->addRow("RemoveSlivers", this->RemoveSlivers);
  return w;
}

QWidget* tcViewerWindow::BuildCurvaturePanel()
{
  auto* w = new QWidget(this);
  auto* form = new QFormLayout(w);
  auto spin = [w](int lo, int hi, int value)
  {
    auto* s = new QSpinBox(w);
    s->setRange(lo, hi);
    s->setValue(value);
    return s;
  };
  this->MinNeighbors = spin(6, 1000, this->Curvature->GetMinNeighbors());
  form->addRow("MinNeighbors", this->MinNeighbors);
  this->MaxRings = spin(1, 20, this->Curvature->GetMaxRings());
  form->addRow("MaxRings", this->MaxRings);
  this->Degree = spin(2, 3, this->Curvature->GetDegree());
  form->addRow("Degree", this->Degree);
  this->Robust = new QCheckBox(w);
  this->Robust->setChecked(this->Curvature->GetRobust());
  form->addRow("Robust", this->Robust);
  this->RobustIterations = spin(1, 10, this->Curvature->GetRobustIterations());
  form->addRow("RobustIterations", this->RobustIterations);
  this->CrestLines = new QCheckBox(w);
  this->CrestLines->setChecked(this->Curvature->GetComputeCrestLines());
  form->addRow("ComputeCrestLines", this->CrestLines);
  this->CrestThreshold = new QDoubleSpinBox(w);
  this->CrestThreshold->setRange(0.0, 100.0);
  this->CrestThreshold->setDecimals(3);
  this->CrestThreshold->setValue(this->Curvature->GetCrestStrengthThreshold());
  form->addRow("CrestStrengthThreshold", this->CrestThreshold);
  return w;
}

QWidget* tcViewerWindow::BuildClusteringPanel()
{
  auto* w = new QWidget(this);
  auto* form = new QFormLayout(w);
  this->NumberOfClusters = new QSpinBox(w);
  this->NumberOfClusters->setRange(1, 1000);
  this->NumberOfClusters->setValue(this->Clustering->GetNumberOfClusters());
  form->addRow("NumberOfClusters", this->NumberOfClusters);
  this->Seed = new QSpinBox(w);
  this->Seed->setRange(0, 1000000);
  this->Seed->setValue(this->Clustering->GetSeed());
  form->addRow("Seed", this->Seed);
  this->ClusterCrestBeta = new QDoubleSpinBox(w);
  this->ClusterCrestBeta->setRange(0.0, 1.0);
  this->ClusterCrestBeta->setSingleStep(0.05);
  this->ClusterCrestBeta->setValue(this->Clustering->GetCrestBeta());
  form->addRow("CrestBeta", this->ClusterCrestBeta);
  this->NystromThreshold = new QSpinBox(w);
  this->NystromThreshold->setRange(100, 100000000);
  this->NystromThreshold->setValue(static_cast<int>(this->Clustering->GetNystromThreshold()));
  form->addRow("NystromThreshold", this->NystromThreshold);
  return w;
}

QWidget* tcViewerWindow::BuildRefinementPanel()
{
  auto* w = new QWidget(this);
  auto* form = new QFormLayout(w);
  auto fraction = [w](double value)
  {
    auto* s = new QDoubleSpinBox(w);
    s->setRange(0.0, 1.0);
    s->setDecimals(3);
    s->setSingleStep(0.01);
    s->setValue(value);
    return s;
  };
  this->BandFraction = fraction(this->Refinement->GetBandFraction());
  form->addRow("BandFraction", this->BandFraction);
  this->CurvatureTopFraction = fraction(this->Refinement->GetCurvatureTopFraction());
  form->addRow("CurvatureTopFraction", this->CurvatureTopFraction);
  this->CurvatureThresholdScale = new QDoubleSpinBox(w);
  this->CurvatureThresholdScale->setRange(0.0, 10.0);
  this->CurvatureThresholdScale->setSingleStep(0.1);
  this->CurvatureThresholdScale->setValue(this->Refinement->GetCurvatureThresholdScale());
  form->addRow("CurvatureThresholdScale", this->CurvatureThresholdScale);
  this->CornerRings = new QSpinBox(w);
  this->CornerRings->setRange(1, 50);
  this->CornerRings->setValue(this->Refinement->GetCornerRings());
  form->addRow("CornerRings", this->CornerRings);
  this->CornerFraction = fraction(this->Refinement->GetCornerFraction());
  form->addRow("CornerFraction", this->CornerFraction);
  this->StraightenLines = new QCheckBox(w);
  this->StraightenLines->setChecked(this->Refinement->GetStraightenLines());
  this->StraightenLines->setToolTip("Straighten one-face zig-zags of the boundaries");
  form->addRow("StraightenLines", this->StraightenLines);
  this->CreaseAngle = new QDoubleSpinBox(w);
  this->CreaseAngle->setRange(
    this->Refinement->GetCreaseAngleMinValue(), this->Refinement->GetCreaseAngleMaxValue());
  this->CreaseAngle->setSingleStep(5.0);
  this->CreaseAngle->setValue(this->Refinement->GetCreaseAngle());
  this->CreaseAngle->setToolTip(
    "Dihedral angle (degrees) of a crease edge, which straightening never trades for a "
    "smoother one");
  form->addRow("CreaseAngle", this->CreaseAngle);
  return w;
}

QWidget* tcViewerWindow::BuildBaseComplexPanel()
{
  auto* w = new QWidget(this);
  auto* form = new QFormLayout(w);
  this->TargetFaces = new QSpinBox(w);
  this->TargetFaces->setRange(4, 10000000);
  this->TargetFaces->setValue(static_cast<int>(this->BaseComplex->GetTargetFaces()));
  form->addRow("TargetFaces", this->TargetFaces);
  this->MaxError = new QDoubleSpinBox(w);
  this->MaxError->setRange(0.0, 1.0);
  this->MaxError->setDecimals(6);
  this->MaxError->setSingleStep(0.0001);
  this->MaxError->setValue(this->BaseComplex->GetMaxError());
  form->addRow("MaxError", this->MaxError);
  return w;
}

QWidget* tcViewerWindow::BuildGeometryImagesPanel()
{
  // Ranges and defaults come from the filters (their clamp macros and initializers).
  auto* w = new QWidget(this);
  auto* form = new QFormLayout(w);
  tcGeometryImages* g = this->GeometryImages;
  this->SampleBudget = new QSpinBox(w);
  this->SampleBudget->setRange(static_cast<int>(g->GetSampleBudgetMinValue()),
    static_cast<int>(std::min<vtkIdType>(g->GetSampleBudgetMaxValue(), 1000000000)));
  this->SampleBudget->setSingleStep(1000);
  this->SampleBudget->setSpecialValueText("input points");
  this->SampleBudget->setValue(static_cast<int>(g->GetSampleBudget()));
  this->SampleBudget->setToolTip(
    "Total samples over all charts at their finest level; 0 uses the input's point count");
  form->addRow("SampleBudget", this->SampleBudget);
  this->MinLevel = new QSpinBox(w);
  this->MinLevel->setRange(g->GetMinLevelMinValue(), g->GetMinLevelMaxValue());
  this->MinLevel->setValue(g->GetMinLevel());
  this->MinLevel->setToolTip("Smallest finest level of a chart (2^d + 1 samples per side)");
  form->addRow("MinLevel", this->MinLevel);
  this->MaxLevel = new QSpinBox(w);
  this->MaxLevel->setRange(g->GetMaxLevelMinValue(), g->GetMaxLevelMaxValue());
  this->MaxLevel->setValue(g->GetMaxLevel());
  this->MaxLevel->setToolTip("Largest finest level of a chart (2^d + 1 samples per side)");
  form->addRow("MaxLevel", this->MaxLevel);
  this->CurvatureWeight = new QDoubleSpinBox(w);
  this->CurvatureWeight->setRange(
    g->GetCurvatureWeightMinValue(), std::min(g->GetCurvatureWeightMaxValue(), 1000.0));
  this->CurvatureWeight->setSingleStep(0.1);
  this->CurvatureWeight->setValue(g->GetCurvatureWeight());
  this->CurvatureWeight->setToolTip(
    "Weight of |mean curvature| x diagonal in the area that sets each chart's level");
  form->addRow("CurvatureWeight", this->CurvatureWeight);
  this->LevelRule = new QComboBox(w);
  this->LevelRule->addItems({ "Area", "Error" }); // index = tcGeometryImages::LEVEL_RULE_*
  this->LevelRule->setCurrentIndex(g->GetLevelRule());
  this->LevelRule->setToolTip("How each chart's finest level is chosen under the budget: Area "
                              "follows the curvature-weighted area (paper 5.2), Error the "
                              "largest measured error");
  form->addRow("LevelRule", this->LevelRule);
  this->StretchIterations = new QSpinBox(w);
  this->StretchIterations->setRange(
    g->GetStretchIterationsMinValue(), g->GetStretchIterationsMaxValue());
  this->StretchIterations->setValue(g->GetStretchIterations());
  this->StretchIterations->setToolTip(
    "Stretch-reducing passes over each chart's mean-value map; 0: Floater's map alone");
  form->addRow("StretchIterations", this->StretchIterations);
  this->FitSamples = new QCheckBox(w);
  this->FitSamples->setChecked(g->GetFitSamples());
  this->FitSamples->setToolTip(
    "Fit the finest samples to the surface by least squares instead of interpolating it");
  form->addRow("FitSamples", this->FitSamples);
  return w;
}

QWidget* tcViewerWindow::BuildReconstructionPanel()
{
  auto* w = new QWidget(this);
  auto* form = new QFormLayout(w);
  this->Level = new QSpinBox(w);
  this->Level->setRange(
    this->Reconstruction->GetLevelMinValue(), this->Reconstruction->GetLevelMaxValue());
  this->Level->setSpecialValueText("-1 (finest)");
  this->Level->setValue(this->Reconstruction->GetLevel());
  this->Level->setToolTip("Level of every chart, capped by each chart's finest; -1: the finest");
  form->addRow("Level", this->Level);
  return w;
}

QWidget* tcViewerWindow::BuildLODPanel()
{
  // View settings, not pipeline parameters: each change redraws at once, no Apply. The viewer
  // opens on the error-target rule and colours by level: the stage is there to show which level
  // each chart takes, and the atlases the pipeline writes carry measured errors.
  auto* w = new QWidget(this);
  auto* form = new QFormLayout(w);
  this->LODBias = new QDoubleSpinBox(w);
  this->LODBias->setRange(-4.0, 4.0);
  this->LODBias->setSingleStep(0.5);
  this->LODBias->setDecimals(1);
  this->LODBias->setValue(0.0);
  this->LODBias->setToolTip("Levels added to every chosen level (positive: finer)");
  form->addRow("LOD bias", this->LODBias);
  this->ErrorTarget = new QDoubleSpinBox(w);
  this->ErrorTarget->setRange(0.0, 64.0);
  this->ErrorTarget->setSingleStep(0.5);
  this->ErrorTarget->setDecimals(1);
  this->ErrorTarget->setSuffix(" px");
  this->ErrorTarget->setSpecialValueText("0 (area, eq. 7)");
  this->ErrorTarget->setValue(1.0);
  this->ErrorTarget->setToolTip("Each chart takes the coarsest level whose measured error "
                                "projects to at most this many pixels; 0 chooses by projected "
                                "area (eq. 7 of Feng et al.)");
  form->addRow("Error target", this->ErrorTarget);
  this->FreezeLOD = new QCheckBox(w);
  this->FreezeLOD->setToolTip("Keep the levels and culling of the last frame while the camera "
                              "moves, to fly around a frozen selection");
  form->addRow("Freeze LOD", this->FreezeLOD);
  this->LODColor = new QComboBox(w);
  // In tcLODMapper::ColorModes order.
  this->LODColor->addItems({ "actor", "chart", "level" });
  this->LODColor->setCurrentIndex(tcLODMapper::ColorByLevel);
  form->addRow("Colour by", this->LODColor);
  this->Wireframe = new QCheckBox(w);
  form->addRow("Wireframe", this->Wireframe);
  this->Instances = new QSpinBox(w);
  this->Instances->setRange(1, 2500);
  this->Instances->setValue(1);
  this->Instances->setToolTip("A crowd: this many copies on a square grid of the ground, each "
                              "turned by its own angle about the vertical (+Y) axis");
  form->addRow("Crowd instances", this->Instances);
  auto* reset = new QPushButton("Reset camera", w);
  reset->setToolTip("Look at the whole crowd from the front and a little to the side, 35 "
                    "degrees above the ground");
  form->addRow(reset);

  this->LODMapper->SetLODBias(this->LODBias->value());
  this->LODMapper->SetErrorTarget(this->ErrorTarget->value());
  this->LODMapper->SetColorMode(this->LODColor->currentIndex());
  connect(this->LODBias, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this,
    [this](double bias)
    {
      this->LODMapper->SetLODBias(bias);
      this->RenderLOD();
    });
  connect(this->ErrorTarget, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this,
    [this](double pixels)
    {
      this->LODMapper->SetErrorTarget(pixels);
      this->RenderLOD();
    });
  connect(this->FreezeLOD, &QCheckBox::toggled, this,
    [this](bool on)
    {
      this->LODMapper->SetFreezeLOD(on);
      this->RenderLOD();
    });
  connect(this->LODColor, QOverload<int>::of(&QComboBox::currentIndexChanged), this,
    [this](int mode)
    {
      this->LODMapper->SetColorMode(mode);
      this->RenderLOD();
    });
  connect(this->Wireframe, &QCheckBox::toggled, this,
    [this](bool on)
    {
      this->LODActor->GetProperty()->SetRepresentation(on ? VTK_WIREFRAME : VTK_SURFACE);
      this->RenderLOD();
    });
  connect(this->Instances, QOverload<int>::of(&QSpinBox::valueChanged), this,
    [this](int)
    {
      // A new crowd is framed whole: the old view would show a corner of a larger one.
      if (this->CurrentStage == LODStage && this->LODActor->GetVisibility())
      {
        this->UpdateCrowd();
        this->FrameCrowd();
        this->RenderLOD();
      }
    });
  connect(reset, &QPushButton::clicked, this,
    [this]()
    {
      this->ResetCamera();
      this->RenderLOD();
    });
  return w;
}

void tcViewerWindow::PushParameters()
{
  // Setting an unchanged value does not modify a filter, so only what changed re-runs.
  this->Preparation->SetMergeTolerance(this->MergeTolerance->value());
  this->Preparation->SetOrient(this->Orient->isChecked());
  this->Preparation->SetSplitNonManifold(this->SplitNonManifold->isChecked());
  this->Preparation->SetFillHoles(this->FillHoles->isChecked());
  this->Preparation->SetMaxHoleEdges(this->MaxHoleEdges->value());
  this->Preparation->SetRemoveSlivers(this->RemoveSlivers->isChecked());
  this->Curvature->SetMinNeighbors(this->MinNeighbors->value());
  this->Curvature->SetMaxRings(this->MaxRings->value());
  this->Curvature->SetDegree(this->Degree->value());
  this->Curvature->SetRobust(this->Robust->isChecked());
  this->Curvature->SetRobustIterations(this->RobustIterations->value());
  this->Curvature->SetComputeCrestLines(this->CrestLines->isChecked());
  this->Curvature->SetCrestStrengthThreshold(this->CrestThreshold->value());
  this->Clustering->SetNumberOfClusters(this->NumberOfClusters->value());
  this->Clustering->SetSeed(this->Seed->value());
  this->Clustering->SetCrestBeta(this->ClusterCrestBeta->value());
  this->Clustering->SetNystromThreshold(this->NystromThreshold->value());
  this->Refinement->SetBandFraction(this->BandFraction->value());
  this->Refinement->SetCurvatureTopFraction(this->CurvatureTopFraction->value());
  this->Refinement->SetCurvatureThresholdScale(this->CurvatureThresholdScale->value());
  this->Refinement->SetCornerRings(this->CornerRings->value());
  this->Refinement->SetCornerFraction(this->CornerFraction->value());
  this->Refinement->SetStraightenLines(this->StraightenLines->isChecked());
  this->Refinement->SetCreaseAngle(this->CreaseAngle->value());
  this->BaseComplex->SetTargetFaces(this->TargetFaces->value());
  this->BaseComplex->SetMaxError(this->MaxError->value());
  this->GeometryImages->SetSampleBudget(this->SampleBudget->value());
  this->GeometryImages->SetMinLevel(this->MinLevel->value());
  this->GeometryImages->SetMaxLevel(this->MaxLevel->value());
  this->GeometryImages->SetCurvatureWeight(this->CurvatureWeight->value());
  this->GeometryImages->SetLevelRule(this->LevelRule->currentIndex());
  this->GeometryImages->SetStretchIterations(this->StretchIterations->value());
  this->GeometryImages->SetFitSamples(this->FitSamples->isChecked());
  this->Reconstruction->SetLevel(this->Level->value());
}

bool tcViewerWindow::OpenFile(const QString& path, int stage)
{
  this->FileName = path;
  this->Note.clear();
  this->AtlasFile = IsAtlasFile(path);
  if (this->AtlasFile)
  {
    this->AtlasReader->SetFileName(path.toStdString().c_str());
    // An atlas has no input mesh: it opens on its reconstruction unless the atlas or its LOD
    // view is asked for.
    stage = stage == AtlasStage || stage == LODStage ? stage : ReconstructionStage;
  }
  else
  {
    this->Reader->SetFileName(path.toStdString().c_str());
  }
  // Re-connecting the same output is no change, so switching files of one kind re-runs nothing
  // that does not depend on the file.
  this->AtlasMesh->SetInputConnection(this->AtlasSource()->GetOutputPort());
  this->Reconstruction->SetInputConnection(this->AtlasSource()->GetOutputPort());
  this->UpdateStageAvailability();
  this->setWindowTitle("TriChart Viewer - " + QFileInfo(path).fileName());
  const bool ok = this->ShowStage(stage);
  if (ok)
  {
    this->AddRecentFile(path);
    this->Renderer->ResetCamera();
    this->RenderWindow->Render();
  }
  return ok;
}

bool tcViewerWindow::Execute(vtkAlgorithm* algorithm, int port)
{
  this->Error.clear();
  this->ErrorSource = nullptr;
  this->Running = true;
  this->Cancel->setEnabled(true);
  this->Progress->setValue(0);
  if (algorithm->GetNumberOfOutputPorts() > port)
  {
    algorithm->Update(port);
  }
  else
  {
    algorithm->Update(); // a writer: no output port, Update() is what runs it
  }
  this->Running = false;
  this->Cancel->setEnabled(false);
  bool aborted = false;
  for (vtkAlgorithm* a : this->Filters())
  {
    aborted = aborted || a->GetAbortExecute();
  }
  if (aborted)
  {
    for (vtkAlgorithm* a : this->Filters())
    {
      a->AbortExecuteOff();
      a->Modified(); // the cancelled result must not be reused
    }
    this->Error = "Cancelled";
    return false;
  }
  return this->Error.isEmpty();
}

bool tcViewerWindow::Run(vtkAlgorithm* algorithm, int port)
{
  bool ok = this->Execute(algorithm, port);
  if (!ok && this->ErrorSource == this->PathTracing.GetPointer() &&
    this->PathTracing->GetUntraceable() && !this->RemoveSlivers->isChecked())
  {
    // As `trichart build` does: slivers are what makes the parameterization of a scan or a CAD
    // mesh too thin to trace, so they are removed and the pipeline runs again; the checked box
    // and the note say so.
    const QString first = this->Error;
    const QString reason = QString::fromUtf8(this->PathTracing->GetUntraceableReason());
    this->RemoveSlivers->setChecked(true);
    this->PushParameters();
    ok = this->Execute(algorithm, port);
    if (ok)
    {
      this->Note = "The paths could not be traced (" + reason +
        "); built again with RemoveSlivers on (Preparation).";
    }
    else if (this->Error != "Cancelled")
    {
      this->RemoveSlivers->setChecked(false);
      this->PushParameters();
      this->Error = first + " Built again with RemoveSlivers on, it failed too: " + this->Error;
    }
  }
  if (!ok && this->Error == "Cancelled")
  {
    this->statusBar()->showMessage("Cancelled", 5000);
    return false;
  }
  if (!ok)
  {
    this->ReportError(this->Error);
    return false;
  }
  this->Progress->setValue(100);
  this->statusBar()->showMessage(this->Note.isEmpty() ? QString("Ready") : this->Note);
  return true;
}

bool tcViewerWindow::ShowStage(int stage)
{
  if (this->FileName.isEmpty() || stage < 0 || stage >= StageCount)
  {
    return false;
  }
  bool ok = this->StageAvailable(stage);
  if (!ok)
  {
    this->Error =
      QString("The %1 stage needs an input mesh; %2 is an atlas. Open a mesh to see it.")
        .arg(kStageNames[stage])
        .arg(QFileInfo(this->FileName).fileName());
    this->ReportError(this->Error);
  }
  else
  {
    this->PushParameters();
    ok = this->Run(this->StageAlgorithm(stage));
  }
  if (!ok)
  {
    this->SurfaceActor->VisibilityOff();
    this->LineActor->VisibilityOff();
    this->CornerActor->VisibilityOff();
    this->Legend->VisibilityOff();
    this->HideAtlasPicture();
    this->HideLOD();
    this->HasLines = false;
    this->Info->setText("<font color='#b00'>" + this->Error.toHtmlEscaped() + "</font>");
    this->RenderWindow->Render();
    return false;
  }
  const bool entering = this->CurrentStage != stage;
  this->CurrentStage = stage;
  {
    const QSignalBlocker block(this->Stages);
    this->Stages->setCurrentRow(stage);
    this->Panels->setCurrentIndex(stage);
  }
  // The display options act on the rebuilt surfaces; the LOD stage has its own in its panel.
  for (QWidget* w : { static_cast<QWidget*>(this->ColorBy), static_cast<QWidget*>(this->ShowLines),
         static_cast<QWidget*>(this->ShowCorners), static_cast<QWidget*>(this->ShowEdges) })
  {
    w->setEnabled(stage != LODStage);
  }
  if (stage == LODStage)
  {
    return this->ShowLOD(entering);
  }
  this->HideLOD();
  vtkAlgorithm* algorithm = this->StageAlgorithm(stage);
  auto* surface = vtkPolyData::SafeDownCast(algorithm->GetOutputDataObject(0));
  // Crest lines, cluster boundaries, feature lines and paths are each stage's port 1; the base
  // complex is drawn as its edges over the parameterized input mesh (its port 1), the
  // reconstruction with its own edges over the split surface that carries the distances.
  vtkPolyData* lines = stage >= CurvatureStage && stage <= PatchesStage
    ? vtkPolyData::SafeDownCast(algorithm->GetOutputDataObject(1))
    : nullptr;
  if (stage == BaseStage)
  {
    this->BaseEdges->Update();
    surface = lines;
    lines = this->BaseEdges->GetOutput();
  }
  vtkPolyData* rebuilt = this->Reconstruction->GetOutput();
  if (stage == ReconstructionStage)
  {
    this->RebuiltEdges->Update();
    lines = this->RebuiltEdges->GetOutput();
  }
  // Feature-like lines stand out; the many edges of a reconstruction must not hide its colours.
  this->LineActor->GetProperty()->SetLineWidth(stage == ReconstructionStage ? 1.0 : 2.0);
  this->SurfaceActor->GetProperty()->SetOpacity(stage == BaseStage ? 0.6 : 1.0);
  vtkPolyData* corners = stage == FeaturesStage ? this->Refinement->GetOutput(2) : nullptr;
  auto* atlas = vtkMultiBlockDataSet::SafeDownCast(this->AtlasSource()->GetOutputDataObject(0));
  const bool split = this->RenderWindow->HasRenderer(this->AtlasRenderer);
  if (stage == AtlasStage)
  {
    this->ShowAtlasPicture(atlas);
  }
  else
  {
    this->HideAtlasPicture();
  }
  this->Display(surface, lines, corners);
  if (!split && this->RenderWindow->HasRenderer(this->AtlasRenderer))
  {
    this->Renderer->ResetCamera(); // half the width now: fit the mesh again
  }

  // A reconstruction is counted as rebuilt, not as drawn (split for the distance colours).
  vtkPolyData* counted = stage == ReconstructionStage ? rebuilt : surface;
  QString info = QString("<b>%1</b><br>%2 points, %3 cells")
                   .arg(kStageLabels[stage])
                   .arg(counted->GetNumberOfPoints())
                   .arg(counted->GetNumberOfCells());
  const char* report = stage == InputStage ? this->Reader->GetReport()
    : stage == PreparationStage            ? this->Preparation->GetReport()
                                           : "";
  if (report && *report)
  {
    // The folder is noise in a narrow panel; the file name says which file it is.
    QString text = QString(report).replace(this->FileName, QFileInfo(this->FileName).fileName());
    info += "<br><pre>" + text.toHtmlEscaped() + "</pre>";
  }
  if (stage == PreparationStage && !this->Preparation->GetClosedManifold())
  {
    info += "<br>" + this->ClosedManifoldHint();
  }
  const char* const lineNames[] = { "", "", "crest lines", "boundary polylines", "feature lines",
    "base edges", "paths", "", "", "" };
  static_assert(sizeof(lineNames) / sizeof(*lineNames) == StageCount, "one line name per stage");
  if (lines && *lineNames[stage])
  {
    info += QString("<br>%1 %2").arg(lines->GetNumberOfLines()).arg(lineNames[stage]);
  }
  if (corners)
  {
    info += QString("<br>%1 corners").arg(corners->GetNumberOfPoints());
  }
  if (stage == PatchesStage)
  {
    double range[2] = { 0.0, -1.0 };
    if (vtkDataArray* patches = surface->GetCellData()->GetArray(tc::kPatchId))
    {
      patches->GetRange(range);
    }
    info += QString("<br>%1 patches").arg(static_cast<long long>(range[1]) + 1);
  }
  if (stage == AtlasStage && atlas)
  {
    auto* charts = vtkTable::SafeDownCast(atlas->GetBlock(0));
    auto* images = vtkMultiBlockDataSet::SafeDownCast(atlas->GetBlock(1));
    auto* finest = images ? vtkImageData::SafeDownCast(images->GetBlock(0)) : nullptr;
    vtkDataArray* maxLevel =
      charts ? vtkArrayDownCast<vtkDataArray>(charts->GetColumnByName(tc::kMaxLevel)) : nullptr;
    if (charts && finest && maxLevel)
    {
      int dims[3];
      finest->GetDimensions(dims);
      double levels[2];
      maxLevel->GetRange(levels);
      info += QString("<br>%1 charts, finest levels %2 to %3<br>%4 mip steps, the finest %5 x %6 "
                      "texels<br>(the mesh is every chart at its finest level)")
                .arg(charts->GetNumberOfRows())
                .arg(levels[0])
                .arg(levels[1])
                .arg(images->GetNumberOfBlocks())
                .arg(dims[0])
                .arg(dims[1]);
    }
  }
  if (stage == ReconstructionStage)
  {
    double levels[2] = { 0.0, 0.0 };
    if (vtkDataArray* level = rebuilt->GetCellData()->GetArray(tc::kLevel))
    {
      level->GetRange(levels);
    }
    const QString requested = this->Reconstruction->GetLevel() < 0
      ? "finest"
      : QString::number(this->Reconstruction->GetLevel());
    info += levels[0] == levels[1]
      ? QString("<br>Level %1 (asked: %2)").arg(levels[0]).arg(requested)
      : QString("<br>Levels %1 to %2 (asked: %3)").arg(levels[0]).arg(levels[1]).arg(requested);
    if (this->AtlasFile)
    {
      info += "<br>No distance colouring: an atlas file has no input mesh to measure against.";
    }
    else
    {
      const double diagonal = this->Distance->GetDiagonal() > 0 ? this->Distance->GetDiagonal() : 1;
      info += QString("<br>Distance to the prepared mesh:<br>Hausdorff %1 (%2% of the "
                      "diagonal)<br>RMS %3 (%4%)")
                .arg(this->Distance->GetHausdorff(), 0, 'g', 4)
                .arg(100.0 * this->Distance->GetHausdorff() / diagonal, 0, 'f', 3)
                .arg(this->Distance->GetRmsDistance(), 0, 'g', 4)
                .arg(100.0 * this->Distance->GetRmsDistance() / diagonal, 0, 'f', 3);
    }
  }
  if (!this->Note.isEmpty())
  {
    info += "<br><font color='#a60'>Note: " + this->Note.toHtmlEscaped() + "</font>";
  }
  this->Info->setText(info);
  if (this->Batch)
  {
    std::cout << "trichart-viewer: " << this->InfoText().simplified().toStdString() << "\n";
  }
  return true;
}

void tcViewerWindow::SetReconstructionLevel(int level)
{
  this->Level->setValue(level);
}

QString tcViewerWindow::InfoText() const
{
  return QTextDocumentFragment::fromHtml(this->Info->text()).toPlainText();
}

void tcViewerWindow::ShowAtlasPicture(vtkMultiBlockDataSet* atlas)
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
  if (!this->RenderWindow->HasRenderer(this->AtlasRenderer))
  {
    this->RenderWindow->AddRenderer(this->AtlasRenderer);
    this->Renderer->SetViewport(0.5, 0.0, 1.0, 1.0);
  }
  this->AtlasRenderer->ResetCamera();
}

void tcViewerWindow::HideAtlasPicture()
{
  if (this->RenderWindow->HasRenderer(this->AtlasRenderer))
  {
    this->RenderWindow->RemoveRenderer(this->AtlasRenderer);
    this->Renderer->SetViewport(0.0, 0.0, 1.0, 1.0);
  }
}

void tcViewerWindow::SetInstances(int instances)
{
  this->Instances->setValue(instances);
}

bool tcViewerWindow::ShowLOD(bool entering)
{
  this->SurfaceActor->VisibilityOff();
  this->LineActor->VisibilityOff();
  this->CornerActor->VisibilityOff();
  this->Legend->VisibilityOff();
  this->HideAtlasPicture();
  this->HasLines = false;
  this->Shown = nullptr;

  // The mapper draws a copy, not the pipeline's output: a render during a later pipeline run
  // (progress events repaint the window) must not update the pipeline from inside it.
  vtkDataObject* atlas = this->AtlasSource()->GetOutputDataObject(0);
  if (atlas != this->LODAtlasSource || atlas->GetMTime() != this->LODAtlasTime)
  {
    auto copy = vtkSmartPointer<vtkMultiBlockDataSet>::New();
    copy->DeepCopy(atlas);
    this->LODMapper->SetInputData(copy);
    this->LODAtlasSource = atlas;
    this->LODAtlasTime = atlas->GetMTime();
    // The crowd is laid out from the bounds of one instance.
    this->LODMapper->SetInstanceMatrices(nullptr);
    this->LODMapper->GetBounds(this->LODBounds);
  }
  this->UpdateCrowd();
  this->LODActor->VisibilityOn();
  if (!this->RenderWindow->HasRenderer(this->OverlayRenderer))
  {
    this->RenderWindow->AddRenderer(this->OverlayRenderer);
  }
  if (this->Renderer->GetActiveCamera() != this->LODCamera)
  {
    this->StageCamera = this->Renderer->GetActiveCamera();
    this->Renderer->SetActiveCamera(this->LODCamera);
  }
  if (entering)
  {
    this->FrameCrowd();
  }
  // The statistics come from the frame: the render fills the info text (OnRendered). The
  // panel just shown may resize the 3-D view; the levels depend on its size in pixels, so the
  // layout settles first.
  this->Info->setText(QString("<b>%1</b>").arg(kStageLabels[LODStage]));
  QApplication::processEvents(QEventLoop::ExcludeUserInputEvents);
  this->RenderWindow->Render();
  if (this->Batch)
  {
    std::cout << "trichart-viewer: " << this->InfoText().simplified().toStdString() << "\n";
    // The timings vary from run to run, so the pictures show "-"; they are printed here.
    std::cout << "trichart-viewer: lod timing: LOD selection "
              << 1e3 * this->LODMapper->GetSelectionSeconds() << " ms, 3-D view "
              << 1e3 * this->Renderer->GetLastRenderTimeInSeconds() << " ms\n";
  }
  return true;
}

void tcViewerWindow::HideLOD()
{
  this->LODActor->VisibilityOff();
  this->GroundActor->VisibilityOff();
  if (this->RenderWindow->HasRenderer(this->OverlayRenderer))
  {
    this->RenderWindow->RemoveRenderer(this->OverlayRenderer);
  }
  if (this->StageCamera && this->Renderer->GetActiveCamera() == this->LODCamera)
  {
    this->Renderer->SetActiveCamera(this->StageCamera);
  }
}

void tcViewerWindow::UpdateCrowd()
{
  const int n = this->Instances->value();
  const double* b = this->LODBounds;
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
  this->LODMapper->SetInstanceMatrices(matrices);
  // The ground: the grid's extent plus half a cell around it, just below the feet.
  const double x0 = cx - 0.5 * columns * spacing, x1 = cx + 0.5 * columns * spacing;
  const double z0 = cz - 0.5 * rows * spacing, z1 = cz + 0.5 * rows * spacing;
  const double y = b[2] - 1e-3 * size;
  this->Ground->SetOrigin(x0, y, z1);
  this->Ground->SetPoint1(x1, y, z1);
  this->Ground->SetPoint2(x0, y, z0);
  this->GroundActor->SetVisibility(n > 1 && this->CurrentStage == LODStage);
}

void tcViewerWindow::FrameCrowd()
{
  // From the front (+Z), 35 degrees up and 30 to the side: the rows of a crowd stand out behind
  // one another instead of hiding each other.
  vtkCamera* camera = this->LODCamera;
  const double up = vtkMath::RadiansFromDegrees(35.0), side = vtkMath::RadiansFromDegrees(30.0);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetPosition(std::cos(up) * std::sin(side), std::sin(up), std::cos(up) * std::cos(side));
  camera->SetViewUp(0.0, 1.0, 0.0);
  this->Renderer->ResetCamera();
}

void tcViewerWindow::RenderLOD()
{
  if (this->CurrentStage == LODStage && this->LODActor->GetVisibility())
  {
    this->RenderWindow->Render();
  }
}

void tcViewerWindow::OnRendered(vtkObject*, unsigned long, void*)
{
  if (!this->LODActor->GetVisibility())
  {
    return;
  }
  // The 3-D layer is drawn and the overlay layer is next: these are this frame's figures, except
  // the frame rate, which is the last whole render's (this one is not finished). Timings vary
  // from run to run: batch pictures show "-" in their place (ShowLOD prints them).
  const tcLODMapper* m = this->LODMapper;
  const double seconds = this->Renderer->GetLastRenderTimeInSeconds();
  const QString fps =
    this->Batch || seconds <= 0 ? QString("-") : QString::number(1.0 / seconds, 'f', 1);
  const QString selection =
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
  const int instances = m->GetNumberOfInstances();
  this->LODStatistics->SetInput(QString("fps %1\n%2 triangles drawn\n%3 charts drawn\n%4\n"
                                        "LOD selection %5 ms\n%6 instance%7")
                                  .arg(fps)
                                  .arg(m->GetTrianglesDrawn())
                                  .arg(m->GetChartsDrawn())
                                  .arg(perLevel.join(" | "))
                                  .arg(selection)
                                  .arg(instances)
                                  .arg(instances == 1 ? "" : "s")
                                  .toStdString()
                                  .c_str());
  this->Info->setText(QString("<b>%1</b><br>%2 charts x %3 instance%4<br>fps %5<br>%6 triangles "
                              "drawn<br>%7 charts drawn<br>charts per level: %8<br>LOD "
                              "selection %9 ms")
                        .arg(kStageLabels[LODStage])
                        .arg(m->GetNumberOfCharts())
                        .arg(instances)
                        .arg(instances == 1 ? "" : "s")
                        .arg(fps)
                        .arg(m->GetTrianglesDrawn())
                        .arg(m->GetChartsDrawn())
                        .arg(perLevel.join(" | "))
                        .arg(selection));
}

bool tcViewerWindow::SaveAtlas(const QString& path)
{
  if (this->Running)
  {
    return false;
  }
  if (this->FileName.isEmpty())
  {
    this->Error = "Open a mesh or an atlas first: there is no atlas to save.";
    this->ReportError(this->Error);
    return false;
  }
  // The writer is one more filter of the pipeline: it builds what the atlas needs with progress
  // and cancel, and reports its errors like any stage.
  this->PushParameters();
  this->AtlasWriter->SetInputConnection(this->AtlasSource()->GetOutputPort());
  this->AtlasWriter->SetFileName(path.toStdString().c_str());
  this->AtlasWriter->Modified(); // write even when nothing upstream changed
  if (!this->Run(this->AtlasWriter))
  {
    return false;
  }
  if (this->AtlasWriter->GetErrorCode() != vtkErrorCode::NoError)
  {
    this->Error = "Cannot write the atlas " + path;
    this->ReportError(this->Error);
    return false;
  }
  this->statusBar()->showMessage("Saved the atlas as " + path, 5000);
  return true;
}

void tcViewerWindow::Display(vtkPolyData* surface, vtkPolyData* lines, vtkPolyData* corners)
{
  this->Shown = vtkSmartPointer<vtkPolyData>::New();
  this->Shown->ShallowCopy(surface);
  if (this->CurrentStage >= CurvatureStage && this->CurrentStage <= PatchesStage &&
    surface->GetPointData()->GetNormals() && surface->GetNumberOfPolys() > 0)
  {
    // These stages' Normals are fitted across creases, which shades a CAD edge as a dark band:
    // draw with normals split where faces meet at 45 degrees or more (the crease angle of the
    // geometry images' error). What is exported stays the stage's own data. (The atlas and its
    // reconstruction are drawn with the atlas's normals, one-sided along feature lines.)
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
  this->HasLines = lines != nullptr;
  if (lines)
  {
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    copy->ShallowCopy(lines);
    this->LineMapper->SetInputData(copy);
  }
  this->LineActor->SetVisibility(lines != nullptr && this->ShowLines->isChecked());
  if (corners)
  {
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    copy->ShallowCopy(corners);
    auto* glyphs = static_cast<vtkGlyph3DMapper*>(this->CornerActor->GetMapper());
    glyphs->SetInputData(copy);
    this->CornerSphere->SetRadius(0.008 * surface->GetLength());
  }
  this->CornerActor->SetVisibility(corners != nullptr && this->ShowCorners->isChecked());
  this->FillArrayChoices(this->Shown);
}

void tcViewerWindow::FillArrayChoices(vtkPolyData* surface)
{
  const QString previous = this->ColorBy->currentText();
  {
    const QSignalBlocker block(this->ColorBy);
    this->ColorBy->clear();
    this->ColorBy->addItem("Solid");
    for (int i = 0; i < surface->GetPointData()->GetNumberOfArrays(); ++i)
    {
      vtkDataArray* a = surface->GetPointData()->GetArray(i);
      if (a && a->GetName() && a != surface->GetPointData()->GetNormals())
      {
        this->ColorBy->addItem(a->GetName());
      }
    }
    for (int i = 0; i < surface->GetCellData()->GetNumberOfArrays(); ++i)
    {
      vtkDataArray* a = surface->GetCellData()->GetArray(i);
      if (a && a->GetName())
      {
        this->ColorBy->addItem(QString("cell:") + a->GetName());
      }
    }
  }
  // Each stage opens on its own result: base faces, clusters, or mean curvature.
  QString choice = previous;
  const QString clusters = QString("cell:") + tc::kClusterId;
  const QString charts = QString("cell:") + tc::kChartId;
  if (this->CurrentStage == BaseStage)
  {
    choice = tc::kBaseFaceId;
  }
  else if (this->CurrentStage == PatchesStage)
  {
    choice = QString("cell:") + tc::kPatchId;
  }
  else if (this->CurrentStage == AtlasStage)
  {
    choice = charts;
  }
  else if (this->CurrentStage == ReconstructionStage)
  {
    choice = this->ColorBy->findText(tc::kDistance) >= 0 ? QString(tc::kDistance) : charts;
  }
  else if (this->ColorBy->findText(clusters) >= 0)
  {
    choice = clusters;
  }
  else if (this->ColorBy->findText(tc::kMeanCurvature) >= 0)
  {
    choice = tc::kMeanCurvature;
  }
  else if (this->ColorBy->findText(choice) < 0)
  {
    choice = "Solid";
  }
  this->SetColorArray(choice);
}

void tcViewerWindow::SetColorArray(const QString& name)
{
  {
    const QSignalBlocker block(this->ColorBy);
    const int index = this->ColorBy->findText(name);
    this->ColorBy->setCurrentIndex(std::max(0, index));
  }
  const bool cell = name.startsWith("cell:");
  const QString arrayName = cell ? name.mid(5) : name;
  vtkDataArray* values = !this->Shown ? nullptr
    : cell ? this->Shown->GetCellData()->GetArray(arrayName.toStdString().c_str())
           : this->Shown->GetPointData()->GetArray(arrayName.toStdString().c_str());
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
  this->Legend->SetVisibility(!labels && this->CurrentStage != LODStage);
}

void tcViewerWindow::ResetCamera()
{
  if (this->CurrentStage == LODStage && this->LODActor->GetVisibility())
  {
    this->FrameCrowd();
    return;
  }
  this->Renderer->ResetCamera();
}

bool tcViewerWindow::SaveScreenshot(const QString& path)
{
  this->RenderWindow->Render();
  QApplication::processEvents();
  const QImage image = this->grab().toImage();
  return !image.isNull() && image.save(path, "PNG");
}

void tcViewerWindow::ReportError(const QString& message)
{
  this->statusBar()->showMessage("Error: " + message.left(200), 10000);
  if (this->Batch)
  {
    std::cerr << "trichart-viewer: error: " << message.toStdString() << "\n";
  }
  else
  {
    QMessageBox::warning(this, "TriChart", message);
  }
}

void tcViewerWindow::AddRecentFile(const QString& path)
{
  QSettings settings("TriChart", "trichart-viewer");
  QStringList files = settings.value("recentFiles").toStringList();
  files.removeAll(QFileInfo(path).absoluteFilePath());
  files.prepend(QFileInfo(path).absoluteFilePath());
  settings.setValue("recentFiles", QStringList(files.mid(0, 8)));
  this->UpdateRecentMenu();
}

void tcViewerWindow::UpdateRecentMenu()
{
  this->RecentMenu->clear();
  QSettings settings("TriChart", "trichart-viewer");
  for (const QString& path : settings.value("recentFiles").toStringList())
  {
    QAction* a = this->RecentMenu->addAction(path);
    connect(a, &QAction::triggered, this,
      [this, path]() { this->OpenFile(path, std::max(0, this->CurrentStage)); });
  }
  this->RecentMenu->setEnabled(!this->RecentMenu->isEmpty());
}

void tcViewerWindow::dragEnterEvent(QDragEnterEvent* event)
{
  if (event->mimeData()->hasUrls())
  {
    event->acceptProposedAction();
  }
}

void tcViewerWindow::dropEvent(QDropEvent* event)
{
  const QList<QUrl> urls = event->mimeData()->urls();
  if (!urls.isEmpty() && urls.first().isLocalFile())
  {
    this->OpenFile(urls.first().toLocalFile(), std::max(0, this->CurrentStage));
  }
}

void tcViewerWindow::OnProgress(vtkObject* caller, unsigned long, void*)
{
  auto* algorithm = static_cast<vtkAlgorithm*>(caller);
  this->Progress->setValue(static_cast<int>(100 * algorithm->GetProgress()));
  this->statusBar()->showMessage(QString("Running %1...").arg(algorithm->GetClassName()));
  // Keep the window (and its Cancel button) responsive during long runs.
  QApplication::processEvents(QEventLoop::ExcludeUserInputEvents);
  QApplication::processEvents();
}

void tcViewerWindow::OnError(vtkObject* caller, unsigned long, void* callData)
{
  if (callData && this->Error.isEmpty())
  {
    this->ErrorSource = caller;
    // VTK prefixes the message with "ERROR: In file, line N\nclass (address): ".
    QString text = QString::fromUtf8(static_cast<const char*>(callData)).trimmed();
    const int colon = text.indexOf("): ");
    this->Error = colon >= 0 ? text.mid(colon + 3).trimmed() : text;
  }
}
