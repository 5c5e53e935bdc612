// SPDX-License-Identifier: BSD-3-Clause
#include "tc/prep/mesh_preparation.h"

#include "prep/surface_repair.h"

#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numeric>
#include <utility>

// Written by hand rather than with CGAL's repair_polygon_soup / orient_polygon_soup: those do
// not say which element they changed and always split non-manifold vertices, while this stage
// must return per-element flags (NonManifoldEdge, NonManifoldVertex, InputPointId, ...) and
// split only when the user asks for it.

namespace tc
{
namespace
{
constexpr int64_t kMaxIndex = std::numeric_limits<int32_t>::max();

/// Triangles with less area than this fraction of diagonal^2 are degenerate: relative to the
/// size of the mesh so that scaling the input does not change what is dropped.
constexpr double kDegenerateArea = 1e-12;

using Vec3 = std::array<double, 3>;

Vec3 pointOf(const double* points, int64_t v)
{
  return { points[3 * v], points[3 * v + 1], points[3 * v + 2] };
}

Vec3 minus(const Vec3& a, const Vec3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}

Vec3 cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

double dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double norm(const Vec3& a)
{
  return std::sqrt(dot(a, a));
}

/// Twice the area of triangle (a, b, c).
double doubleArea(const double* points, int64_t a, int64_t b, int64_t c)
{
  const Vec3 pa = pointOf(points, a);
  return norm(cross(minus(pointOf(points, b), pa), minus(pointOf(points, c), pa)));
}

/// Union-find (corners, faces); the root of a set is its lowest element, so results do not
/// depend on the order of the unions.
class DisjointSets
{
public:
  explicit DisjointSets(int64_t n)
    : Parent(n)
  {
    std::iota(Parent.begin(), Parent.end(), 0);
  }

  int32_t find(int32_t x)
  {
    while (Parent[x] != x)
    {
      Parent[x] = Parent[Parent[x]];
      x = Parent[x];
    }
    return x;
  }

  void unite(int32_t a, int32_t b)
  {
    a = find(a);
    b = find(b);
    if (a < b)
    {
      Parent[b] = a;
    }
    else if (b < a)
    {
      Parent[a] = b;
    }
  }

private:
  std::vector<int32_t> Parent;
};

/// Union-find that also keeps whether each element is flipped relative to its root (the
/// lowest element of its set): the orientation of faces within a patch.
class ParitySets
{
public:
  explicit ParitySets(int64_t n)
    : Parent(n)
    , Parity(n, 0)
  {
    std::iota(Parent.begin(), Parent.end(), 0);
  }

  /// Root of x and the parity of x relative to it.
  std::pair<int32_t, uint8_t> find(int32_t x)
  {
    int32_t root = x;
    uint8_t parity = 0;
    while (Parent[root] != root)
    {
      parity ^= Parity[root];
      root = Parent[root];
    }
    for (uint8_t p = parity; Parent[x] != x;)
    {
      const int32_t next = Parent[x];
      const uint8_t step = Parity[x];
      Parent[x] = root;
      Parity[x] = p;
      p ^= step;
      x = next;
    }
    return { root, parity };
  }

  /// Records that a and b differ by `parity`; false if that contradicts what is known.
  bool unite(int32_t a, int32_t b, uint8_t parity)
  {
    const auto [ra, pa] = find(a);
    const auto [rb, pb] = find(b);
    if (ra == rb)
    {
      return (pa ^ pb) == parity;
    }
    const int32_t low = std::min(ra, rb);
    const int32_t high = std::max(ra, rb);
    Parent[high] = low;
    Parity[high] = static_cast<uint8_t>(pa ^ pb ^ parity);
    return true;
  }

private:
  std::vector<int32_t> Parent;
  std::vector<uint8_t> Parity;
};

std::string plural(int64_t n, const char* singular, const char* many)
{
  return std::to_string(n) + " " + (n == 1 ? singular : many);
}

// ---------------------------------------------------------------------------------------------
// Validation

void validate(const PolygonSoup& soup)
{
  const int64_t nv = soup.numPoints();
  const int64_t np = soup.numPolygons();
  if (soup.points.size() % 3 != 0)
  {
    throw InputError("mesh preparation: the point array has " + std::to_string(soup.points.size()) +
      " values, not a multiple of 3 (x y z per point)");
  }
  if (nv == 0)
  {
    throw InputError("mesh preparation: the input has no points; give a surface mesh");
  }
  if (nv > kMaxIndex)
  {
    throw InputError("mesh preparation: the input has " + std::to_string(nv) +
      " points, more than the 2^31 - 1 this stage supports; split the mesh into parts");
  }
  if (np <= 0)
  {
    throw InputError("mesh preparation: the input has points but no polygons; give a surface "
                     "mesh with faces, not a point cloud");
  }
  if (soup.offsets.front() != 0 ||
    soup.offsets.back() != static_cast<int64_t>(soup.connectivity.size()))
  {
    throw InputError("mesh preparation: malformed polygon offsets: the first must be 0 and the "
                     "last the connectivity size " +
      std::to_string(soup.connectivity.size()));
  }
  for (int64_t p = 0; p < np; ++p)
  {
    if (soup.offsets[p + 1] < soup.offsets[p])
    {
      throw InputError("mesh preparation: malformed polygon offsets: polygon " + std::to_string(p) +
        " ends before it starts");
    }
    for (int64_t k = soup.offsets[p]; k < soup.offsets[p + 1]; ++k)
    {
      const int64_t id = soup.connectivity[k];
      if (id < 0 || id >= nv)
      {
        throw InputError("mesh preparation: polygon " + std::to_string(p) + " refers to point id " +
          std::to_string(id) + ", out of range: the input has " + std::to_string(nv) +
          " points (ids 0 to " + std::to_string(nv - 1) + "); fix the connectivity");
      }
    }
  }
  int64_t firstBad = -1;
  int64_t numBad = 0;
  for (int64_t v = 0; v < nv; ++v)
  {
    if (!std::isfinite(soup.points[3 * v]) || !std::isfinite(soup.points[3 * v + 1]) ||
      !std::isfinite(soup.points[3 * v + 2]))
    {
      firstBad = numBad == 0 ? v : firstBad;
      ++numBad;
    }
  }
  if (numBad > 0)
  {
    throw InputError("mesh preparation: point " + std::to_string(firstBad) +
      " has a NaN or infinite coordinate (" + plural(numBad, "point has", "points have") +
      " one); remove or repair these points before preparing the mesh");
  }
  // Sum of fan-triangle areas: zero only if every polygon is a point or a segment.
  double area = 0.0;
  const double* points = soup.points.data();
  for (int64_t p = 0; p < np && area == 0.0; ++p)
  {
    const int64_t* ids = soup.connectivity.data() + soup.offsets[p];
    const int64_t n = soup.offsets[p + 1] - soup.offsets[p];
    for (int64_t k = 1; k + 1 < n; ++k)
    {
      area += doubleArea(points, ids[0], ids[k], ids[k + 1]);
    }
  }
  if (area == 0.0)
  {
    throw InputError("mesh preparation: the polygons have zero total area (all their points "
                     "coincide or lie on a line); give a surface mesh");
  }
}

/// Mixes 64 bits into a well-spread hash (the finalizer of splitmix64).
uint64_t mix(uint64_t h)
{
  h ^= h >> 30;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 27;
  h *= 0x94D049BB133111EBull;
  return h ^ (h >> 31);
}

/// For items 0 .. n-1 in order, the first item equal to each (itself if none before it), with
/// an open-addressing hash table: linear time, where sorting would cost n log n.
template <typename HashFn, typename EqualFn>
std::vector<int32_t> firstEqual(int64_t n, const HashFn& hash, const EqualFn& equal)
{
  uint64_t capacity = 16;
  while (capacity < 2 * static_cast<uint64_t>(n))
  {
    capacity *= 2;
  }
  const uint64_t mask = capacity - 1;
  std::vector<int32_t> table(capacity, -1);
  std::vector<int32_t> first(n);
  for (int32_t i = 0; i < n; ++i)
  {
    for (uint64_t slot = hash(i) & mask;; slot = (slot + 1) & mask)
    {
      const int32_t j = table[slot];
      if (j < 0)
      {
        table[slot] = i;
        first[i] = i;
        break;
      }
      if (equal(i, j))
      {
        first[i] = j;
        break;
      }
    }
  }
  return first;
}

// ---------------------------------------------------------------------------------------------
// Point merging

/// Open-addressing hash of grid cells; each cell holds the list of group representatives in it,
/// in increasing id order (head, then next[]).
class CellHash
{
public:
  explicit CellHash(int64_t expected)
  {
    int64_t capacity = 16;
    while (capacity < 2 * expected)
    {
      capacity *= 2;
    }
    Mask = static_cast<uint64_t>(capacity - 1);
    Keys.resize(3 * capacity);
    Head.assign(capacity, -1);
    Tail.assign(capacity, -1);
  }

  /// Slot of the cell, or -1 when it is not in the table.
  int64_t find(const std::array<int64_t, 3>& cell) const
  {
    for (uint64_t s = hash(cell) & Mask;; s = (s + 1) & Mask)
    {
      if (Head[s] < 0)
      {
        return -1;
      }
      if (Keys[3 * s] == cell[0] && Keys[3 * s + 1] == cell[1] && Keys[3 * s + 2] == cell[2])
      {
        return static_cast<int64_t>(s);
      }
    }
  }

  /// Appends representative v to its cell's list (v larger than every id already there).
  void append(const std::array<int64_t, 3>& cell, int32_t v, std::vector<int32_t>& next)
  {
    uint64_t s = hash(cell) & Mask;
    for (; Head[s] >= 0; s = (s + 1) & Mask)
    {
      if (Keys[3 * s] == cell[0] && Keys[3 * s + 1] == cell[1] && Keys[3 * s + 2] == cell[2])
      {
        next[Tail[s]] = v;
        Tail[s] = v;
        return;
      }
    }
    Keys[3 * s] = cell[0];
    Keys[3 * s + 1] = cell[1];
    Keys[3 * s + 2] = cell[2];
    Head[s] = v;
    Tail[s] = v;
  }

  int32_t head(int64_t slot) const { return Head[slot]; }

private:
  static uint64_t hash(const std::array<int64_t, 3>& c)
  {
    uint64_t h = static_cast<uint64_t>(c[0]) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<uint64_t>(c[1]) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<uint64_t>(c[2]) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return h ^ (h >> 29);
  }

  uint64_t Mask = 0;
  std::vector<int64_t> Keys;
  std::vector<int32_t> Head;
  std::vector<int32_t> Tail;
};

/// Representative of every used point: the lowest id of its group of duplicates. Exact
/// duplicates are found by hashing; with a tolerance, points are visited in id order and join
/// the lowest-id representative within the tolerance (found in a grid of cells), else become
/// one.
std::vector<int32_t> mergePoints(const PolygonSoup& soup, const std::vector<uint8_t>& used,
  const Vec3& low, double diagonal, double tolerance)
{
  const int64_t nv = soup.numPoints();
  const double* points = soup.points.data();
  std::vector<int32_t> representative(nv);
  std::iota(representative.begin(), representative.end(), 0);
  std::vector<int32_t> ids;
  ids.reserve(nv);
  for (int64_t v = 0; v < nv; ++v)
  {
    if (used[v])
    {
      ids.push_back(static_cast<int32_t>(v));
    }
  }
  if (tolerance <= 0.0)
  {
    // Adding 0.0 turns -0.0 into +0.0, so that equal coordinates have equal bits.
    auto bits = [points](int64_t v, int c)
    {
      const double x = points[3 * v + c] + 0.0;
      uint64_t b = 0;
      std::memcpy(&b, &x, sizeof(b));
      return b;
    };
    const std::vector<int32_t> first = firstEqual(
      static_cast<int64_t>(ids.size()),
      [&](int32_t i) { return mix(bits(ids[i], 0) ^ mix(bits(ids[i], 1) ^ mix(bits(ids[i], 2)))); },
      [&](int32_t i, int32_t j)
      {
        const double* a = points + 3 * static_cast<int64_t>(ids[i]);
        const double* b = points + 3 * static_cast<int64_t>(ids[j]);
        return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
      });
    for (size_t i = 0; i < ids.size(); ++i)
    {
      representative[ids[i]] = ids[first[i]];
    }
    return representative;
  }

  // Cells of 2.5 tolerances: the ball of radius tolerance around a point then reaches, along
  // each axis, only its own cell and the neighbour on the nearer side (8 cells, not 27), with a
  // margin for rounding. Cells no smaller than 1e-9 of the diagonal keep cell coordinates far
  // from overflow.
  const double cellSize = std::max(2.5 * tolerance, 1e-9 * diagonal);
  const double tolerance2 = tolerance * tolerance;
  CellHash cells(static_cast<int64_t>(ids.size()));
  std::vector<int32_t> next(nv, -1);
  for (int32_t v : ids)
  {
    std::array<int64_t, 3> cell;
    std::array<int, 3> side;
    for (int c = 0; c < 3; ++c)
    {
      const double x = (points[3 * static_cast<int64_t>(v) + c] - low[c]) / cellSize;
      cell[c] = static_cast<int64_t>(std::floor(x));
      side[c] = x - static_cast<double>(cell[c]) < 0.5 ? -1 : 1;
    }
    const Vec3 p = pointOf(points, v);
    int32_t best = -1;
    for (int corner = 0; corner < 8; ++corner)
    {
      const int64_t slot = cells.find({ cell[0] + ((corner & 1) ? side[0] : 0),
        cell[1] + ((corner & 2) ? side[1] : 0), cell[2] + ((corner & 4) ? side[2] : 0) });
      if (slot < 0)
      {
        continue;
      }
      for (int32_t q = cells.head(slot); q >= 0 && (best < 0 || q < best); q = next[q])
      {
        const Vec3 d = minus(pointOf(points, q), p);
        if (dot(d, d) <= tolerance2)
        {
          best = q;
          break;
        }
      }
    }
    if (best >= 0)
    {
      representative[v] = best;
    }
    else
    {
      cells.append(cell, v, next);
    }
  }
  return representative;
}

// ---------------------------------------------------------------------------------------------
// Triangulation

/// Scratch arrays reused for every polygon, so triangulating allocates only for the largest.
struct EarScratch
{
  std::vector<double> uv;
  std::vector<int32_t> prev;
  std::vector<int32_t> next;
};

/// Ear clipping of one polygon of m >= 4 distinct consecutive corners in the plane of its
/// Newell normal; robust to non-convex polygons. Appends m - 2 triangles with the polygon's
/// orientation. Self-intersecting polygons (no ear in a whole round) get the most convex corner
/// clipped so the loop always ends; a polygon with a zero Newell normal gets a fan.
///
/// Hand-written rather than CGAL::Polygon_mesh_processing::triangulate_faces, which needs a
/// valid polygon mesh (a raw soup, with non-manifold or badly oriented polygons, is not one),
/// and rather than triangulate_hole_polyline, which is cubic in the corner count and adds no
/// robustness for the planar-ish faces of real files.
void earClip(const double* points, const int32_t* ids, int32_t m, EarScratch& s,
  std::vector<int32_t>& triangles)
{
  const Vec3 origin = pointOf(points, ids[0]);
  Vec3 normal = { 0.0, 0.0, 0.0 };
  for (int32_t i = 0; i < m; ++i)
  {
    const Vec3 a = minus(pointOf(points, ids[i]), origin);
    const Vec3 b = minus(pointOf(points, ids[(i + 1) % m]), origin);
    const Vec3 c = cross(a, b);
    normal = { normal[0] + c[0], normal[1] + c[1], normal[2] + c[2] };
  }
  const double length = norm(normal);
  if (!(length > 0.0))
  {
    for (int32_t i = 1; i + 1 < m; ++i)
    {
      triangles.insert(triangles.end(), { ids[0], ids[i], ids[i + 1] });
    }
    return;
  }
  const Vec3 n = { normal[0] / length, normal[1] / length, normal[2] / length };
  // In-plane basis (u, v) with u x v = n, so the polygon turns counter-clockwise in (u, v).
  int axis = 0;
  for (int c = 1; c < 3; ++c)
  {
    axis = std::abs(n[c]) < std::abs(n[axis]) ? c : axis;
  }
  Vec3 e = { 0.0, 0.0, 0.0 };
  e[axis] = 1.0;
  Vec3 u = cross(n, e);
  const double ul = norm(u);
  u = { u[0] / ul, u[1] / ul, u[2] / ul };
  const Vec3 v = cross(n, u);

  s.uv.resize(2 * m);
  s.prev.resize(m);
  s.next.resize(m);
  for (int32_t i = 0; i < m; ++i)
  {
    const Vec3 d = minus(pointOf(points, ids[i]), origin);
    s.uv[2 * i] = dot(d, u);
    s.uv[2 * i + 1] = dot(d, v);
    s.prev[i] = (i + m - 1) % m;
    s.next[i] = (i + 1) % m;
  }
  auto turn = [&s](int32_t a, int32_t b, int32_t c)
  {
    const double* pa = &s.uv[2 * a];
    const double* pb = &s.uv[2 * b];
    const double* pc = &s.uv[2 * c];
    return (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0]);
  };
  // An ear is a strictly convex corner whose triangle holds no other reflex corner (only those
  // can lie inside it); corners on its border block it too.
  auto isEar = [&](int32_t a, int32_t b, int32_t c)
  {
    if (!(turn(a, b, c) > 0.0))
    {
      return false;
    }
    for (int32_t j = s.next[c]; j != a; j = s.next[j])
    {
      if (ids[j] == ids[a] || ids[j] == ids[b] || ids[j] == ids[c] ||
        turn(s.prev[j], j, s.next[j]) > 0.0)
      {
        continue;
      }
      if (turn(a, b, j) >= 0.0 && turn(b, c, j) >= 0.0 && turn(c, a, j) >= 0.0)
      {
        return false;
      }
    }
    return true;
  };

  int32_t remaining = m;
  int32_t i = 0;
  int32_t sinceEar = 0;
  while (remaining > 3)
  {
    int32_t p = s.prev[i];
    int32_t q = s.next[i];
    if (!isEar(p, i, q))
    {
      i = q;
      if (++sinceEar < remaining)
      {
        continue;
      }
      int32_t best = i;
      double bestTurn = -std::numeric_limits<double>::infinity();
      int32_t j = i;
      do
      {
        const double t = turn(s.prev[j], j, s.next[j]);
        if (t > bestTurn)
        {
          bestTurn = t;
          best = j;
        }
        j = s.next[j];
      } while (j != i);
      i = best;
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

// ---------------------------------------------------------------------------------------------
// Topology helpers

/// Side (0, 1, 2) of face f that lies on edge e.
int sideOf(const EdgeTable& edges, int64_t f, int32_t e)
{
  return edges.faceEdges[3 * f] == e ? 0 : (edges.faceEdges[3 * f + 1] == e ? 1 : 2);
}

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

void joinAcross(const std::vector<int32_t>& triangles, const EdgeTable& edges, int32_t e, int32_t f,
  int32_t g, DisjointSets& corners)
{
  joinSides(triangles, 3 * f + sideOf(edges, f, e), 3 * g + sideOf(edges, g, e), corners);
}

/// True if f and g run along their common edge e in opposite directions (consistent).
bool consistentAcross(
  const std::vector<int32_t>& triangles, const EdgeTable& edges, int32_t e, int32_t f, int32_t g)
{
  const int i = sideOf(edges, f, e);
  const int j = sideOf(edges, g, e);
  return triangles[3 * f + i] != triangles[3 * g + j];
}
/// Flags non-manifold edges (more than 2 faces) and vertices (faces around it form more than
/// one fan, fans being joined across edges with exactly 2 faces) and counts them.
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
      joinAcross(tri, edges, e, faces[0], faces[1], fans);
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

/// Makes the mesh manifold by duplicating vertices. Sides stay glued across edges with 2 faces
/// and, on a non-manifold edge, for the first two consistent faces (or the first two, if none
/// are); every other side there is cut. Each fan of corners joined through glued sides becomes
/// one vertex, the fan of the lowest corner keeping the original vertex; copies are appended.
/// A cut face can still lie on its edge's other faces when its fans wrap around to them; it is
/// then cut away at one end (one more glued side through that corner is cut) and the fans are
/// found again. Cutting only splits fans, so this ends (after 1 or 2 rounds in practice).
/// @param[in,out] tri    #F x 3 triangles, renumbered
/// @param[in,out] edges  rebuilt for the new triangles
/// @return  the number of vertices, copies included
int32_t splitNonManifold(
  std::vector<int32_t>& tri, EdgeTable& edges, int32_t numVertices, PreparationResult& result)
{
  const int64_t nf = static_cast<int64_t>(tri.size() / 3);
  const std::vector<int32_t> original = tri;
  std::vector<int32_t> partner(3 * nf, -1);
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
  // Faces on the same non-manifold edge whose corners there fall into the same two fans end
  // up on one output edge; unglued ones among more than 2 such faces are cut away.
  std::vector<int32_t> nonManifold;
  for (int32_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) > 2)
    {
      nonManifold.push_back(e);
    }
  }
  auto cornerAt = [&original](int32_t f, int32_t v)
  { return 3 * f + (original[3 * f] == v ? 0 : (original[3 * f + 1] == v ? 1 : 2)); };
  std::vector<std::array<int32_t, 2>> fans;
  DisjointSets glued(0);
  for (bool cut = true; cut;)
  {
    glued = DisjointSets(3 * nf);
    for (int32_t side = 0; side < 3 * nf; ++side)
    {
      if (partner[side] > side)
      {
        joinSides(original, side, partner[side], glued);
      }
    }
    cut = false;
    for (const int32_t e : nonManifold)
    {
      const int32_t* faces = edges.edgeFaces.data() + edges.faceOffsets[e];
      const int64_t valence = edges.valence(e);
      fans.resize(valence);
      for (int64_t k = 0; k < valence; ++k)
      {
        fans[k] = { glued.find(cornerAt(faces[k], edges.vertices[2 * e])),
          glued.find(cornerAt(faces[k], edges.vertices[2 * e + 1])) };
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
  }
  result.inputPointId.resize(numVertices);
  result.nonManifoldVertex.resize(numVertices);
  std::vector<int32_t> fanVertex(3 * nf, -1);
  std::vector<uint8_t> vertexTaken(numVertices, 0);
  int32_t next = numVertices;
  for (int32_t c = 0; c < 3 * nf; ++c)
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
  edges = buildEdgeTable(tri);
  return next;
}

/// Components (across every shared edge) and orientation patches (across edges with exactly
/// 2 faces), numbered from their lowest face. Within a patch that lowest face keeps its
/// orientation; a patch where two paths disagree cannot be oriented and is left as it is.
/// A closed, oriented component then faces outward when its signed volume is positive.
/// Union-find over the edges in order rather than a breadth-first search over faces: it visits
/// memory in order, and gives the same result (the orientation of an orientable patch relative
/// to its first face is unique).
void orientComponents(bool orient, const EdgeTable& edges, PreparationResult& result)
{
  const double* points = result.mesh.points.data();
  PreparationReport& report = result.report;
  report.closedComponents = 0;
  report.nonOrientableComponents = 0;
  std::vector<int32_t>& tri = result.mesh.triangles;
  const int64_t nf = static_cast<int64_t>(tri.size() / 3);
  DisjointSets connected(nf);
  ParitySets patches(nf);
  std::vector<int32_t> conflicts;
  for (int32_t e = 0; e < edges.numEdges(); ++e)
  {
    const int64_t valence = edges.valence(e);
    const int32_t* faces = edges.edgeFaces.data() + edges.faceOffsets[e];
    for (int64_t k = 1; k < valence; ++k)
    {
      connected.unite(faces[0], faces[k]);
    }
    if (valence == 2 &&
      !patches.unite(
        faces[0], faces[1], consistentAcross(tri, edges, e, faces[0], faces[1]) ? 0 : 1))
    {
      conflicts.push_back(faces[0]);
    }
  }
  // Roots are lowest faces, so numbering roots in face order numbers components by first face.
  result.componentId.assign(nf, -1);
  int32_t numComponents = 0;
  for (int32_t f = 0; f < nf; ++f)
  {
    const int32_t root = connected.find(f);
    if (result.componentId[root] < 0)
    {
      result.componentId[root] = numComponents++;
    }
    result.componentId[f] = result.componentId[root];
  }
  report.components = numComponents;
  std::vector<uint8_t> closed(numComponents, 1);
  for (int32_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) != 2)
    {
      closed[result.componentId[edges.edgeFaces[edges.faceOffsets[e]]]] = 0;
    }
  }
  std::vector<uint8_t> unorientablePatch(nf, 0);
  for (const int32_t f : conflicts)
  {
    unorientablePatch[patches.find(f).first] = 1;
  }
  std::vector<uint8_t> nonOrientable(numComponents, 0);
  std::vector<uint8_t> flip(nf, 0);
  for (int32_t f = 0; f < nf; ++f)
  {
    const auto [root, parity] = patches.find(f);
    if (unorientablePatch[root])
    {
      nonOrientable[result.componentId[f]] = 1;
    }
    else
    {
      flip[f] = parity;
    }
  }
  // A closed, oriented component faces outward when its signed volume (sum over faces of
  // det(p0 - o, p1 - o, p2 - o) / 6, o any point) is positive; flip it otherwise.
  std::vector<double> volume(numComponents, 0.0);
  std::vector<Vec3> origin(numComponents);
  std::vector<uint8_t> hasOrigin(numComponents, 0);
  for (int32_t f = 0; f < nf; ++f)
  {
    const int32_t k = result.componentId[f];
    if (!closed[k] || nonOrientable[k])
    {
      continue;
    }
    const auto at = [&](int c) { return pointOf(points, tri[3 * f + c]); };
    if (!hasOrigin[k])
    {
      origin[k] = at(0);
      hasOrigin[k] = 1;
    }
    const Vec3 p0 = minus(at(0), origin[k]);
    const Vec3 p1 = minus(at(1), origin[k]);
    const Vec3 p2 = minus(at(2), origin[k]);
    const double det = dot(p0, cross(p1, p2));
    volume[k] += flip[f] ? -det : det;
  }
  for (int32_t k = 0; k < numComponents; ++k)
  {
    report.closedComponents += closed[k];
    report.nonOrientableComponents += nonOrientable[k];
  }
  if (orient)
  {
    for (int32_t f = 0; f < nf; ++f)
    {
      const int32_t k = result.componentId[f];
      const bool reverse = (flip[f] == 1) != (volume[k] < 0.0);
      if (reverse)
      {
        std::swap(tri[3 * f + 1], tri[3 * f + 2]);
        ++report.flippedFaces;
      }
    }
  }
}
/// Counts the boundary edges (one triangle) and flags their vertices.
void markBoundary(const EdgeTable& edges, int32_t numVertices, PreparationResult& result)
{
  result.report.boundaryEdges = 0;
  result.boundaryVertex.assign(numVertices, 0);
  for (int32_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) == 1)
    {
      ++result.report.boundaryEdges;
      result.boundaryVertex[edges.vertices[2 * e]] = 1;
      result.boundaryVertex[edges.vertices[2 * e + 1]] = 1;
    }
  }
}
} // namespace

// ---------------------------------------------------------------------------------------------

bool PreparationReport::changed() const
{
  return polygonsTriangulated > 0 || mergedPoints > 0 || degenerateFaces > 0 ||
    duplicateFaces > 0 || flippedFaces > 0 || unusedPoints > 0 || splitVertices > 0 ||
    filledHoles > 0 || droppedFragments > 0 || sliverPoints > 0 || reshapedTriangles > 0;
}

bool closedManifold(const PreparationReport& report, const PreparationOptions& options)
{
  return options.orient && report.closedComponents == report.components &&
    report.nonOrientableComponents == 0 &&
    (options.splitNonManifold || report.nonManifoldEdges + report.nonManifoldVertices == 0);
}

std::string closedManifoldRepairs(const PreparationReport& report, const PreparationOptions& options)
{
  if (closedManifold(report, options))
  {
    return {};
  }
  std::vector<std::string> problems;
  if (!options.splitNonManifold && report.nonManifoldEdges + report.nonManifoldVertices > 0)
  {
    std::string found;
    if (report.nonManifoldEdges > 0)
    {
      found = plural(report.nonManifoldEdges, "non-manifold edge", "non-manifold edges");
    }
    if (report.nonManifoldVertices > 0)
    {
      found += (found.empty() ? "" : " and ") +
        plural(report.nonManifoldVertices, "non-manifold vertex", "non-manifold vertices");
    }
    problems.push_back(found + " (split them: SplitNonManifold, trichart build --split-non-manifold)");
  }
  if (report.nonOrientableComponents > 0)
  {
    problems.push_back(plural(report.nonOrientableComponents,
                         "non-orientable (Moebius-like) component",
                         "non-orientable (Moebius-like) components") +
      ", which no orientation fixes (repair it in a mesh editor)");
  }
  if (report.boundaryEdges > 0)
  {
    const std::string edges = plural(report.boundaryEdges, "boundary edge", "boundary edges");
    problems.push_back(!options.fillHoles
        ? edges + " (close the holes: FillHoles, trichart build --fill-holes)"
        : plural(report.openHoles, "hole", "holes") + " left open, " + edges +
          " in all (FillHoles closes holes of up to MaxHoleEdges = " +
          std::to_string(options.maxHoleEdges) +
          " edges with a manifold patch: raise it, 0 for any size, trichart build "
          "--max-hole-edges)");
  }
  if (!options.orient)
  {
    problems.push_back("orientation unchecked (turn Orient on)");
  }
  std::string text;
  for (const std::string& p : problems)
  {
    text += (text.empty() ? "" : "; ") + p;
  }
  return text.empty() ? "unknown" : text;
}

std::string PreparationReport::text() const
{
  std::string text;
  auto line = [&text](int64_t n, const std::string& what)
  {
    if (n != 0)
    {
      text += what + "\n";
    }
  };
  line(inputPoints, plural(inputPoints, "input point", "input points"));
  line(inputPolygons, plural(inputPolygons, "input polygon", "input polygons"));
  line(polygonsTriangulated,
    "triangulated " + plural(polygonsTriangulated, "polygon", "polygons") +
      " with more than 3 corners");
  line(mergedPoints, "merged " + plural(mergedPoints, "duplicate point", "duplicate points"));
  line(degenerateFaces,
    "dropped " + plural(degenerateFaces, "degenerate face", "degenerate faces") +
      " (repeated corner or zero area)");
  line(duplicateFaces, "dropped " + plural(duplicateFaces, "duplicate face", "duplicate faces"));
  line(flippedFaces,
    "flipped " + plural(flippedFaces, "face", "faces") + " for a consistent orientation");
  line(unusedPoints, "dropped " + plural(unusedPoints, "unused point", "unused points"));
  line(nonManifoldEdges,
    "found " + plural(nonManifoldEdges, "non-manifold edge", "non-manifold edges") +
      " (more than 2 faces)");
  line(nonManifoldVertices,
    "found " + plural(nonManifoldVertices, "non-manifold vertex", "non-manifold vertices") +
      " (more than one fan of faces)");
  line(splitVertices,
    "added " + plural(splitVertices, "vertex copy", "vertex copies") +
      " to split non-manifold edges and vertices");
  line(filledHoles,
    "filled " + plural(filledHoles, "hole", "holes") + " with " +
      plural(holeTriangles, "triangle", "triangles") + " and " +
      plural(holePoints, "point", "points"));
  line(droppedFragments,
    "dropped " + plural(droppedFragments, "fragment", "fragments") +
      " of fewer than 4 triangles, which no hole filling closes into a surface");
  line(unfairedHoles,
    plural(unfairedHoles, "filled hole", "filled holes") + " left unfaired (flat patch)");
  line(openHoles,
    "left " + plural(openHoles, "hole", "holes") +
      " open (more boundary edges than MaxHoleEdges, or no manifold patch)");
  line(slivers,
    "found " + plural(slivers, "sliver", "slivers") + " (caps and needles): collapsed " +
      plural(sliverPoints, "point", "points") + " and reshaped " +
      plural(reshapedTriangles, "triangle", "triangles"));
  line(remainingSlivers,
    "left " + plural(remainingSlivers, "sliver", "slivers") +
      " (no collapse or flip removes them without a fold)");
  line(boundaryEdges, plural(boundaryEdges, "boundary edge", "boundary edges"));
  line(components, plural(components, "connected component", "connected components"));
  line(closedComponents, plural(closedComponents, "closed component", "closed components"));
  line(nonOrientableComponents,
    plural(nonOrientableComponents, "non-orientable component", "non-orientable components") +
      " (left unoriented)");
  line(outputPoints, plural(outputPoints, "output point", "output points"));
  line(outputTriangles, plural(outputTriangles, "output triangle", "output triangles"));
  return text;
}

PreparationResult prepareMesh(
  const PolygonSoup& soup, const PreparationOptions& options, const Progress& progress)
{
  progress.report(0.0);
  PreparationResult result;
  PreparationReport& report = result.report;
  report.inputPoints = soup.numPoints();
  report.inputPolygons = soup.numPolygons();

  // 1. Validate: every later step may assume ids in range and finite coordinates.
  validate(soup);
  if (options.removeSlivers &&
    !(options.sliverAngle >= kMinSliverAngle && options.sliverAngle <= 180.0 &&
      options.sliverEdgeRatio >= kMinSliverEdgeRatio))
  {
    // Lower thresholds would count ordinary triangles as slivers and collapse the mesh away
    // (a ratio of 1.01 turns the bundled bunny into a tetrahedron).
    auto g = [](double x)
    {
      char text[32];
      std::snprintf(text, sizeof(text), "%g", x);
      return std::string(text);
    };
    throw InputError("mesh preparation: sliverAngle must be " + g(kMinSliverAngle) +
      " .. 180 degrees and sliverEdgeRatio at least " + g(kMinSliverEdgeRatio) + " (got " +
      g(options.sliverAngle) + " and " + g(options.sliverEdgeRatio) + ")");
  }
  const int64_t nv = soup.numPoints();
  const int64_t np = soup.numPolygons();
  const double* points = soup.points.data();
  std::vector<uint8_t> used(nv, 0);
  for (int64_t id : soup.connectivity)
  {
    used[id] = 1;
  }
  Vec3 low = { std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  Vec3 high = { -low[0], -low[1], -low[2] };
  for (int64_t v = 0; v < nv; ++v)
  {
    if (used[v])
    {
      for (int c = 0; c < 3; ++c)
      {
        low[c] = std::min(low[c], points[3 * v + c]);
        high[c] = std::max(high[c], points[3 * v + c]);
      }
    }
  }
  const double diagonal = norm(minus(high, low));
  progress.report(0.05);

  // 2. Merge duplicate points (before triangulating, so that polygons see merged corners).
  const std::vector<int32_t> representative =
    mergePoints(soup, used, low, diagonal, std::max(0.0, options.mergeTolerance) * diagonal);
  for (int64_t v = 0; v < nv; ++v)
  {
    report.mergedPoints += (used[v] && representative[v] != v) ? 1 : 0;
  }
  progress.report(0.2);

  // 3. Triangulate polygons and drop degenerate triangles.
  std::vector<int32_t> triangles;
  std::vector<int64_t> triangleCell;
  {
    int64_t estimate = 0;
    for (int64_t p = 0; p < np; ++p)
    {
      estimate += std::max<int64_t>(1, soup.offsets[p + 1] - soup.offsets[p] - 2);
    }
    triangles.reserve(3 * estimate);
    triangleCell.reserve(estimate);
  }
  const double minDoubleArea = 2.0 * kDegenerateArea * diagonal * diagonal;
  EarScratch scratch;
  std::vector<int32_t> corners;
  for (int64_t p = 0; p < np; ++p)
  {
    const int64_t begin = soup.offsets[p];
    const int64_t n = soup.offsets[p + 1] - begin;
    const size_t first = triangles.size();
    if (n == 3)
    {
      for (int64_t k = 0; k < 3; ++k)
      {
        triangles.push_back(representative[soup.connectivity[begin + k]]);
      }
    }
    else
    {
      report.polygonsTriangulated += n > 3 ? 1 : 0;
      // Merging can make consecutive corners equal; they would only give empty ears.
      corners.clear();
      for (int64_t k = 0; k < n; ++k)
      {
        const int32_t id = representative[soup.connectivity[begin + k]];
        if (corners.empty() || corners.back() != id)
        {
          corners.push_back(id);
        }
      }
      while (corners.size() > 1 && corners.back() == corners.front())
      {
        corners.pop_back();
      }
      const int32_t m = static_cast<int32_t>(corners.size());
      if (m < 3)
      {
        ++report.degenerateFaces;
        continue;
      }
      if (m == 3)
      {
        triangles.insert(triangles.end(), corners.begin(), corners.end());
      }
      else
      {
        earClip(points, corners.data(), m, scratch, triangles);
      }
    }
    // Keep the triangles of this polygon that have 3 distinct corners and a non-zero area.
    size_t out = first;
    for (size_t t = first; t < triangles.size(); t += 3)
    {
      const int32_t a = triangles[t];
      const int32_t b = triangles[t + 1];
      const int32_t c = triangles[t + 2];
      if (a == b || b == c || c == a || doubleArea(points, a, b, c) < minDoubleArea)
      {
        ++report.degenerateFaces;
        continue;
      }
      triangles[out] = a;
      triangles[out + 1] = b;
      triangles[out + 2] = c;
      out += 3;
      triangleCell.push_back(p);
    }
    triangles.resize(out);
  }
  progress.report(0.35);

  // 4. Drop repeated triangles (same three points in any order); the first one stays.
  const int64_t numCandidates = static_cast<int64_t>(triangleCell.size());
  if (3 * numCandidates > kMaxIndex)
  {
    throw InputError("mesh preparation: " + std::to_string(numCandidates) +
      " triangles are more than this stage supports (2^31 / 3); split the mesh into parts");
  }
  std::vector<uint8_t> keep(numCandidates, 1);
  {
    std::vector<std::array<int32_t, 3>> keys(numCandidates);
    for (int64_t t = 0; t < numCandidates; ++t)
    {
      keys[t] = { triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2] };
      std::sort(keys[t].begin(), keys[t].end());
    }
    const std::vector<int32_t> first = firstEqual(
      numCandidates,
      [&keys](int32_t t)
      {
        const auto& k = keys[t];
        return mix(static_cast<uint64_t>(k[0]) << 32 ^
          mix(static_cast<uint64_t>(k[1]) << 32 ^ static_cast<uint64_t>(k[2])));
      },
      [&keys](int32_t a, int32_t b) { return keys[a] == keys[b]; });
    for (int64_t t = 0; t < numCandidates; ++t)
    {
      if (first[t] != t)
      {
        keep[t] = 0;
        ++report.duplicateFaces;
      }
    }
  }
  const int64_t numKept = numCandidates - report.duplicateFaces;
  if (numKept == 0)
  {
    throw InputError("mesh preparation: no triangles with non-zero area are left after cleaning (" +
      plural(report.degenerateFaces, "degenerate face", "degenerate faces") +
      " dropped); give a surface mesh with non-degenerate faces");
  }

  // 5. Number the used points in input order; compact the triangles.
  std::vector<int32_t> newId(nv, -1);
  std::vector<int32_t>& tri = result.mesh.triangles;
  tri.resize(3 * numKept);
  result.inputCellId.resize(numKept);
  int32_t numVertices = 0;
  {
    int64_t f = 0;
    for (int64_t t = 0; t < numCandidates; ++t)
    {
      if (keep[t])
      {
        for (int c = 0; c < 3; ++c)
        {
          newId[triangles[3 * t + c]] = 0;
        }
        result.inputCellId[f] = triangleCell[t];
        ++f;
      }
    }
    for (int64_t v = 0; v < nv; ++v)
    {
      if (newId[v] == 0)
      {
        newId[v] = numVertices++;
        result.inputPointId.push_back(v);
      }
    }
    f = 0;
    for (int64_t t = 0; t < numCandidates; ++t)
    {
      if (keep[t])
      {
        for (int c = 0; c < 3; ++c)
        {
          tri[3 * f + c] = newId[triangles[3 * t + c]];
        }
        ++f;
      }
    }
  }
  report.unusedPoints = nv - report.mergedPoints - numVertices;
  std::vector<int32_t>().swap(triangles);
  std::vector<int64_t>().swap(triangleCell);
  progress.report(0.45);

  // 6. Non-manifold edges and vertices, flagged before any splitting.
  EdgeTable edges = buildEdgeTable(tri);
  findNonManifold(tri, edges, numVertices, result);
  progress.report(0.6);

  // 7. Split (opt-in).
  if (options.splitNonManifold && (report.nonManifoldEdges > 0 || report.nonManifoldVertices > 0))
  {
    const int32_t before = numVertices;
    numVertices = splitNonManifold(tri, edges, numVertices, result);
    report.splitVertices = numVertices - before;
  }
  progress.report(0.7);

  // 8. Output points, components, orientation and boundary.
  result.mesh.points.resize(3 * static_cast<size_t>(numVertices));
  for (int32_t v = 0; v < numVertices; ++v)
  {
    for (int c = 0; c < 3; ++c)
    {
      result.mesh.points[3 * v + c] = points[3 * result.inputPointId[v] + c];
    }
  }
  orientComponents(options.orient, edges, result);
  markBoundary(edges, numVertices, result);
  progress.report(0.8);

  // Why a CGAL repair found the mesh not manifold, and what to do.
  auto notManifold = [&](const std::string& what, const char* option)
  {
    std::string why;
    if (!options.splitNonManifold && report.nonManifoldEdges + report.nonManifoldVertices > 0)
    {
      why = plural(report.nonManifoldEdges, "non-manifold edge", "non-manifold edges") + " and " +
        plural(report.nonManifoldVertices, "non-manifold vertex", "non-manifold vertices") +
        "; split them first (SplitNonManifold, --split-non-manifold)";
    }
    else
    {
      why = plural(report.nonOrientableComponents, "non-orientable component",
              "non-orientable components") +
        " (Moebius-like), which no patch closes consistently; repair the mesh in a mesh "
        "editor, or leave " +
        option + " off";
    }
    return InputError(
      "mesh preparation: cannot " + what + ": the mesh is not an oriented manifold: " + why);
  };

  // After a repair changed the triangles: edges, components, orientation and boundary again.
  auto relink = [&]()
  {
    edges = buildEdgeTable(tri);
    orientComponents(options.orient, edges, result);
    markBoundary(edges, numVertices, result);
  };

  // 9. Holes (opt-in), on the oriented mesh; then the closed components face outward too.
  int64_t nf = numKept;
  // After a repair kept some points and triangles (old ids, ascending): the per-element arrays
  // follow them, and the edges, components, orientation and boundary are found again.
  auto follow =
    [&](const std::vector<int32_t>& keptPoints, const std::vector<int32_t>& keptTriangles)
  {
    auto keep = [](auto& values, const std::vector<int32_t>& kept)
    {
      for (size_t i = 0; i < kept.size(); ++i)
      {
        values[i] = values[kept[i]];
      }
      values.resize(kept.size());
    };
    keep(result.inputPointId, keptPoints);
    keep(result.nonManifoldVertex, keptPoints);
    keep(result.inputCellId, keptTriangles);
    keep(result.nonManifoldEdge, keptTriangles);
    numVertices = static_cast<int32_t>(keptPoints.size());
    nf = static_cast<int64_t>(keptTriangles.size());
    relink();
  };
  if (options.fillHoles)
  {
    if (report.boundaryEdges > 0)
    {
      const HoleFilling filled =
        fillHoles(result.mesh, options.maxHoleEdges, progress.sub(0.8, 0.9));
      if (filled.nonManifold)
      {
        throw notManifold("fill holes", "FillHoles");
      }
      report.filledHoles = filled.filledHoles;
      report.holeTriangles = filled.addedTriangles;
      report.holePoints = filled.addedPoints;
      report.unfairedHoles = filled.unfairedHoles;
      report.openHoles = filled.skippedHoles;
      numVertices += static_cast<int32_t>(filled.addedPoints);
      nf += filled.addedTriangles;
      result.inputPointId.resize(numVertices, -1);
      result.inputCellId.resize(nf, -1);
      result.nonManifoldVertex.resize(numVertices, 0);
      result.nonManifoldEdge.resize(nf, 0);
      if (filled.addedTriangles > 0)
      {
        relink();
      }
    }
    // A component of fewer than 4 triangles is no closed surface once filled (a lone triangle
    // becomes a flat two-sided pair, around whose corners no base complex fits): drop it.
    const FragmentRemoval fragments =
      dropFragments(result.mesh, result.componentId, report.components, 4);
    report.droppedFragments = fragments.fragments;
    if (fragments.fragments > 0)
    {
      follow(fragments.keptPoints, fragments.keptTriangles);
    }
  }
  progress.report(0.9);

  // 10. Slivers (opt-in), last, so that hole patches are repaired too. Only drops points and
  // triangles and changes corners: the per-element arrays follow the kept ones.
  if (options.removeSlivers)
  {
    SliverRemoval removed = tc::removeSlivers(
      result.mesh, options.sliverAngle, options.sliverEdgeRatio, progress.sub(0.9, 1.0));
    if (removed.nonManifold)
    {
      throw notManifold("remove slivers", "RemoveSlivers");
    }
    report.slivers = removed.slivers;
    report.sliverPoints = removed.collapsedPoints;
    report.reshapedTriangles = removed.reshapedTriangles;
    report.remainingSlivers = removed.remainingSlivers;
    if (removed.collapsedPoints > 0 || removed.reshapedTriangles > 0)
    {
      follow(removed.keptPoints, removed.keptTriangles);
    }
  }
  report.outputPoints = numVertices;
  report.outputTriangles = nf;
  progress.report(1.0);
  return result;
}
} // namespace tc
