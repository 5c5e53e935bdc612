// SPDX-License-Identifier: BSD-3-Clause
#include "tcSurfaceDistance.h"

#include "tcMeshConversion.h"

#include "tc/common/array_names.h"
#include "tc/metrics/surface_distance.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <sstream>

vtkStandardNewMacro(tcSurfaceDistance);

tcSurfaceDistance::tcSurfaceDistance()
{
  this->SetNumberOfInputPorts(2);
}

tcSurfaceDistance::~tcSurfaceDistance() = default;

namespace
{
void addFigure(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  fd->RemoveArray(name);
  fd->AddArray(array);
}

/// The figures as field arrays, absolute and relative to the reference's diagonal, and as the
/// text DistanceReport.
void AddFigures(const tc::SurfaceDistanceResult& r, vtkFieldData* fd)
{
  const double diag = r.diagonal > 0 ? r.diagonal : 1.0;
  addFigure(fd, tc::kHausdorff, r.hausdorff);
  addFigure(fd, tc::kMeanDistance, r.meanDistance);
  addFigure(fd, tc::kRmsDistance, r.rmsDistance);
  addFigure(fd, tc::kRelativeHausdorff, r.hausdorff / diag);
  addFigure(fd, tc::kRelativeMeanDistance, r.meanDistance / diag);
  addFigure(fd, tc::kRelativeRmsDistance, r.rmsDistance / diag);
  addFigure(fd, tc::kReferenceDiagonal, r.diagonal);
  std::ostringstream report;
  report << "samples per mesh: " << r.samples << "\n"
         << "Hausdorff: " << r.hausdorff << " (" << 100.0 * r.hausdorff / diag << "% of diagonal)\n"
         << "mean: " << r.meanDistance << " (" << 100.0 * r.meanDistance / diag << "%)\n"
         << "RMS: " << r.rmsDistance << " (" << 100.0 * r.rmsDistance / diag << "%)\n"
         << "mesh to reference max: " << r.forwardMax
         << ", reference to mesh max: " << r.backwardMax << "\n";
  tcvtk::SetTextField(fd, tc::kDistanceReport, report.str());
}
} // namespace

int tcSurfaceDistance::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // 1. Inputs and output.
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* reference = vtkPolyData::GetData(inputVector[1], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);

  // 2 and 3. Both must be triangle meshes.
  tc::TriMesh mesh;
  tc::TriMesh ref;
  std::string error;
  if (!input || !reference)
  {
    vtkErrorMacro("Cannot measure the distance: connect the mesh to port 0 and the reference "
                  "to port 1.");
    return 0;
  }
  if (!tcvtk::ToTriMesh(input, mesh, error))
  {
    vtkErrorMacro("Cannot measure the distance of the mesh: " << error << ".");
    return 0;
  }
  if (!tcvtk::ToTriMesh(reference, ref, error))
  {
    vtkErrorMacro("Cannot measure the distance to the reference: " << error << ".");
    return 0;
  }

  // 4. Sample both surfaces and measure.
  tc::SurfaceDistanceOptions options;
  options.samplesPerMesh = this->SamplesPerMesh;
  options.seed = static_cast<uint32_t>(this->Seed);
  tc::SurfaceDistanceResult r;
  try
  {
    r = tc::surfaceDistance(mesh, ref, options, tcvtk::MakeProgress(this));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot measure the distance: " << e.what());
    return 0;
  }

  // 5. The mesh with its distances, and the figures.
  this->Hausdorff = r.hausdorff;
  this->MeanDistance = r.meanDistance;
  this->RmsDistance = r.rmsDistance;
  this->Diagonal = r.diagonal;
  output->ShallowCopy(input);
  output->GetPointData()->AddArray(tcvtk::MakeArray(tc::kDistance, 1, r.pointDistance));
  output->GetPointData()->SetActiveScalars(tc::kDistance);
  AddFigures(r, output->GetFieldData());
  return 1;
}

void tcSurfaceDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SamplesPerMesh: " << this->SamplesPerMesh << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
}
