// SPDX-License-Identifier: BSD-3-Clause
#include "tcBaseComplex.h"

#include "tcMeshConversion.h"

#include "tc/common/array_names.h"
#include "tc/gim/base_complex.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <numeric>

vtkStandardNewMacro(tcBaseComplex);

tcBaseComplex::tcBaseComplex()
{
  this->SetNumberOfOutputPorts(2);
}

tcBaseComplex::~tcBaseComplex() = default;

namespace
{
/// The optional field array FeatureEdges (point-id pairs) into `edges`; false, saying why in
/// `error`, when it is not made of pairs.
bool ReadFeatureEdges(vtkFieldData* fd, std::vector<int32_t>& edges, std::string& error)
{
  vtkDataArray* array = fd->GetArray(tc::kFeatureEdges);
  if (!array)
  {
    return true;
  }
  if (array->GetNumberOfComponents() != 2)
  {
    error = std::string("field array ") + tc::kFeatureEdges + " must have 2 components";
    return false;
  }
  edges.resize(2 * static_cast<size_t>(array->GetNumberOfTuples()));
  for (vtkIdType e = 0; e < array->GetNumberOfTuples(); ++e)
  {
    edges[2 * e] = static_cast<int32_t>(array->GetComponent(e, 0));
    edges[2 * e + 1] = static_cast<int32_t>(array->GetComponent(e, 1));
  }
  return true;
}

/// Output port 0: the base triangles over the input points they keep, with InputPointId,
/// BaseFaceId and BaseEdgeIsFeature.
void BaseComplexMesh(
  const tc::TriMesh& mesh, const tc::BaseComplexResult& result, vtkPolyData* base)
{
  tc::TriMesh complex;
  complex.points.resize(3 * result.baseVertices.size());
  for (size_t b = 0; b < result.baseVertices.size(); ++b)
  {
    std::copy_n(
      &mesh.points[3 * static_cast<size_t>(result.baseVertices[b])], 3, &complex.points[3 * b]);
  }
  complex.triangles = result.baseTriangles;
  tcvtk::FromTriMesh(complex, base);
  std::vector<int32_t> faceIds(complex.numTriangles());
  std::iota(faceIds.begin(), faceIds.end(), 0);
  base->GetPointData()->AddArray(tcvtk::MakeIntArray(tc::kInputPointId, result.baseVertices));
  base->GetCellData()->AddArray(tcvtk::MakeIntArray(tc::kBaseFaceId, faceIds));
  vtkSmartPointer<vtkDataArray> sides = tcvtk::MakeArray(tc::kBaseEdgeIsFeature, 3,
    std::vector<double>(result.baseEdgeIsFeature.begin(), result.baseEdgeIsFeature.end()));
  base->GetCellData()->AddArray(sides);
}

/// Output port 1: the input with each vertex's base face and barycentric coordinates (MAPS);
/// the base complex itself travels in its field data, so that tcPathTracing needs this output
/// only.
void ParameterizedMesh(
  vtkPolyData* input, const tc::BaseComplexResult& result, vtkPolyData* parameterized)
{
  parameterized->ShallowCopy(input);
  parameterized->GetPointData()->AddArray(
    tcvtk::MakeIntArray(tc::kBaseFaceId, result.vertexBaseFace));
  parameterized->GetPointData()->AddArray(
    tcvtk::MakeArray(tc::kBaseBarycentric, 3, result.vertexBarycentric));
  parameterized->GetPointData()->SetActiveScalars(tc::kBaseFaceId);
  tcvtk::AddBaseComplexFields(result, parameterized->GetFieldData());
}
} // namespace

int tcBaseComplex::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // 1. Input and outputs.
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* base = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* parameterized = vtkPolyData::GetData(outputVector, 1);

  // 2 and 3. Validate while converting; the feature arrays are optional.
  tc::TriMesh mesh;
  std::string error;
  if (!tcvtk::ToTriMesh(input, mesh, error))
  {
    vtkErrorMacro("Cannot build the base complex: " << error << ".");
    return 0;
  }
  std::vector<uint8_t> feature;
  std::vector<uint8_t> corner;
  std::vector<int32_t> featureEdges;
  vtkPointData* pd = input->GetPointData();
  if (!tcvtk::ReadOptionalIntArray(pd, tc::kFeatureVertex, mesh.numPoints(), feature, error) ||
    !tcvtk::ReadOptionalIntArray(pd, tc::kCornerVertex, mesh.numPoints(), corner, error) ||
    !ReadFeatureEdges(input->GetFieldData(), featureEdges, error))
  {
    vtkErrorMacro("Cannot build the base complex: " << error << ".");
    return 0;
  }

  // 4. Simplify with MAPS.
  tc::BaseComplexOptions options;
  options.targetFaces = this->TargetFaces;
  options.maxError = this->MaxError;
  tc::BaseComplexResult result;
  try
  {
    result =
      tc::buildBaseComplex(mesh, feature, corner, featureEdges, options, tcvtk::MakeProgress(this));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot build the base complex: " << e.what());
    return 0;
  }

  // 5. The base complex over the input's points, and the parameterized input mesh.
  BaseComplexMesh(mesh, result, base);
  ParameterizedMesh(input, result, parameterized);
  return 1;
}

void tcBaseComplex::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TargetFaces: " << this->TargetFaces << "\n";
  os << indent << "MaxError: " << this->MaxError << "\n";
}
