// SPDX-License-Identifier: BSD-3-Clause
/// @file atlas.h
/// The atlas of triangular geometry images (Feng et al. 2010, sections 5.2 and 6): the product
/// of the static pipeline. One chart per base face; each chart is a right-triangle grid of
/// (2^d + 1) samples per side at every level d = 0 .. maxLevel; two charts share the
/// (2^dh + 2) x (2^dh + 1) rectangles of one packed image per mip step.
///
/// Sample (i, j) of a chart at level d, with N = 2^d and 0 <= i, j, i + j <= N: corner 0 is
/// (0, 0), corner 1 is (N, 0), corner 2 is (0, N). Side k runs from corner k to corner k + 1
/// (side 0: j = 0; side 1: i + j = N; side 2: i = 0), counter-clockwise seen from outside, like
/// the base face (corner 0, corner 1, corner 2). Parameter t = 0 .. N along side k:
/// side 0 (t, 0), side 1 (N - t, t), side 2 (0, N - t).
///
/// Invariants every producer keeps and every consumer may rely on (validateAtlas checks them):
/// - the neighbour across side k runs that side the other way: sample t on side k of chart c at
///   level d is bit-identical to sample N - t on side neighborSide[k] of neighborChart[k] at the
///   same level d (when both charts have level d);
/// - every sample at dyadic arc-length fraction t / N of a side is the same point at every level,
///   so a coarser side's samples are a subset of a finer side's (what stitching by eq. 8 needs);
/// - the corner samples of all charts around one base vertex are bit-identical.
///
/// The file an atlas is stored in (tc/io/atlas_io.h) is described in docs/atlas-format.md.
#pragma once

#include "tc/skinning/skin.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tc
{
/// Names of the attributes every atlas carries first.
constexpr const char* kAtlasPosition = "Position";
constexpr const char* kAtlasNormal = "Normal";
/// The attribute a texture is looked up with: (u, v), v = 0 at a texture's bottom row.
constexpr const char* kAtlasTextureCoordinates = "TextureCoordinates";
/// The skin of a skinned atlas, tc::kSkinValues (8) components: the sample's 4 joints
/// (integers, indices into Atlas::rig's skeleton) and their 4 weights (tc::blendInfluences of
/// the input's skin).
constexpr const char* kAtlasSkin = "Skin";
/// The name of the input's base-colour texture among Atlas::textures.
constexpr const char* kAtlasBaseColorTexture = "BaseColor";

struct AtlasChart
{
  int32_t maxLevel = 0; ///< d_max: finest level, 2^d_max + 1 samples per side
  std::array<int32_t, 3> cornerVertex{ -1, -1,
    -1 }; ///< input point id of the base vertex at corner k
  std::array<int32_t, 3> neighborChart{ -1, -1, -1 }; ///< chart across side k
  std::array<int32_t, 3> neighborSide{ -1, -1, -1 };  ///< that chart's side (it runs the other way)
  std::array<uint8_t, 3> featureSide{ 0, 0, 0 };      ///< 1 if side k follows a feature curve
  int32_t partner = -1; ///< the chart packed in the same rectangles (-1: none)
  /// 0: sample (i, j) lies at texel origin + (i, j) (lower-left triangle of its rectangle);
  /// 1: at origin - (i, j) (upper-right triangle, turned by 180 degrees).
  uint8_t rotated = 0;
  /// Per image k = 0 .. maxLevel: texel (x, y) of sample (0, 0) of level maxLevel - k in image k.
  std::vector<std::array<int32_t, 2>> origin;
  /// Oriented bounding box as four corners, xyz each: c0 and the three corners adjacent to it
  /// (the pivot and major axes of eq. 6 of Feng et al.).
  std::array<double, 12> box{};
  /// Per level d = 0 .. maxLevel: largest distance between the chart's part of the input surface
  /// and its level-d grid, in input units (empty when not measured).
  std::vector<double> levelError;
};

struct AtlasAttribute
{
  std::string name;
  int32_t components = 0;
};

/// One packed image (a mip step): every attribute as float32, rows y = 0 .. height - 1, each
/// row x = 0 .. width - 1, components interleaved. Texels no chart covers hold 0.
struct AtlasImage
{
  int32_t width = 0;
  int32_t height = 0;
  std::vector<std::vector<float>> data; ///< per attribute: height x width x components
};

/// An image the atlas carries for its renderer and exporters, looked up by the
/// TextureCoordinates attribute (the input's base-colour texture): 8-bit RGBA, as the input's
/// file stored it (sRGB colours for a base-colour texture).
struct AtlasTexture
{
  std::string name;   ///< its role, unique in the atlas: kAtlasBaseColorTexture
  std::string source; ///< the file the input named, or "embedded:<k>" for its k-th image
  int32_t width = 0;
  int32_t height = 0;
  std::vector<uint8_t> rgba; ///< height x width x 4 bytes, row 0 = the bottom (v = 0)
};

struct Atlas
{
  std::vector<AtlasAttribute> attributes; ///< [0] Position (3), [1] Normal (3), then user arrays
  std::vector<AtlasImage> images;         ///< image k = 0 (finest) .. max maxLevel
  std::vector<AtlasChart> charts;         ///< chart c = base face c = PatchId c
  std::vector<AtlasTexture> textures;     ///< none, or the textures the attributes refer to
  Rig rig; ///< the skeleton and animations that pose the Skin attribute (empty: not skinned)
  int64_t inputPoints = 0; ///< of the mesh the atlas was built from
  int64_t inputTriangles = 0;
  double inputDiagonal = 0.0; ///< bounding-box diagonal of that mesh
  std::string source;         ///< what it was built from (file name), free text

  int32_t maxLevel() const
  {
    int32_t m = -1;
    for (const AtlasChart& c : charts)
    {
      m = c.maxLevel > m ? c.maxLevel : m;
    }
    return m;
  }
};

/// Texel (x, y) of sample (i, j) of chart c at level d (0 <= d <= c.maxLevel), in image
/// c.maxLevel - d.
inline std::array<int32_t, 2> atlasTexel(const AtlasChart& c, int32_t d, int32_t i, int32_t j)
{
  const std::array<int32_t, 2>& o = c.origin[static_cast<size_t>(c.maxLevel - d)];
  return c.rotated ? std::array<int32_t, 2>{ o[0] - i, o[1] - j }
                   : std::array<int32_t, 2>{ o[0] + i, o[1] + j };
}

/// Grid coordinates (i, j) of parameter t on side k of a level with N = 2^d samples per side.
inline std::array<int32_t, 2> sidePoint(int32_t side, int32_t t, int32_t n)
{
  switch (side)
  {
    case 0:
      return { t, 0 };
    case 1:
      return { n - t, t };
    default:
      return { 0, n - t };
  }
}

/// The inverse of sidePoint: side k and parameter t of grid point (i, j) of a level with
/// N = n samples per side, or side -1 (t = 0) for a point inside. A corner goes to the first side
/// of 0, 1, 2 that holds it: (0, 0) is t = 0 of side 0, (N, 0) t = N of side 0, (0, N) t = N of
/// side 1.
inline std::array<int32_t, 2> gridSide(int32_t i, int32_t j, int32_t n)
{
  if (j == 0)
  {
    return { 0, i };
  }
  if (i + j == n)
  {
    return { 1, j };
  }
  if (i == 0)
  {
    return { 2, n - j };
  }
  return { -1, 0 };
}

/// Number of samples (i, j), i + j <= N = 2^n, of a chart's level n: (N + 1)(N + 2) / 2.
inline int64_t gridVertexCount(int32_t n)
{
  const int64_t big = int64_t(1) << n;
  return (big + 1) * (big + 2) / 2;
}

/// Index of sample (i, j) of a chart's level n, row by row (j, then i): the order of a level's
/// samples in memory (the builder's grids, RebuiltMesh::chartVertexPoint, a vertex buffer).
inline int64_t gridVertexIndex(int32_t n, int32_t i, int32_t j)
{
  const int64_t big = int64_t(1) << n;
  return static_cast<int64_t>(j) * (big + 1) - static_cast<int64_t>(j) * (j - 1) / 2 + i;
}

/// The attribute values of sample (i, j) of chart `chart` at level d.
inline const float* atlasSample(
  const Atlas& atlas, int32_t chart, int32_t attribute, int32_t d, int32_t i, int32_t j)
{
  const AtlasChart& c = atlas.charts[static_cast<size_t>(chart)];
  const AtlasImage& image = atlas.images[static_cast<size_t>(c.maxLevel - d)];
  const std::array<int32_t, 2> xy = atlasTexel(c, d, i, j);
  const int32_t comps = atlas.attributes[static_cast<size_t>(attribute)].components;
  return image.data[static_cast<size_t>(attribute)].data() +
    (static_cast<size_t>(xy[1]) * static_cast<size_t>(image.width) + static_cast<size_t>(xy[0])) *
    static_cast<size_t>(comps);
}

/// Calls f(c, d, i, j, texel) for every sample (i, j) of every chart c that image k holds (at its
/// level d = maxLevel - k), with texel = y * width + x of that sample in the image. The layout
/// must be valid (validateAtlasLayout) for every texel to lie inside the image.
template <class F>
void forEachImageSample(const Atlas& atlas, size_t k, F&& f)
{
  const size_t width = static_cast<size_t>(atlas.images[k].width);
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    const AtlasChart& chart = atlas.charts[c];
    const int32_t d = chart.maxLevel - static_cast<int32_t>(k);
    if (d < 0)
    {
      continue;
    }
    const int32_t n = 1 << d;
    for (int32_t j = 0; j <= n; ++j)
    {
      for (int32_t i = 0; i + j <= n; ++i)
      {
        const std::array<int32_t, 2> xy = atlasTexel(chart, d, i, j);
        f(static_cast<int32_t>(c), d, i, j,
          static_cast<size_t>(xy[1]) * width + static_cast<size_t>(xy[0]));
      }
    }
  }
}

/// The index of attribute `name` in atlas.attributes, -1 when it has none of that name.
int32_t findAttribute(const Atlas& atlas, const std::string& name);

/// Checks the layout and every invariant above (sizes, texels inside their image and not shared
/// by two charts, neighbour symmetry, bit-identical shared sides and corners; a Skin attribute
/// identical on both sides too, its joints integers of the rig's skeleton, its weights finite
/// and not negative) and the textures.
/// @throws InputError naming the first chart and rule that fail
void validateAtlas(const Atlas& atlas);

/// The part of validateAtlas that needs no texel: attributes, image sizes, chart fields,
/// neighbours and partners, every chart's grid inside its images and no texel shared by two
/// charts (image data may be empty), and the textures: each named once, 1 to 2^16 texels wide
/// and high (their bytes may be empty; validateAtlas counts them), and only beside a
/// TextureCoordinates attribute of 2 components; a Skin attribute of kSkinValues components
/// exactly when the rig has a skeleton. What makes atlasTexel safe to index an image with.
/// @throws InputError naming the first chart and rule that fail
void validateAtlasLayout(const Atlas& atlas);
} // namespace tc
