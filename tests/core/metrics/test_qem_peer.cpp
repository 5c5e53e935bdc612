// SPDX-License-Identifier: BSD-3-Clause
// The QEM peer (meshopt_simplify) on the bundled bunny: at most the target, vertices of the
// input only, and the input itself for a target at or above its count.
#include "pipeline_fixture.h"

#include "tc/common/errors.h"
#include "tc/metrics/qem_peer.h"

#include <gtest/gtest.h>

#include <set>
#include <tuple>

TEST(QemPeer, SimplifiesToAtMostTheTargetWithTheInputsVertices)
{
  const tc::TriMesh mesh = tctest::loadMesh(tctest::pipelineMeshPath("bunny_npm"));
  std::set<std::tuple<double, double, double>> input;
  for (int64_t v = 0; v < mesh.numPoints(); ++v)
  {
    input.insert({ mesh.points[3 * v], mesh.points[3 * v + 1], mesh.points[3 * v + 2] });
  }
  for (const int64_t target : { 100, 1000 })
  {
    const tc::TriMesh simple = tc::simplifyQem(mesh, target);
    EXPECT_LE(simple.numTriangles(), target);
    EXPECT_GT(simple.numTriangles(), target / 2);
    for (int64_t v = 0; v < simple.numPoints(); ++v)
    {
      EXPECT_TRUE(input.count(
        { simple.points[3 * v], simple.points[3 * v + 1], simple.points[3 * v + 2] }));
    }
  }
  EXPECT_EQ(tc::simplifyQem(mesh, mesh.numTriangles()).triangles, mesh.triangles);
  EXPECT_THROW(tc::simplifyQem(mesh, -1), tc::InputError);
}
