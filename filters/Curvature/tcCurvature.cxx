// SPDX-License-Identifier: BSD-3-Clause
#include "tcCurvature.h"

#include "tcMeshConversion.h"

#include "tc/common/array_names.h"
#include "tc/features/crest_lines.h"
#include "tc/features/curvature.h"

#include <vtkCellData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

vtkStandardNewMacro(tcCurvature);

tcCurvature::tcCurvature()
{
  this->SetNumberOfOutputPorts(2);
}

tcCurvature::~tcCurvature() = default;

namespace
{
/// The curvature arrays of the mesh: k1 and k2 side by side, d1 then d2, the mean and Gaussian
/// curvatures, the fitted normals, the face means, and the vertices next to a crest line.
void AddCurvatureArrays(const tc::TriMesh& mesh, const tc::CurvatureResult& k,
  const tc::CrestLines& lines, vtkPolyData* output)
{
  std::vector<double> principal(2 * k.k1.size());
  for (size_t v = 0; v < k.k1.size(); ++v)
  {
    principal[2 * v] = k.k1[v];
    principal[2 * v + 1] = k.k2[v];
  }
  std::vector<double> directions(6 * k.k1.size());
  for (size_t v = 0; v < k.k1.size(); ++v)
  {
    std::copy_n(&k.d1[3 * v], 3, &directions[6 * v]);
    std::copy_n(&k.d2[3 * v], 3, &directions[6 * v + 3]);
  }
  vtkPointData* pd = output->GetPointData();
  pd->AddArray(tcvtk::MakeArray(tc::kPrincipalCurvatures, 2, principal));
  pd->AddArray(tcvtk::MakeArray(tc::kPrincipalDirections, 6, directions));
  pd->AddArray(tcvtk::MakeArray(tc::kMeanCurvature, 1, k.mean));
  pd->AddArray(tcvtk::MakeArray(tc::kGaussianCurvature, 1, k.gaussian));
  pd->SetNormals(tcvtk::MakeArray(tc::kVertexNormal, 3, k.normals));
  pd->SetActiveScalars(tc::kMeanCurvature);
  output->GetCellData()->AddArray(tcvtk::MakeArray(tc::kFaceMeanCurvature, 1, k.faceMean));
  pd->AddArray(tcvtk::MakeIntArray(tc::kCrestVertex, tc::crestVertices(mesh, lines)));
}

/// The crest lines as polylines over their own points, with their strength and type.
void CrestPolylines(const tc::CrestLines& lines, vtkPolyData* crest)
{
  vtkNew<vtkPoints> crestPoints;
  crestPoints->SetDataTypeToDouble();
  crestPoints->SetNumberOfPoints(static_cast<vtkIdType>(lines.points.size() / 3));
  for (vtkIdType i = 0; i < crestPoints->GetNumberOfPoints(); ++i)
  {
    crestPoints->SetPoint(i, &lines.points[3 * i]);
  }
  crest->SetPoints(crestPoints);
  crest->SetLines(tcvtk::MakeCellArray(lines.offsets, lines.connectivity));
  crest->GetCellData()->AddArray(tcvtk::MakeArray(tc::kStrength, 1, lines.strength));
  crest->GetCellData()->AddArray(tcvtk::MakeIntArray(tc::kCrestType, lines.type));
  crest->GetCellData()->SetActiveScalars(tc::kStrength);
}
} // namespace

int tcCurvature::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // 1. Input and outputs.
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* crest = vtkPolyData::GetData(outputVector, 1);

  // 2 and 3. Validate while converting: triangles only.
  tc::TriMesh mesh;
  std::string error;
  if (!tcvtk::ToTriMesh(input, mesh, error))
  {
    vtkErrorMacro("Cannot compute curvature: " << error << ".");
    return 0;
  }

  // 4. Curvature, then crest lines, with progress and abort.
  tc::CurvatureOptions options;
  options.minNeighbors = this->MinNeighbors;
  options.maxRings = this->MaxRings;
  options.degree = this->Degree;
  options.robust = this->Robust;
  options.robustIterations = this->RobustIterations;
  tc::CurvatureResult k;
  tc::CrestLines lines;
  const tc::Progress progress = tcvtk::MakeProgress(this);
  try
  {
    k = tc::computeCurvature(mesh, options, progress.sub(0.0, 0.8));
    if (this->ComputeCrestLines)
    {
      tc::CrestLineOptions crestOptions;
      crestOptions.minStrength = this->CrestStrengthThreshold;
      lines = tc::extractCrestLines(mesh, k, crestOptions, progress.sub(0.8, 1.0));
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot compute curvature: " << e.what());
    return 0;
  }

  // 5. Arrays on the mesh; crest lines as polylines.
  output->ShallowCopy(input);
  AddCurvatureArrays(mesh, k, lines, output);
  CrestPolylines(lines, crest);
  return 1;
}

void tcCurvature::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MinNeighbors: " << this->MinNeighbors << "\n";
  os << indent << "MaxRings: " << this->MaxRings << "\n";
  os << indent << "Degree: " << this->Degree << "\n";
  os << indent << "Robust: " << this->Robust << "\n";
  os << indent << "RobustIterations: " << this->RobustIterations << "\n";
  os << indent << "ComputeCrestLines: " << this->ComputeCrestLines << "\n";
  os << indent << "CrestStrengthThreshold: " << this->CrestStrengthThreshold << "\n";
}
