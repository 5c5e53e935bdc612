// SPDX-License-Identifier: BSD-3-Clause
/// @file gltf_export.h
/// An atlas as a glTF 2.0 LOD chain that game engines and DCC tools load (written with Debian's
/// tinygltf): one mesh per LOD, each the stitched, welded mesh tc::rebuildMesh draws at that LOD's
/// chart levels, so an LOD of the file equals `trichart mesh` at the same levels point for point.
///
/// The chain (GltfExportOptions::chain):
/// - Error (default): LOD 0 has every chart at its finest level; LOD k + 1 lets the largest
///   error grow by errorRatio: each chart takes the coarsest level whose levelError is at most
///   errorRatio times LOD k's largest error. Charts thus stay fine where the surface needs it (the
///   per-chart levels the renderer's error rule draws), and the chain ends with the base complex
///   (every chart at level 0). An LOD whose levels equal the previous one's is skipped.
/// - Uniform: LOD k has every chart at level L - k (capped by its finest), L = the atlas's finest
///   level, down to level 0.
///
/// Layout (GltfExportOptions::layout):
/// - MsftLod (default): one scene with one node, LOD 0's; the coarser LODs are nodes outside the
///   scene that LOD 0's node lists, finest to coarsest, in its MSFT_lod extension (declared in
///   extensionsUsed, not required: a reader that ignores it, Assimp among them, shows LOD 0).
/// - NamedNodes: for pipelines that ignore MSFT_lod and group LODs by name (Unity's and
///   Unreal's importers): one scene node "TriChart" whose children are every LOD's node, named
///   "TriChart_LOD<k>"; a viewer shows them all, on top of each other.
/// Each mesh has one indexed triangle
/// primitive (POSITION with its min and max, NORMAL, the input's look as TEXCOORD_0 (v flipped:
/// glTF puts v = 0 at the image's top) and COLOR_0 (Colors / 255), every other user attribute of
/// the atlas as "_<name>", all float32; indices uint16 when they fit, else uint32) and one
/// metallic-roughness material: the atlas's base-colour texture as an embedded PNG (repeated,
/// linear with mipmaps) on white, or grey without one. Points on a texture seam are split as
/// rebuildMesh splits them, so each side keeps its own coordinates. With MsftLod, LOD 0's node
/// extras hold "MSFT_screencoverage", one value per LOD: LOD k is meant for a screen coverage at or
/// above value k, where the coverage is the fraction of the viewport height that the bounding-box
/// diagonal covers; value k is where LOD k + 1's error would grow to errorPixels pixels in a
/// viewport viewportHeight pixels tall (0 for the coarsest, which stays drawn). Every node's extras
/// also hold its LOD's "error" (input units), "errorFraction" (of the diagonal) and "triangles".
///
/// A skinned atlas (a rig with a skeleton and a kAtlasSkin attribute) also carries its skin:
/// - every primitive has JOINTS_0 (unsigned byte below 256 joints, else unsigned short) and
///   WEIGHTS_0 (float) from the Skin values rebuildMesh reads with each point. The weights are
///   normalized to sum 1 in the file, as the Khronos specification requires, whereas
///   tc::skinPoints (as Assimp) poses the weights as given: a file posed by a glTF viewer equals
///   tc::skinPoints with each point's weights divided by their sum.
/// - one node per joint, in Joint::parent's hierarchy, the roots in the scene beside the LOD
///   nodes (glTF ignores a skinned mesh node's transform, so the joints' globals are those of
///   tc::jointGlobals); each has the translation, rotation and scale of its restLocal (the
///   polar decomposition tc::jointGlobals uses; a joint no animation moves whose restLocal
///   shears keeps it as a matrix, allowed on a node nothing animates). Skin 0 lists the joints
///   in the skeleton's order (JOINTS_0 ids are tc's joint ids) with their inverseBind
///   (column-major in the file) and every LOD node uses it: the positions are the bind pose
///   rebuildMesh gives, and the rest pose a viewer shows is tc::jointGlobals(skeleton, nullptr)'s.
/// - a second joint of one node (Joint::sameNodeAs >= 0, its own inverseBind) is a copy of that
///   node under the joint's parent, with the first joint's transform and keys, named
///   "<name>.bind<j>" so that readers matching bones by name keep it apart: the skin poses
///   exactly as tc::jointGlobals, which moves such a joint with its first.
/// - every keyframed animation is one glTF animation of its name: per track and component one
///   LINEAR sampler (times in seconds with their min and max; rotations as x, y, z, w, which
///   glTF's LINEAR interpolates spherically), with a held key at the duration when the keys end
///   before it, so that glTF's length (the last key) is the duration. Animations of sampled poses
///   (affine proxy bones, which may shear) are not exported: gltfExportNotes says so.
#pragma once

#include "tc/common/progress.h"
#include "tc/gim/atlas.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tc
{
enum class GltfChain : int32_t
{
  Error = 0,   ///< per-chart levels, the largest error growing by errorRatio per LOD
  Uniform = 1, ///< one level for every chart per LOD
};

enum class GltfLayout : int32_t
{
  MsftLod = 0,    ///< LOD 0 in the scene, the others linked to it by MSFT_lod
  NamedNodes = 1, ///< every LOD in the scene, named <name>_LOD<k>
};

struct GltfExportOptions
{
  GltfChain chain = GltfChain::Error;
  GltfLayout layout = GltfLayout::MsftLod;
  double errorRatio = 2.0;        ///< > 1: growth of the largest error per LOD (Error chain)
  int32_t maxLods = 16;           ///< 1 .. 64: the chain stops after this many LODs
  double errorPixels = 1.0;       ///< > 0: the error a screen-coverage hint allows, in pixels
  double viewportHeight = 1080.0; ///< > 0: the viewport the hints are computed for, in pixels
};

struct GltfLod
{
  std::vector<int32_t> chartLevels; ///< #C: the level each chart is drawn at
  double error = 0.0;          ///< largest levelError of the charts at those levels (input units)
  double screenCoverage = 0.0; ///< the hint of MSFT_screencoverage for this LOD
  int64_t points = 0;          ///< of the welded mesh (filled by writeGltf)
  int64_t triangles = 0;
};

/// The chain of `options` for `atlas` (see the file comment), with the screen-coverage hints.
/// @throws InputError for options out of range or an atlas without charts or levelError
std::vector<GltfLod> gltfLodChain(const Atlas& atlas, const GltfExportOptions& options);

/// What writeGltf cannot put in the file for `atlas`, one line each: the rig's animations of
/// sampled poses (see the file comment); empty when the file holds everything.
std::vector<std::string> gltfExportNotes(const Atlas& atlas);

/// Whether writeGltf takes the name `path`: it ends with .glb or .gltf, in any case.
bool isGltfFileName(const std::string& path);

/// Writes the chain as glTF 2.0 to `path`, binary when it ends with .glb, JSON with the buffer
/// embedded as base64 when it ends with .gltf (through a temporary file renamed at the end: a
/// failed write leaves no file and an older one intact), and returns the LODs written.
/// @throws InputError for another extension, bad options or atlas, or any I/O failure; Aborted
///   from `progress`
std::vector<GltfLod> writeGltf(const std::string& path, const Atlas& atlas,
  const GltfExportOptions& options = {}, const Progress& progress = {});
} // namespace tc
