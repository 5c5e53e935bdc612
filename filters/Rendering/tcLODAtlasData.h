// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file tcLODAtlasData.h
 * @brief What tcLODMapper computes on the CPU (Feng et al. 2010, section 6): the grid vertex
 * buffer every chart shares, the atlas packed for the shader's buffer textures, and each frame's
 * levels. Private to the Rendering module; no OpenGL here.
 */
#ifndef tcLODAtlasData_h
#define tcLODAtlasData_h

#include "tc/gim/atlas.h"
#include "tc/gim/lod_selection.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

class vtkActor;
class vtkPolyData;
class vtkRenderer;

namespace tcvtk::lod
{
/// The grids of levels 0 .. finest in one polydata, the vertex buffer every chart shares:
/// points (i, j, copy) and triangles in tc::gridVertexIndex order, counter-clockwise, as
/// tc::rebuildMesh orders them. A coarse level is repeated (copy k carries k in its points'
/// third coordinate) so that one instance draws several charts. `triangleStart` gets the first
/// grid triangle of each level and the total (#levels + 1), `copies` the charts one instance
/// draws per level.
void BuildGrids(int32_t finest, vtkPolyData* grid, std::vector<int64_t>& triangleStart,
  std::vector<int32_t>& copies);

/// What the atlas holds besides Position and Normal, for the message about an unknown
/// ColorAttribute: "it has MeanCurvature, ..." or "it has none besides Position and Normal".
std::string OtherAttributes(const tc::Atlas& atlas);

/// Every image of the atlas, one after another, 4 floats per texel.
struct AtlasTexels
{
  std::vector<int64_t> imageBase; ///< #images: first texel of each image
  std::vector<float> position;    ///< 4 x #texels: x, y, z, the colour value (TexelColor)
  std::vector<float> normal;      ///< 4 x #texels: nx, ny, nz, v of TextureCoordinates (or 0)
};

/// What rides in the fourth components of PackTexels' texels, the colour of a sample.
enum class TexelColor
{
  None,    ///< 0
  Scalar,  ///< the attribute's value, or the magnitude of a vector, in the positions
  Texture, ///< the attribute's (u, v): u in the positions, v in the normals
  Rgb      ///< the attribute's first three values (0 .. 255) as r * 65536 + g * 256 + b
};

/// The texels of the atlas, with attribute `attribute` (an index of atlas.attributes; -1: none)
/// in the fourth components as `color` says.
AtlasTexels PackTexels(const tc::Atlas& atlas, int attribute, TexelColor color);

/// tc::atlasTexel as one linear texel index and a signed row stride per (chart, image):
/// `origins` gets 4 ints per (chart, level) (index, stride, 0, 0; the stride is negative for a
/// rotated chart), `charts` 4 per chart (its first origin, its finest level, 0, 0).
void PackChartTable(const tc::Atlas& atlas, const std::vector<int64_t>& imageBase,
  std::vector<int32_t>& origins, std::vector<int32_t>& charts);

/// The first three rows of every row-major 4 x 4 instance matrix, as floats (12 per instance).
std::vector<float> InstanceRows(const std::vector<double>& instances);

/// The range of the colour attribute over the samples the charts use (texels between charts
/// hold 0), read from the fourth components of PackTexels' positions.
std::array<double, 2> AttributeRange(const tc::Atlas& atlas, const std::vector<float>& position);

/// The levels SetChartLevels or SetFixedLevel ask for, the same in every instance: each clamped
/// to its chart's finest, -1 (not drawn) kept; every chart at its finest when `chartLevels` does
/// not hold one level per chart. `levels` holds #instances x #charts values.
void FixedLevels(const tc::Atlas& atlas, const std::vector<int32_t>& chartLevels, int fixedLevel,
  int instances, std::vector<int32_t>& levels);

/// The view-dependent levels (eq. 6 and 7, tc::selectLevels) of the `nc` charts in every
/// instance (16 doubles each, row-major), for the renderer's camera and viewport and the actor's
/// matrix; in parallel over the instances. With `posedBox` and `posedArea` (instances x nc x 12
/// and instances x nc: each instance's posed boxes, tcLODSkinning.h) instead of the charts'.
void ViewLevels(vtkRenderer* ren, vtkActor* act, const tc::LodCharts& charts,
  const std::vector<double>& instances, const tc::LodOptions& options, size_t nc,
  std::vector<int32_t>& levels, const float* posedBox = nullptr, const float* posedArea = nullptr);

} // namespace tcvtk::lod

#endif
