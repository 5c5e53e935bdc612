// SPDX-License-Identifier: BSD-3-Clause
/// @file build_memory.h
/// The peak memory of the static pipeline (preparation to the atlas), estimated from the counts
/// alone, so that a face can refuse a request before the work starts.
///
/// The model has two phases, the larger of which is the peak:
/// - front (preparation to path tracing): every stage's mesh and arrays, which the pipeline keeps,
///   plus the transient of the spectral clustering: its exact sparse graph below
///   SpectralClusteringOptions::nystromThreshold faces, the Nystrom blocks (#F x rank floats and
///   their products) above it;
/// - geometry images: the meshes kept after path tracing plus the grids the error rule samples,
///   at most 16 times the budget (kErrorRuleLevelsAbove levels above the area rule's), and at
///   most every chart at maxLevel; with an error target each counts more bytes (its measuring
///   rounds sample charts again, and its finest levels may hold every sample).
/// The coefficients are bytes per triangle or per sample of peak resident memory measured on the
/// shared meshes (bench/build_memory.sh prints estimate and measurement); the estimate is meant
/// to be a little above the measurement, never far below it.
#pragma once

#include "tc/gim/geometry_images.h"

#include <cstdint>

namespace tc
{
struct BuildMemoryRequest
{
  int64_t points = 0;                       ///< input points (0 .. 2^31)
  int64_t triangles = 0;                    ///< input triangles (a polygon counts as its fan)
  int64_t sampleBudget = 0;                 ///< GeometryImageOptions::sampleBudget; 0: `points`
  double errorTarget = kDefaultErrorTarget; ///< GeometryImageOptions::errorTarget
  int32_t maxLevel = 8;                     ///< GeometryImageOptions::maxLevel
  int64_t targetFaces = 100;                ///< BaseComplexOptions::targetFaces
  int64_t nystromThreshold = 100000;        ///< SpectralClusteringOptions::nystromThreshold
};

struct BuildMemoryEstimate
{
  int64_t front = 0;   ///< bytes from the preparation to the path tracing
  int64_t images = 0;  ///< bytes during the geometry images (the meshes kept included)
  int64_t samples = 0; ///< grid samples the geometry images may hold at once
  int64_t charts = 0;  ///< the charts assumed for the maxLevel cap (an upper guess)
  /// The larger phase: the estimate of the peak, in bytes, above the process's own memory.
  int64_t peak() const { return front > images ? front : images; }
};

/// The estimate for `request` (see the file comment). Saturates at INT64_MAX, never overflows.
/// @throws InputError for negative counts or a maxLevel outside 0 .. 12
BuildMemoryEstimate estimateBuildMemory(const BuildMemoryRequest& request);
} // namespace tc
