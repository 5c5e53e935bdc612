// SPDX-License-Identifier: BSD-3-Clause
#include "tcViewerWindow.h"

#include "tcAnimationControls.h"
#include "tcLODView.h"
#include "tcMeshPreparation.h"
#include "tcMeshReader.h"
#include "tcParameterPanel.h"
#include "tcStagePanels.h"
#include "tcStagePipeline.h"
#include "tcStageSummary.h"
#include "tcStageView.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
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

#include "tcMeshWriter.h"
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <iostream>

tcViewerWindow::tcViewerWindow()
  : Pipeline(new tcStagePipeline)
{
  this->Pipeline->SetProgressCallback(
    [this](const char* filter, double progress) { this->OnProgress(filter, progress); });
  this->BuildUi();
  this->setAcceptDrops(true);
}

tcViewerWindow::~tcViewerWindow() = default;

QStringList tcViewerWindow::StageNames()
{
  QStringList names;
  for (int s = 0; s < tcStage::Count; ++s)
  {
    names << tcStage::Name(s);
  }
  return names;
}

int tcViewerWindow::StageFromName(const QString& name)
{
  for (int s = 0; s < tcStage::Count; ++s)
  {
    if (name.compare(tcStage::Name(s), Qt::CaseInsensitive) == 0)
    {
      return s;
    }
  }
  return -1;
}

bool tcViewerWindow::IsAtlasFile(const QString& path)
{
  return tcStagePipeline::IsAtlasFile(path.toStdString());
}

void tcViewerWindow::SetBatchMode(bool batch)
{
  this->Batch = batch;
  this->LODView->SetBatchMode(batch);
}

void tcViewerWindow::BuildUi()
{
  this->setWindowTitle("TriChart Viewer");
  this->resize(1100, 780);
  this->BuildView();

  // Pipeline panel: stages, their parameters, apply, display options, summary.
  auto* dock = new QDockWidget("Pipeline", this);
  dock->setObjectName("PipelineDock");
  dock->setFeatures(QDockWidget::NoDockWidgetFeatures);
  auto* panel = new QWidget(dock);
  auto* layout = new QVBoxLayout(panel);
  this->BuildStageList(panel, layout);
  this->BuildPanels(panel, layout);
  auto* apply = new QPushButton("Apply", panel);
  layout->addWidget(apply);
  this->BuildDisplayOptions(panel, layout);
  this->BuildSummary(panel, layout);
  dock->setWidget(panel);
  dock->setMinimumWidth(260);
  this->addDockWidget(Qt::LeftDockWidgetArea, dock);
  this->ConnectPipelineDock(apply);

  this->BuildProgress();
  this->BuildFileMenu();
}

void tcViewerWindow::BuildView()
{
  this->View = new QVTKOpenGLNativeWidget(this);
  this->View->setRenderWindow(this->RenderWindow);
  this->RenderWindow->AddRenderer(this->Renderer);
  this->Renderer->SetBackground(0.32, 0.34, 0.43);
  this->StageView = std::make_unique<tcStageView>(this->RenderWindow, this->Renderer);
  this->setCentralWidget(this->View);
  this->LODView = std::make_unique<tcLODView>(this->RenderWindow, this->Renderer);
  this->LODView->SetFrameCallback(
    [this](const tcLODFrame& frame) { this->Info->setText(tcStageSummary::LOD(frame)); });
  this->StageView->UseInteractor(this->View->interactor());
}

void tcViewerWindow::BuildStageList(QWidget* panel, QVBoxLayout* layout)
{
  this->Stages = new QListWidget(panel);
  for (int s = 0; s < tcStage::Count; ++s)
  {
    this->Stages->addItem(tcStage::Label(s));
  }
  // Every stage in view without scrolling; the parameter panel below takes what is left.
  this->Stages->setFixedHeight(
    this->Stages->sizeHintForRow(0) * this->Stages->count() + 2 * this->Stages->frameWidth() + 2);
  layout->addWidget(new QLabel("<b>Stages</b>", panel));
  layout->addWidget(this->Stages);
}

void tcViewerWindow::BuildPanels(QWidget* panel, QVBoxLayout* layout)
{
  // One page per stage, in stage order.
  tcStagePipeline* p = this->Pipeline.get();
  this->Panels = new QStackedWidget(panel);
  this->Panels->addWidget(new QLabel(
    "Reads .ply, .ply.gz, .obj, .stl,\n.off, .vtp and .vtk files, and the\nsurfaces "
    "of scene files in their\nrest pose: .glb, .gltf, .fbx, .x\nand .md2; terrain rasters "
    ".tif,\n.asc, .hgt, .dem, .pgm, .png\nand .bmp (VerticalScale: under\nPreparation).",
    panel));
  this->Panels->addWidget(tcStagePanels::Preparation(p->GetReader(), p->GetPreparation(), this));
  this->Panels->addWidget(tcStagePanels::Curvature(p->GetCurvature(), this));
  this->Panels->addWidget(tcStagePanels::Clustering(p->GetClustering(), this));
  this->Panels->addWidget(tcStagePanels::Refinement(p->GetRefinement(), this));
  this->Panels->addWidget(tcStagePanels::BaseComplex(p->GetBaseComplex(), this));
  this->Panels->addWidget(new QLabel(
    "No parameters: each base edge is traced\nonto the mesh, which is cut into one\ntriangle "
    "patch per base face.",
    panel));
  this->Panels->addWidget(tcStagePanels::GeometryImages(p->GetGeometryImages(), this));
  this->Panels->addWidget(tcStagePanels::Reconstruction(p->GetReconstruction(), this));
  this->Panels->addWidget(tcStagePanels::LOD(
    this->LODView.get(),
    [this]()
    {
      this->ResetCamera();
      this->LODView->Render();
    },
    this));
  this->AnimationControls = this->ParameterPanel(tcStage::LOD)->findChild<tcAnimationControls*>();
  // The parameters scroll rather than grow the window past its size (screenshots keep one
  // size whatever the tallest panel holds); ConnectPipelineDock keeps the area as tall as the
  // shown panel.
  this->PanelScroll = new QScrollArea(panel);
  this->PanelScroll->setFrameShape(QFrame::NoFrame);
  this->PanelScroll->setWidgetResizable(true);
  this->PanelScroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  this->PanelScroll->setWidget(this->Panels);
  this->PanelScroll->setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Maximum);
  layout->addWidget(this->PanelScroll);
}

void tcViewerWindow::BuildDisplayOptions(QWidget* panel, QVBoxLayout* layout)
{
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
}

void tcViewerWindow::BuildSummary(QWidget* panel, QVBoxLayout* layout)
{
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
}

void tcViewerWindow::ConnectPipelineDock(QPushButton* apply)
{
  // The panel stack is as tall as the shown panel, not as the tallest one, so that the summary
  // below it has room.
  connect(
    this->Panels, &QStackedWidget::currentChanged, this, [this](int) { this->FitPanelScroll(); });
  this->FitPanelScroll();
  connect(this->Stages, &QListWidget::currentRowChanged, this,
    [this](int row)
    {
      this->Panels->setCurrentIndex(std::max(0, row));
      if (!this->Running && this->Pipeline->StageAvailable(row) && row != this->CurrentStage &&
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
      this->StageView->SetLinesVisible(on);
      this->RenderWindow->Render();
    });
  connect(this->ShowCorners, &QCheckBox::toggled, this,
    [this](bool on)
    {
      this->StageView->SetCornersVisible(on);
      this->RenderWindow->Render();
    });
  connect(this->ShowEdges, &QCheckBox::toggled, this,
    [this](bool on)
    {
      this->StageView->SetEdgesVisible(on);
      this->RenderWindow->Render();
    });
}

void tcViewerWindow::FitPanelScroll()
{
  const int index = this->Panels->currentIndex();
  for (int i = 0; i < this->Panels->count(); ++i)
  {
    const auto policy = i == index ? QSizePolicy::Preferred : QSizePolicy::Ignored;
    this->Panels->widget(i)->setSizePolicy(policy, policy);
  }
  this->Panels->adjustSize();
  // Short panels whole; a tall one to 14 lines of text, the rest scrolled, so that the summary
  // below keeps its lines and the window its size.
  const int height = this->Panels->currentWidget()->sizeHint().height();
  this->PanelScroll->setMaximumHeight(height);
  this->PanelScroll->setMinimumHeight(
    std::min(height, 14 * this->PanelScroll->fontMetrics().lineSpacing()));
}

void tcViewerWindow::BuildProgress()
{
  this->Progress = new QProgressBar(this);
  this->Progress->setRange(0, 100);
  this->Progress->setMaximumWidth(250);
  this->Cancel = new QPushButton("Cancel", this);
  this->Cancel->setEnabled(false);
  this->statusBar()->addPermanentWidget(this->Progress);
  this->statusBar()->addPermanentWidget(this->Cancel);
  connect(this->Cancel, &QPushButton::clicked, this, [this]() { this->Pipeline->Abort(); });
}

void tcViewerWindow::BuildFileMenu()
{
  QMenu* file = this->menuBar()->addMenu("&File");
  QAction* open = file->addAction("&Open...");
  open->setShortcut(QKeySequence::Open);
  connect(open, &QAction::triggered, this, &tcViewerWindow::OpenDialog);
  this->RecentMenu = file->addMenu("Open &Recent");
  this->UpdateRecentMenu();
  QAction* exportStage = file->addAction("&Export stage...");
  connect(exportStage, &QAction::triggered, this, &tcViewerWindow::ExportStage);
  QAction* exportGltf = file->addAction("Export LOD chain as &glTF...");
  connect(exportGltf, &QAction::triggered, this, &tcViewerWindow::ExportGltfDialog);
  QAction* saveAtlas = file->addAction("Save &atlas...");
  connect(saveAtlas, &QAction::triggered, this, &tcViewerWindow::SaveAtlasDialog);
  QAction* shot = file->addAction("Save &screenshot...");
  connect(shot, &QAction::triggered, this, &tcViewerWindow::ScreenshotDialog);
  file->addSeparator();
  QAction* quit = file->addAction("&Quit");
  quit->setShortcut(QKeySequence::Quit);
  connect(quit, &QAction::triggered, qApp, &QApplication::quit);
}

void tcViewerWindow::OpenDialog()
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
    this->OpenChosenFile(path);
  }
}

void tcViewerWindow::OpenChosenFile(const QString& path)
{
  // The command line's pose is for the files it names.
  this->PoseAnimation.reset();
  this->PoseTime.reset();
  this->OpenFile(path, std::max(0, this->CurrentStage));
}

void tcViewerWindow::ExportStage()
{
  if (this->CurrentStage == tcStage::LOD)
  {
    this->ReportError("The LOD stage draws the atlas on the GPU and builds no mesh: export "
                      "the reconstruction stage, or save the atlas.");
    return;
  }
  vtkPolyData* shown = this->StageView->GetShown();
  if (!shown)
  {
    return;
  }
  // The formats tcMeshWriter writes; the name's extension chooses one (as on the command line).
  QStringList patterns;
  for (const QString& extension : QString(tcMeshWriter::GetSupportedExtensions()).split(' '))
  {
    patterns << "*" + extension;
  }
  const QString path = QFileDialog::getSaveFileName(this, "Export stage",
    QString(tcStage::Name(this->CurrentStage)) + ".vtp",
    "Meshes (" + patterns.join(' ') + ");;All files (*)");
  if (path.isEmpty())
  {
    return;
  }
  if (!tcMeshWriter::IsMeshFileName(path.toStdString().c_str()))
  {
    this->ReportError("Cannot write " + path + ": name the file with one of " +
      QString(tcMeshWriter::GetSupportedExtensions()) + " (the format follows the extension)");
    return;
  }
  if (this->Run(this->Pipeline->MeshWriterFor(shown, path.toStdString())) &&
    !this->Pipeline->MeshWritten())
  {
    this->ReportError("Cannot write " + path);
  }
}

void tcViewerWindow::ExportGltfDialog()
{
  if (this->FileName.isEmpty())
  {
    this->ReportError("Open a mesh or an atlas first: there is no atlas to export.");
    return;
  }
  const QString path = QFileDialog::getSaveFileName(this, "Export LOD chain as glTF",
    QFileInfo(this->FileName).completeBaseName() + ".glb", "glTF (*.glb *.gltf)");
  if (!path.isEmpty())
  {
    this->ExportGltf(path);
  }
}

bool tcViewerWindow::ExportGltf(const QString& path)
{
  this->PushParameters();
  if (!this->Run(this->Pipeline->GltfWriterFor(path.toStdString())))
  {
    return false;
  }
  if (!this->Pipeline->GltfWritten())
  {
    this->Error = "Cannot write the glTF file " + path;
    this->ReportError(this->Error);
    return false;
  }
  this->statusBar()->showMessage("Exported the LOD chain as " + path, 5000);
  return true;
}

void tcViewerWindow::SaveAtlasDialog()
{
  if (this->FileName.isEmpty())
  {
    this->ReportError("Open a mesh or an atlas first: there is no atlas to save.");
    return;
  }
  const QString path = QFileDialog::getSaveFileName(
    this, "Save atlas", QFileInfo(this->FileName).completeBaseName() + ".exr", "Atlases (*.exr)");
  if (!path.isEmpty())
  {
    this->SaveAtlas(path);
  }
}

void tcViewerWindow::ScreenshotDialog()
{
  const QString path =
    QFileDialog::getSaveFileName(this, "Save screenshot", "trichart.png", "PNG (*.png)");
  if (!path.isEmpty() && !this->SaveScreenshot(path))
  {
    this->ReportError("Cannot write " + path);
  }
}

tcParameterPanel* tcViewerWindow::ParameterPanel(int stage) const
{
  return dynamic_cast<tcParameterPanel*>(this->Panels->widget(stage));
}

void tcViewerWindow::UpdateStageAvailability()
{
  for (int s = 0; s < tcStage::Count; ++s)
  {
    QListWidgetItem* item = this->Stages->item(s);
    const bool available = this->Pipeline->StageAvailable(s);
    item->setFlags(
      available ? item->flags() | Qt::ItemIsEnabled : item->flags() & ~Qt::ItemIsEnabled);
    item->setToolTip(available ? QString() : "Needs an input mesh: an atlas file is open");
  }
  // An opened atlas is shown as it is: its geometry-image parameters cannot change.
  const bool atlasFile = this->Pipeline->HasAtlasFile();
  QWidget* geometryImages = this->Panels->widget(tcStage::Atlas);
  geometryImages->setEnabled(!atlasFile);
  geometryImages->setToolTip(
    atlasFile ? "The atlas comes from a file: open a mesh to build a new one" : QString());
}

void tcViewerWindow::PushParameters()
{
  for (int s = 0; s < tcStage::LOD; ++s)
  {
    if (tcParameterPanel* panel = this->ParameterPanel(s))
    {
      panel->Push();
    }
  }
}

bool tcViewerWindow::OpenFile(const QString& path, int stage)
{
  this->FileName = path;
  this->Pipeline->Open(path.toStdString());
  if (this->Pipeline->HasAtlasFile())
  {
    // An atlas has no input mesh: it opens on its reconstruction unless the atlas or its LOD
    // view is asked for.
    stage = stage == tcStage::Atlas || stage == tcStage::LOD ? stage : tcStage::Reconstruction;
  }
  this->UpdateStageAvailability();
  this->setWindowTitle("TriChart Viewer - " + QFileInfo(path).fileName());
  const bool ok = this->ShowStage(stage);
  if (ok)
  {
    this->AddRecentFile(path);
    this->CameraView.Apply(this->Renderer); // the default view: ResetCamera alone
    this->RenderWindow->Render();
  }
  return ok;
}

bool tcViewerWindow::Run(vtkAlgorithm* algorithm)
{
  this->Running = true;
  this->Cancel->setEnabled(true);
  this->Progress->setValue(0);
  const bool ok = this->Pipeline->Run(algorithm);
  this->Running = false;
  this->Cancel->setEnabled(false);
  // The sliver retry may have turned RemoveSlivers on: the box says so, and later runs keep it.
  this->ParameterPanel(tcStage::Preparation)
    ->Field<QCheckBox>("RemoveSlivers")
    ->setChecked(this->Pipeline->GetPreparation()->GetRemoveSlivers());
  this->Error = QString::fromStdString(this->Pipeline->GetError());
  if (!ok && this->Pipeline->Cancelled())
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
  const QString note = QString::fromStdString(this->Pipeline->GetNote());
  this->statusBar()->showMessage(note.isEmpty() ? QString("Ready") : note);
  return true;
}

bool tcViewerWindow::RunStage(int stage)
{
  if (!this->Pipeline->StageAvailable(stage))
  {
    this->Error =
      QString("The %1 stage needs an input mesh; %2 is an atlas. Open a mesh to see it.")
        .arg(tcStage::Name(stage))
        .arg(QFileInfo(this->FileName).fileName());
    this->ReportError(this->Error);
    return false;
  }
  this->PushParameters();
  return this->Run(this->Pipeline->StageAlgorithm(stage));
}

bool tcViewerWindow::ShowStage(int stage)
{
  if (this->FileName.isEmpty() || stage < 0 || stage >= tcStage::Count)
  {
    return false;
  }
  if (!this->RunStage(stage))
  {
    this->ShowFailure();
    return false;
  }
  const bool entering = this->CurrentStage != stage;
  this->CurrentStage = stage;
  this->SelectStage(stage);
  if (stage == tcStage::LOD)
  {
    return this->ShowLOD(entering);
  }
  this->LODView->Hide();
  const tcStageOutput output = this->Pipeline->Output(stage);
  this->StageView->Show(stage, output);
  this->FillArrayChoices();
  this->Info->setText(tcStageSummary::Stage(*this->Pipeline, stage, output, this->FileName));
  this->PrintSummary();
  return true;
}

void tcViewerWindow::ShowFailure()
{
  this->StageView->Hide();
  this->LODView->Hide();
  this->Info->setText(tcStageSummary::Failure(this->Error));
  this->RenderWindow->Render();
}

void tcViewerWindow::SelectStage(int stage)
{
  {
    const QSignalBlocker block(this->Stages);
    this->Stages->setCurrentRow(stage);
    this->Panels->setCurrentIndex(stage);
  }
  // The display options act on the rebuilt surfaces; the LOD stage has its own in its panel.
  for (QWidget* w : { static_cast<QWidget*>(this->ColorBy), static_cast<QWidget*>(this->ShowLines),
         static_cast<QWidget*>(this->ShowCorners), static_cast<QWidget*>(this->ShowEdges) })
  {
    w->setEnabled(stage != tcStage::LOD);
  }
}

bool tcViewerWindow::ShowLOD(bool entering)
{
  this->StageView->Hide();
  this->StageView->Forget();
  if (this->LODView->Show(this->Pipeline->AtlasSource()->GetOutputDataObject(0), entering))
  {
    if (!this->ApplyPose())
    {
      this->ShowFailure();
      return false;
    }
    // Framed anew: the bounds are those of the pose just chosen.
    if (entering)
    {
      this->LODView->Frame();
    }
  }
  // The animation box shows for a skinned atlas only: the panel's height follows.
  this->AnimationControls->Sync();
  this->FitPanelScroll();
  // The statistics come from the frame: the render fills the summary (the LOD view's frame
  // callback). The panel just shown may resize the 3-D view; the levels depend on its size in
  // pixels, so the layout settles first.
  this->Info->setText(tcStageSummary::Title(tcStage::LOD));
  QApplication::processEvents(QEventLoop::ExcludeUserInputEvents);
  if (!this->AnimationControls->isHidden())
  {
    // The panel scrolls past its 14 lines: a skinned atlas brings its animation box into view.
    this->PanelScroll->ensureWidgetVisible(this->AnimationControls, 0, 0);
  }
  this->RenderWindow->Render();
  if (this->Batch)
  {
    this->PrintSummary();
    // The timings vary from run to run, so the pictures show "-"; they are printed here.
    std::cout << "trichart-viewer: lod timing: LOD selection "
              << this->LODView->GetSelectionMilliseconds() << " ms, 3-D view "
              << this->LODView->GetRenderMilliseconds() << " ms\n";
  }
  return true;
}

bool tcViewerWindow::ApplyPose()
{
  if (!this->PoseAnimation && !this->PoseTime)
  {
    return true;
  }
  QString error;
  const int index = this->LODView->FindAnimation(this->PoseAnimation.value_or(""), error);
  if (index >= 0)
  {
    this->LODView->SetAnimation(index);
    const double duration = this->LODView->GetAnimationDuration();
    const double t = this->PoseTime.value_or(0.0);
    if (t > duration)
    {
      error = QString("the time %1 s is past the end of the animation '%2' (%3 s)")
                .arg(QString::number(t), this->LODView->GetAnimationNames()[index],
                  QString::number(duration));
    }
    this->LODView->SetAnimationTime(t);
  }
  if (error.isEmpty())
  {
    return true;
  }
  this->Error =
    QString("Cannot pose %1 as asked: %2").arg(QFileInfo(this->FileName).fileName(), error);
  this->ReportError(this->Error);
  return false;
}

void tcViewerWindow::PrintSummary() const
{
  if (this->Batch)
  {
    std::cout << "trichart-viewer: " << this->InfoText().simplified().toStdString() << "\n";
  }
}

void tcViewerWindow::SetReconstructionLevel(int level)
{
  this->ParameterPanel(tcStage::Reconstruction)->Field<QSpinBox>("Level")->setValue(level);
}

void tcViewerWindow::SetVerticalScale(double scale)
{
  this->ParameterPanel(tcStage::Preparation)
    ->Field<QDoubleSpinBox>("VerticalScale")
    ->setValue(scale);
  this->Pipeline->GetReader()->SetVerticalScale(scale);
}

void tcViewerWindow::SetInstances(int instances)
{
  this->ParameterPanel(tcStage::LOD)->Field<QSpinBox>("Crowd instances")->setValue(instances);
}

QString tcViewerWindow::InfoText() const
{
  return QTextDocumentFragment::fromHtml(this->Info->text()).toPlainText();
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
  this->PushParameters();
  if (!this->Run(this->Pipeline->AtlasWriterFor(path.toStdString())))
  {
    return false;
  }
  if (!this->Pipeline->AtlasWritten())
  {
    this->Error = "Cannot write the atlas " + path;
    this->ReportError(this->Error);
    return false;
  }
  this->statusBar()->showMessage("Saved the atlas as " + path, 5000);
  return true;
}

void tcViewerWindow::FillArrayChoices()
{
  const QString previous = this->ColorBy->currentText();
  const QStringList choices = this->StageView->ColorChoices();
  {
    const QSignalBlocker block(this->ColorBy);
    this->ColorBy->clear();
    this->ColorBy->addItems(choices);
  }
  this->SetColorArray(tcStageView::DefaultColor(this->CurrentStage, choices, previous));
}

void tcViewerWindow::SetColorArray(const QString& name)
{
  // The LOD view's own colour modes: its texture for "Texture" (the stages' choice).
  if (this->CurrentStage == tcStage::LOD && name == "Texture")
  {
    this->ParameterPanel(tcStage::LOD)->Field<QComboBox>("Colour by")->setCurrentText("texture");
  }
  {
    const QSignalBlocker block(this->ColorBy);
    const int index = this->ColorBy->findText(name);
    this->ColorBy->setCurrentIndex(std::max(0, index));
  }
  this->StageView->ColorBy(name);
}

void tcViewerWindow::ResetCamera()
{
  if (this->CurrentStage == tcStage::LOD && this->LODView->IsShown())
  {
    this->LODView->Frame();
    return;
  }
  this->CameraView.Apply(this->Renderer);
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
    connect(a, &QAction::triggered, this, [this, path]() { this->OpenChosenFile(path); });
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
    this->OpenChosenFile(urls.first().toLocalFile());
  }
}

void tcViewerWindow::OnProgress(const char* filter, double progress)
{
  this->Progress->setValue(static_cast<int>(100 * progress));
  this->statusBar()->showMessage(QString("Running %1...").arg(filter));
  // Keep the window (and its Cancel button) responsive during long runs.
  QApplication::processEvents(QEventLoop::ExcludeUserInputEvents);
  QApplication::processEvents();
}
