// SPDX-License-Identifier: BSD-3-Clause
#include "skinning/sequence_checks.h"

#include "tc/common/errors.h"

#include <cmath>

namespace tc
{
namespace detail
{
void requireTriangles(const std::string& stage, const std::vector<int32_t>& triangles, int64_t nv)
{
  if (triangles.empty() || triangles.size() % 3 != 0)
  {
    throw InputError(stage + "the connectivity holds " + std::to_string(triangles.size()) +
      " point ids; it needs at least one triangle and 3 ids per triangle");
  }
  for (size_t i = 0; i < triangles.size(); ++i)
  {
    if (triangles[i] < 0 || triangles[i] >= nv)
    {
      throw InputError(stage + "triangle " + std::to_string(i / 3) + " references point " +
        std::to_string(triangles[i]) + " of " + std::to_string(nv) + "; fix the connectivity");
    }
  }
}

void requireSequence(const std::string& stage, const std::vector<int32_t>& triangles,
  const std::vector<std::vector<float>>& frames)
{
  if (frames.empty())
  {
    throw InputError(stage + "the sequence has no frame; give at least the rest frame");
  }
  const size_t size = frames[0].size();
  for (size_t k = 0; k < frames.size(); ++k)
  {
    if (frames[k].size() != size || size % 3 != 0)
    {
      throw InputError(stage + "frame " + std::to_string(k) + " holds " +
        std::to_string(frames[k].size()) + " coordinates and frame 0 " + std::to_string(size) +
        "; every frame needs 3 per point and the same points as frame 0");
    }
    for (size_t i = 0; i < size; ++i)
    {
      if (!std::isfinite(frames[k][i]))
      {
        throw InputError(stage + "point " + std::to_string(i / 3) + " of frame " +
          std::to_string(k) + " has a non-finite coordinate; fix or drop that frame");
      }
    }
  }
  requireTriangles(stage, triangles, static_cast<int64_t>(size / 3));
}
} // namespace detail
} // namespace tc
