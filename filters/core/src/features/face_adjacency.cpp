// SPDX-License-Identifier: BSD-3-Clause
#include "features/face_adjacency.h"

#include <numeric>

namespace tc
{
namespace detail
{
FaceAdjacency buildFaceAdjacency(const EdgeTable& edges, int64_t nf)
{
  FaceAdjacency dual;
  dual.offsets.assign(nf + 1, 0);
  const int64_t ne = edges.numEdges();
  for (int64_t e = 0; e < ne; ++e)
  {
    const int64_t k = edges.valence(e);
    for (int64_t i = edges.faceOffsets[e]; i < edges.faceOffsets[e + 1]; ++i)
    {
      dual.offsets[edges.edgeFaces[i] + 1] += k - 1;
    }
  }
  std::partial_sum(dual.offsets.begin(), dual.offsets.end(), dual.offsets.begin());
  dual.faces.resize(dual.offsets[nf]);
  dual.edges.resize(dual.offsets[nf]);
  std::vector<int64_t> fill(dual.offsets.begin(), dual.offsets.end() - 1);
  for (int64_t e = 0; e < ne; ++e)
  {
    for (int64_t i = edges.faceOffsets[e]; i < edges.faceOffsets[e + 1]; ++i)
    {
      for (int64_t j = edges.faceOffsets[e]; j < edges.faceOffsets[e + 1]; ++j)
      {
        if (i != j)
        {
          const int32_t f = edges.edgeFaces[i];
          dual.faces[fill[f]] = edges.edgeFaces[j];
          dual.edges[fill[f]++] = static_cast<int32_t>(e);
        }
      }
    }
  }
  return dual;
}
} // namespace detail
} // namespace tc
