// SPDX-License-Identifier: BSD-3-Clause
#include "tcStagePanels.h"

#include "tcAnimationControls.h"
#include "tcBaseComplex.h"
#include "tcCurvature.h"
#include "tcFeatureRefinement.h"
#include "tcGeometryImageMesh.h"
#include "tcGeometryImages.h"
#include "tcLODMapper.h"
#include "tcLODView.h"
#include "tcMeshPreparation.h"
#include "tcMeshReader.h"
#include "tcParameterPanel.h"
#include "tcSpectralClustering.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QSpinBox>

#include <algorithm>
#include <array>

tcParameterPanel* tcStagePanels::Preparation(
  tcMeshReader* reader, tcMeshPreparation* f, QWidget* parent)
{
  auto* panel = new tcParameterPanel(tcParameterPanel::Apply, parent);
  panel
    ->AddDouble("VerticalScale", 1e-4, 1e4, 4, 0.1, reader->GetVerticalScale(),
      [reader](double v) { reader->SetVerticalScale(v); })
    ->setToolTip("A terrain raster (.tif, .asc, .pgm, ...): its heights times this");
  panel
    ->AddDouble("MergeTolerance", 0.0, 0.1, 5, 0.0001, f->GetMergeTolerance(),
      [f](double v) { f->SetMergeTolerance(v); })
    ->setToolTip("Merge points closer than this fraction of the diagonal");
  panel->AddCheck("Orient", f->GetOrient(), [f](bool on) { f->SetOrient(on); });
  panel->AddCheck(
    "SplitNonManifold", f->GetSplitNonManifold(), [f](bool on) { f->SetSplitNonManifold(on); });
  panel->AddCheck("FillHoles", f->GetFillHoles(), [f](bool on) { f->SetFillHoles(on); });
  QSpinBox* maxHoleEdges = panel->AddInt("MaxHoleEdges", 0, 10000000,
    static_cast<int>(f->GetMaxHoleEdges()), [f](int v) { f->SetMaxHoleEdges(v); });
  maxHoleEdges->setSpecialValueText("any size"); // 0
  maxHoleEdges->setToolTip("The largest hole FillHoles closes, in boundary edges");
  panel->AddCheck("RemoveSlivers", f->GetRemoveSlivers(), [f](bool on) { f->SetRemoveSlivers(on); })
    ->setToolTip("Collapse needles and flip caps (a scan's slivers)");
  panel
    ->AddCheck(
      "DropNonOrientable", f->GetDropNonOrientable(), [f](bool on) { f->SetDropNonOrientable(on); })
    ->setToolTip("Drop the components that cannot be oriented (Moebius-like)");
  QSpinBox* minTriangles = panel->AddInt("MinComponentTriangles", 0, 100000000,
    static_cast<int>(f->GetMinComponentTriangles()),
    [f](int v) { f->SetMinComponentTriangles(v); });
  minTriangles->setSpecialValueText("keep all"); // 0
  minTriangles->setToolTip("Drop the components of fewer triangles (a scan's stray islands)");
  panel
    ->AddCheck("KeepLargestComponent", f->GetKeepLargestComponent(),
      [f](bool on) { f->SetKeepLargestComponent(on); })
    ->setToolTip("Keep only the component of the most triangles");
  return panel;
}

tcParameterPanel* tcStagePanels::Curvature(tcCurvature* f, QWidget* parent)
{
  auto* panel = new tcParameterPanel(tcParameterPanel::Apply, parent);
  panel->AddInt(
    "MinNeighbors", 6, 1000, f->GetMinNeighbors(), [f](int v) { f->SetMinNeighbors(v); });
  panel->AddInt("MaxRings", 1, 20, f->GetMaxRings(), [f](int v) { f->SetMaxRings(v); });
  panel->AddInt("Degree", 2, 3, f->GetDegree(), [f](int v) { f->SetDegree(v); });
  panel->AddCheck("Robust", f->GetRobust(), [f](bool on) { f->SetRobust(on); });
  panel->AddInt(
    "RobustIterations", 1, 10, f->GetRobustIterations(), [f](int v) { f->SetRobustIterations(v); });
  panel->AddCheck(
    "ComputeCrestLines", f->GetComputeCrestLines(), [f](bool on) { f->SetComputeCrestLines(on); });
  panel->AddDouble("CrestStrengthThreshold", 0.0, 100.0, 3, 1.0, f->GetCrestStrengthThreshold(),
    [f](double v) { f->SetCrestStrengthThreshold(v); });
  return panel;
}

tcParameterPanel* tcStagePanels::Clustering(tcSpectralClustering* f, QWidget* parent)
{
  auto* panel = new tcParameterPanel(tcParameterPanel::Apply, parent);
  panel->AddInt("NumberOfClusters", 1, 1000, f->GetNumberOfClusters(),
    [f](int v) { f->SetNumberOfClusters(v); });
  panel->AddInt("Seed", 0, 1000000, f->GetSeed(), [f](int v) { f->SetSeed(v); });
  panel->AddDouble(
    "CrestBeta", 0.0, 1.0, 2, 0.05, f->GetCrestBeta(), [f](double v) { f->SetCrestBeta(v); });
  panel->AddInt("NystromThreshold", 100, 100000000, static_cast<int>(f->GetNystromThreshold()),
    [f](int v) { f->SetNystromThreshold(v); });
  return panel;
}

tcParameterPanel* tcStagePanels::Refinement(tcFeatureRefinement* f, QWidget* parent)
{
  auto* panel = new tcParameterPanel(tcParameterPanel::Apply, parent);
  panel->AddDouble("BandFraction", 0.0, 1.0, 3, 0.01, f->GetBandFraction(),
    [f](double v) { f->SetBandFraction(v); });
  panel->AddDouble("CurvatureTopFraction", 0.0, 1.0, 3, 0.01, f->GetCurvatureTopFraction(),
    [f](double v) { f->SetCurvatureTopFraction(v); });
  panel->AddDouble("CurvatureThresholdScale", 0.0, 10.0, 2, 0.1, f->GetCurvatureThresholdScale(),
    [f](double v) { f->SetCurvatureThresholdScale(v); });
  panel->AddInt("CornerRings", 1, 50, f->GetCornerRings(), [f](int v) { f->SetCornerRings(v); });
  panel->AddDouble("CornerFraction", 0.0, 1.0, 3, 0.01, f->GetCornerFraction(),
    [f](double v) { f->SetCornerFraction(v); });
  panel
    ->AddCheck(
      "StraightenLines", f->GetStraightenLines(), [f](bool on) { f->SetStraightenLines(on); })
    ->setToolTip("Straighten one-face zig-zags of the boundaries");
  panel
    ->AddDouble("CreaseAngle", f->GetCreaseAngleMinValue(), f->GetCreaseAngleMaxValue(), 2, 5.0,
      f->GetCreaseAngle(), [f](double v) { f->SetCreaseAngle(v); })
    ->setToolTip("Dihedral angle (degrees) of a crease edge, which straightening never trades for "
                 "a smoother one");
  QDoubleSpinBox* creaseLines = panel->AddDouble("CreaseLineAngle", f->GetCreaseLineAngleMinValue(),
    f->GetCreaseLineAngleMaxValue(), 1, 5.0, f->GetCreaseLineAngle(),
    [f](double v) { f->SetCreaseLineAngle(v); });
  creaseLines->setSpecialValueText("off");
  creaseLines->setToolTip("Crease chains whose edges all bend more than this many degrees join "
                          "the feature lines where no cluster boundary follows them; 0: off");
  panel->AddCheck("SeamLines", f->GetSeamLines(), [f](bool on) { f->SetSeamLines(on); })
    ->setToolTip("Texture seams of the input join the feature lines, so that every chart lies on "
                 "one side of a seam and keeps its own texture coordinates");
  panel->AddCheck("SkinLines", f->GetSkinLines(), [f](bool on) { f->SetSkinLines(on); })
    ->setToolTip("A skinned mesh: the boundaries between the faces that different joints "
                 "dominate join the feature lines, so that no chart straddles two bones");
  return panel;
}

tcParameterPanel* tcStagePanels::BaseComplex(tcBaseComplex* f, QWidget* parent)
{
  auto* panel = new tcParameterPanel(tcParameterPanel::Apply, parent);
  panel->AddInt("TargetFaces", 4, 10000000, static_cast<int>(f->GetTargetFaces()),
    [f](int v) { f->SetTargetFaces(v); });
  panel->AddDouble(
    "MaxError", 0.0, 1.0, 6, 0.0001, f->GetMaxError(), [f](double v) { f->SetMaxError(v); });
  return panel;
}

tcParameterPanel* tcStagePanels::GeometryImages(tcGeometryImages* g, QWidget* parent)
{
  auto* panel = new tcParameterPanel(tcParameterPanel::Apply, parent);
  QDoubleSpinBox* target =
    panel->AddDouble("ErrorTarget", g->GetErrorTargetMinValue(), g->GetErrorTargetMaxValue(), 5,
      0.0001, g->GetErrorTarget(), [g](double v) { g->SetErrorTarget(v); });
  target->setSpecialValueText("none");
  target->setToolTip("Each chart rises until its measured error is below this fraction of the "
                     "diagonal; none: the SampleBudget alone decides");
  QSpinBox* budget = panel->AddInt("SampleBudget", static_cast<int>(g->GetSampleBudgetMinValue()),
    static_cast<int>(std::min<vtkIdType>(g->GetSampleBudgetMaxValue(), 1000000000)),
    static_cast<int>(g->GetSampleBudget()), [g](int v) { g->SetSampleBudget(v); });
  budget->setSingleStep(1000);
  budget->setSpecialValueText("automatic");
  budget->setToolTip("Total samples over all charts at their finest level; automatic: as many "
                     "as the ErrorTarget needs (up to 16 times the input's points), or with no "
                     "target the input's point count");
  panel
    ->AddInt("MinLevel", g->GetMinLevelMinValue(), g->GetMinLevelMaxValue(), g->GetMinLevel(),
      [g](int v) { g->SetMinLevel(v); })
    ->setToolTip("Smallest finest level of a chart (2^d + 1 samples per side)");
  panel
    ->AddInt("MaxLevel", g->GetMaxLevelMinValue(), g->GetMaxLevelMaxValue(), g->GetMaxLevel(),
      [g](int v) { g->SetMaxLevel(v); })
    ->setToolTip("Largest finest level of a chart (2^d + 1 samples per side)");
  panel
    ->AddDouble("CurvatureWeight", g->GetCurvatureWeightMinValue(),
      std::min(g->GetCurvatureWeightMaxValue(), 1000.0), 2, 0.1, g->GetCurvatureWeight(),
      [g](double v) { g->SetCurvatureWeight(v); })
    ->setToolTip("Weight of |mean curvature| x diagonal in the area that sets each chart's level");
  // Index = tcGeometryImages::LEVEL_RULE_*.
  panel
    ->AddChoice(
      "LevelRule", { "Area", "Error" }, g->GetLevelRule(), [g](int rule) { g->SetLevelRule(rule); })
    ->setToolTip("How each chart's finest level is chosen under the budget: Area follows the "
                 "curvature-weighted area (paper 5.2), Error the largest measured error");
  panel
    ->AddInt("StretchIterations", g->GetStretchIterationsMinValue(),
      g->GetStretchIterationsMaxValue(), g->GetStretchIterations(),
      [g](int v) { g->SetStretchIterations(v); })
    ->setToolTip(
      "Stretch-reducing passes over each chart's mean-value map; 0: Floater's map alone");
  panel->AddCheck("FitSamples", g->GetFitSamples(), [g](bool on) { g->SetFitSamples(on); })
    ->setToolTip("Fit the finest samples to the surface by least squares instead of interpolating "
                 "it");
  panel
    ->AddCheck("KeepAppearance", g->GetKeepAppearance(), [g](bool on) { g->SetKeepAppearance(on); })
    ->setToolTip("Resample the input's texture coordinates and vertex colours and carry its "
                 "base-colour texture into the atlas");
  return panel;
}

tcParameterPanel* tcStagePanels::Reconstruction(tcGeometryImageMesh* f, QWidget* parent)
{
  auto* panel = new tcParameterPanel(tcParameterPanel::Apply, parent);
  QSpinBox* level = panel->AddInt("Level", f->GetLevelMinValue(), f->GetLevelMaxValue(),
    f->GetLevel(), [f](int v) { f->SetLevel(v); });
  level->setSpecialValueText("-1 (finest)");
  level->setToolTip("Level of every chart, capped by each chart's finest; -1: the finest");
  return panel;
}

tcParameterPanel* tcStagePanels::LOD(
  tcLODView* view, std::function<void()> resetCamera, QWidget* parent)
{
  // The viewer opens on the mapper's defaults (the error-target rule) and colours by level: the
  // stage is there to show which level each chart takes.
  auto* panel = new tcParameterPanel(tcParameterPanel::Live, parent);
  const tc::LodOptions defaults; // tcLODMapper's defaults
  panel
    ->AddDouble(
      "LOD bias", -4.0, 4.0, 1, 0.5, defaults.bias, [view](double b) { view->SetLODBias(b); })
    ->setToolTip("Levels added to every chosen level (positive: finer)");
  QDoubleSpinBox* target = panel->AddDouble("Error target", 0.0, 64.0, 1, 0.5, defaults.errorPixels,
    [view](double px) { view->SetErrorTarget(px); });
  target->setSuffix(" px");
  target->setSpecialValueText("0 (area, eq. 7)");
  target->setToolTip("Each chart takes the coarsest level whose measured error projects to at "
                     "most this many pixels; 0 chooses by projected area (eq. 7 of Feng et al.)");
  panel->AddCheck("Freeze LOD", false, [view](bool on) { view->SetFreezeLOD(on); })
    ->setToolTip("Keep the levels and culling of the last frame while the camera moves, to fly "
                 "around a frozen selection");
  // The tcLODMapper::ColorModes without an attribute name to give, in their order.
  static const std::array<int, 5> modes{ tcLODMapper::ColorByActor, tcLODMapper::ColorByChart,
    tcLODMapper::ColorByLevel, tcLODMapper::ColorByTexture, tcLODMapper::ColorByVertexColors };
  panel
    ->AddChoice("Colour by", { "actor", "chart", "level", "texture", "vertex colours" }, 2,
      [view](int choice) { view->SetColorMode(modes[static_cast<size_t>(choice)]); })
    ->setToolTip("Texture: the input's base-colour texture; vertex colours: its Colors. An atlas "
                 "built without them is drawn in the actor's colour");
  panel->AddCheck("Wireframe", false, [view](bool on) { view->SetWireframe(on); });
  panel->AddInt("Crowd instances", 1, 2500, 1, [view](int n) { view->SetInstances(n); })
    ->setToolTip("A crowd: this many copies on a square grid of the ground, each turned by its "
                 "own angle about the vertical (+Y) axis");
  panel->AddButton("Reset camera",
    "Look at the whole crowd from the front and a little to the side, 35 degrees above the "
    "ground",
    std::move(resetCamera));
  // Below the rows, shown for a skinned atlas only (tcAnimationControls::Sync).
  panel->AddWidget(new tcAnimationControls(view, panel));
  panel->Push();
  return panel;
}
