// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcSurfaceDistance
 * @brief Symmetric Hausdorff, mean and RMS distance between two surfaces by dense surface
 * sampling (Metro, Cignoni et al. 1998; the error measure of Feng et al. 2010, section 7).
 *
 * Input port 0: the mesh to measure (e.g. tcGeometryImageMesh's output); input port 1: the
 * reference (e.g. the original mesh). Both surfaces are sampled densely and deterministically
 * (vertices plus area-proportional points on the triangles) and each sample is measured to the
 * other surface. The output is the first input with point array Distance (each point's distance
 * to the reference, in input units) and one-value field arrays Hausdorff, MeanDistance,
 * RmsDistance (absolute), the same divided by the reference's bounding-box diagonal
 * (RelativeHausdorff, RelativeMeanDistance, RelativeRmsDistance), ReferenceDiagonal, and the
 * DistanceReport text. Either input missing or not made of triangles is an error.
 */
#ifndef tcSurfaceDistance_h
#define tcSurfaceDistance_h

#include "TriChartGeometryImagesModule.h"

#include "tc/metrics/surface_distance.h" // for the defaults of the properties

#include <vtkPolyDataAlgorithm.h>

class TRICHARTGEOMETRYIMAGES_EXPORT tcSurfaceDistance : public vtkPolyDataAlgorithm
{
public:
  static tcSurfaceDistance* New();
  vtkTypeMacro(tcSurfaceDistance, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The reference surface (input port 1).
  void SetReferenceConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetReferenceData(vtkDataObject* data) { this->SetInputData(1, data); }

  ///@{
  /// Samples drawn on each surface; 0 chooses a density from the triangle counts.
  vtkSetClampMacro(SamplesPerMesh, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(SamplesPerMesh, vtkIdType);
  ///@}

  ///@{
  /// Seed of the sampling: the same seed gives the same figures.
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /// The figures of the last run (absolute, in input units, and relative to the reference's
  /// bounding-box diagonal).
  vtkGetMacro(Hausdorff, double);
  vtkGetMacro(MeanDistance, double);
  vtkGetMacro(RmsDistance, double);
  vtkGetMacro(Diagonal, double);
  ///@}

protected:
  tcSurfaceDistance();
  ~tcSurfaceDistance() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcSurfaceDistance(const tcSurfaceDistance&) = delete;
  void operator=(const tcSurfaceDistance&) = delete;

  vtkIdType SamplesPerMesh = tc::SurfaceDistanceOptions{}.samplesPerMesh;
  // int(...), not static_cast: VTK's wrapper parser cannot read a static_cast here.
  int Seed = int(tc::SurfaceDistanceOptions{}.seed);
  double Hausdorff = 0.0;
  double MeanDistance = 0.0;
  double RmsDistance = 0.0;
  double Diagonal = 0.0;
};

#endif
