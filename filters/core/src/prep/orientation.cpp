// SPDX-License-Identifier: BSD-3-Clause
#include "prep/orientation.h"

#include "detail/union_find.h"
#include "prep/face_sides.h"
#include "prep/points.h"

#include <utility>

namespace tc
{
namespace detail
{
namespace
{
/// Faces of a component and how they lie relative to the first face of their patch.
struct Linked
{
  DisjointSets connected;         ///< faces across every shared edge
  ParitySets patches;             ///< faces across edges with 2 faces, with relative flips
  std::vector<int32_t> conflicts; ///< a face of every patch where two paths disagree
};

Linked linkFaces(const std::vector<int32_t>& tri, const EdgeTable& edges)
{
  const int64_t nf = static_cast<int64_t>(tri.size() / 3);
  Linked linked{ DisjointSets(nf), ParitySets(nf), {} };
  for (int32_t e = 0; e < edges.numEdges(); ++e)
  {
    const int64_t valence = edges.valence(e);
    const int32_t* faces = edges.edgeFaces.data() + edges.faceOffsets[e];
    for (int64_t k = 1; k < valence; ++k)
    {
      linked.connected.unite(faces[0], faces[k]);
    }
    if (valence == 2 &&
      !linked.patches.unite(
        faces[0], faces[1], consistentAcross(tri, edges, e, faces[0], faces[1]) ? 0 : 1))
    {
      linked.conflicts.push_back(faces[0]);
    }
  }
  return linked;
}

/// componentId of every face; returns the number of components.
int32_t numberComponents(DisjointSets& connected, int64_t nf, std::vector<int32_t>& componentId)
{
  // Roots are lowest faces, so numbering roots in face order numbers components by first face.
  componentId.assign(nf, -1);
  int32_t numComponents = 0;
  for (int32_t f = 0; f < nf; ++f)
  {
    const int32_t root = connected.find(f);
    if (componentId[root] < 0)
    {
      componentId[root] = numComponents++;
    }
    componentId[f] = componentId[root];
  }
  return numComponents;
}

/// Per component: 1 if no edge of it has other than 2 faces.
std::vector<uint8_t> closedComponents(
  const EdgeTable& edges, const std::vector<int32_t>& componentId, int32_t numComponents)
{
  std::vector<uint8_t> closed(numComponents, 1);
  for (int32_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) != 2)
    {
      closed[componentId[edges.edgeFaces[edges.faceOffsets[e]]]] = 0;
    }
  }
  return closed;
}

/// Per face: 1 to flip it for the orientation of the first face of its patch (0 in a patch
/// that cannot be oriented); per component in `nonOrientable`: 1 if a patch of it cannot be.
std::vector<uint8_t> patchFlips(
  Linked& linked, const std::vector<int32_t>& componentId, std::vector<uint8_t>& nonOrientable)
{
  const size_t nf = componentId.size();
  std::vector<uint8_t> unorientablePatch(nf, 0);
  for (const int32_t f : linked.conflicts)
  {
    unorientablePatch[linked.patches.find(f).first] = 1;
  }
  std::vector<uint8_t> flip(nf, 0);
  for (int32_t f = 0; f < static_cast<int32_t>(nf); ++f)
  {
    const auto [root, parity] = linked.patches.find(f);
    if (unorientablePatch[root])
    {
      nonOrientable[componentId[f]] = 1;
    }
    else
    {
      flip[f] = parity;
    }
  }
  return flip;
}

/// Per component: 6 times the signed volume of its faces after `flip` (sum over faces of
/// det(p0 - o, p1 - o, p2 - o), o the first corner of its first face), for the closed and
/// orientable ones; 0 for the others.
std::vector<double> signedVolumes(const TriMesh& mesh, const std::vector<int32_t>& componentId,
  const std::vector<uint8_t>& eligible, const std::vector<uint8_t>& flip)
{
  const double* points = mesh.points.data();
  const std::vector<int32_t>& tri = mesh.triangles;
  const size_t numComponents = eligible.size();
  std::vector<double> volume(numComponents, 0.0);
  std::vector<V3> origin(numComponents);
  std::vector<uint8_t> hasOrigin(numComponents, 0);
  for (int32_t f = 0; f < static_cast<int32_t>(componentId.size()); ++f)
  {
    const int32_t k = componentId[f];
    if (!eligible[k])
    {
      continue;
    }
    const auto at = [&](int c) { return pointOf(points, tri[3 * f + c]); };
    if (!hasOrigin[k])
    {
      origin[k] = at(0);
      hasOrigin[k] = 1;
    }
    const V3 p0 = sub(at(0), origin[k]);
    const V3 p1 = sub(at(1), origin[k]);
    const V3 p2 = sub(at(2), origin[k]);
    const double det = dot(p0, cross(p1, p2));
    volume[k] += flip[f] ? -det : det;
  }
  return volume;
}
} // namespace

ComponentKinds orientComponents(bool orient, const EdgeTable& edges, PreparationResult& result)
{
  PreparationReport& report = result.report;
  std::vector<int32_t>& tri = result.mesh.triangles;
  const int64_t nf = static_cast<int64_t>(tri.size() / 3);
  Linked linked = linkFaces(tri, edges);
  const int32_t numComponents = numberComponents(linked.connected, nf, result.componentId);
  report.components = numComponents;
  std::vector<uint8_t> closed = closedComponents(edges, result.componentId, numComponents);
  std::vector<uint8_t> nonOrientable(numComponents, 0);
  const std::vector<uint8_t> flip = patchFlips(linked, result.componentId, nonOrientable);

  // A closed, oriented component faces outward when its signed volume is positive; flip it
  // otherwise.
  std::vector<uint8_t> eligible(numComponents, 0);
  report.closedComponents = 0;
  report.nonOrientableComponents = 0;
  for (int32_t k = 0; k < numComponents; ++k)
  {
    eligible[k] = closed[k] && !nonOrientable[k];
    report.closedComponents += closed[k];
    report.nonOrientableComponents += nonOrientable[k];
  }
  const std::vector<double> volume = signedVolumes(result.mesh, result.componentId, eligible, flip);
  if (orient)
  {
    for (int32_t f = 0; f < nf; ++f)
    {
      const bool reverse = (flip[f] == 1) != (volume[result.componentId[f]] < 0.0);
      if (reverse)
      {
        std::swap(tri[3 * f + 1], tri[3 * f + 2]);
        ++report.flippedFaces;
      }
    }
  }
  return { std::move(closed), std::move(nonOrientable) };
}
} // namespace detail
} // namespace tc
