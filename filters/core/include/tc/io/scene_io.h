// SPDX-License-Identifier: BSD-3-Clause
/// @file scene_io.h
/// Scene formats (glTF, FBX, DirectX X, MD2) read through Assimp: the surfaces of a skinned or
/// animated character, in its rest pose, as one polygon soup, with its skeleton, skin weights
/// and animations.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"
#include "tc/skinning/skin.h"
#include "tc/io/mesh_file.h"

#include <string>
#include <vector>

namespace tc
{
/// The surfaces of a scene file.
struct Scene
{
  PolygonSoup soup;                   ///< every mesh of every node, node transforms applied
  std::vector<int32_t> meshId;        ///< #P: index of the scene mesh each polygon came from
  std::vector<std::string> meshNames; ///< one per scene mesh (may be empty strings)
  std::string importer;          ///< the Assimp importer that read the file, e.g. "glTF2 Importer"
  int64_t meshInstances = 0;     ///< meshes placed by nodes (a mesh used by 2 nodes counts 2)
  int64_t skinnedMeshes = 0;     ///< scene meshes with bones
  int64_t bones = 0;             ///< distinct bone names over all meshes
  int64_t morphTargets = 0;      ///< vertex animation targets (not applied)
  int64_t skippedPrimitives = 0; ///< points and lines, which are no surface
  PointAttributes attributes;    ///< texture coordinates (set 0) and colours (set 0) per point
  BaseColorTexture texture;      ///< of the first material, in mesh order, that has one
  /// The joints that move points, empty when the file has neither bones nor animations.
  Skeleton skeleton;
  /// #V: each point's joints and weights (empty with the skeleton). A point of a mesh without
  /// bones (or that no bone weights) is bound to its node's joint with weight 1, so node
  /// animations move it too.
  SkinWeights skin;
  std::vector<Animation> animations; ///< every animation of the file, in its order
  int64_t unweightedPoints = 0;      ///< points of skinned meshes that no bone weights
  std::vector<std::string> warnings; ///< what was left out or doubted, one sentence each
};

/// File extensions readScene handles, space-separated, without dots.
const char* sceneExtensions();

/// True if `path` ends (case-insensitively) with one of sceneExtensions().
bool isSceneFile(const std::string& path);

/// Reads the surfaces of a scene file with Assimp (no post-processing but joining identical
/// vertices, so that each scene mesh is indexed). Every node's meshes are placed with the
/// node's transform accumulated from the root, so the soup is the scene as the file positions
/// it, in the rest (bind) pose. The skeleton, the skin (4 largest weights per point,
/// renormalized when cut, as Assimp's LimitBoneWeights does) and the animations are read so that
/// tc::skinPoints(soup.points, skin, skinningMatrices(skeleton, jointGlobals(skeleton, &animation,
/// t))) gives the mesh Assimp's definition of skinning poses at t seconds (see scene_skin.h).
/// Polygons keep their corner count (tc::prepareMesh triangulates); points and lines are
/// skipped and counted.
///
/// Texture coordinates (the first set) and colours (the first set) are kept when every placed
/// mesh has them, else dropped with a warning. v is as Assimp gives it, with the origin at the
/// image's bottom for every importer: its glTF importer turns glTF's top-left v into 1 - v.
/// The texture is the base-colour (else diffuse) texture of the first mesh's material, in the
/// file's mesh order, that has one: an image embedded in the file ("*k", name "embedded:k"), its
/// encoded bytes or raw texels, or a file relative to the scene's folder (a missing one is a
/// warning); the other materials' distinct textures are counted in `texture.leftOut`.
///
/// @param[in] path      the file (and, for glTF, the files it refers to beside it)
/// @param[in] progress  reported while Assimp reads; may abort (tc::Aborted)
/// @throws tc::InputError  for a missing file, an extension none of sceneExtensions(), a file
///   Assimp cannot parse (its message is kept), or a scene without a polygon
Scene readScene(const std::string& path, const Progress& progress = {});
} // namespace tc
