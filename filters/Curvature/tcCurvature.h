// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcCurvature
 * @brief Robust per-vertex principal curvatures and directions, and crest lines
 * (Feng et al. 2010, section 4.2).
 *
 * Each vertex gets a weighted least-squares fit of a height function (degree 2 or 3) over an
 * adaptive neighbourhood of rings, iteratively reweighted against outliers in the spirit of
 * Kalogerakis et al. 2007. The result does not depend on the mesh's scale
 * (k(s * mesh) = k(mesh) / s) and little on its density.
 *
 * Output port 0: the input mesh with point arrays PrincipalCurvatures (k1 >= k2, positive where
 * convex, in 1 / input length units), PrincipalDirections (d1 then d2, 6 components, unit
 * vectors), MeanCurvature, GaussianCurvature, Normals, CrestVertex (1 next to a crest line:
 * what the clustering stages read), and cell array FaceMeanCurvature (mean of its vertices).
 * Output port 1: crest lines (ridges, where k1 is maximal along d1, and valleys, where k2 is
 * minimal along d2) as polylines with cell arrays Strength (integral of |k| along the line,
 * dimensionless) and CrestType (0 ridge, 1 valley).
 *
 * The input must be triangles only (run tcMeshPreparation first); anything else is an error.
 */
#ifndef tcCurvature_h
#define tcCurvature_h

#include "TriChartCurvatureModule.h"

#include "tc/features/crest_lines.h" // for the defaults of the properties

#include <vtkPolyDataAlgorithm.h>

class TRICHARTCURVATURE_EXPORT tcCurvature : public vtkPolyDataAlgorithm
{
public:
  static tcCurvature* New();
  vtkTypeMacro(tcCurvature, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Rings are added to a vertex's neighbourhood until it has at least this many vertices.
  vtkSetClampMacro(MinNeighbors, int, 6, 1000);
  vtkGetMacro(MinNeighbors, int);
  ///@}

  ///@{
  /// The neighbourhood never grows beyond this many rings.
  vtkSetClampMacro(MaxRings, int, 1, 20);
  vtkGetMacro(MaxRings, int);
  ///@}

  ///@{
  /// Degree of the fitted height function: 2 (quadric) or 3 (cubic).
  vtkSetClampMacro(Degree, int, 2, 3);
  vtkGetMacro(Degree, int);
  ///@}

  ///@{
  /// Reweight the fit against outliers (noise, sharp features across the neighbourhood).
  vtkSetMacro(Robust, bool);
  vtkGetMacro(Robust, bool);
  vtkBooleanMacro(Robust, bool);
  ///@}

  ///@{
  /// Number of reweighting iterations when Robust is on.
  vtkSetClampMacro(RobustIterations, int, 1, 10);
  vtkGetMacro(RobustIterations, int);
  ///@}

  ///@{
  /// Extract crest lines on output port 1.
  vtkSetMacro(ComputeCrestLines, bool);
  vtkGetMacro(ComputeCrestLines, bool);
  vtkBooleanMacro(ComputeCrestLines, bool);
  ///@}

  ///@{
  /// Crest lines weaker than this (integral of |k| along the line) are dropped.
  vtkSetClampMacro(CrestStrengthThreshold, double, 0.0, 1.0e6);
  vtkGetMacro(CrestStrengthThreshold, double);
  ///@}

protected:
  tcCurvature();
  ~tcCurvature() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcCurvature(const tcCurvature&) = delete;
  void operator=(const tcCurvature&) = delete;

  int MinNeighbors = tc::CurvatureOptions{}.minNeighbors;
  int MaxRings = tc::CurvatureOptions{}.maxRings;
  int Degree = tc::CurvatureOptions{}.degree;
  bool Robust = tc::CurvatureOptions{}.robust;
  int RobustIterations = tc::CurvatureOptions{}.robustIterations;
  bool ComputeCrestLines = true;
  double CrestStrengthThreshold = tc::CrestLineOptions{}.minStrength;
};

#endif
