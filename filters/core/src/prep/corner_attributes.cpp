// SPDX-License-Identifier: BSD-3-Clause
#include "tc/prep/corner_attributes.h"

#include "tc/common/close_values.h"
#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tc
{
namespace
{
/// Values equal up to float rounding of what an exporter wrote twice (1e-6 relative): a seam is
/// a jump, not the last bit of a copy.
bool sameValue(const double* a, const double* b, int32_t components)
{
  return closeValues(a, b, static_cast<size_t>(components), 1e-6);
}

/// The point of polygon c of `soup` nearest to `p`.
int64_t nearestPolygonPoint(const PolygonSoup& soup, int64_t c, const double* p)
{
  int64_t best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (int64_t i = soup.offsets[c]; i < soup.offsets[c + 1]; ++i)
  {
    const int64_t q = soup.connectivity[i];
    double d = 0.0;
    for (int x = 0; x < 3; ++x)
    {
      const double dx = soup.points[3 * q + x] - p[x];
      d += dx * dx;
    }
    if (d < bestDistance)
    {
      bestDistance = d;
      best = q;
    }
  }
  return best;
}
} // namespace

std::vector<int64_t> cornerInputPoints(const PolygonSoup& soup, const PreparationResult& result)
{
  const std::vector<int32_t>& triangles = result.mesh.triangles;
  std::vector<int64_t> corners(triangles.size(), -1);
  for (size_t f = 0; f < result.inputCellId.size(); ++f)
  {
    const int64_t c = result.inputCellId[f];
    if (c < 0)
    {
      continue;
    }
    for (size_t k = 0; k < 3; ++k)
    {
      const int64_t p = triangles[3 * f + k];
      corners[3 * f + k] = nearestPolygonPoint(soup, c, &result.mesh.points[3 * p]);
    }
  }
  return corners;
}

bool mergeSplitsAttribute(const std::vector<double>& pointValues, int32_t components,
  const std::vector<int64_t>& corners, const PreparationResult& result)
{
  for (size_t i = 0; i < corners.size(); ++i)
  {
    const int64_t kept = result.inputPointId[static_cast<size_t>(result.mesh.triangles[i])];
    if (corners[i] < 0 || kept < 0 || corners[i] == kept)
    {
      continue;
    }
    if (!sameValue(
          &pointValues[corners[i] * components], &pointValues[kept * components], components))
    {
      return true;
    }
  }
  return false;
}

CornerAttribute makeCornerAttribute(const std::string& name, const std::vector<double>& pointValues,
  int32_t components, const std::vector<int64_t>& corners, const PreparationResult& result)
{
  CornerAttribute out;
  out.name = name;
  out.components = components;
  out.values.assign(corners.size() * static_cast<size_t>(components), 0.0);
  for (size_t i = 0; i < corners.size(); ++i)
  {
    int64_t from = corners[i];
    if (from < 0)
    {
      from = result.inputPointId[static_cast<size_t>(result.mesh.triangles[i])];
    }
    if (from < 0)
    {
      continue; // a hole-filling point: no value in the file, zeros as for its point arrays
    }
    std::copy_n(&pointValues[from * components], components, &out.values[i * components]);
  }
  return out;
}

std::vector<uint8_t> seamSides(
  const std::vector<int32_t>& triangles, const std::vector<CornerAttribute>& attributes)
{
  const int64_t nf = static_cast<int64_t>(triangles.size() / 3);
  std::vector<uint8_t> seams(static_cast<size_t>(nf), 0);
  if (attributes.empty() || nf == 0)
  {
    return seams;
  }
  const EdgeTable edges = buildEdgeTable(triangles);
  // The slot (3 f + k) of the corner of triangle f at vertex v.
  auto slot = [&](int32_t f, int32_t v)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (triangles[3 * static_cast<size_t>(f) + k] == v)
      {
        return 3 * static_cast<int64_t>(f) + k;
      }
    }
    throw InputError("seamSides: a triangle of an edge does not hold its vertex");
  };
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) != 2)
    {
      continue;
    }
    const int32_t f = edges.edgeFaces[edges.faceOffsets[e]];
    const int32_t g = edges.edgeFaces[edges.faceOffsets[e] + 1];
    bool seam = false;
    for (const CornerAttribute& a : attributes)
    {
      const int32_t n = a.components;
      bool differs[2];
      for (int end = 0; end < 2; ++end)
      {
        const int32_t v = edges.vertices[2 * e + end];
        differs[end] = !sameValue(&a.values[slot(f, v) * n], &a.values[slot(g, v) * n], n);
      }
      seam = seam || (differs[0] && differs[1]);
    }
    if (!seam)
    {
      continue;
    }
    for (const int32_t t : { f, g })
    {
      for (int k = 0; k < 3; ++k)
      {
        seams[static_cast<size_t>(t)] |= edges.faceEdges[3 * static_cast<size_t>(t) + k] == e
          ? static_cast<uint8_t>(1u << k)
          : uint8_t(0);
      }
    }
  }
  return seams;
}
} // namespace tc
