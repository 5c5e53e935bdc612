// SPDX-License-Identifier: BSD-3-Clause
#include "tc/gim/build_memory.h"

#include "tc/common/errors.h"
#include "tc/gim/atlas.h"

#include "gim/geometry_images_input.h" // kMaxLevelLimit; tc/gim/geometry_images.h

#include <algorithm>
#include <limits>
#include <string>

namespace tc
{
namespace
{
// Bytes of peak resident memory, per input triangle or per grid sample (see the file comment).
/// What every build touches whatever its size (library code paged in, thread stacks, the
/// allocator's arenas), in both phases.
constexpr double kFixed = 12.0 * 1024.0 * 1024.0;
constexpr double kKeptBeforeClustering = 400.0; ///< the meshes of read, preparation, curvature
constexpr double kExactGraph = 1600.0;          ///< the exact sparse graph and its eigensolver
constexpr double kNystrom = 500.0;              ///< the Nystrom blocks and their products
constexpr double kKeptAfterPaths = 550.0;       ///< every stage's mesh, up to the patches
constexpr double kPerSample = 34.0;             ///< a grid sample: attributes, fit, error
/// A grid sample under an error target: the measuring rounds sample the raised charts again
/// (the grids they replace stay resident in the allocator) and the finest levels may hold every
/// measured sample, which the atlas and its file then copy.
constexpr double kPerTargetSample = 136.0;
/// Charts are at most the larger of the base target and one per this many input triangles
/// (an upper guess for the maxLevel cap: simplification stops above the target on detailed
/// meshes when BaseComplexOptions::maxError holds it back).
constexpr int64_t kTrianglesPerChart = 50;

int64_t saturated(double bytes)
{
  constexpr double top = static_cast<double>(std::numeric_limits<int64_t>::max());
  return bytes >= top ? std::numeric_limits<int64_t>::max() : static_cast<int64_t>(bytes);
}
} // namespace

BuildMemoryEstimate estimateBuildMemory(const BuildMemoryRequest& r)
{
  if (r.points < 0 || r.triangles < 0 || r.sampleBudget < 0 || r.targetFaces < 0 ||
    r.nystromThreshold < 0)
  {
    throw InputError("estimateBuildMemory: counts must not be negative (points " +
      std::to_string(r.points) + ", triangles " + std::to_string(r.triangles) + ", budget " +
      std::to_string(r.sampleBudget) + ")");
  }
  if (r.maxLevel < 0 || r.maxLevel > detail::geometry_images::kMaxLevelLimit)
  {
    throw InputError("estimateBuildMemory: maxLevel " + std::to_string(r.maxLevel) +
      " is outside 0 .. " + std::to_string(detail::geometry_images::kMaxLevelLimit));
  }
  const double triangles = static_cast<double>(r.triangles);
  BuildMemoryEstimate e;
  const double clustering = r.triangles > r.nystromThreshold ? kNystrom : kExactGraph;
  e.front = saturated(kFixed + triangles * (kKeptBeforeClustering + clustering));

  e.charts =
    std::max<int64_t>(std::max<int64_t>(r.targetFaces, 1), r.triangles / kTrianglesPerChart);
  const double budget = static_cast<double>(r.sampleBudget > 0 ? r.sampleBudget : r.points);
  const bool target = r.errorTarget > 0.0;
  const double measured = budget * static_cast<double>(int64_t(1) << (2 * kErrorRuleLevelsAbove));
  const double capped =
    static_cast<double>(e.charts) * static_cast<double>(gridVertexCount(r.maxLevel));
  const double samples = std::min(measured, capped);
  e.samples = saturated(samples);
  e.images = saturated(
    kFixed + triangles * kKeptAfterPaths + samples * (target ? kPerTargetSample : kPerSample));
  return e;
}
} // namespace tc
