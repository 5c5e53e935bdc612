// SPDX-License-Identifier: BSD-3-Clause
/// @file sequence_checks.h
/// The input checks of the deformation stages (deformation clustering, proxy bones): one
/// wording for every entry point.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tc
{
namespace detail
{
/// @param[in] stage      the message's prefix, e.g. "clusterDeformation: "
/// @param[in] triangles  #F x 3 point ids
/// @param[in] frames     #K x (#V x 3) positions
/// @throws InputError  for no frame, a frame whose size is not a multiple of 3 or differs from
///   frame 0's, a non-finite coordinate (naming the frame and the point), no triangle, a
///   triangle array whose size is not a multiple of 3, or a point id out of range
void requireSequence(const std::string& stage, const std::vector<int32_t>& triangles,
  const std::vector<std::vector<float>>& frames);

/// @param[in] stage  the message's prefix
/// @param[in] nv     number of points
/// @throws InputError  for no triangle, a size that is not a multiple of 3, or an id outside
///   [0, nv)
void requireTriangles(const std::string& stage, const std::vector<int32_t>& triangles, int64_t nv);
} // namespace detail
} // namespace tc
