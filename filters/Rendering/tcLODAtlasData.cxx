// SPDX-License-Identifier: BSD-3-Clause
#include "tcLODAtlasData.h"

#include "tc/common/array_names.h"
#include "tc/common/parallel.h"
#include "tc/gim/geometry_image_mesh.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <cmath>

namespace
{
/// Appends the grid of level n: points (i, j, copy), triangles in tc::gridVertexIndex order, as
/// tc::rebuildMesh orders them, counter-clockwise; the first point gets index `base`.
void AppendGrid(int32_t n, int32_t copy, vtkIdType base, vtkPoints* points, vtkCellArray* polys)
{
  const int32_t big = 1 << n;
  for (int32_t j = 0; j <= big; ++j)
  {
    for (int32_t i = 0; i + j <= big; ++i)
    {
      points->InsertNextPoint(i, j, copy);
    }
  }
  for (int32_t j = 0; j < big; ++j)
  {
    for (int32_t i = 0; i + j < big; ++i)
    {
      const vtkIdType a = base + tc::gridVertexIndex(n, i, j);
      const vtkIdType b = base + tc::gridVertexIndex(n, i + 1, j);
      const vtkIdType c = base + tc::gridVertexIndex(n, i, j + 1);
      const vtkIdType tri0[3] = { a, b, c };
      polys->InsertNextCell(3, tri0);
      if (i + j + 1 < big)
      {
        const vtkIdType d = base + tc::gridVertexIndex(n, i + 1, j + 1);
        const vtkIdType tri1[3] = { b, d, c };
        polys->InsertNextCell(3, tri1);
      }
    }
  }
}

/// The value an attribute sample shows: itself, or the magnitude of a vector.
float ScalarValue(const float* v, int comps)
{
  double value = comps == 1 ? v[0] : 0.0;
  if (comps > 1)
  {
    for (int c = 0; c < comps; ++c)
    {
      value += double(v[c]) * v[c];
    }
    value = std::sqrt(value);
  }
  return static_cast<float>(value);
}

/// An RGB colour of 0 .. 255 values as one float that holds the integer r * 65536 + g * 256 + b
/// exactly (below 2^24), for the shader to take apart; missing components are 0.
float RgbValue(const float* v, int comps)
{
  int32_t packed = 0;
  for (int c = 0; c < 3; ++c)
  {
    const float x = c < comps && std::isfinite(v[c]) ? v[c] : 0.0f;
    packed = packed * 256 + static_cast<int32_t>(std::lround(std::clamp(x, 0.0f, 255.0f)));
  }
  return static_cast<float>(packed);
}

/// The fourth components of texel t from attribute values `v` (of `comps` components).
void SetTexelColor(
  const float* v, int comps, tcvtk::lod::TexelColor color, float& position, float& normal)
{
  using tcvtk::lod::TexelColor;
  switch (color)
  {
    case TexelColor::Scalar:
      position = ScalarValue(v, comps);
      break;
    case TexelColor::Texture:
      position = v[0];
      normal = comps > 1 ? v[1] : 0.0f;
      break;
    case TexelColor::Rgb:
      position = RgbValue(v, comps);
      break;
    case TexelColor::None:
      break;
  }
}
} // namespace

namespace tcvtk::lod
{
void BuildGrids(int32_t finest, vtkPolyData* grid, std::vector<int64_t>& triangleStart,
  std::vector<int32_t>& copies)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  vtkNew<vtkCellArray> polys;
  triangleStart.assign(1, 0);
  copies.clear();
  vtkIdType base = 0;
  for (int32_t n = 0; n <= std::max(finest, 0); ++n)
  {
    const int32_t big = 1 << n;
    // An instance of one or four triangles costs far more than its triangles (GPUs start few
    // instances per clock), so the coarse grids are repeated: one instance draws
    // kCopyTriangles / 4^n charts.
    constexpr int32_t kCopyTriangles = 64;
    const int32_t levelCopies = std::max(1, kCopyTriangles >> (2 * n));
    copies.push_back(levelCopies);
    for (int32_t k = 0; k < levelCopies; ++k)
    {
      AppendGrid(n, k, base, points, polys);
      base += tc::gridVertexCount(n);
    }
    triangleStart.push_back(triangleStart.back() + int64_t(levelCopies) * big * big);
  }
  // Normals only so that VTK declares and lights them; the shader reads the normal image.
  vtkNew<vtkFloatArray> normals;
  normals->SetName(tc::kVertexNormal);
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(points->GetNumberOfPoints());
  normals->FillValue(0.0f);
  grid->Initialize();
  grid->SetPoints(points);
  grid->SetPolys(polys);
  grid->GetPointData()->SetNormals(normals);
}

std::string OtherAttributes(const tc::Atlas& atlas)
{
  std::string names;
  for (size_t a = 2; a < atlas.attributes.size(); ++a)
  {
    names += (names.empty() ? "" : ", ") + atlas.attributes[a].name;
  }
  return names.empty()
    ? std::string("it has none besides ") + tc::kAtlasPosition + " and " + tc::kAtlasNormal
    : "it has " + names;
}

AtlasTexels PackTexels(const tc::Atlas& atlas, int attribute, TexelColor color)
{
  AtlasTexels texels;
  int64_t count = 0;
  for (const tc::AtlasImage& image : atlas.images)
  {
    texels.imageBase.push_back(count);
    count += int64_t(image.width) * image.height;
  }
  texels.position.assign(static_cast<size_t>(4 * count), 0.0f);
  texels.normal.assign(static_cast<size_t>(4 * count), 0.0f);
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    const tc::AtlasImage& image = atlas.images[k];
    const int64_t base = texels.imageBase[k];
    const int64_t size = int64_t(image.width) * image.height;
    for (int64_t t = 0; t < size; ++t)
    {
      for (int c = 0; c < 3; ++c)
      {
        texels.position[static_cast<size_t>(4 * (base + t) + c)] =
          image.data[0][static_cast<size_t>(3 * t + c)];
        texels.normal[static_cast<size_t>(4 * (base + t) + c)] =
          image.data[1][static_cast<size_t>(3 * t + c)];
      }
      if (attribute >= 0)
      {
        const int comps = atlas.attributes[static_cast<size_t>(attribute)].components;
        const float* v = image.data[static_cast<size_t>(attribute)].data() + comps * t;
        SetTexelColor(v, comps, color, texels.position[static_cast<size_t>(4 * (base + t) + 3)],
          texels.normal[static_cast<size_t>(4 * (base + t) + 3)]);
      }
    }
  }
  return texels;
}

void PackChartTable(const tc::Atlas& atlas, const std::vector<int64_t>& imageBase,
  std::vector<int32_t>& origins, std::vector<int32_t>& charts)
{
  for (const tc::AtlasChart& chart : atlas.charts)
  {
    charts.insert(charts.end(), { static_cast<int32_t>(origins.size() / 4), chart.maxLevel, 0, 0 });
    for (int32_t k = 0; k <= chart.maxLevel; ++k)
    {
      const auto& o = chart.origin[static_cast<size_t>(k)];
      const int32_t width = atlas.images[static_cast<size_t>(k)].width;
      const int64_t linear = imageBase[static_cast<size_t>(k)] + int64_t(o[1]) * width + o[0];
      origins.insert(
        origins.end(), { static_cast<int32_t>(linear), chart.rotated ? -width : width, 0, 0 });
    }
  }
}

std::vector<float> InstanceRows(const std::vector<double>& instances)
{
  std::vector<float> rows;
  for (size_t m = 0; m < instances.size(); m += 16)
  {
    for (size_t e = 0; e < 12; ++e)
    {
      rows.push_back(static_cast<float>(instances[m + e]));
    }
  }
  return rows;
}

std::array<double, 2> AttributeRange(const tc::Atlas& atlas, const std::vector<float>& position)
{
  std::array<double, 2> range{ VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    const int32_t n = atlas.charts[c].maxLevel;
    for (int32_t j = 0; j <= (1 << n); ++j)
    {
      for (int32_t i = 0; i + j <= (1 << n); ++i)
      {
        // A chart's finest level lies in image 0.
        const auto xy = tc::atlasTexel(atlas.charts[c], n, i, j);
        const float value =
          position[static_cast<size_t>(4 * (int64_t(xy[1]) * atlas.images[0].width + xy[0]) + 3)];
        range[0] = std::min(range[0], double(value));
        range[1] = std::max(range[1], double(value));
      }
    }
  }
  return range;
}

void FixedLevels(const tc::Atlas& atlas, const std::vector<int32_t>& chartLevels, int fixedLevel,
  int instances, std::vector<int32_t>& levels)
{
  const size_t nc = atlas.charts.size();
  for (size_t c = 0; c < nc; ++c)
  {
    const int32_t finest = atlas.charts[c].maxLevel;
    int32_t level = chartLevels.size() == nc ? chartLevels[c]
      : fixedLevel >= 0                      ? fixedLevel
                                             : finest;
    level = level < 0 ? -1 : std::min(level, finest);
    for (int i = 0; i < instances; ++i)
    {
      levels[static_cast<size_t>(i) * nc + c] = level;
    }
  }
}

void ViewLevels(vtkRenderer* ren, vtkActor* act, const tc::LodCharts& charts,
  const std::vector<double>& instances, const tc::LodOptions& options, size_t nc,
  std::vector<int32_t>& levels, const float* posedBox, const float* posedArea)
{
  int width = 0, height = 0;
  ren->GetTiledSize(&width, &height);
  vtkMatrix4x4* worldToClip = ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
    ren->GetTiledAspectRatio(), -1, 1);
  vtkNew<vtkMatrix4x4> modelToClip;
  vtkMatrix4x4::Multiply4x4(worldToClip, act->GetMatrix(), modelToClip);
  const double* toClip = modelToClip->GetData();
  // Instances in parallel: a crowd has many of them, each with a few hundred charts.
  tc::parallel_for(
    static_cast<int64_t>(instances.size() / 16),
    [&](int64_t i)
    {
      tc::LodView view;
      view.width = std::max(1, width);
      view.height = std::max(1, height);
      vtkMatrix4x4::Multiply4x4(
        toClip, instances.data() + 16 * static_cast<size_t>(i), view.worldToClip.data());
      int32_t* out = levels.data() + static_cast<size_t>(i) * nc;
      if (posedBox)
      {
        tc::selectLevels(charts, posedBox + static_cast<size_t>(i) * nc * 12,
          posedArea + static_cast<size_t>(i) * nc, view, options, out);
      }
      else
      {
        tc::selectLevels(charts, view, options, out);
      }
    },
    tc::Progress(), 1);
}

} // namespace tcvtk::lod
