// SPDX-License-Identifier: BSD-3-Clause
/// @file cluster_allocation.h
/// How the clusters (proxy bones) of a deforming sequence are shared among its edge-connected
/// components: by how badly one rigid bone would fit each, not by face count alone, since a
/// part that moves rigidly needs one bone however many faces it has, and a long part that bends
/// needs several however few.
#pragma once

#include "features/components.h"

#include "tc/common/progress.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
namespace proxy
{
/// Replaces components.clusters (the face-count shares of findComponents()) by shares of k
/// proportional to (n_c r_c^2)^(1/3), n_c the component's face count and r_c the RMS residual of
/// the one rigid motion per frame that fits the whole component best (Kabsch). Largest
/// remainder, at least one cluster per component and never more than its faces, as
/// allocateClusters(). Without any residual (one frame, or every component rigid) the
/// face-count shares stay.
/// @param[in] triangles  #F x 3 point ids
/// @param[in] frames     #K x (#V x 3), frame 0 the rest
void allocateByRigidResidual(const std::vector<int32_t>& triangles,
  const std::vector<std::vector<float>>& frames, int k, spectral::Components& components,
  const Progress& progress);
} // namespace proxy
} // namespace detail
} // namespace tc
