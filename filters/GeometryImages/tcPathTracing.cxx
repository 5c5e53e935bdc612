// SPDX-License-Identifier: BSD-3-Clause
#include "tcPathTracing.h"

#include "tc/skinning/skin.h"

#include "tcMeshConversion.h"

#include "tc/common/array_names.h"
#include "tc/common/errors.h"
#include "tc/gim/path_tracing.h"

#include <vtkCellData.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <string>

vtkStandardNewMacro(tcPathTracing);

tcPathTracing::tcPathTracing()
{
  this->SetNumberOfOutputPorts(2);
}

tcPathTracing::~tcPathTracing() = default;

namespace
{
/// The skin of point `v` (its SkinIndices and SkinWeights).
tc::PointSkin SkinOf(vtkIntArray* joints, vtkFloatArray* weights, vtkIdType v)
{
  tc::PointSkin skin;
  std::copy_n(joints->GetPointer(tc::kMaxInfluences * v), tc::kMaxInfluences, skin.joints.begin());
  std::copy_n(
    weights->GetPointer(tc::kMaxInfluences * v), tc::kMaxInfluences, skin.weights.begin());
  return skin;
}

/// The skin of the Steiner points: tc::blendInfluences of their edge's two ends, not the linear
/// blend of joint ids that InterpolateEdge gave.
void BlendSteinerSkin(vtkPointData* inPoints, const tc::PatchMesh& patches, vtkPointData* outPoints)
{
  auto* joints = vtkIntArray::SafeDownCast(outPoints->GetArray(tc::kSkinIndices));
  auto* weights = vtkFloatArray::SafeDownCast(outPoints->GetArray(tc::kSkinWeights));
  auto* inJoints = vtkIntArray::SafeDownCast(inPoints->GetArray(tc::kSkinIndices));
  auto* inWeights = vtkFloatArray::SafeDownCast(inPoints->GetArray(tc::kSkinWeights));
  if (!joints || !weights || !inJoints || !inWeights ||
    joints->GetNumberOfComponents() != tc::kMaxInfluences ||
    weights->GetNumberOfComponents() != tc::kMaxInfluences)
  {
    return;
  }
  const vtkIdType nInput = inPoints->GetNumberOfTuples();
  for (vtkIdType p = nInput; p < joints->GetNumberOfTuples(); ++p)
  {
    const size_t s = static_cast<size_t>(p - nInput);
    const tc::PointSkin ends[2] = { SkinOf(inJoints, inWeights, patches.steinerEdge[2 * s]),
      SkinOf(inJoints, inWeights, patches.steinerEdge[2 * s + 1]) };
    const double t = patches.steinerParameter[s];
    const double blend[2] = { 1.0 - t, t };
    const tc::PointSkin skin = tc::blendInfluences(2, ends, blend);
    std::copy(skin.joints.begin(), skin.joints.end(), joints->GetPointer(tc::kMaxInfluences * p));
    std::copy(
      skin.weights.begin(), skin.weights.end(), weights->GetPointer(tc::kMaxInfluences * p));
  }
}

/// Point data of the split mesh: the input's kept for input points and interpolated along the
/// input edge for Steiner points (the skin blended as influences; the MAPS arrays are meaningless
/// for those and are dropped), then InputPointId, SteinerEdge and SteinerParameter.
void CopyPointData(vtkPolyData* input, const tc::PatchMesh& patches, vtkPointData* outPoints)
{
  const vtkIdType np = patches.mesh.numPoints();
  const vtkIdType nInput = input->GetNumberOfPoints();
  vtkNew<vtkPointData> inPoints;
  inPoints->ShallowCopy(input->GetPointData());
  inPoints->RemoveArray(tc::kBaseFaceId);
  inPoints->RemoveArray(tc::kBaseBarycentric);
  inPoints->RemoveArray(tc::kInputPointId);
  outPoints->InterpolateAllocate(inPoints, np);
  for (vtkIdType p = 0; p < nInput; ++p)
  {
    outPoints->CopyData(inPoints, p, p);
  }
  std::vector<int32_t> steinerEdge(2 * static_cast<size_t>(np), -1);
  std::vector<double> steinerParameter(static_cast<size_t>(np), 0.0);
  for (vtkIdType p = nInput; p < np; ++p)
  {
    const size_t s = static_cast<size_t>(p - nInput);
    const int32_t a = patches.steinerEdge[2 * s];
    const int32_t b = patches.steinerEdge[2 * s + 1];
    const double t = patches.steinerParameter[s];
    outPoints->InterpolateEdge(inPoints, p, a, b, t);
    steinerEdge[2 * static_cast<size_t>(p)] = a;
    steinerEdge[2 * static_cast<size_t>(p) + 1] = b;
    steinerParameter[static_cast<size_t>(p)] = t;
  }
  BlendSteinerSkin(inPoints, patches, outPoints);
  outPoints->AddArray(tcvtk::MakeIntArray(tc::kInputPointId, patches.inputPointId));
  outPoints->AddArray(tcvtk::MakeIntTuples(tc::kSteinerEdge, 2, steinerEdge));
  outPoints->AddArray(tcvtk::MakeArray(tc::kSteinerParameter, 1, steinerParameter));
}

/// True for a cell array of corner values ("<name>Corners", 3 x k components).
bool IsCornerArray(vtkDataArray* array)
{
  const std::string suffix = tc::kCornerValuesSuffix;
  const std::string name = array && array->GetName() ? array->GetName() : "";
  return name.size() > suffix.size() &&
    name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0 &&
    array->GetNumberOfComponents() % 3 == 0;
}

/// Corner-value arrays recomputed at the pieces' own corners (tc::pieceCornerValues); the seam
/// sides of the input triangles mean nothing for their pieces and are left out.
void ReplaceCornerArrays(vtkCellData* inCells, const tc::TriMesh& mesh,
  const tc::PatchMesh& patches, vtkCellData* outCells)
{
  outCells->RemoveArray(tc::kSeamSides);
  for (int a = 0; a < inCells->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = inCells->GetArray(a);
    if (!IsCornerArray(array) || array->GetNumberOfTuples() != mesh.numTriangles())
    {
      continue;
    }
    const int n = array->GetNumberOfComponents();
    std::vector<double> values(static_cast<size_t>(mesh.numTriangles()) * n);
    for (vtkIdType f = 0; f < mesh.numTriangles(); ++f)
    {
      array->GetTuple(f, &values[static_cast<size_t>(f) * n]);
    }
    const std::vector<double> pieces = tc::pieceCornerValues(patches, mesh, values, n / 3);
    outCells->RemoveArray(array->GetName());
    outCells->AddArray(tcvtk::MakeArray(array->GetName(), n, pieces));
  }
}

/// Cell data of the split mesh: that of the input triangle each piece came from (corner values
/// at the piece's corners), then PatchId and InputCellId.
void CopyCellData(
  vtkPolyData* input, const tc::TriMesh& mesh, const tc::PatchMesh& patches, vtkCellData* outCells)
{
  vtkCellData* inCells = input->GetCellData();
  const vtkIdType nf = patches.mesh.numTriangles();
  outCells->CopyAllocate(inCells, nf);
  for (vtkIdType f = 0; f < nf; ++f)
  {
    outCells->CopyData(inCells, patches.inputTriangle[static_cast<size_t>(f)], f);
  }
  ReplaceCornerArrays(inCells, mesh, patches, outCells);
  outCells->AddArray(tcvtk::MakeIntArray(tc::kPatchId, patches.patchId));
  outCells->AddArray(tcvtk::MakeIntArray(tc::kInputCellId, patches.inputTriangle));
  outCells->SetActiveScalars(tc::kPatchId);
}

/// Field data of the split mesh: the input's, the base complex and the paths, for
/// tcGeometryImages.
void AddPathFields(vtkPolyData* input, const tc::BaseComplexResult& base,
  const tc::PatchMesh& patches, vtkFieldData* fd)
{
  fd->ShallowCopy(input->GetFieldData());
  tcvtk::AddBaseComplexFields(base, fd);
  tcvtk::AddIntField(fd, tc::kBaseEdges, 2, patches.baseEdges);
  tcvtk::AddIntField(fd, tc::kFaceEdges, 3, patches.faceEdges);
  tcvtk::AddIntField(fd, tc::kPathPoints, 1, patches.pathPoints);
  fd->RemoveArray(tc::kPathOffsets);
  fd->AddArray(tcvtk::MakeIntArray(tc::kPathOffsets, patches.pathOffsets));
}

/// Output port 1: the paths, one polyline each, with its base edge and whether it is a feature.
void PathPolylines(
  const tc::BaseComplexResult& base, const tc::PatchMesh& patches, vtkPolyData* paths)
{
  tcvtk::FromVertexPaths(patches.mesh, patches.pathOffsets, patches.pathPoints, paths);
  const size_t ne = patches.baseEdges.size() / 2;
  std::vector<int32_t> edgeIds(ne);
  std::vector<uint8_t> edgeFeature(ne, 0);
  for (size_t f = 0; f < patches.faceEdges.size(); ++f)
  {
    if (base.baseEdgeIsFeature[f])
    {
      edgeFeature[static_cast<size_t>(patches.faceEdges[f])] = 1;
    }
  }
  for (size_t e = 0; e < ne; ++e)
  {
    edgeIds[e] = static_cast<int32_t>(e);
  }
  paths->GetCellData()->AddArray(tcvtk::MakeIntArray(tc::kBaseEdgeId, edgeIds));
  paths->GetCellData()->AddArray(tcvtk::MakeIntArray(tc::kBaseEdgeIsFeature, edgeFeature));
  paths->GetCellData()->SetActiveScalars(tc::kBaseEdgeId);
}
} // namespace

int tcPathTracing::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // 1. Input and outputs.
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* paths = vtkPolyData::GetData(outputVector, 1);

  this->Untraceable = false;
  this->UntraceableReason.clear();

  // 2 and 3. The mesh, its base complex and the MAPS parameterization.
  tc::TriMesh mesh;
  tc::BaseComplexResult base;
  std::string error;
  if (!tcvtk::ToTriMesh(input, mesh, error) || !tcvtk::ReadBaseComplex(input, base, error))
  {
    vtkErrorMacro("Cannot trace paths: " << error << ".");
    return 0;
  }

  // 4. Trace.
  tc::PatchMesh patches;
  try
  {
    patches = tc::tracePaths(mesh, base, tcvtk::MakeProgress(this));
  }
  catch (const tc::UntraceableError& e)
  {
    this->Untraceable = true;
    this->UntraceableReason = e.reason();
    vtkErrorMacro("Cannot trace paths: " << e.what());
    return 0;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot trace paths: " << e.what());
    return 0;
  }

  // 5. The split mesh with its point, cell and field data; the paths as polylines.
  tcvtk::FromTriMesh(patches.mesh, output);
  CopyPointData(input, patches, output->GetPointData());
  try
  {
    CopyCellData(input, mesh, patches, output->GetCellData());
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot trace paths: " << e.what());
    return 0;
  }
  AddPathFields(input, base, patches, output->GetFieldData());
  PathPolylines(base, patches, paths);
  return 1;
}

void tcPathTracing::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Untraceable: " << this->Untraceable << "\n";
  os << indent << "UntraceableReason: " << this->UntraceableReason << "\n";
}
