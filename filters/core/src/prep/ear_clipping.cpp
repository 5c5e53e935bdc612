// SPDX-License-Identifier: BSD-3-Clause
#include "prep/ear_clipping.h"

#include "prep/points.h"

#include <cmath>
#include <limits>

namespace tc
{
namespace detail
{
namespace
{
/// Corners of the polygon in an in-plane basis (u, v) with u x v = n, the unit Newell normal,
/// so that the polygon turns counter-clockwise in (u, v); prev/next link the corners in a ring.
/// False (and nothing set) when the Newell normal is zero.
bool planeCoordinates(const double* points, const int32_t* ids, int32_t m, EarScratch& s)
{
  const V3 origin = pointOf(points, ids[0]);
  V3 normal = { 0.0, 0.0, 0.0 };
  for (int32_t i = 0; i < m; ++i)
  {
    const V3 a = sub(pointOf(points, ids[i]), origin);
    const V3 b = sub(pointOf(points, ids[(i + 1) % m]), origin);
    const V3 c = cross(a, b);
    normal = { normal.x + c.x, normal.y + c.y, normal.z + c.z };
  }
  const double length = norm(normal);
  if (!(length > 0.0))
  {
    return false;
  }
  const V3 n = { normal.x / length, normal.y / length, normal.z / length };
  // u is n x (the axis along which n is smallest).
  const double size[3] = { std::abs(n.x), std::abs(n.y), std::abs(n.z) };
  int axis = 0;
  for (int c = 1; c < 3; ++c)
  {
    axis = size[c] < size[axis] ? c : axis;
  }
  const V3 e = { axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0 };
  V3 u = cross(n, e);
  const double ul = norm(u);
  u = { u.x / ul, u.y / ul, u.z / ul };
  const V3 v = cross(n, u);

  s.uv.resize(m);
  s.prev.resize(m);
  s.next.resize(m);
  for (int32_t i = 0; i < m; ++i)
  {
    const V3 d = sub(pointOf(points, ids[i]), origin);
    s.uv[i] = { dot(d, u), dot(d, v) };
    s.prev[i] = (i + m - 1) % m;
    s.next[i] = (i + 1) % m;
  }
  return true;
}

/// Twice the signed area of corners (a, b, c) in the plane: positive when they turn left.
double turn(const EarScratch& s, int32_t a, int32_t b, int32_t c)
{
  return orient(s.uv[a], s.uv[b], s.uv[c]);
}

/// An ear is a strictly convex corner whose triangle holds no other reflex corner (only those
/// can lie inside it); corners on its border block it too.
bool isEar(const EarScratch& s, const int32_t* ids, int32_t a, int32_t b, int32_t c)
{
  if (!(turn(s, a, b, c) > 0.0))
  {
    return false;
  }
  for (int32_t j = s.next[c]; j != a; j = s.next[j])
  {
    if (ids[j] == ids[a] || ids[j] == ids[b] || ids[j] == ids[c] ||
      turn(s, s.prev[j], j, s.next[j]) > 0.0)
    {
      continue;
    }
    if (turn(s, a, b, j) >= 0.0 && turn(s, b, c, j) >= 0.0 && turn(s, c, a, j) >= 0.0)
    {
      return false;
    }
  }
  return true;
}

/// The most convex corner of the remaining polygon, from corner i on (the first of equals).
int32_t mostConvexCorner(const EarScratch& s, int32_t i)
{
  int32_t best = i;
  double bestTurn = -std::numeric_limits<double>::infinity();
  int32_t j = i;
  do
  {
    const double t = turn(s, s.prev[j], j, s.next[j]);
    if (t > bestTurn)
    {
      bestTurn = t;
      best = j;
    }
    j = s.next[j];
  } while (j != i);
  return best;
}

/// Clips ears of the ring in `s` until a triangle is left, appending each.
void clipEars(const int32_t* ids, int32_t m, EarScratch& s, std::vector<int32_t>& triangles)
{
  int32_t remaining = m;
  int32_t i = 0;
  int32_t sinceEar = 0;
  while (remaining > 3)
  {
    int32_t p = s.prev[i];
    int32_t q = s.next[i];
    if (!isEar(s, ids, p, i, q))
    {
      i = q;
      if (++sinceEar < remaining)
      {
        continue;
      }
      // A whole round without an ear (a self-intersecting polygon): clip the most convex corner.
      i = mostConvexCorner(s, i);
      p = s.prev[i];
      q = s.next[i];
    }
    triangles.insert(triangles.end(), { ids[p], ids[i], ids[q] });
    s.next[p] = q;
    s.prev[q] = p;
    --remaining;
    sinceEar = 0;
    i = p;
  }
  triangles.insert(triangles.end(), { ids[s.prev[i]], ids[i], ids[s.next[i]] });
}
} // namespace

void earClip(const double* points, const int32_t* ids, int32_t m, EarScratch& scratch,
  std::vector<int32_t>& triangles)
{
  if (!planeCoordinates(points, ids, m, scratch))
  {
    for (int32_t i = 1; i + 1 < m; ++i)
    {
      triangles.insert(triangles.end(), { ids[0], ids[i], ids[i + 1] });
    }
    return;
  }
  clipEars(ids, m, scratch, triangles);
}
} // namespace detail
} // namespace tc
