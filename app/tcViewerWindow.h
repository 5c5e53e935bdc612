// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcViewerWindow
 * @brief The main window of trichart-viewer: a stage browser over the TriChart pipeline.
 *
 * Selecting a stage runs the pipeline (tcStagePipeline) up to it and shows its output: the LOD
 * stage in tcLODView, the others in tcStageView, with its summary (tcStageSummary). Its
 * parameters are edited in its panel (tcStagePanels) and "Apply" re-runs what changed (the VTK
 * pipeline's modified times decide). Long runs show progress and can be cancelled; errors are
 * shown in the window, which stays usable. The window itself keeps the layout, the menus, the
 * recent files, drag and drop, and the progress bar.
 *
 * An atlas file (.exr) can be opened instead of a mesh: it feeds the atlas and reconstruction
 * stages; the stages before them are unavailable (there is no input mesh).
 */
#ifndef tcViewerWindow_h
#define tcViewerWindow_h

#include "tcCameraView.h"
#include "tcStage.h"

#include <QMainWindow>
#include <QStringList>

#include <vtkNew.h>

#include <memory>
#include <optional>

class QCheckBox;
class QComboBox;
class QLabel;
class QListWidget;
class QMenu;
class QProgressBar;
class QPushButton;
class QScrollArea;
class QStackedWidget;
class QVBoxLayout;
class QVTKOpenGLNativeWidget;
class tcAnimationControls;
class tcLODView;
class tcParameterPanel;
class tcStagePipeline;
class tcStageView;
class vtkAlgorithm;
class vtkGenericOpenGLRenderWindow;
class vtkRenderer;

class tcViewerWindow : public QMainWindow
{
  Q_OBJECT
public:
  tcViewerWindow();
  ~tcViewerWindow() override;

  /// Stage from its command-line name (tcStage::Name, any case); -1 if unknown.
  static int StageFromName(const QString& name);

  /// The command-line names of all stages, in pipeline order.
  static QStringList StageNames();

  /// True if `path` is opened as an atlas (.exr, or a file tcAtlasReader recognises).
  static bool IsAtlasFile(const QString& path);

  /// Opens a mesh and shows `stage`, or an atlas and shows its reconstruction (or the atlas or
  /// LOD stage when that is `stage`); false (with the error shown) on failure.
  bool OpenFile(const QString& path, int stage = tcStage::Curvature);

  /// Runs the pipeline up to `stage` and shows its output; false on error, cancel or a stage
  /// that needs an input mesh while an atlas file is open.
  bool ShowStage(int stage);

  /// Runs the pipeline up to the atlas (or takes the opened atlas) and writes it with
  /// tcAtlasWriter; false (with the error shown) on failure.
  bool SaveAtlas(const QString& path);
  /// Exports the open file's atlas as a glTF LOD chain (.glb or .gltf), as File > Export LOD
  /// chain as glTF does; false (and an error shown) when it fails.
  bool ExportGltf(const QString& path);

  /// Sets the level of the reconstruction panel (-1: each chart's finest); Apply or the next
  /// stage shown uses it.
  void SetReconstructionLevel(int level);

  /// Sets the number of instances of the LOD stage's crowd (1 to 2500); the crowd is framed
  /// anew when the LOD stage is shown.
  void SetInstances(int instances);
  /// A terrain raster's vertical scale (the reader's VerticalScale, the Prepare panel's row).
  void SetVerticalScale(double scale);

  ///@{
  /// The animation (a name, or an index as digits) and the time in seconds at which the LOD
  /// stage poses each skinned atlas it shows anew (the command line's --animation and --time,
  /// for the files it names: a file opened from the window forgets them); unset: the first
  /// animation at 0. Showing an atlas that has no animation, or none of that name, or a time
  /// past its end, fails with an error that says so.
  void SetPoseAnimation(const QString& choice) { this->PoseAnimation = choice; }
  void SetPoseTime(double seconds) { this->PoseTime = seconds; }
  ///@}

  /// Colours the surface by this array of the shown output ("" for a plain surface).
  void SetColorArray(const QString& name);

  /// Fits the camera of the 3-D view to the shown surface, from SetCameraView's direction; in
  /// the LOD stage, looks at the whole crowd from the front (+Z) and 30 degrees to the side,
  /// 35 degrees above its ground plane.
  void ResetCamera();

  /// The direction, turns and zoom every later ResetCamera (and file opened) frames with.
  void SetCameraView(const tcCameraView& view) { this->CameraView = view; }

  /// Renders and saves the whole window as PNG.
  bool SaveScreenshot(const QString& path);

  /// The last error message ("" if the last run succeeded).
  QString LastError() const { return this->Error; }

  /// The shown stage's summary (what the info label says) as plain text.
  QString InfoText() const;

  /// In batch mode errors go to stderr instead of a dialog, and the summaries to stdout.
  void SetBatchMode(bool batch);

protected:
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

private:
  void BuildUi();
  void BuildView();
  void BuildStageList(QWidget* panel, QVBoxLayout* layout);
  void BuildPanels(QWidget* panel, QVBoxLayout* layout);
  void BuildDisplayOptions(QWidget* panel, QVBoxLayout* layout);
  void BuildSummary(QWidget* panel, QVBoxLayout* layout);
  void ConnectPipelineDock(QPushButton* apply);
  void FitPanelScroll();
  void BuildProgress();
  void BuildFileMenu();
  void OpenDialog();
  /// Opens a file chosen in the window (dialog, recent files, drop) on the shown stage.
  void OpenChosenFile(const QString& path);
  void ExportStage();
  void SaveAtlasDialog();
  void ExportGltfDialog();
  void ScreenshotDialog();
  /// The parameter panel of `stage` (nullptr for a stage without parameters).
  tcParameterPanel* ParameterPanel(int stage) const;
  void UpdateStageAvailability();
  void PushParameters();
  /// Runs the pipeline up to `stage`, reporting what failed.
  bool RunStage(int stage);
  /// Runs `algorithm` with progress and cancel, reporting what failed.
  bool Run(vtkAlgorithm* algorithm);
  void ShowFailure();
  void SelectStage(int stage);
  bool ShowLOD(bool entering);
  bool ApplyPose();
  void FillArrayChoices();
  void PrintSummary() const;
  void ReportError(const QString& message);
  void AddRecentFile(const QString& path);
  void UpdateRecentMenu();
  void OnProgress(const char* filter, double progress);

  std::unique_ptr<tcStagePipeline> Pipeline;
  vtkNew<vtkGenericOpenGLRenderWindow> RenderWindow;
  vtkNew<vtkRenderer> Renderer;
  std::unique_ptr<tcStageView> StageView;
  std::unique_ptr<tcLODView> LODView;
  tcAnimationControls* AnimationControls = nullptr; // in the LOD panel

  QVTKOpenGLNativeWidget* View = nullptr;
  QListWidget* Stages = nullptr;
  QStackedWidget* Panels = nullptr;
  QScrollArea* PanelScroll = nullptr; // around Panels
  QComboBox* ColorBy = nullptr;
  QCheckBox* ShowLines = nullptr;
  QCheckBox* ShowEdges = nullptr;
  QCheckBox* ShowCorners = nullptr;
  QProgressBar* Progress = nullptr;
  QPushButton* Cancel = nullptr;
  QLabel* Info = nullptr;
  QMenu* RecentMenu = nullptr;

  tcCameraView CameraView;
  std::optional<QString> PoseAnimation;
  std::optional<double> PoseTime;
  QString FileName;
  QString Error;
  int CurrentStage = tcStage::Input;
  bool Batch = false;
  bool Running = false;
};

#endif
