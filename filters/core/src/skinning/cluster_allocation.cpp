// SPDX-License-Identifier: BSD-3-Clause
#include "skinning/cluster_allocation.h"

#include "skinning/bone_transforms.h"

#include <algorithm>
#include <cmath>

namespace tc
{
namespace detail
{
namespace proxy
{
void allocateByRigidResidual(const std::vector<int32_t>& triangles,
  const std::vector<std::vector<float>>& frames, int k, spectral::Components& components,
  const Progress& progress)
{
  const int64_t nc = components.count();
  if (nc < 2)
  {
    progress.report(1.0);
    return;
  }
  std::vector<int32_t> componentOf(triangles.size() / 3);
  for (int64_t c = 0; c < nc; ++c)
  {
    for (int32_t f : components.faces[c])
    {
      componentOf[f] = static_cast<int32_t>(c);
    }
  }
  const BonePoints pieces = bonePoints(triangles, componentOf, static_cast<int32_t>(nc));
  const std::vector<double> residual =
    rigidResiduals(frames, pieces, rigidTransforms(frames, pieces, progress));
  // If m_c bones cut a component's error to about r_c / m_c, the total squared error
  // sum_c n_c r_c^2 / m_c^2 under sum_c m_c = k is smallest (Lagrange) for m_c proportional to
  // (n_c r_c^2)^(1/3).
  std::vector<double> share(nc);
  double total = 0.0;
  for (int64_t c = 0; c < nc; ++c)
  {
    share[c] = std::cbrt(static_cast<double>(components.sizes[c]) * residual[c] * residual[c]);
    total += share[c];
  }
  if (!(total > 0.0))
  {
    return;
  }
  // allocateClusters() shares in proportion to integer sizes: the shares scaled to large ones.
  std::vector<int64_t> scaled(nc);
  for (int64_t c = 0; c < nc; ++c)
  {
    scaled[c] = std::llround(share[c] / total * 1e12);
  }
  components.clusters = spectral::allocateClusters(scaled, k);
  for (int64_t c = 0; c < nc; ++c)
  {
    components.clusters[c] =
      static_cast<int>(std::min<int64_t>(components.clusters[c], components.sizes[c]));
  }
}
} // namespace proxy
} // namespace detail
} // namespace tc
