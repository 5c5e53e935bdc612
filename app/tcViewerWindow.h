// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcViewerWindow
 * @brief The main window of trichart-viewer: a stage browser over the TriChart pipeline.
 *
 * The pipeline is tcMeshReader -> tcMeshPreparation -> tcCurvature -> tcSpectralClustering ->
 * tcFeatureRefinement -> tcBaseComplex -> tcPathTracing -> tcGeometryImages ->
 * tcGeometryImageMesh -> tcSurfaceDistance (against the prepared mesh). Selecting a stage shows
 * its output; its parameters are edited in the panel and "Apply" re-runs what changed (the
 * VTK pipeline's modified times decide). Long runs show progress and can be cancelled;
 * errors are shown in the window, which stays usable.
 *
 * An atlas file (.exr, tcAtlasReader) can be opened instead of a mesh: it feeds the atlas and
 * reconstruction stages, the stages before them are unavailable (there is no input mesh) and
 * the reconstruction is not coloured by distance (there is nothing to measure against).
 *
 * The vertices of a reconstruction are samples of the input surface, so their own distance to it
 * is float rounding (about 1e-7 of the diagonal): the error lies inside the triangles. The
 * reconstruction is therefore measured and drawn with each triangle split in 16
 * (vtkLinearSubdivisionFilter: the same flat surface), which puts distance samples inside every
 * triangle; its own edges are drawn over it as lines.
 *
 * The atlas stage splits the one render window in two viewports: the finest mip step of the
 * atlas as a flat picture (normals as colours) on the left, the mesh rebuilt from it in 3-D on
 * the right. One window keeps a single screenshot, camera and interactor; the left viewport
 * pans and zooms but does not rotate.
 *
 * The LOD stage draws the atlas itself (not a mesh rebuilt from it) with tcLODMapper: each
 * chart at the level the view asks for, optionally as a crowd of instances on a ground grid.
 * It has its own camera, so flying around the crowd leaves the other stages' view as it was,
 * and a statistics overlay in a second renderer layer, filled after the 3-D layer has drawn
 * (the mapper chooses its levels while it draws) and before the overlay layer draws, so the
 * figures shown are those of the frame they are drawn over.
 */
#ifndef tcViewerWindow_h
#define tcViewerWindow_h

#include <QMainWindow>
#include <QStringList>

#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <string>
#include <vector>

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
class tcAtlasReader;
class tcAtlasWriter;
class tcBaseComplex;
class tcCurvature;
class tcFeatureRefinement;
class tcGeometryImageMesh;
class tcGeometryImages;
class tcLODMapper;
class tcMeshPreparation;
class tcMeshReader;
class tcPathTracing;
class tcSpectralClustering;
class tcSurfaceDistance;
class vtkActor;
class vtkAlgorithm;
class vtkCamera;
class vtkDataObject;
class vtkExtractEdges;
class vtkGenericOpenGLRenderWindow;
class vtkImageActor;
class vtkLinearSubdivisionFilter;
class vtkMultiBlockDataSet;
class vtkObject;
class vtkPlaneSource;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkRenderer;
class vtkScalarBarActor;
class vtkSphereSource;
class vtkTextActor;

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
    PatchesStage,
    AtlasStage,
    ReconstructionStage,
    LODStage,
    StageCount
  };

  tcViewerWindow();
  ~tcViewerWindow() override;

  /// Stage from its command-line name ("input", "preparation", "curvature", "clusters",
  /// "features", "base", "patches", "atlas", "reconstruction", "lod"); -1 if unknown.
  static int StageFromName(const QString& name);

  /// The command-line names of all stages, in pipeline order.
  static QStringList StageNames();

  /// True if `path` is opened as an atlas (.exr, or a file tcAtlasReader recognises).
  static bool IsAtlasFile(const QString& path);

  /// Opens a mesh and shows `stage`, or an atlas and shows its reconstruction (or the atlas or
  /// LOD stage when that is `stage`); false (with the error shown) on failure.
  bool OpenFile(const QString& path, int stage = CurvatureStage);

  /// Runs the pipeline up to `stage` and shows its output; false on error, cancel or a stage
  /// that needs an input mesh while an atlas file is open.
  bool ShowStage(int stage);

  /// Runs the pipeline up to the atlas (or takes the opened atlas) and writes it with
  /// tcAtlasWriter; false (with the error shown) on failure.
  bool SaveAtlas(const QString& path);

  /// Sets the level of the reconstruction panel (-1: each chart's finest); Apply or the next
  /// stage shown uses it.
  void SetReconstructionLevel(int level);

  /// Sets the number of instances of the LOD stage's crowd (1 to 2500); the crowd is framed
  /// anew when the LOD stage is shown.
  void SetInstances(int instances);

  /// Colours the surface by this array of the shown output ("" for a plain surface).
  void SetColorArray(const QString& name);

  /// Fits the camera of the 3-D view to the shown surface; in the LOD stage, looks at the whole
  /// crowd from the front (+Z) and 30 degrees to the side, 35 degrees above its ground plane.
  void ResetCamera();

  /// Renders and saves the whole window as PNG.
  bool SaveScreenshot(const QString& path);

  /// The last error message ("" if the last run succeeded).
  QString LastError() const { return this->Error; }

  /// The shown stage's summary (what the info label says) as plain text.
  QString InfoText() const;

  /// In batch mode errors go to stderr instead of a dialog.
  void SetBatchMode(bool batch) { this->Batch = batch; }

protected:
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

private:
  void BuildUi();
  QWidget* BuildPreparationPanel();
  /// What to check in the preparation panel so that the base complex takes the prepared mesh
  /// (shown in the preparation stage's summary when it is no closed, oriented manifold).
  QString ClosedManifoldHint() const;
  QWidget* BuildCurvaturePanel();
  QWidget* BuildClusteringPanel();
  QWidget* BuildRefinementPanel();
  QWidget* BuildBaseComplexPanel();
  QWidget* BuildGeometryImagesPanel();
  QWidget* BuildReconstructionPanel();
  QWidget* BuildLODPanel();
  std::vector<vtkAlgorithm*> Filters() const;
  vtkAlgorithm* StageAlgorithm(int stage) const;
  vtkAlgorithm* AtlasSource() const;
  bool StageAvailable(int stage) const;
  void UpdateStageAvailability();
  void PushParameters();
  bool Run(vtkAlgorithm* algorithm, int port = 0);
  /// Updates `algorithm` (port) and says whether it succeeded, leaving the message in Error;
  /// reports nothing.
  bool Execute(vtkAlgorithm* algorithm, int port);
  void Display(vtkPolyData* surface, vtkPolyData* lines, vtkPolyData* corners);
  bool ShowLOD(bool entering);
  void HideLOD();
  void UpdateCrowd();
  void FrameCrowd();
  void RenderLOD();
  void OnRendered(vtkObject*, unsigned long, void*);
  void ShowAtlasPicture(vtkMultiBlockDataSet* atlas);
  void HideAtlasPicture();
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
  vtkNew<tcPathTracing> PathTracing;
  vtkNew<tcGeometryImages> GeometryImages;
  vtkNew<tcAtlasReader> AtlasReader;
  vtkNew<tcGeometryImageMesh> AtlasMesh; ///< every chart at its finest level, for the atlas stage
  vtkNew<tcGeometryImageMesh> Reconstruction;
  vtkNew<vtkLinearSubdivisionFilter> Subdivision; ///< the reconstruction, each triangle in 16
  vtkNew<tcSurfaceDistance> Distance;
  vtkNew<vtkExtractEdges> RebuiltEdges;
  vtkNew<tcAtlasWriter> AtlasWriter;
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
  vtkNew<vtkRenderer> AtlasRenderer;
  vtkNew<vtkImageActor> AtlasPicture;
  vtkNew<vtkTextActor> AtlasCaption;
  vtkNew<tcLODMapper> LODMapper;
  vtkNew<vtkActor> LODActor;
  vtkNew<vtkPlaneSource> Ground; ///< the crowd's ground plane (more than one instance)
  vtkNew<vtkPolyDataMapper> GroundMapper;
  vtkNew<vtkActor> GroundActor;
  vtkNew<vtkCamera> LODCamera;
  vtkSmartPointer<vtkCamera> StageCamera; ///< the other stages' camera, while the LOD stage shows
  vtkNew<vtkRenderer> OverlayRenderer;    ///< layer 1 over the 3-D view: the LOD statistics
  vtkNew<vtkTextActor> LODStatistics;
  vtkDataObject* LODAtlasSource = nullptr; ///< the atlas output the LOD mapper's copy was made of
  vtkMTimeType LODAtlasTime = 0;           ///< and its modified time then
  double LODBounds[6] = { 0, -1, 0, -1, 0, -1 }; ///< the atlas's bounds, one instance
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
  QCheckBox* FillHoles = nullptr;
  QSpinBox* MaxHoleEdges = nullptr;
  QCheckBox* RemoveSlivers = nullptr;
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
  QCheckBox* StraightenLines = nullptr;
  QDoubleSpinBox* CreaseAngle = nullptr;
  QSpinBox* TargetFaces = nullptr;
  QDoubleSpinBox* MaxError = nullptr;
  QSpinBox* SampleBudget = nullptr;
  QSpinBox* MinLevel = nullptr;
  QSpinBox* MaxLevel = nullptr;
  QDoubleSpinBox* CurvatureWeight = nullptr;
  QComboBox* LevelRule = nullptr;
  QSpinBox* StretchIterations = nullptr;
  QCheckBox* FitSamples = nullptr;
  QSpinBox* Level = nullptr;
  QDoubleSpinBox* LODBias = nullptr;
  QDoubleSpinBox* ErrorTarget = nullptr;
  QCheckBox* FreezeLOD = nullptr;
  QComboBox* LODColor = nullptr;
  QCheckBox* Wireframe = nullptr;
  QSpinBox* Instances = nullptr;

  QString FileName;
  QString Error;
  /// The filter whose ErrorEvent set Error (nullptr: none, or not a filter's).
  vtkObject* ErrorSource = nullptr;
  /// What the viewer did on its own for the open file (the sliver retry), shown in the summary.
  QString Note;
  int CurrentStage = InputStage;
  bool AtlasFile = false; ///< the open file is an atlas: no input mesh
  bool HasLines = false;  ///< the shown stage has lines to draw
  bool Batch = false;
  bool Running = false;
};

#endif
