// SPDX-License-Identifier: BSD-3-Clause
#include "tcMultilevelMesh.h"

#include "tcMeshConversion.h"

#include "tc/common/array_names.h"

#include <vtkCompositeDataSet.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <string>

vtkStandardNewMacro(tcMultilevelMesh);

tcMultilevelMesh::tcMultilevelMesh() = default;

tcMultilevelMesh::~tcMultilevelMesh() = default;

namespace
{
/// The arrays every level carries: ParentId, ClusterSize, QuadricError.
void AddLevelArrays(const tc::MultilevelLevel& level, vtkPolyData* output)
{
  vtkPointData* pd = output->GetPointData();
  pd->AddArray(tcvtk::MakeIntArray(tc::kParentId, level.parents));
  pd->AddArray(tcvtk::MakeIntArray(tc::kClusterSize, level.clusterSizes));
  pd->AddArray(tcvtk::MakeArray(tc::kQuadricError, 1, level.errors));
  pd->SetActiveScalars(tc::kQuadricError);
}

/// Level k >= 1 as a mesh of its own vertices and derived triangles.
void LevelMesh(const tc::MultilevelLevel& level, vtkPolyData* output)
{
  tc::TriMesh mesh;
  mesh.points = level.points;
  mesh.triangles = level.triangles;
  tcvtk::FromTriMesh(mesh, output);
  AddLevelArrays(level, output);
}

/// The input with its levels' arrays and, per coarser level k, ClusterId<k>.
void FinestLevel(vtkPolyData* input, const tc::MultilevelMesh& multilevel, vtkPolyData* output)
{
  output->ShallowCopy(input);
  AddLevelArrays(multilevel.levels[0], output);
  for (size_t k = 1; k < multilevel.levels.size(); ++k)
  {
    const std::string name = tc::kLevelClusterIdPrefix + std::to_string(k);
    output->GetPointData()->AddArray(
      tcvtk::MakeIntArray(name.c_str(), multilevel.clusterOf(static_cast<int>(k))));
  }
}
} // namespace

int tcMultilevelMesh::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int tcMultilevelMesh::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // 1. Input and output.
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkMultiBlockDataSet* output = vtkMultiBlockDataSet::GetData(outputVector, 0);

  // 2 and 3. Validate while converting: triangles only.
  tc::TriMesh mesh;
  std::string error;
  if (!tcvtk::ToTriMesh(input, mesh, error))
  {
    vtkErrorMacro("Cannot build the multilevel mesh: " << error << ".");
    return 0;
  }

  // 4. The levels, with progress and abort.
  tc::MultilevelOptions options;
  options.branchingFactor = this->BranchingFactor;
  options.maxLevels = this->MaxLevels;
  options.coarsestVertices = this->CoarsestVertices;
  options.linkCondition = this->LinkCondition;
  tc::MultilevelMesh multilevel;
  try
  {
    multilevel = tc::buildMultilevelMesh(mesh, options, tcvtk::MakeProgress(this));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot build the multilevel mesh: " << e.what());
    return 0;
  }

  // 5. One block per level, finest first; the input's arrays pass through on block 0.
  const unsigned int levels = static_cast<unsigned int>(multilevel.levels.size());
  output->SetNumberOfBlocks(levels);
  for (unsigned int k = 0; k < levels; ++k)
  {
    vtkNew<vtkPolyData> block;
    if (k == 0)
    {
      FinestLevel(input, multilevel, block);
    }
    else
    {
      LevelMesh(multilevel.levels[k], block);
    }
    output->SetBlock(k, block);
    const std::string name = tc::kLevelBlockPrefix + std::to_string(k);
    output->GetMetaData(k)->Set(vtkCompositeDataSet::NAME(), name.c_str());
  }
  return 1;
}

void tcMultilevelMesh::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "BranchingFactor: " << this->BranchingFactor << "\n";
  os << indent << "MaxLevels: " << this->MaxLevels << "\n";
  os << indent << "CoarsestVertices: " << this->CoarsestVertices << "\n";
  os << indent << "LinkCondition: " << this->LinkCondition << "\n";
}
