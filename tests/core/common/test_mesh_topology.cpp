// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/mesh_topology.h"

#include <gtest/gtest.h>

namespace
{
// A closed tetrahedron: 4 vertices, 4 faces, 6 edges, each edge in exactly 2 faces.
const std::vector<int32_t> kTetra = { 0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2 };
}

TEST(MeshTopology, TetrahedronEdgesHaveTwoFaces)
{
  const tc::EdgeTable et = tc::buildEdgeTable(kTetra);
  ASSERT_EQ(et.numEdges(), 6);
  for (int64_t e = 0; e < et.numEdges(); ++e)
  {
    EXPECT_EQ(et.valence(e), 2);
    EXPECT_LT(et.vertices[2 * e], et.vertices[2 * e + 1]);
  }
}

TEST(MeshTopology, FaceEdgesJoinTheFaceCorners)
{
  const tc::EdgeTable et = tc::buildEdgeTable(kTetra);
  for (int f = 0; f < 4; ++f)
  {
    for (int i = 0; i < 3; ++i)
    {
      const int32_t e = et.faceEdges[3 * f + i];
      const int32_t a = kTetra[3 * f + i];
      const int32_t b = kTetra[3 * f + (i + 1) % 3];
      EXPECT_EQ(std::min(a, b), et.vertices[2 * e]);
      EXPECT_EQ(std::max(a, b), et.vertices[2 * e + 1]);
    }
  }
}

TEST(MeshTopology, VertexFacesAndRingsOfATetrahedron)
{
  const tc::VertexFaces vf = tc::buildVertexFaces(kTetra, 4);
  const tc::VertexRing ring = tc::buildVertexRing(tc::buildEdgeTable(kTetra), 4);
  for (int v = 0; v < 4; ++v)
  {
    EXPECT_EQ(vf.offsets[v + 1] - vf.offsets[v], 3);
    ASSERT_EQ(ring.offsets[v + 1] - ring.offsets[v], 3);
    for (int64_t k = ring.offsets[v]; k < ring.offsets[v + 1]; ++k)
    {
      EXPECT_NE(ring.ids[k], v);
    }
  }
}
