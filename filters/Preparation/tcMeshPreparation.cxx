// SPDX-License-Identifier: BSD-3-Clause
#include "tcMeshPreparation.h"

#include "tcMeshConversion.h"

#include "tc/common/array_names.h"
#include "tc/prep/corner_attributes.h"
#include "tc/prep/mesh_preparation.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStaticPointLocator.h>

vtkStandardNewMacro(tcMeshPreparation);

tcMeshPreparation::tcMeshPreparation() = default;
tcMeshPreparation::~tcMeshPreparation() = default;

namespace
{
/// Copies the arrays of `in` to `out`, element i of `out` taking element ids[i] of `in`; an
/// element with id -1 (added by hole filling) gets zeros in numeric arrays, and arrays of other
/// kinds (strings) are then left out.
void CopyArrays(
  vtkDataSetAttributes* in, vtkDataSetAttributes* out, const std::vector<int64_t>& ids)
{
  vtkNew<vtkIdList> from;
  vtkNew<vtkIdList> to;
  std::vector<vtkIdType> added;
  for (size_t i = 0; i < ids.size(); ++i)
  {
    if (ids[i] < 0)
    {
      added.push_back(static_cast<vtkIdType>(i));
      continue;
    }
    from->InsertNextId(ids[i]);
    to->InsertNextId(static_cast<vtkIdType>(i));
  }
  out->CopyAllocate(in, static_cast<vtkIdType>(ids.size()));
  out->CopyData(in, from, to);
  if (added.empty())
  {
    return;
  }
  for (int a = out->GetNumberOfArrays() - 1; a >= 0; --a)
  {
    vtkDataArray* array = vtkDataArray::SafeDownCast(out->GetAbstractArray(a));
    if (!array)
    {
      out->RemoveArray(a);
      continue;
    }
    const std::vector<double> zeros(static_cast<size_t>(array->GetNumberOfComponents()), 0.0);
    for (const vtkIdType i : added)
    {
      array->InsertTuple(i, zeros.data());
    }
  }
}

/// `inputPointId` with each point that hole filling added (-1) given the input point of the
/// nearest point that has one: a filled hole takes its rim's skin weights and texture
/// coordinates rather than zeros (zero weights would pose it at the origin).
std::vector<int64_t> NearestInputPoints(vtkPolyData* output, std::vector<int64_t> inputPointId)
{
  vtkNew<vtkPoints> kept;
  std::vector<int64_t> keptInput;
  for (size_t i = 0; i < inputPointId.size(); ++i)
  {
    if (inputPointId[i] >= 0)
    {
      kept->InsertNextPoint(output->GetPoint(static_cast<vtkIdType>(i)));
      keptInput.push_back(inputPointId[i]);
    }
  }
  if (keptInput.size() == inputPointId.size() || keptInput.empty())
  {
    return inputPointId;
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(kept);
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(cloud);
  locator->BuildLocator();
  for (size_t i = 0; i < inputPointId.size(); ++i)
  {
    if (inputPointId[i] < 0)
    {
      inputPointId[i] = keptInput[static_cast<size_t>(
        locator->FindClosestPoint(output->GetPoint(static_cast<vtkIdType>(i))))];
    }
  }
  return inputPointId;
}

/// The output's arrays: the input's point and cell arrays carried over (through InputPointId,
/// the nearest input point for a point hole filling added, and the input cell of each
/// triangle, `inputCells`), where each element came from, the
/// non-manifold and boundary flags, the components, and the input's field data.
void AddPreparationArrays(vtkPolyData* input, const tc::PreparationResult& result,
  const std::vector<int64_t>& inputCells, vtkPolyData* output)
{
  CopyArrays(
    input->GetPointData(), output->GetPointData(), NearestInputPoints(output, result.inputPointId));
  CopyArrays(input->GetCellData(), output->GetCellData(), inputCells);
  vtkPointData* pd = output->GetPointData();
  vtkCellData* cd = output->GetCellData();
  pd->AddArray(tcvtk::MakeIntArray(tc::kInputPointId, result.inputPointId));
  pd->AddArray(tcvtk::MakeIntArray(tc::kNonManifoldVertex, result.nonManifoldVertex));
  pd->AddArray(tcvtk::MakeIntArray(tc::kBoundaryVertex, result.boundaryVertex));
  cd->AddArray(tcvtk::MakeIntArray(tc::kInputCellId, inputCells));
  cd->AddArray(tcvtk::MakeIntArray(tc::kNonManifoldEdge, result.nonManifoldEdge));
  cd->AddArray(tcvtk::MakeIntArray(tc::kComponentId, result.componentId));
  output->GetFieldData()->PassData(input->GetFieldData());
}
/// Corner values (tc/prep/corner_attributes.h) of the input's point arrays of floats or bytes
/// (texture coordinates, colours; not ids or labels) that the merge made discontinuous, as cell
/// arrays "<name>Corners", and the seam sides; returns the report line ("" if none).
std::string AddCornerArrays(vtkPolyData* input, const tc::PolygonSoup& soup,
  const tc::PreparationResult& result, vtkPolyData* output)
{
  vtkPointData* pd = input->GetPointData();
  std::vector<int64_t> corners;
  std::vector<tc::CornerAttribute> attributes;
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pd->GetArray(a);
    const int type = array ? array->GetDataType() : VTK_VOID;
    if (!array || !array->GetName() ||
      (type != VTK_FLOAT && type != VTK_DOUBLE && type != VTK_UNSIGNED_CHAR) ||
      array->GetNumberOfTuples() != soup.numPoints() || array->GetNumberOfComponents() > 64)
    {
      continue;
    }
    const int32_t n = array->GetNumberOfComponents();
    std::vector<double> values(static_cast<size_t>(soup.numPoints()) * n);
    for (vtkIdType i = 0; i < soup.numPoints(); ++i)
    {
      array->GetTuple(i, &values[static_cast<size_t>(i) * n]);
    }
    if (corners.empty())
    {
      corners = tc::cornerInputPoints(soup, result);
    }
    if (tc::mergeSplitsAttribute(values, n, corners, result))
    {
      attributes.push_back(tc::makeCornerAttribute(array->GetName(), values, n, corners, result));
    }
  }
  if (attributes.empty())
  {
    return "";
  }
  std::string names;
  for (const tc::CornerAttribute& a : attributes)
  {
    output->GetCellData()->AddArray(
      tcvtk::MakeArray((a.name + tc::kCornerValuesSuffix).c_str(), 3 * a.components, a.values));
    names += (names.empty() ? "" : ", ") + a.name;
  }
  const std::vector<uint8_t> seams = tc::seamSides(result.mesh.triangles, attributes);
  output->GetCellData()->AddArray(tcvtk::MakeIntArray(tc::kSeamSides, seams));
  int64_t sides = 0;
  for (const uint8_t s : seams)
  {
    sides += (s & 1) + ((s >> 1) & 1) + ((s >> 2) & 1);
  }
  return "kept the values of " + names + " at each triangle corner (" + std::to_string(sides / 2) +
    " seam edges)\n";
}
} // namespace

void tcMeshPreparation::ClearReport()
{
  this->Report.clear();
  this->Changed = false;
  this->NonManifoldEdges = this->NonManifoldVertices = this->BoundaryEdges = 0;
  this->OpenHoles = this->NonOrientableComponents = 0;
  this->DroppedComponents = this->DroppedComponentTriangles = 0;
  this->ClosedManifold = false;
  this->ClosedManifoldRepairs.clear();
}

void tcMeshPreparation::RecordReport(
  const tc::PreparationReport& counts, const tc::PreparationOptions& options, int64_t ignored)
{
  this->NonManifoldEdges = counts.nonManifoldEdges;
  this->NonManifoldVertices = counts.nonManifoldVertices;
  this->BoundaryEdges = counts.boundaryEdges;
  this->OpenHoles = counts.openHoles;
  this->NonOrientableComponents = counts.nonOrientableComponents;
  this->DroppedComponents =
    counts.droppedNonOrientable + counts.droppedSmallComponents + counts.droppedMinorComponents;
  this->DroppedComponentTriangles = counts.droppedNonOrientableTriangles +
    counts.droppedSmallTriangles + counts.droppedMinorTriangles;
  this->ClosedManifold = tc::closedManifold(counts, options);
  this->ClosedManifoldRepairs = tc::closedManifoldRepairs(counts, options);
  this->Report = counts.text();
  if (ignored > 0)
  {
    this->Report += "ignored " + std::to_string(ignored) + " vertex and line cells\n";
  }
  this->Changed = counts.changed() || ignored > 0;
}

int tcMeshPreparation::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // 1. Input and output.
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->ClearReport();

  // 2. Validate: a surface needs polygons; the core checks everything else.
  if (!input || input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    vtkErrorMacro("The input has no polygons; give a surface mesh (polygons or triangle strips).");
    return 0;
  }

  // 3. Convert.
  int64_t ignored = 0;
  std::vector<int64_t> polygonCell;
  const tc::PolygonSoup soup = tcvtk::ToPolygonSoup(input, polygonCell, ignored);

  // 4. Prepare, with progress and abort.
  tc::PreparationOptions options;
  options.mergeTolerance = this->MergeTolerance;
  options.splitNonManifold = this->SplitNonManifold;
  options.orient = this->Orient;
  options.fillHoles = this->FillHoles;
  options.maxHoleEdges = this->MaxHoleEdges;
  options.removeSlivers = this->RemoveSlivers;
  options.sliverAngle = this->SliverAngle;
  options.sliverEdgeRatio = this->SliverEdgeRatio;
  options.dropNonOrientable = this->DropNonOrientable;
  options.minComponentTriangles = this->MinComponentTriangles;
  options.keepLargestComponent = this->KeepLargestComponent;
  tc::PreparationResult result;
  try
  {
    result = tc::prepareMesh(soup, options, tcvtk::MakeProgress(this));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot prepare the mesh: " << e.what());
    return 0;
  }

  // 5. Output: the mesh, where each element came from, the flags, the input's arrays, the report.
  tcvtk::FromTriMesh(result.mesh, output);
  std::vector<int64_t> inputCells(result.inputCellId.size());
  for (size_t f = 0; f < inputCells.size(); ++f)
  {
    inputCells[f] = result.inputCellId[f] < 0 ? -1 : polygonCell[result.inputCellId[f]];
  }
  AddPreparationArrays(input, result, inputCells, output);
  const std::string seams = AddCornerArrays(input, soup, result, output);
  this->RecordReport(result.report, options, ignored);
  this->Report += seams;
  tcvtk::SetTextField(output->GetFieldData(), tc::kPreparationReport, this->Report);
  if (result.report.nonManifoldEdges + result.report.nonManifoldVertices > 0 &&
    !this->SplitNonManifold)
  {
    vtkWarningMacro("The mesh has " << result.report.nonManifoldEdges << " non-manifold edges and "
                                    << result.report.nonManifoldVertices
                                    << " non-manifold vertices (flagged in " << tc::kNonManifoldEdge
                                    << " / " << tc::kNonManifoldVertex
                                    << "); turn on SplitNonManifold to split them.");
  }
  else if (this->Changed)
  {
    vtkLog(INFO, "tcMeshPreparation: " << this->Report);
  }
  return 1;
}

void tcMeshPreparation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MergeTolerance: " << this->MergeTolerance << "\n";
  os << indent << "SplitNonManifold: " << this->SplitNonManifold << "\n";
  os << indent << "Orient: " << this->Orient << "\n";
  os << indent << "FillHoles: " << this->FillHoles << "\n";
  os << indent << "MaxHoleEdges: " << this->MaxHoleEdges << "\n";
  os << indent << "RemoveSlivers: " << this->RemoveSlivers << "\n";
  os << indent << "SliverAngle: " << this->SliverAngle << "\n";
  os << indent << "SliverEdgeRatio: " << this->SliverEdgeRatio << "\n";
  os << indent << "DropNonOrientable: " << this->DropNonOrientable << "\n";
  os << indent << "MinComponentTriangles: " << this->MinComponentTriangles << "\n";
  os << indent << "KeepLargestComponent: " << this->KeepLargestComponent << "\n";
  os << indent << "Report: " << this->Report << "\n";
}
