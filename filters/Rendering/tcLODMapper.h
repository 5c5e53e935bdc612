// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcLODMapper
 * @brief Draws an atlas of triangular geometry images with view-dependent level of detail,
 * stitched without cracks (Feng et al. 2010, section 6).
 *
 * Input: an atlas (tcGeometryImages, tcAtlasReader). The geometry images go to the GPU once as
 * buffer textures; one triangular grid per level, shared by every chart, is the only vertex
 * buffer, and it carries integer sample coordinates only. Per frame, on the CPU:
 * - each chart's oriented box is projected and its level chosen (eq. 6 and 7 of the paper, with
 *   LODBias; or, with ErrorTarget > 0, the coarsest level whose measured error projects to at
 *   most ErrorTarget pixels); charts whose box lies outside the view are not drawn (Culling);
 * - the drawn (instance, chart) pairs are sorted by level, with the levels of their neighbours.
 * Then one instanced draw call per level draws every chart of that level in every instance; the
 * vertex shader (shaders/GeometryImage*VS.glsl) fetches each vertex's sample with texelFetch,
 * snaps the vertices of a side whose neighbour is coarser onto that neighbour's samples (eq. 8)
 * and applies the instance's transform. The vertices it draws are those tcGeometryImageMesh
 * builds for the same levels, bit for bit (CaptureVertices reads them back).
 *
 * Instances (a crowd): SetInstanceMatrices takes one 4 x 4 matrix per instance (16 components,
 * row-major, model to actor coordinates; rigid with a uniform scale so that normals follow).
 * Without it the atlas is drawn once, untransformed.
 *
 * Every setting of the actor applies (docs/lod-mapper.md lists them): lighting on or off, flat,
 * Gouraud or Phong interpolation, surface, wireframe, points and surface with edges, opacity
 * with or without depth peeling, backface and frontface culling, clipping planes, and the
 * user's own replacements in the actor's vtkShaderProperty (applied before the mapper's, which
 * live in its grid mapper, not in that property). The actor's textures are not drawn (the
 * grid has no texture coordinates of its own; a warning says so): the atlas's are.
 *
 * Colour: the actor's, or per chart, per level, by an attribute of the atlas through the
 * lookup table (ColorMode, ColorAttribute), by the atlas's base-colour texture looked up with
 * its TextureCoordinates, or by its Colors (the input's vertex colours), while ScalarVisibility
 * is on (the default); off, the actor's colour. Lighting uses the atlas's normal image.
 *
 * Selection: with vtkHardwareSelector over cells, a picked cell id is the LOD draw list's
 * (tc::LodDrawList): LocateCell maps it to the instance, chart, level and grid triangle of the
 * last frame drawn. A point selection draws nothing (a warning says so).
 *
 * Skinning (Feng et al. 2010, 5.2, 6.1, 6.2): an atlas with a Skin attribute and a rig (built
 * from a skinned file or a deforming sequence) is posed by linear blend skinning in the vertex
 * shader (shaders/SkinningVS.glsl), each instance at its own time (SetInstanceTimes) of its own
 * animation (SetInstanceAnimations), with the skinning matrices of every instance computed on the
 * CPU each frame and read from a buffer texture. Shared sides carry the same skin in both charts,
 * so a posed atlas stays crack-free. LOD selection and culling use skinned boxes
 * (tc::fitSkinnedBoxes, fitted when the atlas arrives): their corners are skinned by the
 * instance's matrices, so that the box holds the chart in every pose.
 *
 * Bounds (GetBounds, hence ResetCamera): those of the drawn surface, from the finest samples in
 * every instance (tc::drawnBounds); LOD selection and culling use the charts' oriented boxes.
 *
 * Statistics of the last frame: GetTrianglesDrawn, GetChartsDrawn, GetChartsAtLevel,
 * GetSelectionSeconds, GetDrawListSeconds.
 *
 * Windows: the buffer textures belong to one window's context at a time. A mapper drawn into
 * another window frees them in the first and uploads the atlas again (every switch), so a mapper
 * per window, as ParaView's views and the viewer have, is the fast way to show several.
 */
#ifndef tcLODMapper_h
#define tcLODMapper_h

#include "TriChartRenderingModule.h"

#include "tc/gim/lod_selection.h" // for the defaults of the properties

#include <vtkMapper.h>

#include <memory>

class vtkDataArray;
class vtkDataObject;
class vtkFloatArray;
class vtkIntArray;
class vtkObject;
class vtkOpenGLRenderWindow;

class TRICHARTRENDERING_EXPORT tcLODMapper : public vtkMapper
{
public:
  static tcLODMapper* New();
  vtkTypeMacro(tcLODMapper, vtkMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The atlas to draw, without a pipeline (or SetInputConnection to a reader or filter).
  /// nullptr also frees the mapper's converted copy of the previous atlas.
  void SetInputData(vtkDataObject* atlas);

  enum ColorModes
  {
    ColorByActor = 0,
    ColorByChart = 1,
    ColorByLevel = 2,
    ColorByAttribute = 3,
    ColorByTexture = 4,
    ColorByVertexColors = 5
  };

  ///@{
  /// Levels added to every chosen level (positive: finer); fractional values shift the rounding
  /// of eq. 7. Default 0.
  vtkSetMacro(LODBias, double);
  vtkGetMacro(LODBias, double);
  ///@}

  ///@{
  /// Screen-space error target in pixels: each chart takes the coarsest level whose measured
  /// error (the atlas's LevelError) projects to at most this many pixels; default 1. 0 chooses by
  /// projected area instead (the paper's eq. 7, with LODBias); charts without measured errors
  /// always do.
  vtkSetClampMacro(ErrorTarget, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ErrorTarget, double);
  ///@}

  ///@{
  /// Keep the last frame's levels and culling while the camera moves (to fly around a frozen
  /// selection). Default off.
  vtkSetMacro(FreezeLOD, bool);
  vtkGetMacro(FreezeLOD, bool);
  vtkBooleanMacro(FreezeLOD, bool);
  ///@}

  ///@{
  /// Skip charts whose oriented box lies outside the view frustum. Default on.
  vtkSetMacro(Culling, bool);
  vtkGetMacro(Culling, bool);
  vtkBooleanMacro(Culling, bool);
  ///@}

  ///@{
  /// Snap sides to coarser neighbours (eq. 8). Off shows the cracks stitching mends. Default on.
  vtkSetMacro(Stitching, bool);
  vtkGetMacro(Stitching, bool);
  vtkBooleanMacro(Stitching, bool);
  ///@}

  ///@{
  /// One level for every chart (clamped to each chart's finest), in place of the view-dependent
  /// choice; -1 (default) chooses per view.
  vtkSetClampMacro(FixedLevel, int, -1, 15);
  vtkGetMacro(FixedLevel, int);
  ///@}

  /// Levels per chart (one tuple per chart, clamped to each chart's finest; -1 leaves the chart
  /// out), in place of the view-dependent choice, for every instance; nullptr (default) chooses
  /// per view. The array is copied.
  void SetChartLevels(vtkIntArray* levels);

  ///@{
  /// ColorByActor (default), ColorByChart, ColorByLevel, ColorByAttribute (ColorAttribute),
  /// ColorByTexture (the atlas's BaseColor texture at its TextureCoordinates, linearly filtered
  /// with mipmaps and repeated outside [0, 1], as glTF samples it) or ColorByVertexColors (its
  /// Colors attribute, 0 .. 255). An atlas without what the mode needs is drawn in the actor's
  /// colour, and a warning says why.
  vtkSetClampMacro(ColorMode, int, ColorByActor, ColorByVertexColors);
  vtkGetMacro(ColorMode, int);
  ///@}

  ///@{
  /// The atlas attribute ColorByAttribute shows (an array tcGeometryImages resampled, e.g.
  /// "MeanCurvature"; the magnitude of a vector), mapped through the mapper's lookup table over
  /// the attribute's range, or over the table's range with UseLookupTableScalarRange. An
  /// unknown name is reported and the actor's colour is used.
  vtkSetStringMacro(ColorAttribute);
  vtkGetStringMacro(ColorAttribute);
  ///@}

  /// One instance per tuple of 16 components (row-major 4 x 4, model to actor coordinates);
  /// nullptr (default): one instance, the identity. The array is copied.
  void SetInstanceMatrices(vtkDataArray* matrices);
  int GetNumberOfInstances() const;

  ///@{
  /// Pose an atlas that has a Skin attribute and a rig (default on); off, or without them, the
  /// atlas is drawn in its bind pose.
  vtkSetMacro(Skinning, bool);
  vtkGetMacro(Skinning, bool);
  vtkBooleanMacro(Skinning, bool);
  ///@}

  ///@{
  /// The animation of the rig that poses every instance without an animation of its own: its
  /// name, or its index as digits; "" (default) the first. An unknown name is reported (the
  /// message lists the animations) and the bind pose is drawn.
  vtkSetStringMacro(Animation);
  vtkGetStringMacro(Animation);
  ///@}

  ///@{
  /// The time in seconds of the animation at which every instance without a time of its own is
  /// posed (default 0). Times outside [0, duration] hold the first or last key, as the mesh
  /// reader's poses do.
  vtkSetMacro(AnimationTime, double);
  vtkGetMacro(AnimationTime, double);
  ///@}

  /// A time in seconds per instance (one component, one tuple per instance, e.g. a crowd where
  /// each character is at its own phase); nullptr (default): AnimationTime for all. The array is
  /// copied; instances past its end use AnimationTime.
  void SetInstanceTimes(vtkDataArray* seconds);

  /// An animation index of the rig per instance (one component, one tuple per instance; -1 and
  /// instances past the end: Animation); nullptr (default): Animation for all. Copied.
  void SetInstanceAnimations(vtkIntArray* animations);

  /// Whether the last frame drawn was posed (Skinning on and an atlas with a skin and a rig).
  bool GetSkinned() const;

  ///@{
  /// Read back every vertex the next frames draw (transform feedback): GetCapturedVertices then
  /// holds 8 floats per drawn triangle corner, in draw order: the model position x, y, z, the
  /// chart, then the grid sample i, j (before stitching), the level and the instance.
  vtkSetMacro(CaptureVertices, bool);
  vtkGetMacro(CaptureVertices, bool);
  vtkBooleanMacro(CaptureVertices, bool);
  vtkFloatArray* GetCapturedVertices();
  ///@}

  ///@{
  /// Statistics of the last frame: grid triangles issued, (instance, chart) pairs drawn, pairs
  /// drawn at `level`, the wall-clock seconds of the level selection (projecting every box and
  /// choosing its level, eq. 6 and 7), and those of the draw list (sorting the drawn pairs by
  /// level with their neighbours' levels, and uploading it).
  vtkIdType GetTrianglesDrawn() const;
  vtkIdType GetChartsDrawn() const;
  vtkIdType GetChartsAtLevel(int level) const;
  double GetSelectionSeconds() const;
  double GetDrawListSeconds() const;
  ///@}

  /// The levels of the last frame, one tuple per chart and `instances` components (-1: not
  /// drawn); `levels` is resized.
  void GetLevels(vtkIntArray* levels) const;

  /// Number of charts of the atlas (0 before the first render or update of bounds).
  vtkIdType GetNumberOfCharts() const;

  /// Where a cell id of a hardware selection of the last frame lies: `location` gets the
  /// instance, the chart, the chart's level and the triangle's index in its level-grid (grid
  /// order, 0 .. 4^level - 1); false (all -1) when no triangle of the last frame has that id.
  bool LocateCell(vtkIdType cellId, vtkIdType location[4]) const;

  /// The bounds of the drawn surface: every chart's finest samples, in every instance.
  double* GetBounds() override;
  void GetBounds(double bounds[6]) override { this->vtkAbstractMapper3D::GetBounds(bounds); }

  void Render(vtkRenderer* ren, vtkActor* act) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  tcLODMapper();
  ~tcLODMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  double LODBias = tc::LodOptions{}.bias;
  double ErrorTarget = tc::LodOptions{}.errorPixels;
  bool FreezeLOD = false;
  bool Culling = tc::LodOptions{}.cull;
  bool Stitching = true;
  int FixedLevel = -1;
  int ColorMode = ColorByActor;
  char* ColorAttribute = nullptr;
  bool CaptureVertices = false;
  bool Skinning = true;
  char* Animation = nullptr;
  double AnimationTime = 0.0;

private:
  tcLODMapper(const tcLODMapper&) = delete;
  void operator=(const tcLODMapper&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
  friend class tcLODGridMapper;

  bool UpdateAtlas();
  void ReleaseAtlas();
  void UploadAtlas(vtkRenderer* ren);
  void UploadTexture(vtkOpenGLRenderWindow* window, bool baseColor);
  void SelectLevels(vtkRenderer* ren, vtkActor* act);
  void UpdatePalettes();
  void UploadBones();
  void WarnAboutSettings(vtkRenderer* ren, vtkActor* act);
  void UseWindow(vtkOpenGLRenderWindow* window);
  void WindowDeleted(vtkObject* window, unsigned long event, void* data);
};

#endif
