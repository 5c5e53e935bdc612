// SPDX-License-Identifier: BSD-3-Clause
#include "tcGeometryImages.h"

#include "tcAtlasConversion.h"
#include "tcMeshConversion.h"

#include "tc/common/array_names.h"
#include "tc/common/errors.h"
#include "tc/gim/geometry_images.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>

vtkStandardNewMacro(tcGeometryImages);

// The property's values are the core's (the default member initializer casts one to the other).
static_assert(tcGeometryImages::LEVEL_RULE_AREA == static_cast<int>(tc::LevelRule::Area) &&
    tcGeometryImages::LEVEL_RULE_ERROR == static_cast<int>(tc::LevelRule::Error),
  "LevelRules and tc::LevelRule must agree");

tcGeometryImages::tcGeometryImages() = default;

tcGeometryImages::~tcGeometryImages() = default;

void tcGeometryImages::AddResampledArray(const char* name)
{
  if (name && *name &&
    std::find(this->ResampledArrays.begin(), this->ResampledArrays.end(), name) ==
      this->ResampledArrays.end())
  {
    this->ResampledArrays.emplace_back(name);
    this->Modified();
  }
}

void tcGeometryImages::ClearResampledArrays()
{
  if (!this->ResampledArrays.empty())
  {
    this->ResampledArrays.clear();
    this->Modified();
  }
}

namespace
{
/// The arrays to resample: the user's, then those of the input's look when kept.
std::vector<std::string> ArraysToResample(
  vtkPolyData* input, std::vector<std::string> names, bool appearance)
{
  for (const char* look : { tc::kTextureCoordinates, tc::kColors })
  {
    if (appearance && input->GetPointData()->GetArray(look) &&
      std::find(names.begin(), names.end(), look) == names.end())
    {
      names.emplace_back(look);
    }
  }
  return names;
}

/// The input's base-colour texture (the reader's field arrays) as the atlas's, when the atlas
/// has texture coordinates to look it up; false, saying what is inconsistent, in `error`.
bool ReadBaseColorTexture(vtkPolyData* input, tc::Atlas& atlas, std::string& error)
{
  vtkFieldData* fd = input->GetFieldData();
  auto* bytes = vtkUnsignedCharArray::SafeDownCast(fd->GetAbstractArray(tc::kBaseColorTexture));
  vtkDataArray* size = fd->GetArray(tc::kBaseColorTextureSize);
  if (!bytes || tc::findAttribute(atlas, tc::kAtlasTextureCoordinates) < 0)
  {
    return true;
  }
  if (!size || size->GetNumberOfTuples() != 1 || size->GetNumberOfComponents() != 2 ||
    bytes->GetNumberOfComponents() != 4 ||
    bytes->GetNumberOfTuples() !=
      static_cast<vtkIdType>(size->GetComponent(0, 0)) *
        static_cast<vtkIdType>(size->GetComponent(0, 1)))
  {
    error = std::string("the field ") + tc::kBaseColorTexture + " is not " +
      tc::kBaseColorTextureSize + " RGBA bytes (read the mesh again with tcMeshReader)";
    return false;
  }
  tc::AtlasTexture texture;
  texture.name = tc::kAtlasBaseColorTexture;
  texture.source = tcvtk::GetTextField(fd, tc::kBaseColorTextureName);
  texture.width = static_cast<int32_t>(size->GetComponent(0, 0));
  texture.height = static_cast<int32_t>(size->GetComponent(0, 1));
  texture.rgba.assign(bytes->GetPointer(0), bytes->GetPointer(0) + bytes->GetNumberOfValues());
  atlas.textures.push_back(std::move(texture));
  return true;
}

/// The point arrays to resample, each with its components; false, saying which is missing or
/// of the wrong size in `error`.
bool ReadResampledArrays(vtkPolyData* input, const std::vector<std::string>& names,
  std::vector<tc::GeometryImageAttribute>& extra, std::string& error)
{
  vtkPointData* pd = input->GetPointData();
  const vtkIdType np = input->GetNumberOfPoints();
  for (const std::string& name : names)
  {
    vtkDataArray* array = pd->GetArray(name.c_str());
    if (!array)
    {
      error = "the input has no numeric point array '" + name + "' to resample";
      return false;
    }
    tc::GeometryImageAttribute attribute;
    attribute.name = name;
    attribute.components = array->GetNumberOfComponents();
    if (!tcvtk::ReadArray(pd, name.c_str(), np, attribute.components, attribute.values, error))
    {
      return false;
    }
    // Values per triangle corner where the input's copies disagreed (a seam), if it has them.
    const std::string corners = name + tc::kCornerValuesSuffix;
    if (input->GetCellData()->GetArray(corners.c_str()) &&
      !tcvtk::ReadArray(input->GetCellData(), corners.c_str(), input->GetNumberOfCells(),
        3 * attribute.components, attribute.cornerValues, error))
    {
      return false;
    }
    extra.push_back(std::move(attribute));
  }
  return true;
}
/// The input's skin as the influences attribute Skin (tc::kSkinValues components: 4 joints, 4
/// weights) and its rig, when it has SkinIndices, SkinWeights and Rig; false, saying what is wrong,
/// in `error`.
bool ReadSkin(vtkPolyData* input, std::vector<tc::GeometryImageAttribute>& extra, tc::Rig& rig,
  std::string& error)
{
  vtkPointData* pd = input->GetPointData();
  const std::string text = tcvtk::GetTextField(input->GetFieldData(), tc::kRig);
  if (!pd->GetArray(tc::kSkinIndices) || !pd->GetArray(tc::kSkinWeights) || text.empty())
  {
    return true;
  }
  const vtkIdType np = input->GetNumberOfPoints();
  std::vector<double> joints, weights;
  if (!tcvtk::ReadArray(pd, tc::kSkinIndices, np, tc::kMaxInfluences, joints, error) ||
    !tcvtk::ReadArray(pd, tc::kSkinWeights, np, tc::kMaxInfluences, weights, error))
  {
    return false;
  }
  try
  {
    rig = tc::decodeRig(text);
  }
  catch (const tc::InputError& e)
  {
    error = e.what();
    return false;
  }
  tc::GeometryImageAttribute skin;
  skin.name = tc::kAtlasSkin;
  skin.components = tc::kSkinValues;
  skin.influences = true;
  skin.values.resize(static_cast<size_t>(np) * skin.components);
  for (vtkIdType p = 0; p < np; ++p)
  {
    double* row = &skin.values[tc::kSkinValues * p];
    std::copy_n(&joints[tc::kMaxInfluences * p], tc::kMaxInfluences, row);
    std::copy_n(&weights[tc::kMaxInfluences * p], tc::kMaxInfluences, row + tc::kMaxInfluences);
  }
  extra.push_back(std::move(skin));
  return true;
}
} // namespace

int tcGeometryImages::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int tcGeometryImages::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // 1. Input and output.
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkMultiBlockDataSet* output = vtkMultiBlockDataSet::GetData(outputVector, 0);

  // 2 and 3. The patches, paths and base complex; curvature and the arrays to resample.
  tc::PatchMesh patches;
  tc::BaseComplexResult base;
  std::string error;
  if (!tcvtk::ReadPatchMesh(input, patches, base, error))
  {
    vtkErrorMacro("Cannot build geometry images: " << error << ".");
    return 0;
  }
  if (this->MinLevel > this->MaxLevel)
  {
    vtkErrorMacro("Cannot build geometry images: MinLevel ("
      << this->MinLevel << ") is above MaxLevel (" << this->MaxLevel << ").");
    return 0;
  }
  const vtkIdType np = input->GetNumberOfPoints();
  std::vector<double> curvature;
  if (input->GetPointData()->GetArray(tc::kMeanCurvature) &&
    !tcvtk::ReadArray(input->GetPointData(), tc::kMeanCurvature, np, 1, curvature, error))
  {
    vtkErrorMacro("Cannot build geometry images: " << error << ".");
    return 0;
  }
  std::vector<tc::GeometryImageAttribute> extra;
  tc::Rig rig;
  if (!ReadResampledArrays(input,
        ArraysToResample(input, this->ResampledArrays, this->KeepAppearance), extra, error) ||
    (this->KeepSkin && !ReadSkin(input, extra, rig, error)))
  {
    vtkErrorMacro("Cannot build geometry images: " << error << ".");
    return 0;
  }

  // 4. Parameterize, resample, pack.
  tc::GeometryImageOptions options;
  options.errorTarget = this->ErrorTarget;
  options.sampleBudget = this->SampleBudget;
  options.minLevel = this->MinLevel;
  options.maxLevel = this->MaxLevel;
  options.curvatureWeight = this->CurvatureWeight;
  options.levelRule =
    this->LevelRule == LEVEL_RULE_AREA ? tc::LevelRule::Area : tc::LevelRule::Error;
  options.stretchIterations = this->StretchIterations;
  options.fitSamples = this->FitSamples;
  tc::Atlas atlas;
  try
  {
    atlas = tc::buildGeometryImages(
      patches, base, {}, curvature, extra, options, tcvtk::MakeProgress(this));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot build geometry images: " << e.what());
    return 0;
  }

  // 5. The input's texture, and the atlas as a multiblock.
  if (this->KeepAppearance && !ReadBaseColorTexture(input, atlas, error))
  {
    vtkErrorMacro("Cannot build geometry images: " << error << ".");
    return 0;
  }
  atlas.rig = std::move(rig);
  const std::string report = tcvtk::GetTextField(input->GetFieldData(), tc::kReaderReport);
  atlas.source = report.substr(0, report.find('\n'));
  tcvtk::FromAtlas(atlas, output);
  return 1;
}

void tcGeometryImages::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ErrorTarget: " << this->ErrorTarget << "\n";
  os << indent << "SampleBudget: " << this->SampleBudget << "\n";
  os << indent << "MinLevel: " << this->MinLevel << "\n";
  os << indent << "MaxLevel: " << this->MaxLevel << "\n";
  os << indent << "CurvatureWeight: " << this->CurvatureWeight << "\n";
  os << indent << "LevelRule: " << (this->LevelRule == LEVEL_RULE_AREA ? "Area" : "Error") << "\n";
  os << indent << "StretchIterations: " << this->StretchIterations << "\n";
  os << indent << "KeepSkin: " << this->KeepSkin << "\n";
  os << indent << "FitSamples: " << this->FitSamples << "\n";
  os << indent << "KeepAppearance: " << this->KeepAppearance << "\n";
  os << indent << "ResampledArrays:";
  for (const std::string& name : this->ResampledArrays)
  {
    os << " " << name;
  }
  os << "\n";
}
