// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcMeshoptSimplify
 * @brief The peer of TriChart's levels: meshoptimizer's quadric simplification
 * (meshopt_simplify, what gltfpack's discrete LOD chains are made of) of a triangle mesh to a
 * triangle count, so that an error curve can show both at the same counts (tc/metrics/qem_peer.h).
 *
 * The output keeps the vertices the simplified triangles use (positions only); a target at or
 * above the input's count returns the input's triangles.
 */
#ifndef tcMeshoptSimplify_h
#define tcMeshoptSimplify_h

#include "TriChartGeometryImagesModule.h"

#include <vtkPolyDataAlgorithm.h>

class TRICHARTGEOMETRYIMAGES_EXPORT tcMeshoptSimplify : public vtkPolyDataAlgorithm
{
public:
  static tcMeshoptSimplify* New();
  vtkTypeMacro(tcMeshoptSimplify, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The most triangles the output may have; default 1000.
  vtkSetClampMacro(TargetTriangles, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(TargetTriangles, vtkIdType);
  ///@}

protected:
  tcMeshoptSimplify() = default;
  ~tcMeshoptSimplify() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcMeshoptSimplify(const tcMeshoptSimplify&) = delete;
  void operator=(const tcMeshoptSimplify&) = delete;

  vtkIdType TargetTriangles = 1000;
};

#endif
