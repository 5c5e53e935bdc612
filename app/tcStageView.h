// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcStageView
 * @brief What trichart-viewer draws of a stage other than the LOD one: its surface, coloured by
 * one of its arrays with a legend, its lines and corners, and the atlas picture.
 *
 * The stages of the curvature through the patches are drawn with normals split at 45 degrees
 * (their own normals are fitted across creases, which shades a CAD edge as a dark band); the
 * atlas and its reconstruction with the atlas's normals. The shown surface (GetShown) stays the
 * stage's own data, for export.
 *
 * The atlas stage splits the one render window in two viewports: the finest mip step of the
 * atlas as a flat picture (normals as colours) on the left, the mesh rebuilt from it in 3-D on
 * the right. One window keeps a single screenshot, camera and interactor; the left viewport
 * pans and zooms but does not rotate (UseInteractor).
 */
#ifndef tcStageView_h
#define tcStageView_h

#include <QStringList>

#include <vtkNew.h>
#include <vtkSmartPointer.h>

class vtkActor;
class vtkImageActor;
class vtkMultiBlockDataSet;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkRenderWindow;
class vtkRenderWindowInteractor;
class vtkRenderer;
class vtkScalarBarActor;
class vtkSphereSource;
class vtkTextActor;
struct tcStageOutput;

class tcStageView
{
public:
  /// Adds the surface, lines, corners and legend to `renderer`, the 3-D view of `window`; the
  /// atlas picture has a renderer of its own, in the window only while the atlas stage shows.
  tcStageView(vtkRenderWindow* window, vtkRenderer* renderer);
  ~tcStageView();
  tcStageView(const tcStageView&) = delete;
  tcStageView& operator=(const tcStageView&) = delete;

  /// Gives `interactor` the trackball style, except that the left button pans the flat atlas
  /// picture instead of turning it out of its plane.
  void UseInteractor(vtkRenderWindowInteractor* interactor);

  /// Draws `output`, what `stage` shows (a tcStage other than the LOD one), in a plain colour
  /// until ColorBy; fits the camera again when the atlas picture has just taken half the window.
  void Show(int stage, const tcStageOutput& output);

  /// Draws nothing (a failed run, or the LOD stage), keeping the shown surface.
  void Hide();

  /// Forgets the shown surface: the LOD stage shows, which builds none.
  void Forget();

  /// The shown stage's surface, as the stage made it (nullptr: none).
  vtkPolyData* GetShown() const { return this->Shown; }

  /// What the shown surface can be coloured by: "Solid", its point arrays but the normals, and
  /// its cell arrays as "cell:<name>".
  QStringList ColorChoices() const;

  /// The colour each stage opens on among `choices`: base faces, patches, charts, the distance,
  /// clusters or mean curvature, else `previous` if it is there, else "Solid".
  static QString DefaultColor(int stage, const QStringList& choices, const QString& previous);

  /// Colours the surface by this array of the shown output ("cell:<name>" for a cell array;
  /// another name, or "Solid", for a plain surface): signed curvatures diverging about 0, ids as
  /// labels (without a legend), anything else over its range.
  void ColorBy(const QString& name);

  ///@{
  /// The display options: lines (when the stage has some), corners (features stage), edges.
  void SetLinesVisible(bool on);
  void SetCornersVisible(bool on);
  void SetEdgesVisible(bool on);
  ///@}

private:
  void ShowAtlasPicture(vtkMultiBlockDataSet* atlas);
  void HideAtlasPicture();
  void ShowSurface(vtkPolyData* surface);
  void ShowLines(vtkPolyData* lines);
  void ShowCorners(vtkPolyData* corners, double diagonal);

  vtkRenderWindow* Window;
  vtkRenderer* Renderer;
  vtkNew<vtkPolyDataMapper> SurfaceMapper;
  vtkNew<vtkActor> SurfaceActor;
  vtkNew<vtkPolyDataMapper> LineMapper;
  vtkNew<vtkActor> LineActor;
  vtkNew<vtkActor> CornerActor;
  vtkNew<vtkSphereSource> CornerSphere;
  vtkNew<vtkScalarBarActor> Legend;
  vtkNew<vtkRenderer> AtlasRenderer;
  vtkNew<vtkImageActor> AtlasPicture;
  vtkNew<vtkTextActor> AtlasCaption;
  vtkSmartPointer<vtkPolyData> Shown;
  int Stage = 0;         ///< the stage shown last (the LOD stage after Forget)
  bool HasLines = false; ///< the shown stage has lines to draw
  bool LinesOn = true;
  bool CornersOn = true;
};

#endif
