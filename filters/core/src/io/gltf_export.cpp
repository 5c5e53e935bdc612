// SPDX-License-Identifier: BSD-3-Clause
#include "tc/io/gltf_export.h"

#include "tc/common/array_names.h"
#include "tc/common/errors.h"
#include "tc/common/file_names.h"
#include "tc/gim/geometry_image_mesh.h"
#include "tc/io/png_write.h"

#include "io/gltf_skin.h"
#include "tc/io/temporary_file.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

namespace tc
{
namespace
{
const std::string kWhere = "writeGltf: ";

void checkOptions(const Atlas& atlas, const GltfExportOptions& o)
{
  if (!(o.errorRatio > 1.0 && std::isfinite(o.errorRatio)) || o.maxLods < 1 || o.maxLods > 64 ||
    (o.chain != GltfChain::Error && o.chain != GltfChain::Uniform) ||
    (o.layout != GltfLayout::MsftLod && o.layout != GltfLayout::NamedNodes) ||
    !(o.errorPixels > 0.0 && std::isfinite(o.errorPixels)) ||
    !(o.viewportHeight > 0.0 && std::isfinite(o.viewportHeight)))
  {
    throw InputError(kWhere + "errorRatio must be > 1, maxLods 1 .. 64, errorPixels and " +
      "viewportHeight > 0, chain Error or Uniform, layout MsftLod or NamedNodes " + "(got " +
      std::to_string(o.errorRatio) + ", " + std::to_string(o.maxLods) + ", " +
      std::to_string(o.errorPixels) + ", " + std::to_string(o.viewportHeight) + ")");
  }
  if (atlas.charts.empty() || atlas.attributes.size() < 2)
  {
    throw InputError(kWhere + "the atlas has no charts or no normals; build it again");
  }
  for (const AtlasChart& c : atlas.charts)
  {
    if (c.levelError.size() != static_cast<size_t>(c.maxLevel) + 1)
    {
      throw InputError(kWhere + "the atlas has no measured error per level (levelError); " +
        "build it again with this version");
    }
  }
}

/// The largest levelError of the charts at `levels`.
double largestError(const Atlas& atlas, const std::vector<int32_t>& levels)
{
  double e = 0.0;
  for (size_t c = 0; c < levels.size(); ++c)
  {
    e = std::max(e, atlas.charts[c].levelError[static_cast<size_t>(levels[c])]);
  }
  return e;
}

std::vector<std::vector<int32_t>> uniformLevels(const Atlas& atlas, int32_t maxLods)
{
  std::vector<std::vector<int32_t>> chain;
  for (int32_t level = atlas.maxLevel(); level >= 0 && chain.size() < size_t(maxLods); --level)
  {
    std::vector<int32_t> levels(atlas.charts.size());
    for (size_t c = 0; c < levels.size(); ++c)
    {
      levels[c] = std::min(level, atlas.charts[c].maxLevel);
    }
    chain.push_back(std::move(levels));
  }
  return chain;
}

/// Each chart at the coarsest level whose error is at most `bound`.
std::vector<int32_t> levelsWithin(const Atlas& atlas, double bound)
{
  std::vector<int32_t> levels(atlas.charts.size());
  for (size_t c = 0; c < levels.size(); ++c)
  {
    const AtlasChart& chart = atlas.charts[c];
    int32_t d = 0;
    while (d < chart.maxLevel && chart.levelError[static_cast<size_t>(d)] > bound)
    {
      ++d;
    }
    levels[c] = d;
  }
  return levels;
}

std::vector<std::vector<int32_t>> errorLevels(const Atlas& atlas, const GltfExportOptions& o)
{
  std::vector<std::vector<int32_t>> chain;
  std::vector<int32_t> levels(atlas.charts.size());
  for (size_t c = 0; c < levels.size(); ++c)
  {
    levels[c] = atlas.charts[c].maxLevel;
  }
  chain.push_back(levels);
  // The bound grows from the finest error (or, on an exact atlas, from the first non-zero one).
  double bound = largestError(atlas, levels);
  const std::vector<int32_t> coarsest(atlas.charts.size(), 0);
  while (levels != coarsest && chain.size() < size_t(o.maxLods))
  {
    bound = bound > 0.0 ? bound * o.errorRatio : std::numeric_limits<double>::min();
    std::vector<int32_t> next = levelsWithin(atlas, bound);
    if (next != levels)
    {
      levels = std::move(next);
      chain.push_back(levels);
      bound = largestError(atlas, levels); // the next LOD grows from what this one reached
    }
  }
  return chain;
}
} // namespace

std::vector<GltfLod> gltfLodChain(const Atlas& atlas, const GltfExportOptions& o)
{
  checkOptions(atlas, o);
  const std::vector<std::vector<int32_t>> chain =
    o.chain == GltfChain::Uniform ? uniformLevels(atlas, o.maxLods) : errorLevels(atlas, o);
  std::vector<GltfLod> lods(chain.size());
  for (size_t k = 0; k < chain.size(); ++k)
  {
    lods[k].chartLevels = chain[k];
    lods[k].error = largestError(atlas, chain[k]);
  }
  // LOD k serves coverages down to where LOD k + 1's error projects to errorPixels: an error e
  // projects to e / D * coverage * viewportHeight pixels for a diagonal D.
  const double diagonal = atlas.inputDiagonal > 0.0 ? atlas.inputDiagonal : 1.0;
  for (size_t k = 0; k + 1 < lods.size(); ++k)
  {
    const double e = lods[k + 1].error;
    lods[k].screenCoverage =
      e > 0.0 ? std::min(1.0, o.errorPixels * diagonal / (e * o.viewportHeight)) : 0.0;
  }
  return lods;
}

namespace
{
/// Appends `bytes` to the buffer at a 4-byte boundary and returns its buffer view.
int addView(tinygltf::Model& model, const void* bytes, size_t n, int target)
{
  return detail::addGltfView(model, bytes, n, target);
}

/// A float vertex attribute of `components` (1 .. 4), with its min and max when `bounds` (the
/// spec requires them for POSITION).
int addFloats(tinygltf::Model& model, const std::vector<float>& values, int components, bool bounds)
{
  static const int kTypes[] = { TINYGLTF_TYPE_SCALAR, TINYGLTF_TYPE_VEC2, TINYGLTF_TYPE_VEC3,
    TINYGLTF_TYPE_VEC4 };
  return detail::addGltfFloats(
    model, values, kTypes[components - 1], components, bounds, TINYGLTF_TARGET_ARRAY_BUFFER);
}

template <typename Index>
int addIndexView(tinygltf::Model& model, const std::vector<int32_t>& triangles)
{
  std::vector<Index> narrow(triangles.begin(), triangles.end());
  return addView(
    model, narrow.data(), narrow.size() * sizeof(Index), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
}

int addIndices(tinygltf::Model& model, const std::vector<int32_t>& triangles, int64_t points)
{
  tinygltf::Accessor a;
  const bool small = points <= std::numeric_limits<uint16_t>::max();
  a.bufferView =
    small ? addIndexView<uint16_t>(model, triangles) : addIndexView<uint32_t>(model, triangles);
  a.componentType =
    small ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  a.type = TINYGLTF_TYPE_SCALAR;
  a.count = triangles.size();
  model.accessors.push_back(a);
  return static_cast<int>(model.accessors.size()) - 1;
}

/// Unit normals: the atlas's are interpolated and quantized, glTF wants them normalized.
std::vector<float> unitNormals(std::vector<float> n)
{
  for (size_t i = 0; i + 2 < n.size(); i += 3)
  {
    const float length = std::sqrt(n[i] * n[i] + n[i + 1] * n[i + 1] + n[i + 2] * n[i + 2]);
    const float s = length > 0.0f ? 1.0f / length : 0.0f;
    n[i] *= s, n[i + 1] *= s, n[i + 2] *= s;
  }
  return n;
}

/// glTF's TEXCOORD_0 from the atlas's coordinates: glTF puts v = 0 at the image's top row, the
/// atlas (as OpenGL and VTK) at its bottom.
std::vector<float> gltfTexCoords(std::vector<float> uv)
{
  for (size_t i = 1; i < uv.size(); i += 2)
  {
    uv[i] = 1.0f - uv[i];
  }
  return uv;
}

/// glTF's COLOR_0 (floats in [0, 1]) from the atlas's Colors (0 .. 255).
std::vector<float> gltfColors(std::vector<float> rgba)
{
  for (float& x : rgba)
  {
    x = std::clamp(x / 255.0f, 0.0f, 1.0f);
  }
  return rgba;
}

/// The attribute semantic and values of atlas attribute a (>= 2) in glTF: TEXCOORD_0 and
/// COLOR_0 for the input's look, "_<name>" for any other; "" for one glTF cannot hold.
std::pair<std::string, std::vector<float>> gltfAttribute(
  const Atlas& atlas, size_t a, const std::vector<float>& values)
{
  const AtlasAttribute& attribute = atlas.attributes[a];
  if (attribute.name == kAtlasTextureCoordinates && attribute.components == 2)
  {
    return { "TEXCOORD_0", gltfTexCoords(values) };
  }
  if (attribute.name == kColors && (attribute.components == 3 || attribute.components == 4))
  {
    return { "COLOR_0", gltfColors(values) };
  }
  // glTF has no attribute of more components.
  return { attribute.components <= 4 ? "_" + attribute.name : "", values };
}

/// LOD `k`'s mesh (one primitive) into `model`; fills its counts.
void addMesh(tinygltf::Model& model, const Atlas& atlas, GltfLod& lod, size_t k)
{
  const RebuiltMesh rebuilt = rebuildMesh(atlas, lod.chartLevels);
  const TriMesh& m = rebuilt.mesh;
  lod.points = m.numPoints();
  lod.triangles = m.numTriangles();
  const std::vector<float> positions(m.points.begin(), m.points.end());
  tinygltf::Primitive p;
  p.mode = TINYGLTF_MODE_TRIANGLES;
  p.material = 0;
  p.attributes["POSITION"] = addFloats(model, positions, 3, true);
  p.attributes["NORMAL"] = addFloats(model, unitNormals(rebuilt.attributes[0]), 3, false);
  for (size_t a = 2; a < atlas.attributes.size(); ++a)
  {
    const auto [semantic, values] = gltfAttribute(atlas, a, rebuilt.attributes[a - 1]);
    if (!semantic.empty())
    {
      p.attributes[semantic] = addFloats(model, values, atlas.attributes[a].components, false);
    }
  }
  const int32_t skin = findAttribute(atlas, kAtlasSkin);
  if (!atlas.rig.empty() && skin >= 1)
  {
    detail::addGltfSkinAttributes(
      model, rebuilt.attributes[size_t(skin) - 1], atlas.rig.skeleton.joints.size(), p);
  }
  p.indices = addIndices(model, m.triangles, m.numPoints());
  tinygltf::Mesh mesh;
  mesh.name = "LOD" + std::to_string(k);
  mesh.primitives.push_back(p);
  model.meshes.push_back(mesh);
}

tinygltf::Value lodExtras(const GltfLod& lod, double diagonal)
{
  tinygltf::Value::Object o;
  o["error"] = tinygltf::Value(lod.error);
  o["errorFraction"] = tinygltf::Value(diagonal > 0.0 ? lod.error / diagonal : 0.0);
  o["triangles"] = tinygltf::Value(static_cast<double>(lod.triangles));
  return tinygltf::Value(o);
}

/// LOD 0's node (node 0) lists the others in MSFT_lod, with the coverage hints in its extras.
void linkByMsftLod(tinygltf::Model& model, const std::vector<GltfLod>& lods)
{
  tinygltf::Value::Array ids, coverage;
  for (size_t k = 0; k < lods.size(); ++k)
  {
    coverage.push_back(tinygltf::Value(lods[k].screenCoverage));
    if (k > 0)
    {
      ids.push_back(tinygltf::Value(static_cast<int>(k)));
    }
  }
  tinygltf::Value::Object lod;
  lod["ids"] = tinygltf::Value(ids);
  model.nodes[0].extensions["MSFT_lod"] = tinygltf::Value(lod);
  tinygltf::Value::Object extras = model.nodes[0].extras.Get<tinygltf::Value::Object>();
  extras["MSFT_screencoverage"] = tinygltf::Value(coverage);
  model.nodes[0].extras = tinygltf::Value(extras);
  model.extensionsUsed.push_back("MSFT_lod");
}

/// Nodes 0 .. #LOD - 1, one per LOD, and the scene of `layout`.
void addNodes(
  tinygltf::Model& model, const std::vector<GltfLod>& lods, double diagonal, GltfLayout layout)
{
  const bool named = layout == GltfLayout::NamedNodes;
  for (size_t k = 0; k < lods.size(); ++k)
  {
    tinygltf::Node node;
    node.name = (named ? "TriChart_LOD" : "LOD") + std::to_string(k);
    node.mesh = static_cast<int>(k);
    node.extras = lodExtras(lods[k], diagonal);
    model.nodes.push_back(node);
  }
  tinygltf::Scene scene;
  if (named)
  {
    tinygltf::Node group;
    group.name = "TriChart";
    for (size_t k = 0; k < lods.size(); ++k)
    {
      group.children.push_back(static_cast<int>(k));
    }
    model.nodes.push_back(group);
    scene.nodes.push_back(static_cast<int>(lods.size()));
  }
  else
  {
    if (lods.size() > 1)
    {
      linkByMsftLod(model, lods);
    }
    scene.nodes.push_back(0);
  }
  model.scenes.push_back(scene);
  model.defaultScene = 0;
}

/// The atlas's base-colour texture, when it has one and the coordinates to look it up.
const AtlasTexture* baseColorTexture(const Atlas& atlas)
{
  for (const AtlasTexture& texture : atlas.textures)
  {
    if (texture.name == kAtlasBaseColorTexture &&
      findAttribute(atlas, kAtlasTextureCoordinates) >= 0)
    {
      return &texture;
    }
  }
  return nullptr;
}

/// The one material: the base-colour texture as an embedded PNG (repeated, mipmapped: glTF's
/// defaults spelled out) on white, or grey without one.
void addMaterial(tinygltf::Model& model, const Atlas& atlas)
{
  tinygltf::Material material;
  material.name = "TriChart";
  material.pbrMetallicRoughness.baseColorFactor = { 0.8, 0.8, 0.8, 1.0 };
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 0.6;
  if (const AtlasTexture* texture = baseColorTexture(atlas))
  {
    const std::string png = encodePng(texture->width, texture->height, texture->rgba);
    tinygltf::Image image;
    image.name = texture->name;
    image.mimeType = "image/png";
    image.bufferView = addView(model, png.data(), png.size(), 0);
    model.images.push_back(image);
    tinygltf::Sampler sampler;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    sampler.wrapS = sampler.wrapT = TINYGLTF_TEXTURE_WRAP_REPEAT;
    model.samplers.push_back(sampler);
    tinygltf::Texture gltfTexture;
    gltfTexture.source = 0;
    gltfTexture.sampler = 0;
    model.textures.push_back(gltfTexture);
    material.pbrMetallicRoughness.baseColorTexture.index = 0;
    material.pbrMetallicRoughness.baseColorFactor = { 1.0, 1.0, 1.0, 1.0 };
  }
  model.materials.push_back(material);
}

bool isSkinned(const Atlas& atlas)
{
  return !atlas.rig.empty() && findAttribute(atlas, kAtlasSkin) >= 1;
}

/// The joints' nodes (their roots in the scene, beside the LODs: a skinned mesh's node
/// transform is ignored, so the joints' globals are their own), skin 0 on every LOD's node, and
/// the keyframed animations.
void addRig(tinygltf::Model& model, const Rig& rig, size_t lodCount)
{
  const int firstJoint = static_cast<int>(model.nodes.size());
  for (const int root : detail::addGltfSkeleton(model, rig))
  {
    model.scenes[0].nodes.push_back(root);
  }
  for (size_t k = 0; k < lodCount; ++k)
  {
    model.nodes[k].skin = 0;
  }
  detail::addGltfAnimations(model, rig, firstJoint);
}

tinygltf::Model makeModel(
  const Atlas& atlas, std::vector<GltfLod>& lods, GltfLayout layout, const Progress& progress)
{
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "TriChart";
  model.buffers.resize(1);
  addMaterial(model, atlas);
  for (size_t k = 0; k < lods.size(); ++k)
  {
    addMesh(model, atlas, lods[k], k);
    progress.report(double(k + 1) / double(lods.size()));
  }
  addNodes(model, lods, atlas.inputDiagonal, layout);
  if (isSkinned(atlas))
  {
    addRig(model, atlas.rig, lods.size());
  }
  return model;
}
} // namespace

std::vector<std::string> gltfExportNotes(const Atlas& atlas)
{
  return isSkinned(atlas) ? detail::gltfRigNotes(atlas.rig) : std::vector<std::string>{};
}

bool isGltfFileName(const std::string& path)
{
  return hasExtension(path, ".glb") || hasExtension(path, ".gltf");
}

std::vector<GltfLod> writeGltf(const std::string& path, const Atlas& atlas,
  const GltfExportOptions& options, const Progress& progress)
{
  const bool binary = hasExtension(path, ".glb");
  if (!isGltfFileName(path))
  {
    throw InputError(
      kWhere + "cannot write '" + path + "': a glTF file is named .glb (binary) or .gltf (JSON)");
  }
  std::vector<GltfLod> lods = gltfLodChain(atlas, options);
  const tinygltf::Model model = makeModel(atlas, lods, options.layout, progress.sub(0.0, 0.9));
  std::ostringstream text;
  tinygltf::TinyGLTF gltf;
  if (!gltf.WriteGltfSceneToStream(&model, text, !binary, binary))
  {
    throw InputError(kWhere + "tinygltf could not serialize the model of " + path);
  }
  detail::TemporaryFile file(path, "cannot write glTF " + path);
  const std::string bytes = text.str();
  file.write(bytes.data(), bytes.size());
  file.finish();
  file.commit();
  progress.report(1.0);
  return lods;
}
} // namespace tc
