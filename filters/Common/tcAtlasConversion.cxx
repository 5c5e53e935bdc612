// SPDX-License-Identifier: BSD-3-Clause
#include "tcAtlasConversion.h"

#include "tcMeshConversion.h"

#include "tc/common/array_names.h"
#include "tc/common/errors.h"

#include <vtkDataObject.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace tcvtk
{
namespace
{
vtkSmartPointer<vtkIntArray> intColumn(const char* name, int components, vtkIdType rows)
{
  auto array = vtkSmartPointer<vtkIntArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(rows);
  array->Fill(-1);
  return array;
}

vtkSmartPointer<vtkDoubleArray> doubleColumn(const char* name, int components, vtkIdType rows)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(rows);
  array->Fill(std::numeric_limits<double>::quiet_NaN());
  return array;
}

/// The column `name` as an array of type A with the table's rows and at least `components`
/// components, or nullptr with the reason in `error`.
template <typename A>
A* columnOf(vtkTable* table, const char* name, int components, const char* kind, std::string& error)
{
  auto* array = A::SafeDownCast(table->GetColumnByName(name));
  if (!array || array->GetNumberOfTuples() != table->GetNumberOfRows() ||
    array->GetNumberOfComponents() < components)
  {
    error = std::string("the chart table has no ") + kind + " column '" + name + "' with " +
      std::to_string(components) + " components";
    return nullptr;
  }
  return array;
}

vtkIntArray* intColumnOf(vtkTable* table, const char* name, int components, std::string& error)
{
  return columnOf<vtkIntArray>(table, name, components, "int", error);
}

vtkDoubleArray* doubleColumnOf(
  vtkTable* table, const char* name, int components, std::string& error)
{
  return columnOf<vtkDoubleArray>(table, name, components, "double", error);
}
} // namespace

namespace
{
/// Block 0 of the atlas: one row per chart (tcAtlasConversion.h lists the columns).
vtkSmartPointer<vtkTable> ChartTable(const tc::Atlas& atlas, int levels)
{
  const vtkIdType nc = static_cast<vtkIdType>(atlas.charts.size());
  auto id = intColumn(tc::kChartId, 1, nc);
  auto maxLevel = intColumn(tc::kMaxLevel, 1, nc);
  auto corners = intColumn(tc::kChartCorners, 3, nc);
  auto neighborChart = intColumn(tc::kNeighborChart, 3, nc);
  auto neighborSide = intColumn(tc::kNeighborSide, 3, nc);
  auto featureSide = intColumn(tc::kFeatureSide, 3, nc);
  auto partner = intColumn(tc::kPartner, 1, nc);
  auto rotated = intColumn(tc::kRotated, 1, nc);
  auto origin = intColumn(tc::kOrigin, 2 * levels, nc);
  auto box = doubleColumn(tc::kBox, 12, nc);
  auto levelError = doubleColumn(tc::kLevelError, levels, nc);
  for (vtkIdType c = 0; c < nc; ++c)
  {
    const tc::AtlasChart& chart = atlas.charts[static_cast<size_t>(c)];
    id->SetValue(c, static_cast<int>(c));
    maxLevel->SetValue(c, chart.maxLevel);
    partner->SetValue(c, chart.partner);
    rotated->SetValue(c, chart.rotated);
    for (int k = 0; k < 3; ++k)
    {
      corners->SetTypedComponent(c, k, chart.cornerVertex[static_cast<size_t>(k)]);
      neighborChart->SetTypedComponent(c, k, chart.neighborChart[static_cast<size_t>(k)]);
      neighborSide->SetTypedComponent(c, k, chart.neighborSide[static_cast<size_t>(k)]);
      featureSide->SetTypedComponent(c, k, chart.featureSide[static_cast<size_t>(k)]);
    }
    for (size_t k = 0; k < chart.origin.size() && k < static_cast<size_t>(levels); ++k)
    {
      origin->SetTypedComponent(c, static_cast<int>(2 * k), chart.origin[k][0]);
      origin->SetTypedComponent(c, static_cast<int>(2 * k + 1), chart.origin[k][1]);
    }
    for (int i = 0; i < 12; ++i)
    {
      box->SetTypedComponent(c, i, chart.box[static_cast<size_t>(i)]);
    }
    for (size_t d = 0; d < chart.levelError.size() && d < static_cast<size_t>(levels); ++d)
    {
      levelError->SetTypedComponent(c, static_cast<int>(d), chart.levelError[d]);
    }
  }
  auto table = vtkSmartPointer<vtkTable>::New();
  for (vtkAbstractArray* column : std::vector<vtkAbstractArray*>{ id, maxLevel, corners,
         neighborChart, neighborSide, featureSide, partner, rotated, origin, box, levelError })
  {
    table->AddColumn(column);
  }
  return table;
}

/// Block 1 of the atlas: one image per mip step, a float point array per attribute.
vtkSmartPointer<vtkMultiBlockDataSet> ImageBlocks(const tc::Atlas& atlas)
{
  auto images = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  images->SetNumberOfBlocks(static_cast<unsigned int>(atlas.images.size()));
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    const tc::AtlasImage& source = atlas.images[k];
    vtkNew<vtkImageData> image;
    image->SetDimensions(source.width, source.height, 1);
    for (size_t a = 0; a < atlas.attributes.size() && a < source.data.size(); ++a)
    {
      vtkNew<vtkFloatArray> array;
      array->SetName(atlas.attributes[a].name.c_str());
      array->SetNumberOfComponents(atlas.attributes[a].components);
      array->SetNumberOfTuples(static_cast<vtkIdType>(source.width) * source.height);
      std::copy(source.data[a].begin(), source.data[a].end(), array->GetPointer(0));
      image->GetPointData()->AddArray(array);
    }
    image->GetPointData()->SetActiveScalars(tc::kAtlasNormal);
    images->SetBlock(static_cast<unsigned int>(k), image);
    images->GetMetaData(static_cast<unsigned int>(k))
      ->Set(vtkCompositeDataSet::NAME(), (tc::kImageBlockPrefix + std::to_string(k)).c_str());
  }
  return images;
}

/// Block 2 of an atlas with textures: one image per texture, its bytes as RGBA scalars.
vtkSmartPointer<vtkMultiBlockDataSet> TextureBlocks(const tc::Atlas& atlas)
{
  auto textures = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  textures->SetNumberOfBlocks(static_cast<unsigned int>(atlas.textures.size()));
  for (size_t t = 0; t < atlas.textures.size(); ++t)
  {
    const tc::AtlasTexture& source = atlas.textures[t];
    vtkNew<vtkImageData> image;
    image->SetDimensions(source.width, source.height, 1);
    vtkNew<vtkUnsignedCharArray> bytes;
    bytes->SetName(tc::kTextureBytes);
    bytes->SetNumberOfComponents(4);
    bytes->SetNumberOfTuples(static_cast<vtkIdType>(source.width) * source.height);
    std::copy(source.rgba.begin(), source.rgba.end(), bytes->GetPointer(0));
    image->GetPointData()->SetScalars(bytes);
    vtkNew<vtkStringArray> file;
    file->SetName(tc::kTextureSource);
    file->InsertNextValue(source.source);
    image->GetFieldData()->AddArray(file);
    textures->SetBlock(static_cast<unsigned int>(t), image);
    textures->GetMetaData(static_cast<unsigned int>(t))
      ->Set(vtkCompositeDataSet::NAME(), source.name.c_str());
  }
  return textures;
}

/// The textures of block 2, each an image with its RGBA bytes.
bool ReadTextures(vtkMultiBlockDataSet* textures, tc::Atlas& atlas, std::string& error)
{
  for (unsigned int t = 0; t < textures->GetNumberOfBlocks(); ++t)
  {
    auto* image = vtkImageData::SafeDownCast(textures->GetBlock(t));
    const char* name = textures->HasMetaData(t)
      ? textures->GetMetaData(t)->Get(vtkCompositeDataSet::NAME())
      : nullptr;
    auto* bytes = image ? vtkUnsignedCharArray::SafeDownCast(
                            image->GetPointData()->GetAbstractArray(tc::kTextureBytes))
                        : nullptr;
    int dims[3] = { 0, 0, 0 };
    if (image)
    {
      image->GetDimensions(dims);
    }
    if (!bytes || !name || bytes->GetNumberOfComponents() != 4 || dims[2] != 1 ||
      bytes->GetNumberOfTuples() != static_cast<vtkIdType>(dims[0]) * dims[1])
    {
      error = "texture block " + std::to_string(t) +
        " is not a named image with an unsigned char RGBA array of its size";
      return false;
    }
    tc::AtlasTexture out;
    out.name = name;
    auto* file =
      vtkStringArray::SafeDownCast(image->GetFieldData()->GetAbstractArray(tc::kTextureSource));
    out.source = file && file->GetNumberOfValues() > 0 ? file->GetValue(0) : std::string();
    out.width = dims[0];
    out.height = dims[1];
    out.rgba.assign(bytes->GetPointer(0), bytes->GetPointer(0) + bytes->GetNumberOfValues());
    atlas.textures.push_back(std::move(out));
  }
  return true;
}

/// The field data of the atlas: where it came from.
void AddProvenance(const tc::Atlas& atlas, vtkFieldData* fd)
{
  vtkNew<vtkStringArray> source;
  source->SetName(tc::kAtlasSource);
  source->InsertNextValue(atlas.source);
  fd->AddArray(source);
  vtkNew<vtkTypeInt64Array> counts;
  counts->SetName(tc::kInputPoints);
  counts->InsertNextValue(atlas.inputPoints);
  fd->AddArray(counts);
  vtkNew<vtkTypeInt64Array> triangles;
  triangles->SetName(tc::kInputTriangles);
  triangles->InsertNextValue(atlas.inputTriangles);
  fd->AddArray(triangles);
  vtkNew<vtkDoubleArray> diagonal;
  diagonal->SetName(tc::kInputDiagonal);
  diagonal->InsertNextValue(atlas.inputDiagonal);
  fd->AddArray(diagonal);
  if (!atlas.rig.empty())
  {
    SetTextField(fd, tc::kRig, tc::encodeRig(atlas.rig));
  }
}

/// The columns of a chart table, each checked for its type, rows and components.
struct ChartColumns
{
  vtkIntArray* maxLevel = nullptr;
  vtkIntArray* corners = nullptr;
  vtkIntArray* neighborChart = nullptr;
  vtkIntArray* neighborSide = nullptr;
  vtkIntArray* featureSide = nullptr;
  vtkIntArray* partner = nullptr;
  vtkIntArray* rotated = nullptr;
  vtkIntArray* origin = nullptr;
  vtkDoubleArray* box = nullptr;
  vtkDoubleArray* levelError = nullptr;
};

/// Finds every column, in table order; false with the first missing one in `error`.
bool FindChartColumns(vtkTable* table, ChartColumns& t, std::string& error)
{
  t.maxLevel = intColumnOf(table, tc::kMaxLevel, 1, error);
  t.corners = t.maxLevel ? intColumnOf(table, tc::kChartCorners, 3, error) : nullptr;
  t.neighborChart = t.corners ? intColumnOf(table, tc::kNeighborChart, 3, error) : nullptr;
  t.neighborSide = t.neighborChart ? intColumnOf(table, tc::kNeighborSide, 3, error) : nullptr;
  t.featureSide = t.neighborSide ? intColumnOf(table, tc::kFeatureSide, 3, error) : nullptr;
  t.partner = t.featureSide ? intColumnOf(table, tc::kPartner, 1, error) : nullptr;
  t.rotated = t.partner ? intColumnOf(table, tc::kRotated, 1, error) : nullptr;
  t.origin = t.rotated ? intColumnOf(table, tc::kOrigin, 2, error) : nullptr;
  t.box = t.origin ? doubleColumnOf(table, tc::kBox, 12, error) : nullptr;
  t.levelError = t.box ? doubleColumnOf(table, tc::kLevelError, 1, error) : nullptr;
  return t.levelError != nullptr;
}

/// Row c of the chart table; false when its level exceeds what the columns hold.
bool ReadChart(const ChartColumns& t, vtkIdType c, tc::AtlasChart& chart, std::string& error)
{
  chart.maxLevel = t.maxLevel->GetValue(c);
  if (chart.maxLevel < 0 || 2 * (chart.maxLevel + 1) > t.origin->GetNumberOfComponents() ||
    chart.maxLevel + 1 > t.levelError->GetNumberOfComponents())
  {
    error = "chart " + std::to_string(c) + " has a level the table's columns do not cover";
    return false;
  }
  chart.partner = t.partner->GetValue(c);
  chart.rotated = static_cast<uint8_t>(t.rotated->GetValue(c) != 0);
  for (int k = 0; k < 3; ++k)
  {
    chart.cornerVertex[static_cast<size_t>(k)] = t.corners->GetTypedComponent(c, k);
    chart.neighborChart[static_cast<size_t>(k)] = t.neighborChart->GetTypedComponent(c, k);
    chart.neighborSide[static_cast<size_t>(k)] = t.neighborSide->GetTypedComponent(c, k);
    chart.featureSide[static_cast<size_t>(k)] =
      static_cast<uint8_t>(t.featureSide->GetTypedComponent(c, k) != 0);
  }
  for (int k = 0; k <= chart.maxLevel; ++k)
  {
    chart.origin.push_back(
      { t.origin->GetTypedComponent(c, 2 * k), t.origin->GetTypedComponent(c, 2 * k + 1) });
  }
  for (int i = 0; i < 12; ++i)
  {
    chart.box[static_cast<size_t>(i)] = t.box->GetTypedComponent(c, i);
  }
  bool measured = true;
  for (int d = 0; d <= chart.maxLevel; ++d)
  {
    measured &= !std::isnan(t.levelError->GetTypedComponent(c, d));
  }
  for (int d = 0; measured && d <= chart.maxLevel; ++d)
  {
    chart.levelError.push_back(t.levelError->GetTypedComponent(c, d));
  }
  return true;
}

/// The images and their attributes: the first image names the attributes, in its array order.
bool ReadImages(vtkMultiBlockDataSet* images, tc::Atlas& atlas, std::string& error)
{
  for (unsigned int k = 0; k < images->GetNumberOfBlocks(); ++k)
  {
    auto* image = vtkImageData::SafeDownCast(images->GetBlock(k));
    if (!image)
    {
      error = "block " + std::to_string(k) + " of the images is not a vtkImageData";
      return false;
    }
    int dims[3];
    image->GetDimensions(dims);
    tc::AtlasImage out;
    out.width = dims[0];
    out.height = dims[1];
    vtkPointData* pd = image->GetPointData();
    if (k == 0)
    {
      for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
      {
        if (vtkFloatArray::SafeDownCast(pd->GetAbstractArray(a)) && pd->GetArrayName(a))
        {
          atlas.attributes.push_back(
            { pd->GetArrayName(a), pd->GetAbstractArray(a)->GetNumberOfComponents() });
        }
      }
    }
    for (const tc::AtlasAttribute& attribute : atlas.attributes)
    {
      auto* array = vtkFloatArray::SafeDownCast(pd->GetAbstractArray(attribute.name.c_str()));
      if (!array || array->GetNumberOfComponents() != attribute.components ||
        array->GetNumberOfTuples() != static_cast<vtkIdType>(dims[0]) * dims[1] || dims[2] != 1)
      {
        error = "image " + std::to_string(k) + " lacks a float array '" + attribute.name +
          "' of its size";
        return false;
      }
      const float* values = array->GetPointer(0);
      out.data.emplace_back(values, values + array->GetNumberOfValues());
    }
    atlas.images.push_back(std::move(out));
  }
  return true;
}

/// Where the atlas came from (optional fields), and its rig.
/// @throws tc::InputError  for a Rig field that does not decode
void ReadProvenance(vtkFieldData* fd, tc::Atlas& atlas)
{
  const std::string rig = GetTextField(fd, tc::kRig);
  if (!rig.empty())
  {
    atlas.rig = tc::decodeRig(rig);
  }
  if (auto* source = vtkStringArray::SafeDownCast(fd->GetAbstractArray(tc::kAtlasSource)))
  {
    atlas.source = source->GetNumberOfValues() > 0 ? source->GetValue(0) : std::string();
  }
  if (vtkDataArray* a = fd->GetArray(tc::kInputPoints))
  {
    atlas.inputPoints = static_cast<int64_t>(a->GetTuple1(0));
  }
  if (vtkDataArray* a = fd->GetArray(tc::kInputTriangles))
  {
    atlas.inputTriangles = static_cast<int64_t>(a->GetTuple1(0));
  }
  if (vtkDataArray* a = fd->GetArray(tc::kInputDiagonal))
  {
    atlas.inputDiagonal = a->GetTuple1(0);
  }
}
} // namespace

void FromAtlas(const tc::Atlas& atlas, vtkMultiBlockDataSet* output)
{
  output->Initialize();
  const int levels = std::max(atlas.maxLevel() + 1, 1);
  output->SetBlock(0, ChartTable(atlas, levels));
  output->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), tc::kChartsBlock);
  output->SetBlock(1, ImageBlocks(atlas));
  output->GetMetaData(1u)->Set(vtkCompositeDataSet::NAME(), tc::kImagesBlock);
  if (!atlas.textures.empty())
  {
    output->SetBlock(2, TextureBlocks(atlas));
    output->GetMetaData(2u)->Set(vtkCompositeDataSet::NAME(), tc::kTexturesBlock);
  }
  AddProvenance(atlas, output->GetFieldData());
}

bool ToAtlas(vtkDataObject* input, tc::Atlas& atlas, std::string& error)
{
  atlas = tc::Atlas();
  auto* top = vtkMultiBlockDataSet::SafeDownCast(input);
  const unsigned int blocks = top ? top->GetNumberOfBlocks() : 0;
  vtkTable* table = blocks == 2 || blocks == 3 ? vtkTable::SafeDownCast(top->GetBlock(0)) : nullptr;
  auto* images = table ? vtkMultiBlockDataSet::SafeDownCast(top->GetBlock(1)) : nullptr;
  auto* textures =
    images && blocks == 3 ? vtkMultiBlockDataSet::SafeDownCast(top->GetBlock(2)) : nullptr;
  if (!images || (blocks == 3 && !textures))
  {
    error = "the input is not an atlas (a multiblock of a chart table, images and maybe "
            "textures, as made by tcGeometryImages or tcAtlasReader)";
    return false;
  }
  ChartColumns columns;
  if (!FindChartColumns(table, columns, error))
  {
    return false;
  }
  atlas.charts.resize(static_cast<size_t>(table->GetNumberOfRows()));
  for (vtkIdType c = 0; c < table->GetNumberOfRows(); ++c)
  {
    if (!ReadChart(columns, c, atlas.charts[static_cast<size_t>(c)], error))
    {
      return false;
    }
  }
  if (!ReadImages(images, atlas, error) || (textures && !ReadTextures(textures, atlas, error)))
  {
    return false;
  }
  try
  {
    ReadProvenance(top->GetFieldData(), atlas);
    tc::validateAtlas(atlas);
  }
  catch (const tc::InputError& e)
  {
    error = e.what();
    return false;
  }
  return true;
}
} // namespace tcvtk
