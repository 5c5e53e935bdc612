// SPDX-License-Identifier: BSD-3-Clause
#include "tcMeshConversion.h"

#include "tc/common/array_names.h"

#include <vtkAlgorithm.h>
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDataSetAttributes.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSignedCharArray.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>

#include <type_traits>

#include <cmath>
#include <sstream>

namespace tcvtk
{
namespace
{
void CopyPoints(vtkPolyData* input, std::vector<double>& points)
{
  const vtkIdType n = input->GetNumberOfPoints();
  points.resize(3 * n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    input->GetPoint(i, &points[3 * i]);
  }
}
}

tc::PolygonSoup ToPolygonSoup(
  vtkPolyData* input, std::vector<int64_t>& polygonCell, int64_t& ignoredCells)
{
  tc::PolygonSoup soup;
  polygonCell.clear();
  // vtkPolyData numbers its cells verts, lines, polys, strips.
  ignoredCells = input->GetNumberOfVerts() + input->GetNumberOfLines();
  int64_t cellId = ignoredCells;
  CopyPoints(input, soup.points);
  const vtkIdType* ids = nullptr;
  vtkIdType n = 0;
  auto it = vtk::TakeSmartPointer(input->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    it->GetCurrentCell(n, ids);
    std::vector<int64_t> polygon(ids, ids + n);
    soup.addPolygon(polygon.data(), n);
    polygonCell.push_back(cellId++);
  }
  auto strips = vtk::TakeSmartPointer(input->GetStrips()->NewIterator());
  for (strips->GoToFirstCell(); !strips->IsDoneWithTraversal(); strips->GoToNextCell())
  {
    strips->GetCurrentCell(n, ids);
    for (vtkIdType k = 0; k + 2 < n; ++k)
    {
      // Alternate the winding so every triangle of the strip keeps the strip's orientation.
      const int64_t tri[3] = { ids[k], ids[k + 1 + (k % 2)], ids[k + 2 - (k % 2)] };
      soup.addPolygon(tri, 3);
      polygonCell.push_back(cellId);
    }
    ++cellId;
  }
  return soup;
}

bool ToTriMesh(vtkPolyData* input, tc::TriMesh& mesh, std::string& error)
{
  if (!input)
  {
    error = "no input";
    return false;
  }
  const vtkIdType nonSurface =
    input->GetNumberOfVerts() + input->GetNumberOfLines() + input->GetNumberOfStrips();
  vtkCellArray* polys = input->GetPolys();
  const vtkIdType nf = polys->GetNumberOfCells();
  if (nf == 0)
  {
    error = "the input has no triangles; give a surface mesh";
    return false;
  }
  if (nonSurface > 0 || polys->GetNumberOfConnectivityIds() != 3 * nf)
  {
    error = "the input has cells that are not triangles; run tcMeshPreparation first";
    return false;
  }
  if (input->GetNumberOfPoints() > INT32_MAX)
  {
    error = "the input has more than 2^31 points, which TriChart does not support";
    return false;
  }
  CopyPoints(input, mesh.points);
  mesh.triangles.resize(3 * nf);
  const vtkIdType* ids = nullptr;
  vtkIdType n = 0;
  vtkIdType f = 0;
  auto it = vtk::TakeSmartPointer(polys->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++f)
  {
    it->GetCurrentCell(n, ids);
    for (int i = 0; i < 3; ++i)
    {
      mesh.triangles[3 * f + i] = static_cast<int32_t>(ids[i]);
    }
  }
  return true;
}

namespace
{
/// Double-precision points holding `xyz` (#points x 3, interleaved).
vtkSmartPointer<vtkPoints> MakePoints(const std::vector<double>& xyz)
{
  auto coords = vtkSmartPointer<vtkDoubleArray>::New();
  coords->SetNumberOfComponents(3);
  coords->SetNumberOfTuples(static_cast<vtkIdType>(xyz.size() / 3));
  std::copy(xyz.begin(), xyz.end(), coords->GetPointer(0));
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetData(coords);
  return points;
}
} // namespace

vtkSmartPointer<vtkCellArray> MakeCellArray(
  const std::vector<int64_t>& offsets, const std::vector<int64_t>& connectivity)
{
  auto offsetArray = vtkSmartPointer<vtkIdTypeArray>::New();
  auto connectivityArray = vtkSmartPointer<vtkIdTypeArray>::New();
  offsetArray->SetNumberOfValues(static_cast<vtkIdType>(offsets.size()));
  std::copy(offsets.begin(), offsets.end(), offsetArray->GetPointer(0));
  connectivityArray->SetNumberOfValues(static_cast<vtkIdType>(connectivity.size()));
  std::copy(connectivity.begin(), connectivity.end(), connectivityArray->GetPointer(0));
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsetArray, connectivityArray);
  return cells;
}

void FromPolygonSoup(const tc::PolygonSoup& soup, vtkPolyData* output)
{
  output->SetPoints(MakePoints(soup.points));
  output->SetPolys(MakeCellArray(soup.offsets, soup.connectivity));
}

void FromTriMesh(const tc::TriMesh& mesh, vtkPolyData* output)
{
  vtkSmartPointer<vtkPoints> points = MakePoints(mesh.points);
  auto offsets = vtkSmartPointer<vtkIdTypeArray>::New();
  auto connectivity = vtkSmartPointer<vtkIdTypeArray>::New();
  const int64_t nf = mesh.numTriangles();
  offsets->SetNumberOfValues(nf + 1);
  connectivity->SetNumberOfValues(3 * nf);
  for (int64_t f = 0; f <= nf; ++f)
  {
    offsets->SetValue(f, 3 * f);
  }
  for (int64_t k = 0; k < 3 * nf; ++k)
  {
    connectivity->SetValue(k, mesh.triangles[k]);
  }
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, connectivity);
  output->SetPoints(points);
  output->SetPolys(cells);
}

void FromVertexPaths(const tc::TriMesh& mesh, const std::vector<int64_t>& offsets,
  const std::vector<int32_t>& ids, vtkPolyData* output, bool asVertices)
{
  std::vector<int64_t> local(mesh.numPoints(), -1);
  std::vector<int64_t> inputIds;
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  for (size_t k = 0; k + 1 < offsets.size(); ++k)
  {
    cells->InsertNextCell(static_cast<vtkIdType>(offsets[k + 1] - offsets[k]));
    for (int64_t i = offsets[k]; i < offsets[k + 1]; ++i)
    {
      const int32_t v = ids[i];
      if (local[v] < 0)
      {
        local[v] = points->InsertNextPoint(&mesh.points[3 * static_cast<size_t>(v)]);
        inputIds.push_back(v);
      }
      cells->InsertCellPoint(local[v]);
    }
  }
  output->SetPoints(points);
  if (asVertices)
  {
    output->SetVerts(cells);
  }
  else
  {
    output->SetLines(cells);
  }
  output->GetPointData()->AddArray(MakeIntArray(tc::kInputPointId, inputIds));
}

vtkSmartPointer<vtkDataArray> MakeArray(
  const char* name, int components, const std::vector<double>& values)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / components));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  return array;
}

template <typename T>
vtkSmartPointer<vtkDataArray> MakeIntArray(const char* name, const std::vector<T>& values)
{
  vtkSmartPointer<vtkDataArray> array;
  if constexpr (sizeof(T) == 1 && std::is_signed<T>::value)
  {
    array = vtkSmartPointer<vtkSignedCharArray>::New();
  }
  else if constexpr (sizeof(T) == 1)
  {
    array = vtkSmartPointer<vtkUnsignedCharArray>::New();
  }
  else if constexpr (sizeof(T) == 4)
  {
    array = vtkSmartPointer<vtkIntArray>::New();
  }
  else
  {
    array = vtkSmartPointer<vtkIdTypeArray>::New();
  }
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (size_t i = 0; i < values.size(); ++i)
  {
    array->SetTuple1(static_cast<vtkIdType>(i), static_cast<double>(values[i]));
  }
  return array;
}

template TRICHARTCOMMON_EXPORT vtkSmartPointer<vtkDataArray> MakeIntArray<uint8_t>(
  const char*, const std::vector<uint8_t>&);
template TRICHARTCOMMON_EXPORT vtkSmartPointer<vtkDataArray> MakeIntArray<int8_t>(
  const char*, const std::vector<int8_t>&);
template TRICHARTCOMMON_EXPORT vtkSmartPointer<vtkDataArray> MakeIntArray<int32_t>(
  const char*, const std::vector<int32_t>&);
template TRICHARTCOMMON_EXPORT vtkSmartPointer<vtkDataArray> MakeIntArray<int64_t>(
  const char*, const std::vector<int64_t>&);

vtkSmartPointer<vtkDataArray> MakeIntTuples(
  const char* name, int components, const std::vector<int32_t>& values)
{
  auto array = vtkSmartPointer<vtkIntArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / static_cast<size_t>(components)));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  return array;
}

namespace
{
vtkDataArray* FindArray(vtkDataSetAttributes* attributes, const char* name, vtkIdType tuples,
  int components, std::string& error)
{
  vtkDataArray* array = attributes ? attributes->GetArray(name) : nullptr;
  if (!array)
  {
    error = std::string("the input has no array '") + name + "'";
    return nullptr;
  }
  if (array->GetNumberOfTuples() != tuples || array->GetNumberOfComponents() != components)
  {
    error = std::string("the array '") + name + "' has " +
      std::to_string(array->GetNumberOfTuples()) + " x " +
      std::to_string(array->GetNumberOfComponents()) + " values, expected " +
      std::to_string(tuples) + " x " + std::to_string(components);
    return nullptr;
  }
  return array;
}
}

bool ReadArray(vtkDataSetAttributes* attributes, const char* name, vtkIdType tuples, int components,
  std::vector<double>& values, std::string& error)
{
  vtkDataArray* array = FindArray(attributes, name, tuples, components, error);
  if (!array)
  {
    return false;
  }
  values.resize(static_cast<size_t>(tuples) * components);
  for (vtkIdType i = 0; i < tuples; ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      values[static_cast<size_t>(i) * components + c] = array->GetComponent(i, c);
    }
  }
  return true;
}

template <typename T>
bool ReadIntArray(vtkDataSetAttributes* attributes, const char* name, vtkIdType tuples,
  std::vector<T>& values, std::string& error)
{
  vtkDataArray* array = FindArray(attributes, name, tuples, 1, error);
  if (!array)
  {
    return false;
  }
  values.resize(static_cast<size_t>(tuples));
  for (vtkIdType i = 0; i < tuples; ++i)
  {
    values[static_cast<size_t>(i)] = static_cast<T>(std::llround(array->GetComponent(i, 0)));
  }
  return true;
}

template TRICHARTCOMMON_EXPORT bool ReadIntArray<uint8_t>(
  vtkDataSetAttributes*, const char*, vtkIdType, std::vector<uint8_t>&, std::string&);
template TRICHARTCOMMON_EXPORT bool ReadIntArray<int32_t>(
  vtkDataSetAttributes*, const char*, vtkIdType, std::vector<int32_t>&, std::string&);

template <typename T>
bool ReadOptionalIntArray(vtkDataSetAttributes* attributes, const char* name, vtkIdType tuples,
  std::vector<T>& values, std::string& error)
{
  return !attributes->GetArray(name) || ReadIntArray(attributes, name, tuples, values, error);
}

template TRICHARTCOMMON_EXPORT bool ReadOptionalIntArray<uint8_t>(
  vtkDataSetAttributes*, const char*, vtkIdType, std::vector<uint8_t>&, std::string&);

void AddBaseColorTextureFields(
  vtkFieldData* fd, vtkUnsignedCharArray* rgba, int width, int height, const std::string& name)
{
  rgba->SetName(tc::kBaseColorTexture);
  fd->AddArray(rgba);
  vtkNew<vtkIntArray> size;
  size->SetName(tc::kBaseColorTextureSize);
  size->SetNumberOfComponents(2);
  size->InsertNextTuple2(width, height);
  fd->AddArray(size);
  vtkNew<vtkStringArray> label;
  label->SetName(tc::kBaseColorTextureName);
  label->InsertNextValue(name);
  fd->AddArray(label);
}

void SetTextField(vtkFieldData* fd, const char* name, const std::string& text)
{
  auto lines = vtkSmartPointer<vtkStringArray>::New();
  lines->SetName(name);
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
  {
    lines->InsertNextValue(line);
  }
  fd->RemoveArray(name);
  fd->AddArray(lines);
}

std::string GetTextField(vtkFieldData* fd, const char* name)
{
  auto* lines = fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray(name)) : nullptr;
  std::string text;
  for (vtkIdType i = 0; lines && i < lines->GetNumberOfValues(); ++i)
  {
    text += lines->GetValue(i) + "\n";
  }
  return text;
}

std::string GetTextLine(vtkFieldData* fd, const char* name)
{
  auto* lines = fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray(name)) : nullptr;
  return lines && lines->GetNumberOfValues() > 0 ? lines->GetValue(0) : std::string();
}

namespace
{
bool readIntField(
  vtkFieldData* fd, const char* name, int components, std::vector<int32_t>& v, std::string& error)
{
  vtkDataArray* array = fd ? fd->GetArray(name) : nullptr;
  if (!array || array->GetNumberOfComponents() != components)
  {
    error = std::string("field array ") + name + " with " + std::to_string(components) +
      " components is missing";
    return false;
  }
  v.resize(static_cast<size_t>(array->GetNumberOfValues()));
  for (vtkIdType i = 0; i < array->GetNumberOfValues(); ++i)
  {
    v[static_cast<size_t>(i)] =
      static_cast<int32_t>(std::llround(array->GetComponent(i / components, i % components)));
  }
  return true;
}
} // namespace

void AddIntField(vtkFieldData* fd, const char* name, int components, const std::vector<int32_t>& v)
{
  fd->RemoveArray(name);
  fd->AddArray(MakeIntTuples(name, components, v));
}

namespace
{
/// The base complex as AddBaseComplexFields writes it, checked against a mesh of `numPoints`.
bool readBaseComplexFields(
  vtkFieldData* fd, vtkIdType numPoints, tc::BaseComplexResult& base, std::string& error)
{
  if (!readIntField(fd, tc::kBaseVertexIds, 1, base.baseVertices, error) ||
    !readIntField(fd, tc::kBaseTriangles, 3, base.baseTriangles, error) ||
    !readIntField(fd, tc::kBaseEdgeIsFeature, 3, base.baseEdgeIsFeature, error))
  {
    return false;
  }
  if (base.baseEdgeIsFeature.size() != base.baseTriangles.size())
  {
    error = std::string(tc::kBaseEdgeIsFeature) + " and " + tc::kBaseTriangles +
      " do not have the same number of faces";
    return false;
  }
  const int32_t nb = static_cast<int32_t>(base.baseVertices.size());
  for (int32_t v : base.baseVertices)
  {
    if (v < 0 || v >= numPoints)
    {
      error = std::string(tc::kBaseVertexIds) + " names a point the mesh does not have";
      return false;
    }
  }
  for (int32_t v : base.baseTriangles)
  {
    if (v < 0 || v >= nb)
    {
      error = std::string(tc::kBaseTriangles) + " names a base vertex that does not exist";
      return false;
    }
  }
  return true;
}
} // namespace

void AddBaseComplexFields(const tc::BaseComplexResult& base, vtkFieldData* fd)
{
  AddIntField(fd, tc::kBaseVertexIds, 1, base.baseVertices);
  AddIntField(fd, tc::kBaseTriangles, 3, base.baseTriangles);
  AddIntField(fd, tc::kBaseEdgeIsFeature, 3,
    std::vector<int32_t>(base.baseEdgeIsFeature.begin(), base.baseEdgeIsFeature.end()));
}

bool ReadBaseComplex(vtkPolyData* parameterized, tc::BaseComplexResult& base, std::string& error)
{
  base = tc::BaseComplexResult();
  const vtkIdType n = parameterized->GetNumberOfPoints();
  if (!readBaseComplexFields(parameterized->GetFieldData(), n, base, error) ||
    !ReadIntArray(parameterized->GetPointData(), tc::kBaseFaceId, n, base.vertexBaseFace, error) ||
    !ReadArray(
      parameterized->GetPointData(), tc::kBaseBarycentric, n, 3, base.vertexBarycentric, error))
  {
    error += " (connect the second output of tcBaseComplex)";
    return false;
  }
  const int32_t nf = static_cast<int32_t>(base.baseTriangles.size() / 3);
  for (int32_t f : base.vertexBaseFace)
  {
    if (f < 0 || f >= nf)
    {
      error = std::string(tc::kBaseFaceId) + " names a base face that does not exist";
      return false;
    }
  }
  return true;
}

namespace
{
/// True if the paths and base edges of `mesh` fit each other, the `np` points and the base
/// faces: one non-empty path per base edge, point ids and face edges in range.
bool PathsConsistent(const tc::PatchMesh& mesh, const tc::BaseComplexResult& base, vtkIdType np)
{
  const size_t ne = mesh.baseEdges.size() / 2;
  bool consistent = mesh.pathOffsets.size() == ne + 1 && mesh.pathOffsets.front() == 0 &&
    mesh.pathOffsets.back() == static_cast<int64_t>(mesh.pathPoints.size()) &&
    mesh.faceEdges.size() == base.baseTriangles.size();
  for (size_t e = 0; consistent && e < ne; ++e)
  {
    consistent = mesh.pathOffsets[e] < mesh.pathOffsets[e + 1];
  }
  for (int32_t p : mesh.pathPoints)
  {
    consistent = consistent && p >= 0 && p < np;
  }
  for (int32_t e : mesh.faceEdges)
  {
    consistent = consistent && e >= 0 && static_cast<size_t>(e) < ne;
  }
  return consistent;
}
} // namespace

bool ReadPatchMesh(
  vtkPolyData* patches, tc::PatchMesh& mesh, tc::BaseComplexResult& base, std::string& error)
{
  mesh = tc::PatchMesh();
  base = tc::BaseComplexResult();
  if (!ToTriMesh(patches, mesh.mesh, error))
  {
    return false;
  }
  const vtkIdType np = patches->GetNumberOfPoints();
  const vtkIdType nf = patches->GetNumberOfCells();
  vtkFieldData* fd = patches->GetFieldData();
  std::vector<int32_t> offsets;
  std::vector<double> steinerParameter;
  if (!ReadIntArray(patches->GetPointData(), tc::kInputPointId, np, mesh.inputPointId, error) ||
    !ReadIntArray(patches->GetCellData(), tc::kPatchId, nf, mesh.patchId, error) ||
    !ReadIntArray(patches->GetCellData(), tc::kInputCellId, nf, mesh.inputTriangle, error) ||
    !ReadArray(patches->GetPointData(), tc::kSteinerParameter, np, 1, steinerParameter, error) ||
    !readBaseComplexFields(fd, np, base, error) ||
    !readIntField(fd, tc::kBaseEdges, 2, mesh.baseEdges, error) ||
    !readIntField(fd, tc::kFaceEdges, 3, mesh.faceEdges, error) ||
    !readIntField(fd, tc::kPathOffsets, 1, offsets, error) ||
    !readIntField(fd, tc::kPathPoints, 1, mesh.pathPoints, error))
  {
    error += " (connect the first output of tcPathTracing)";
    return false;
  }
  vtkDataArray* edges = patches->GetPointData()->GetArray(tc::kSteinerEdge);
  if (!edges || edges->GetNumberOfComponents() != 2 || edges->GetNumberOfTuples() != np)
  {
    error = std::string("point array ") + tc::kSteinerEdge + " with 2 components is missing";
    return false;
  }
  for (vtkIdType p = 0; p < np; ++p)
  {
    if (mesh.inputPointId[static_cast<size_t>(p)] < 0)
    {
      mesh.steinerEdge.push_back(static_cast<int32_t>(edges->GetComponent(p, 0)));
      mesh.steinerEdge.push_back(static_cast<int32_t>(edges->GetComponent(p, 1)));
      mesh.steinerParameter.push_back(steinerParameter[static_cast<size_t>(p)]);
    }
  }
  mesh.pathOffsets.assign(offsets.begin(), offsets.end());
  if (!PathsConsistent(mesh, base, np))
  {
    error = "the paths and base edges in the field data do not match each other";
    return false;
  }
  return true;
}

tc::Progress MakeProgress(vtkAlgorithm* algorithm)
{
  return tc::Progress(
    [algorithm](double fraction)
    {
      algorithm->UpdateProgress(fraction);
      return algorithm->GetAbortExecute() == 0;
    });
}
} // namespace tcvtk
