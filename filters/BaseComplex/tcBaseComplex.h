// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcBaseComplex
 * @brief The feature-constrained base complex and the MAPS parameterization of every input
 * vertex over it (Feng et al. 2010, section 5.1; Lee et al. 1998).
 *
 * Quadric-error half-edge collapses, each keeping one endpoint, simplify the mesh until it has
 * TargetFaces triangles or the next collapse would exceed MaxError, a fraction of the squared
 * bounding-box diagonal (a quadric error is a squared distance: 1e-4 is an RMS distance of 1% of
 * the diagonal; 0 lets the count alone decide). Feature curves simplify only along themselves
 * and become base edges; corners are never removed; no collapse changes the topology or flips a
 * triangle. As vertices are removed, MAPS keeps each one's position on the coarser mesh, so that
 * every input vertex ends with a base face and barycentric coordinates.
 *
 * Input: a closed manifold triangle mesh, normally tcFeatureRefinement's output (point arrays
 * FeatureVertex and CornerVertex, 0/1 per vertex, and field array FeatureEdges, #E x 2 point
 * ids, are used when present).
 * Output port 0: the base complex, #Fb triangles over #Vb input vertices (point array
 * InputPointId), cell arrays BaseFaceId (0 .. #Fb - 1) and BaseEdgeIsFeature (3 flags, side i
 * from corner i to i + 1). Output port 1: the input mesh with point arrays BaseFaceId and
 * BaseBarycentric (3 barycentric coordinates in that base face), and the base complex as field
 * arrays (BaseVertexIds, BaseTriangles, BaseEdgeIsFeature) for tcPathTracing.
 * A mesh that is not a closed manifold, or feature arrays of the wrong size, is an error.
 */
#ifndef tcBaseComplex_h
#define tcBaseComplex_h

#include "TriChartBaseComplexModule.h"

#include "tc/gim/base_complex.h" // for the defaults of the properties

#include <vtkPolyDataAlgorithm.h>

class TRICHARTBASECOMPLEX_EXPORT tcBaseComplex : public vtkPolyDataAlgorithm
{
public:
  static tcBaseComplex* New();
  vtkTypeMacro(tcBaseComplex, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Simplification stops when the base complex has at most this many triangles.
  vtkSetClampMacro(TargetFaces, vtkIdType, 4, VTK_ID_MAX);
  vtkGetMacro(TargetFaces, vtkIdType);
  ///@}

  ///@{
  /// It also stops before a collapse whose quadric error exceeds this fraction of the squared
  /// bounding-box diagonal; 0 disables the bound.
  vtkSetClampMacro(MaxError, double, 0.0, 1.0);
  vtkGetMacro(MaxError, double);
  ///@}

protected:
  tcBaseComplex();
  ~tcBaseComplex() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcBaseComplex(const tcBaseComplex&) = delete;
  void operator=(const tcBaseComplex&) = delete;

  vtkIdType TargetFaces = tc::BaseComplexOptions{}.targetFaces;
  double MaxError = tc::BaseComplexOptions{}.maxError;
};

#endif
