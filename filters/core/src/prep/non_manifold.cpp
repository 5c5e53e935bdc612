// SPDX-License-Identifier: BSD-3-Clause
#include "prep/non_manifold.h"

#include "detail/union_find.h"
#include "prep/face_sides.h"

#include <algorithm>
#include <array>

namespace tc
{
namespace detail
{
namespace
{
/// Joins the corners at both ends of side s (3 f + i: corner i to corner i + 1 of face f) with
/// those of side t on the same vertices: across the sides, the fan of each end vertex continues
/// from one face into the other.
void joinSides(const std::vector<int32_t>& triangles, int32_t s, int32_t t, DisjointSets& corners)
{
  const int32_t s1 = 3 * (s / 3) + (s % 3 + 1) % 3;
  const int32_t t1 = 3 * (t / 3) + (t % 3 + 1) % 3;
  const bool sameStart = triangles[t] == triangles[s];
  corners.unite(s, sameStart ? t : t1);
  corners.unite(s1, sameStart ? t1 : t);
}

/// The side glued to each side (3 f + i), -1 for a cut one: across an edge with 2 faces, and on
/// a non-manifold edge for its first two consistent faces (or its first two, if none are).
std::vector<int32_t> gluedSides(const std::vector<int32_t>& tri, const EdgeTable& edges)
{
  std::vector<int32_t> partner(tri.size(), -1);
  for (int32_t e = 0; e < edges.numEdges(); ++e)
  {
    const int64_t valence = edges.valence(e);
    const int32_t* faces = edges.edgeFaces.data() + edges.faceOffsets[e];
    if (valence < 2)
    {
      continue;
    }
    int32_t f = faces[0];
    int32_t g = faces[1];
    for (int64_t a = 0; a < valence && valence > 2; ++a)
    {
      int64_t b = a + 1;
      while (b < valence && !consistentAcross(tri, edges, e, faces[a], faces[b]))
      {
        ++b;
      }
      if (b < valence)
      {
        f = faces[a];
        g = faces[b];
        break;
      }
    }
    const int32_t sf = 3 * f + sideOf(edges, f, e);
    const int32_t sg = 3 * g + sideOf(edges, g, e);
    partner[sf] = sg;
    partner[sg] = sf;
  }
  return partner;
}

/// Fans of corners: corners joined across every glued side.
DisjointSets fansOf(const std::vector<int32_t>& tri, const std::vector<int32_t>& partner)
{
  const int32_t numCorners = static_cast<int32_t>(tri.size());
  DisjointSets glued(numCorners);
  for (int32_t side = 0; side < numCorners; ++side)
  {
    if (partner[side] > side)
    {
      joinSides(tri, side, partner[side], glued);
    }
  }
  return glued;
}

/// Corner of face f at vertex v.
int32_t cornerAt(const std::vector<int32_t>& tri, int32_t f, int32_t v)
{
  return 3 * f + (tri[3 * f] == v ? 0 : (tri[3 * f + 1] == v ? 1 : 2));
}

/// Faces on the same non-manifold edge whose corners there fall into the same two fans end up
/// on one output edge; unglued ones among more than 2 such faces are cut away at one end (one
/// more glued side through that corner is cut). True if a side was cut.
bool cutWrappedFaces(const std::vector<int32_t>& tri, const EdgeTable& edges,
  const std::vector<int32_t>& nonManifold, DisjointSets& glued, std::vector<int32_t>& partner)
{
  bool cut = false;
  std::vector<std::array<int32_t, 2>> fans;
  for (const int32_t e : nonManifold)
  {
    const int32_t* faces = edges.edgeFaces.data() + edges.faceOffsets[e];
    const int64_t valence = edges.valence(e);
    fans.resize(valence);
    for (int64_t k = 0; k < valence; ++k)
    {
      fans[k] = { glued.find(cornerAt(tri, faces[k], edges.vertices[2 * e])),
        glued.find(cornerAt(tri, faces[k], edges.vertices[2 * e + 1])) };
    }
    for (int64_t k = 0; k < valence; ++k)
    {
      const int32_t f = faces[k];
      const int i = sideOf(edges, f, e);
      if (partner[3 * f + i] >= 0 || std::count(fans.begin(), fans.end(), fans[k]) <= 2)
      {
        continue;
      }
      // Cut one more glued side through an end of side i.
      const int32_t before = 3 * f + (i + 2) % 3;
      const int32_t after = 3 * f + (i + 1) % 3;
      const int32_t side = partner[before] >= 0 ? before : after;
      if (partner[side] >= 0)
      {
        partner[partner[side]] = -1;
        partner[side] = -1;
        cut = true;
      }
    }
  }
  return cut;
}

/// One vertex per fan: the fan of the lowest corner of a vertex keeps it, every other fan gets a
/// copy appended (inheriting inputPointId and nonManifoldVertex). Writes the new corners to
/// `tri`; returns the number of vertices.
int32_t fanVertices(const std::vector<int32_t>& original, DisjointSets& glued, int32_t numVertices,
  std::vector<int32_t>& tri, PreparationResult& result)
{
  const int32_t numCorners = static_cast<int32_t>(original.size());
  result.inputPointId.resize(numVertices);
  result.nonManifoldVertex.resize(numVertices);
  std::vector<int32_t> fanVertex(numCorners, -1);
  std::vector<uint8_t> vertexTaken(numVertices, 0);
  int32_t next = numVertices;
  for (int32_t c = 0; c < numCorners; ++c)
  {
    const int32_t root = glued.find(c);
    if (fanVertex[root] < 0)
    {
      const int32_t v = original[c];
      if (!vertexTaken[v])
      {
        vertexTaken[v] = 1;
        fanVertex[root] = v;
      }
      else
      {
        fanVertex[root] = next++;
        result.inputPointId.push_back(result.inputPointId[v]);
        result.nonManifoldVertex.push_back(result.nonManifoldVertex[v]);
      }
    }
    tri[c] = fanVertex[root];
  }
  return next;
}
} // namespace

void findNonManifold(const std::vector<int32_t>& tri, const EdgeTable& edges, int32_t numVertices,
  PreparationResult& result)
{
  PreparationReport& report = result.report;
  const int64_t nf = static_cast<int64_t>(tri.size() / 3);
  result.nonManifoldEdge.assign(nf, 0);
  result.nonManifoldVertex.assign(numVertices, 0);
  DisjointSets fans(3 * nf);
  for (int32_t e = 0; e < edges.numEdges(); ++e)
  {
    const int64_t valence = edges.valence(e);
    const int32_t* faces = edges.edgeFaces.data() + edges.faceOffsets[e];
    if (valence == 2)
    {
      joinSides(tri, 3 * faces[0] + sideOf(edges, faces[0], e),
        3 * faces[1] + sideOf(edges, faces[1], e), fans);
    }
    else if (valence > 2)
    {
      ++report.nonManifoldEdges;
      for (int64_t k = 0; k < valence; ++k)
      {
        result.nonManifoldEdge[faces[k]] = 1;
      }
    }
  }
  std::vector<uint8_t> fanSeen(3 * nf, 0);
  std::vector<uint8_t> vertexSeen(numVertices, 0);
  for (int32_t c = 0; c < 3 * nf; ++c)
  {
    const int32_t root = fans.find(c);
    if (!fanSeen[root])
    {
      fanSeen[root] = 1;
      const int32_t v = tri[c];
      if (vertexSeen[v] && !result.nonManifoldVertex[v])
      {
        result.nonManifoldVertex[v] = 1;
        ++report.nonManifoldVertices;
      }
      vertexSeen[v] = 1;
    }
  }
}

int32_t splitNonManifold(
  std::vector<int32_t>& tri, EdgeTable& edges, int32_t numVertices, PreparationResult& result)
{
  const std::vector<int32_t> original = tri;
  std::vector<int32_t> partner = gluedSides(tri, edges);
  std::vector<int32_t> nonManifold;
  for (int32_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) > 2)
    {
      nonManifold.push_back(e);
    }
  }
  DisjointSets glued = fansOf(original, partner);
  while (cutWrappedFaces(original, edges, nonManifold, glued, partner))
  {
    glued = fansOf(original, partner);
  }
  const int32_t count = fanVertices(original, glued, numVertices, tri, result);
  edges = buildEdgeTable(tri);
  return count;
}
} // namespace detail
} // namespace tc
