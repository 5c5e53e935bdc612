// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcLODView
 * @brief The LOD stage of trichart-viewer: the atlas drawn by tcLODMapper, as one model or a
 * crowd on a ground grid, with the statistics of each frame in an overlay.
 *
 * The LOD stage draws the atlas itself (not a mesh rebuilt from it) with tcLODMapper: each chart
 * at the level the view asks for, optionally as a crowd of instances on a ground grid. It has
 * its own camera, so flying around the crowd leaves the other stages' view as it was, and a
 * statistics overlay in a second renderer layer, filled after the 3-D layer has drawn (the
 * mapper chooses its levels while it draws) and before the overlay layer draws, so the figures
 * shown are those of the frame they are drawn over. The same figures go to the frame callback
 * (the window's summary).
 *
 * A skinned atlas (a Skin attribute and a rig with animations) is posed by the mapper at the
 * view's animation and time; in a crowd each instance is at that time plus a phase of its own,
 * so that the crowd does not move in lockstep. The view holds the pose; tcAnimationControls
 * plays it.
 */
#ifndef tcLODView_h
#define tcLODView_h

#include <QString>

#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>

#include "tc/skinning/skin.h"

#include <QStringList>

#include <functional>
#include <vector>

class tcLODMapper;
class vtkActor;
class vtkCamera;
class vtkDataObject;
class vtkObject;
class vtkPlaneSource;
class vtkPolyDataMapper;
class vtkRenderWindow;
class vtkRenderer;
class vtkTextActor;

/// The figures of one LOD frame, as the overlay and the summary show them.
struct tcLODFrame
{
  QString Fps;       ///< frames per second of the last whole render; "-" in batch mode
  QString Selection; ///< the LOD selection's time in ms; "-" in batch mode
  QString PerLevel;  ///< "L0 n | L1 n | ...": charts drawn per level, up to the finest drawn
  vtkIdType Charts = 0;
  vtkIdType TrianglesDrawn = 0;
  vtkIdType ChartsDrawn = 0;
  int Instances = 0;
  /// "'name' at t s of d s" (and whether each instance has its own phase) for a posed frame;
  /// "" when the atlas has no skin and rig, or no animation
  QString Animation;
};

class tcLODView
{
public:
  /// Adds the LOD actor and the ground to `renderer` (the 3-D view of `window`, whose second
  /// layer the overlay takes while the LOD stage shows).
  tcLODView(vtkRenderWindow* window, vtkRenderer* renderer);
  ~tcLODView();
  tcLODView(const tcLODView&) = delete;
  tcLODView& operator=(const tcLODView&) = delete;

  /// In batch mode timings, which vary from run to run, show as "-".
  void SetBatchMode(bool batch) { this->Batch = batch; }

  /// Called after each frame's 3-D layer has drawn, while the LOD stage shows.
  void SetFrameCallback(std::function<void(const tcLODFrame&)> callback);

  /// Shows `atlas` (a copy of it: a render during a later pipeline run must not update the
  /// pipeline from inside it) in place of the other stages, with the LOD camera; frames the
  /// crowd when `entering` the stage. Does not render. True when `atlas` is not the one shown
  /// last: its animations were read anew, and the pose is the first animation at time 0 unless
  /// the animations are those of the last atlas (then the pose is kept).
  bool Show(vtkDataObject* atlas, bool entering);

  /// Hides the LOD stage and gives the 3-D view back its camera.
  void Hide();

  /// The LOD stage shows.
  bool IsShown() const;

  /// Looks at the whole crowd from the front (+Z) and 30 degrees to the side, 35 degrees above
  /// its ground plane.
  void Frame();

  /// Renders the window if the LOD stage shows.
  void Render();

  ///@{
  /// The view's settings (the LOD panel); each redraws at once if the stage shows.
  void SetLODBias(double bias);
  void SetErrorTarget(double pixels);
  void SetFreezeLOD(bool freeze);
  void SetColorMode(int mode);
  void SetWireframe(bool wireframe);
  /// A new crowd (1 to 2500 instances) is framed whole: the old view would show a corner of it.
  void SetInstances(int instances);
  ///@}

  ///@{
  /// The pose of a skinned atlas. The names of its animations (none for an atlas without a
  /// skin and a rig: it is drawn as it is); the animation shown (an index of them, -1 when there
  /// are none); its duration and the crowd's time, in seconds (0 .. duration).
  QStringList GetAnimationNames() const;
  int GetAnimation() const { return this->AnimationIndex; }
  double GetAnimationDuration() const;
  double GetAnimationTime() const { return this->Time; }
  ///@}

  /// The index of the animation `choice` names: "" the first, a name, or an index as digits
  /// (tc::findAnimation); -1 with `error` (which lists the animations) when it names none.
  int FindAnimation(const QString& choice, QString& error) const;

  ///@{
  /// Each redraws at once if the stage shows. The animation (an index of GetAnimationNames; the
  /// time is kept if the new one lasts that long, else 0); the crowd's time in seconds, clamped
  /// to 0 .. duration; and whether each instance is at its own phase (default on): instance k
  /// at the time plus its phase, wrapped into the animation (SetPhased(false): all in step).
  void SetAnimation(int index);
  void SetAnimationTime(double seconds);
  void SetPhased(bool phased);
  bool GetPhased() const { return this->Phased; }
  ///@}

  ///@{
  /// The last frame's timings, in milliseconds.
  double GetSelectionMilliseconds() const;
  double GetRenderMilliseconds() const;
  ///@}

private:
  void UpdateCrowd();
  void ReadAnimations(vtkDataObject* atlas);
  void UpdatePoses();
  QString PoseText() const;
  tcLODFrame Statistics() const;
  void OnRendered(vtkObject*, unsigned long, void*);
  void BuildLevelLegend();
  void UpdateLevelLegend(vtkDataObject* atlas);

  vtkRenderWindow* Window;
  vtkRenderer* Renderer;
  vtkNew<tcLODMapper> Mapper;
  vtkNew<vtkActor> Actor;
  vtkNew<vtkPlaneSource> Ground; ///< the crowd's ground plane (more than one instance)
  vtkNew<vtkPolyDataMapper> GroundMapper;
  vtkNew<vtkActor> GroundActor;
  vtkNew<vtkCamera> Camera;
  vtkSmartPointer<vtkCamera> StageCamera; ///< the other stages' camera, while the LOD stage shows
  vtkNew<vtkRenderer> OverlayRenderer;    ///< layer 1 over the 3-D view: the statistics
  vtkNew<vtkTextActor> Overlay;
  vtkNew<vtkScalarBarActor> LevelLegend; ///< the level colours, when coloured by level
  vtkNew<vtkLookupTable> LevelColors;
  vtkDataObject* AtlasSource = nullptr;       ///< the atlas output the mapper's copy was made of
  vtkMTimeType AtlasTime = 0;                 ///< and its modified time then
  double Bounds[6] = { 0, -1, 0, -1, 0, -1 }; ///< the atlas's bounds, one instance
  int Instances = 1;
  std::vector<tc::Animation> Animations; ///< the shown atlas's, when it has a skin and a rig
  int AnimationIndex = -1;
  double Time = 0.0;
  bool Phased = true;
  bool Batch = false;
  unsigned long RenderedTag = 0;
  std::function<void(const tcLODFrame&)> FrameDrawn;
};

#endif
