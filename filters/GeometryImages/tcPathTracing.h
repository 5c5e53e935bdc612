// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcPathTracing
 * @brief Traces every base edge onto the input mesh and splits the mesh into one triangle patch
 * per base face (Feng et al. 2010, section 5.1, Fig. 9).
 *
 * Each base edge is a straight segment in the plane of its two unfolded base triangles; the
 * input triangles the MAPS parameterization puts there are cut where the segment crosses them
 * (Steiner points on input edges), so that the path of every base edge runs along mesh edges.
 * Every patch is then a topological disk bounded by the three paths of its base face.
 *
 * Input: tcBaseComplex's second output (the parameterized mesh: point arrays BaseFaceId and
 * BaseBarycentric, field arrays BaseVertexIds, BaseTriangles and BaseEdgeIsFeature).
 * Output port 0: the input split along the paths, cell array PatchId (the base face), point
 * array InputPointId (-1 for Steiner points, whose other point arrays are interpolated along
 * their input edge: SteinerEdge, SteinerParameter), cell data of the input triangle each piece
 * came from, and field arrays that describe the base complex and the paths (BaseVertexIds,
 * BaseTriangles, BaseEdgeIsFeature, BaseEdges, FaceEdges, PathOffsets, PathPoints) for
 * tcGeometryImages. Output port 1: the paths as polylines with cell arrays BaseEdgeId and
 * BaseEdgeIsFeature.
 */
#ifndef tcPathTracing_h
#define tcPathTracing_h

#include "TriChartGeometryImagesModule.h"

#include <vtkPolyDataAlgorithm.h>

#include <string>

class TRICHARTGEOMETRYIMAGES_EXPORT tcPathTracing : public vtkPolyDataAlgorithm
{
public:
  static tcPathTracing* New();
  vtkTypeMacro(tcPathTracing, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * After a failed update: whether it failed because the paths could not be traced (the
   * parameterization is not one-to-one somewhere, which slivers cause; removing them in
   * tcMeshPreparation, RemoveSlivers, is the repair), and what could not be traced. Cleared by
   * every update.
   */
  vtkGetMacro(Untraceable, bool);
  const char* GetUntraceableReason() const { return this->UntraceableReason.c_str(); }
  ///@}

protected:
  tcPathTracing();
  ~tcPathTracing() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  bool Untraceable = false;
  std::string UntraceableReason;

  tcPathTracing(const tcPathTracing&) = delete;
  void operator=(const tcPathTracing&) = delete;
};

#endif
