// SPDX-License-Identifier: BSD-3-Clause
/// @file gltf_skin.h
/// Private helpers of gltf_export.cpp: buffer views and accessors, and a skinned atlas's skin,
/// joints and keyframed animations in a tinygltf model (see gltf_export.h for the choices).
#pragma once

#include "tc/skinning/skin.h"

#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace tc
{
namespace detail
{
/// Appends `n` bytes to buffer 0 at a 4-byte boundary and returns their buffer view (`target`
/// 0: none, as for images, inverse bind matrices and animation data).
int addGltfView(tinygltf::Model& model, const void* bytes, size_t n, int target);

/// A float accessor of `values` as `type` (TINYGLTF_TYPE_SCALAR .. VEC4, MAT4) with
/// `components` floats per element, with its min and max when `bounds` (POSITION and
/// animation inputs require them).
int addGltfFloats(tinygltf::Model& model, const std::vector<float>& values, int type,
  int components, bool bounds, int target);

/// JOINTS_0 (unsigned byte below 256 joints, else unsigned short) and WEIGHTS_0 (float,
/// normalized to sum 1) of `primitive` from the atlas's Skin values (#V x kSkinValues).
void addGltfSkinAttributes(tinygltf::Model& model, const std::vector<float>& skinValues,
  size_t jointCount, tinygltf::Primitive& primitive);

/// Appends one node per joint (and the skin, skin 0, listing them in joint order with their
/// inverse bind matrices); returns the joints' root nodes, for the scene.
std::vector<int> addGltfSkeleton(tinygltf::Model& model, const Rig& rig);

/// Appends one glTF animation per keyframed animation of `rig` (channels on the joint nodes
/// addGltfSkeleton made, which start at node `firstJointNode`).
void addGltfAnimations(tinygltf::Model& model, const Rig& rig, int firstJointNode);

/// What the file cannot hold of `rig`: one line per animation of sampled poses, skipped.
std::vector<std::string> gltfRigNotes(const Rig& rig);
} // namespace detail
} // namespace tc
