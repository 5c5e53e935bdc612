// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcViewerWindow
 * @brief The main window of trichart-viewer: a stage browser over the TriChart pipeline.
 *
 * The pipeline is tcMeshReader -> tcMeshPreparation -> tcCurvature -> tcSpectralClustering ->
 * tcFeatureRefinement -> tcBaseComplex. Selecting a stage shows
 * its output; its parameters are edited in the panel and "Apply" re-runs what changed (the
 * VTK pipeline's modified times decide). Long runs show progress and can be cancelled;
 * errors are shown in the window, which stays usable.
 */
#ifndef tcViewerWindow_h
#define tcViewerWindow_h

#include <QMainWindow>

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <string>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QListWidget;
class QMenu;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QStackedWidget;
class QVTKOpenGLNativeWidget;
class tcCurvature;
class tcBaseComplex;
class tcFeatureRefinement;
class tcSpectralClustering;
class tcMeshPreparation;
class tcMeshReader;
class vtkActor;
class vtkAlgorithm;
class vtkExtractEdges;
class vtkGenericOpenGLRenderWindow;
class vtkObject;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkRenderer;
class vtkScalarBarActor;
class vtkSphereSource;

class tcViewerWindow : public QMainWindow
{
  Q_OBJECT
public:
  /// The stages of the browser, in pipeline order.
  enum Stage
  {
    InputStage = 0,
    PreparationStage,
    CurvatureStage,
    ClustersStage,
    FeaturesStage,
    BaseStage,
    StageCount
  };

  tcViewerWindow();
  ~tcViewerWindow() override;

  /// Stage from its command-line name ("input", "preparation", "curvature", "clusters",
  /// "features", "base"); -1 if unknown.
  static int StageFromName(const QString& name);

  /// Opens a mesh and shows `stage`; false (with the error shown) on failure.
  bool OpenFile(const QString& path, int stage = CurvatureStage);

  /// Runs the pipeline up to `stage` and shows its output; false on error or cancel.
  bool ShowStage(int stage);

  /// Colours the surface by this array of the shown output ("" for a plain surface).
  void SetColorArray(const QString& name);

  /// Renders and saves the whole window as PNG.
  bool SaveScreenshot(const QString& path);

  /// The last error message ("" if the last run succeeded).
  QString LastError() const { return this->Error; }

  /// In batch mode errors go to stderr instead of a dialog.
  void SetBatchMode(bool batch) { this->Batch = batch; }

protected:
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

private:
  void BuildUi();
  QWidget* BuildPreparationPanel();
  QWidget* BuildCurvaturePanel();
  QWidget* BuildClusteringPanel();
  QWidget* BuildRefinementPanel();
  QWidget* BuildBaseComplexPanel();
  vtkAlgorithm* StageAlgorithm(int stage) const;
  void PushParameters();
  bool Run(vtkAlgorithm* algorithm, int port = 0);
  void Display(vtkPolyData* surface, vtkPolyData* lines, vtkPolyData* corners);
  void FillArrayChoices(vtkPolyData* surface);
  void ReportError(const QString& message);
  void AddRecentFile(const QString& path);
  void UpdateRecentMenu();
  void OnProgress(vtkObject* caller, unsigned long, void*);
  void OnError(vtkObject* caller, unsigned long, void* callData);

  vtkNew<tcMeshReader> Reader;
  vtkNew<tcMeshPreparation> Preparation;
  vtkNew<tcCurvature> Curvature;
  vtkNew<tcSpectralClustering> Clustering;
  vtkNew<tcFeatureRefinement> Refinement;
  vtkNew<tcBaseComplex> BaseComplex;
  vtkNew<vtkExtractEdges> BaseEdges;
  vtkNew<vtkGenericOpenGLRenderWindow> RenderWindow;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkPolyDataMapper> SurfaceMapper;
  vtkNew<vtkActor> SurfaceActor;
  vtkNew<vtkPolyDataMapper> LineMapper;
  vtkNew<vtkActor> LineActor;
  vtkNew<vtkPolyDataMapper> CornerMapper;
  vtkNew<vtkActor> CornerActor;
  vtkNew<vtkSphereSource> CornerSphere;
  vtkNew<vtkScalarBarActor> Legend;
  vtkSmartPointer<vtkPolyData> Shown;

  QVTKOpenGLNativeWidget* View = nullptr;
  QListWidget* Stages = nullptr;
  QStackedWidget* Panels = nullptr;
  QComboBox* ColorBy = nullptr;
  QCheckBox* ShowLines = nullptr;
  QCheckBox* ShowEdges = nullptr;
  QCheckBox* ShowCorners = nullptr;
  QProgressBar* Progress = nullptr;
  QPushButton* Cancel = nullptr;
  QLabel* Info = nullptr;
  QMenu* RecentMenu = nullptr;
  QDoubleSpinBox* MergeTolerance = nullptr;
  QCheckBox* Orient = nullptr;
  QCheckBox* SplitNonManifold = nullptr;
  QSpinBox* MinNeighbors = nullptr;
  QSpinBox* MaxRings = nullptr;
  QSpinBox* Degree = nullptr;
  QCheckBox* Robust = nullptr;
  QSpinBox* RobustIterations = nullptr;
  QCheckBox* CrestLines = nullptr;
  QDoubleSpinBox* CrestThreshold = nullptr;
  QSpinBox* NumberOfClusters = nullptr;
  QSpinBox* Seed = nullptr;
  QDoubleSpinBox* ClusterCrestBeta = nullptr;
  QSpinBox* NystromThreshold = nullptr;
  QDoubleSpinBox* BandFraction = nullptr;
  QDoubleSpinBox* CurvatureTopFraction = nullptr;
  QDoubleSpinBox* CurvatureThresholdScale = nullptr;
  QSpinBox* CornerRings = nullptr;
  QDoubleSpinBox* CornerFraction = nullptr;
  QSpinBox* TargetFaces = nullptr;
  QDoubleSpinBox* MaxError = nullptr;

  QString FileName;
  QString Error;
  int CurrentStage = InputStage;
  bool Batch = false;
  bool Running = false;
};

#endif
