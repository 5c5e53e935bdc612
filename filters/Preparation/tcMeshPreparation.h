// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcMeshPreparation
 * @brief Turns any polygonal input into a clean triangle mesh for the later stages, and says
 * what it changed.
 *
 * Triangulates polygons and strips, merges duplicate points (exactly or within a tolerance
 * relative to the bounding-box diagonal), drops degenerate and repeated faces, orients every
 * component consistently (closed components outward), drops unused points. Non-manifold edges
 * and vertices are flagged (cell array NonManifoldEdge, point array NonManifoldVertex) and, with
 * SplitNonManifold, split so that the output is manifold. Point and cell arrays of the input
 * are carried over (InputPointId, InputCellId say where each element came from).
 *
 * What changed is in GetReport() and the field array "PreparationReport". Input that cannot be
 * made into a mesh (no polygons, NaN or infinite coordinates, zero area) is an error that
 * says what to fix.
 */
#ifndef tcMeshPreparation_h
#define tcMeshPreparation_h

#include "TriChartPreparationModule.h"

#include "tc/prep/mesh_preparation.h" // for the defaults of the properties

#include <vtkPolyDataAlgorithm.h>

#include <string>

class TRICHARTPREPARATION_EXPORT tcMeshPreparation : public vtkPolyDataAlgorithm
{
public:
  static tcMeshPreparation* New();
  vtkTypeMacro(tcMeshPreparation, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Points closer than this fraction of the bounding-box diagonal are merged; 0 (default)
  /// merges exact duplicates only.
  vtkSetClampMacro(MergeTolerance, double, 0.0, 0.1);
  vtkGetMacro(MergeTolerance, double);
  ///@}

  ///@{
  /// Split non-manifold edges and vertices so that the output is a manifold (default off:
  /// they are only flagged).
  vtkSetMacro(SplitNonManifold, bool);
  vtkGetMacro(SplitNonManifold, bool);
  vtkBooleanMacro(SplitNonManifold, bool);
  ///@}

  ///@{
  /// Orient the faces of every component consistently, closed components outward (default on).
  vtkSetMacro(Orient, bool);
  vtkGetMacro(Orient, bool);
  vtkBooleanMacro(Orient, bool);

  /// Close the holes (boundary loops) with faired patches at the density around them (CGAL's
  /// triangulate_refine_and_fair_hole), so that an open scan can go through the pipeline, which
  /// needs closed surfaces (default off). New points and cells have InputPointId /
  /// InputCellId -1 and zeros in the input's numeric arrays. Needs a manifold mesh.
  vtkSetMacro(FillHoles, bool);
  vtkGetMacro(FillHoles, bool);
  vtkBooleanMacro(FillHoles, bool);

  /// With FillHoles: loops of more boundary edges stay open (default 1000; 0: any size).
  vtkSetClampMacro(MaxHoleEdges, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MaxHoleEdges, vtkIdType);

  /// Remove slivers last (default off): collapse the shortest edge of every needle and flip the
  /// longest edge of every cap where no triangle folds (CGAL's remove_almost_degenerate_faces).
  /// Scans often have thousands, which the base complex keeps and path tracing cannot cut
  /// through. No point moves; collapsed points are dropped. Needs a manifold mesh.
  vtkSetMacro(RemoveSlivers, bool);
  vtkGetMacro(RemoveSlivers, bool);
  vtkBooleanMacro(RemoveSlivers, bool);

  /// With RemoveSlivers: a triangle with a larger angle (degrees) is a cap (default 170).
  vtkSetClampMacro(SliverAngle, double, tc::kMinSliverAngle, 180.0);
  vtkGetMacro(SliverAngle, double);

  /// With RemoveSlivers: a triangle whose longest side exceeds its shortest by a larger ratio is
  /// a needle (default 10).
  vtkSetClampMacro(SliverEdgeRatio, double, tc::kMinSliverEdgeRatio, VTK_DOUBLE_MAX);
  vtkGetMacro(SliverEdgeRatio, double);
  ///@}

  ///@{
  /// Drop edge-connected components, after orienting and before filling holes (all off by
  /// default: a mesh is never cut unasked). A component is dropped by the first that applies:
  /// DropNonOrientable drops the Moebius-like ones, which no repair or later stage takes;
  /// MinComponentTriangles (0: off) those of fewer triangles, a scan's stray islands;
  /// KeepLargestComponent all but the one of the most triangles. Their points go with them.
  vtkSetMacro(DropNonOrientable, bool);
  vtkGetMacro(DropNonOrientable, bool);
  vtkBooleanMacro(DropNonOrientable, bool);
  vtkSetClampMacro(MinComponentTriangles, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MinComponentTriangles, vtkIdType);
  vtkSetMacro(KeepLargestComponent, bool);
  vtkGetMacro(KeepLargestComponent, bool);
  vtkBooleanMacro(KeepLargestComponent, bool);
  ///@}

  /// What the last run changed, one item per line.
  const char* GetReport() const { return this->Report.c_str(); }

  /// True if the last run altered geometry or connectivity.
  bool GetChanged() const { return this->Changed; }

  ///@{
  /// Counts of the last run (also in the report): non-manifold edges and vertices found in the
  /// input (before splitting), boundary edges of the output, holes FillHoles left open,
  /// components left unoriented, and the components (and their triangles) that
  /// DropNonOrientable, MinComponentTriangles and KeepLargestComponent dropped.
  vtkIdType GetNonManifoldEdges() const { return this->NonManifoldEdges; }
  vtkIdType GetNonManifoldVertices() const { return this->NonManifoldVertices; }
  vtkIdType GetBoundaryEdges() const { return this->BoundaryEdges; }
  vtkIdType GetOpenHoles() const { return this->OpenHoles; }
  vtkIdType GetNonOrientableComponents() const { return this->NonOrientableComponents; }
  vtkIdType GetDroppedComponents() const { return this->DroppedComponents; }
  vtkIdType GetDroppedComponentTriangles() const { return this->DroppedComponentTriangles; }
  ///@}

  /// True if the last run's output is what tcBaseComplex and the stages after it need: every
  /// component closed, manifold (nothing left unsplit) and consistently oriented (false with
  /// Orient off, which leaves the orientation unchecked).
  bool GetClosedManifold() const { return this->ClosedManifold; }

  /// After a run whose output is not a closed manifold: each defect with its count and the
  /// property (and `trichart build` flag) that repairs it, e.g. "3 boundary edges (close the
  /// holes: FillHoles, trichart build --fill-holes)"; "" otherwise.
  const char* GetClosedManifoldRepairs() const { return this->ClosedManifoldRepairs.c_str(); }

protected:
  tcMeshPreparation();
  ~tcMeshPreparation() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcMeshPreparation(const tcMeshPreparation&) = delete;
  void operator=(const tcMeshPreparation&) = delete;

  /// The counts, flags and report of the last run: cleared, then set from the core's report.
  void ClearReport();
  void RecordReport(
    const tc::PreparationReport& counts, const tc::PreparationOptions& options, int64_t ignored);

  double MergeTolerance = tc::PreparationOptions{}.mergeTolerance;
  bool SplitNonManifold = tc::PreparationOptions{}.splitNonManifold;
  bool Orient = tc::PreparationOptions{}.orient;
  bool FillHoles = tc::PreparationOptions{}.fillHoles;
  vtkIdType MaxHoleEdges = tc::PreparationOptions{}.maxHoleEdges;
  bool RemoveSlivers = tc::PreparationOptions{}.removeSlivers;
  double SliverAngle = tc::PreparationOptions{}.sliverAngle;
  double SliverEdgeRatio = tc::PreparationOptions{}.sliverEdgeRatio;
  bool DropNonOrientable = tc::PreparationOptions{}.dropNonOrientable;
  vtkIdType MinComponentTriangles = tc::PreparationOptions{}.minComponentTriangles;
  bool KeepLargestComponent = tc::PreparationOptions{}.keepLargestComponent;
  std::string Report;
  bool Changed = false;
  vtkIdType NonManifoldEdges = 0;
  vtkIdType NonManifoldVertices = 0;
  vtkIdType BoundaryEdges = 0;
  vtkIdType OpenHoles = 0;
  vtkIdType NonOrientableComponents = 0;
  vtkIdType DroppedComponents = 0;
  vtkIdType DroppedComponentTriangles = 0;
  bool ClosedManifold = false;
  std::string ClosedManifoldRepairs;
};

#endif
