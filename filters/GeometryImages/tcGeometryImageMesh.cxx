// SPDX-License-Identifier: BSD-3-Clause
#include "tcGeometryImageMesh.h"

#include "tcAtlasConversion.h"
#include "tcMeshConversion.h"
#include "tcSkinData.h"

#include "tc/common/array_names.h"
#include "tc/gim/geometry_image_mesh.h"

#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

vtkStandardNewMacro(tcGeometryImageMesh);

tcGeometryImageMesh::tcGeometryImageMesh() = default;
tcGeometryImageMesh::~tcGeometryImageMesh() = default;

void tcGeometryImageMesh::SetChartLevels(vtkIntArray* levels)
{
  if (levels != this->ChartLevels)
  {
    this->ChartLevels = levels;
    this->Modified();
  }
}

vtkIntArray* tcGeometryImageMesh::GetChartLevels()
{
  return this->ChartLevels;
}

namespace
{
/// The atlas attribute Skin (tc::kSkinValues floats a point) as the point arrays SkinIndices
/// and SkinWeights.
void AddSkin(const std::vector<float>& values, vtkPointData* pd)
{
  tc::SkinWeights skin;
  const size_t n = values.size() / tc::kSkinValues;
  for (size_t p = 0; p < n; ++p)
  {
    const float* row = &values[tc::kSkinValues * p];
    for (int k = 0; k < tc::kMaxInfluences; ++k)
    {
      skin.joints.push_back(static_cast<int32_t>(row[k]));
      skin.weights.push_back(row[tc::kMaxInfluences + k]);
    }
  }
  tcvtk::AddSkinArrays(pd, skin);
}

/// The atlas attributes after Position as point arrays of the rebuilt mesh; Normal becomes its
/// normals (Normals), Skin the skin arrays.
void AddAtlasAttributes(const tc::Atlas& atlas, const tc::RebuiltMesh& rebuilt, vtkPointData* pd)
{
  const vtkIdType np = rebuilt.mesh.numPoints();
  for (size_t a = 1; a < atlas.attributes.size(); ++a)
  {
    if (atlas.attributes[a].name == tc::kAtlasSkin)
    {
      AddSkin(rebuilt.attributes[a - 1], pd);
      continue;
    }
    vtkNew<vtkFloatArray> array;
    const bool normal = atlas.attributes[a].name == tc::kAtlasNormal;
    array->SetName(normal ? tc::kVertexNormal : atlas.attributes[a].name.c_str());
    array->SetNumberOfComponents(atlas.attributes[a].components);
    array->SetNumberOfTuples(np);
    std::copy(
      rebuilt.attributes[a - 1].begin(), rebuilt.attributes[a - 1].end(), array->GetPointer(0));
    pd->AddArray(array);
    if (normal)
    {
      pd->SetNormals(array);
    }
  }
}
/// The atlas's base-colour texture as the reader's field arrays, and its coordinates as the
/// active texture coordinates, so that the rebuilt mesh is textured as the input was.
void AddBaseColorTexture(const tc::Atlas& atlas, vtkPolyData* output)
{
  vtkPointData* pd = output->GetPointData();
  for (const tc::AtlasTexture& texture : atlas.textures)
  {
    if (texture.name != tc::kAtlasBaseColorTexture || !pd->GetArray(tc::kTextureCoordinates))
    {
      continue;
    }
    vtkNew<vtkUnsignedCharArray> rgba;
    rgba->SetNumberOfComponents(4);
    rgba->SetNumberOfTuples(static_cast<vtkIdType>(texture.width) * texture.height);
    std::copy(texture.rgba.begin(), texture.rgba.end(), rgba->GetPointer(0));
    tcvtk::AddBaseColorTextureFields(
      output->GetFieldData(), rgba, texture.width, texture.height, texture.source);
    pd->SetActiveTCoords(tc::kTextureCoordinates);
  }
}
} // namespace

int tcGeometryImageMesh::FillInputPortInformation(int, vtkInformation* info)
{
  // Any data object: ToAtlas explains what an atlas is when it gets something else.
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

int tcGeometryImageMesh::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // 1. Input and output.
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);

  // 2 and 3. The atlas and the levels.
  tc::Atlas atlas;
  std::string error;
  if (!input || !tcvtk::ToAtlas(input, atlas, error))
  {
    vtkErrorMacro("Cannot rebuild a mesh: " << (input ? error : "no input") << ".");
    return 0;
  }
  std::vector<int32_t> levels;
  if (this->ChartLevels)
  {
    if (this->ChartLevels->GetNumberOfTuples() != static_cast<vtkIdType>(atlas.charts.size()))
    {
      vtkErrorMacro("Cannot rebuild a mesh: ChartLevels has "
        << this->ChartLevels->GetNumberOfTuples() << " values but the atlas has "
        << atlas.charts.size() << " charts.");
      return 0;
    }
    levels.assign(
      this->ChartLevels->GetPointer(0), this->ChartLevels->GetPointer(0) + atlas.charts.size());
  }
  else
  {
    for (const tc::AtlasChart& chart : atlas.charts)
    {
      levels.push_back(this->Level < 0 ? chart.maxLevel : this->Level);
    }
  }

  // 4. Rebuild with stitching.
  tc::RebuiltMesh rebuilt;
  try
  {
    rebuilt = tc::rebuildMesh(atlas, levels, tcvtk::MakeProgress(this));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot rebuild a mesh: " << e.what());
    return 0;
  }

  // 5. The mesh and its arrays.
  tcvtk::FromTriMesh(rebuilt.mesh, output);
  AddAtlasAttributes(atlas, rebuilt, output->GetPointData());
  output->GetPointData()->AddArray(tcvtk::MakeIntTuples(tc::kSampleChart, 3, rebuilt.pointSource));
  output->GetCellData()->AddArray(tcvtk::MakeIntArray(tc::kChartId, rebuilt.chartId));
  output->GetCellData()->AddArray(tcvtk::MakeIntArray(tc::kLevel, rebuilt.level));
  output->GetCellData()->SetActiveScalars(tc::kChartId);
  AddBaseColorTexture(atlas, output);
  if (!atlas.rig.empty())
  {
    tcvtk::SetTextField(output->GetFieldData(), tc::kRig, tc::encodeRig(atlas.rig));
  }
  return 1;
}

void tcGeometryImageMesh::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Level: " << this->Level << "\n";
  os << indent << "ChartLevels: " << (this->ChartLevels ? "set" : "(none)") << "\n";
}
