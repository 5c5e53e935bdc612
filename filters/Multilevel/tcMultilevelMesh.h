// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcMultilevelMesh
 * @brief The multilevel mesh of a triangle mesh: levels M0 .. Mn by QSlim with a constant
 * branching factor (Kircher and Garland 2005, section 3).
 *
 * Each level has about 1 / BranchingFactor of the vertices of the one below, made by
 * quadric-error pair contractions (Garland and Heckbert 1997) along its edges; the vertices of
 * one level contracted into one vertex of the next form a cluster, whose quadric is the sum of
 * its M0 vertices' and whose position minimizes it. A level's faces are the M0 faces whose
 * corners fall in three distinct clusters, so levels above M1 may be non-manifold; with
 * LinkCondition on, M1 is homeomorphic to M0 (which must then be a manifold).
 *
 * Output: a vtkMultiBlockDataSet with one vtkPolyData per level, finest first, block k named
 * "Level k". Each has point arrays ParentId (its vertex in level k + 1, -1 at the coarsest),
 * ClusterSize (M0 vertices under it) and QuadricError (its cluster's quadric at its position,
 * area x length^2). Block 0 is the input with, in addition, ClusterId1 .. ClusterIdn: the
 * vertex of level k each input point lies under, to colour M0 by the clusters of any level.
 *
 * The input must be triangles only (run tcMeshPreparation first); anything else is an error.
 */
#ifndef tcMultilevelMesh_h
#define tcMultilevelMesh_h

#include "TriChartMultilevelModule.h"

#include "tc/multilevel/multilevel_mesh.h" // for the defaults of the properties

#include <vtkMultiBlockDataSetAlgorithm.h>

class TRICHARTMULTILEVEL_EXPORT tcMultilevelMesh : public vtkMultiBlockDataSetAlgorithm
{
public:
  static tcMultilevelMesh* New();
  vtkTypeMacro(tcMultilevelMesh, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Each level has about 1 / BranchingFactor of the vertices of the one below (the paper
  /// uses 8).
  vtkSetClampMacro(BranchingFactor, int, 2, 1024);
  vtkGetMacro(BranchingFactor, int);
  ///@}

  ///@{
  /// Levels above the input at most; 0: as many as CoarsestVertices allows.
  vtkSetClampMacro(MaxLevels, int, 0, 64);
  vtkGetMacro(MaxLevels, int);
  ///@}

  ///@{
  /// A level is built only if it is to have at least this many vertices.
  vtkSetClampMacro(CoarsestVertices, int, 1, VTK_INT_MAX);
  vtkGetMacro(CoarsestVertices, int);
  ///@}

  ///@{
  /// Contract the input into level 1 only where the link condition holds, so that level 1 is
  /// homeomorphic to the input (which must then be a manifold).
  vtkSetMacro(LinkCondition, bool);
  vtkGetMacro(LinkCondition, bool);
  vtkBooleanMacro(LinkCondition, bool);
  ///@}

protected:
  tcMultilevelMesh();
  ~tcMultilevelMesh() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcMultilevelMesh(const tcMultilevelMesh&) = delete;
  void operator=(const tcMultilevelMesh&) = delete;

  int BranchingFactor = tc::MultilevelOptions{}.branchingFactor;
  int MaxLevels = tc::MultilevelOptions{}.maxLevels;
  int CoarsestVertices = tc::MultilevelOptions{}.coarsestVertices;
  bool LinkCondition = tc::MultilevelOptions{}.linkCondition;
};

#endif
