// SPDX-License-Identifier: BSD-3-Clause
#include "prep/point_merging.h"

#include "detail/splitmix.h"
#include "prep/first_equal.h"
#include "prep/points.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

namespace tc
{
namespace detail
{
namespace
{
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

/// Exact duplicates among the points `ids`: each takes the lowest id with the same coordinates.
void mergeExact(
  const double* points, const std::vector<int32_t>& ids, std::vector<int32_t>& representative)
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
    [&](int32_t i)
    { return mix64(bits(ids[i], 0) ^ mix64(bits(ids[i], 1) ^ mix64(bits(ids[i], 2)))); },
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
}

/// The points `ids` within `tolerance` of an earlier representative join the lowest-id one.
void mergeWithin(const double* points, const std::vector<int32_t>& ids,
  const std::array<double, 3>& low, double diagonal, double tolerance,
  std::vector<int32_t>& representative)
{
  // Cells of 2.5 tolerances: the ball of radius tolerance around a point then reaches, along
  // each axis, only its own cell and the neighbour on the nearer side (8 cells, not 27), with a
  // margin for rounding. Cells no smaller than 1e-9 of the diagonal keep cell coordinates far
  // from overflow.
  const double cellSize = std::max(2.5 * tolerance, 1e-9 * diagonal);
  const double tolerance2 = tolerance * tolerance;
  CellHash cells(static_cast<int64_t>(ids.size()));
  std::vector<int32_t> next(representative.size(), -1);
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
    const V3 p = pointOf(points, v);
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
        const V3 d = sub(pointOf(points, q), p);
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
}
} // namespace

std::vector<int32_t> mergePoints(const PolygonSoup& soup, const std::vector<uint8_t>& used,
  const std::array<double, 3>& low, double diagonal, double tolerance)
{
  const int64_t nv = soup.numPoints();
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
    mergeExact(soup.points.data(), ids, representative);
  }
  else
  {
    mergeWithin(soup.points.data(), ids, low, diagonal, tolerance, representative);
  }
  return representative;
}
} // namespace detail
} // namespace tc
