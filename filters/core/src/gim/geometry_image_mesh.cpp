// SPDX-License-Identifier: BSD-3-Clause
#include "tc/gim/geometry_image_mesh.h"

#include "tc/common/close_values.h"
#include "tc/common/errors.h"
#include "tc/common/parallel.h"

// Written by hand: stitching and welding by eq. (8) is specific to this atlas layout; no library
// does it. How this file works:
//  1. checkLevels, checkImages, checkCharts: what reading and welding need (O(C)); the sample
//     invariants are validateAtlas's.
//  2. makePlan: the index of every output point follows from counts (base vertices, then the
//     2^m - 1 inner samples of every base edge at the lower of its two levels, then every chart's
//     interior), so charts can be processed independently and the weld is deterministic.
//  3. One parallel pass over charts applies the vertex rule (stitchedGridPoint) to every grid
//     vertex and maps it to its point (mapChartVertices), sets the sources of the points the
//     chart owns (setOwnedSources) and emits the triangles that keep three distinct corners
//     (chartTriangles).
//  4. One parallel pass over points reads every attribute from the point's source sample
//     (readPointAttributes).

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>

namespace tc
{
namespace
{
std::string chartName(size_t c)
{
  return "Atlas chart " + std::to_string(c);
}

void checkImages(const Atlas& atlas)
{
  if (atlas.attributes.empty() || atlas.attributes[0].components != 3)
  {
    throw InputError("The atlas must list Position (3 components) as attribute 0; it lists " +
      (atlas.attributes.empty() ? std::string("no attribute")
                                : atlas.attributes[0].name + " with " +
            std::to_string(atlas.attributes[0].components) + " components") +
      ".");
  }
  for (size_t a = 0; a < atlas.attributes.size(); ++a)
  {
    if (atlas.attributes[a].components < 1)
    {
      throw InputError("Atlas attribute " + std::to_string(a) + " (" + atlas.attributes[a].name +
        ") has " + std::to_string(atlas.attributes[a].components) +
        " components; every attribute needs at least 1.");
    }
  }
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    const AtlasImage& image = atlas.images[k];
    if (image.width < 0 || image.height < 0 || image.data.size() != atlas.attributes.size())
    {
      throw InputError("Atlas image " + std::to_string(k) + " is " + std::to_string(image.width) +
        " x " + std::to_string(image.height) + " with " + std::to_string(image.data.size()) +
        " attribute planes; it needs a non-negative size and one plane per attribute (" +
        std::to_string(atlas.attributes.size()) + ").");
    }
    for (size_t a = 0; a < atlas.attributes.size(); ++a)
    {
      const size_t expected = static_cast<size_t>(image.width) * static_cast<size_t>(image.height) *
        static_cast<size_t>(atlas.attributes[a].components);
      if (image.data[a].size() != expected)
      {
        throw InputError("Atlas image " + std::to_string(k) + ", attribute " +
          atlas.attributes[a].name + ": " + std::to_string(image.data[a].size()) +
          " floats where width x height x components = " + std::to_string(expected) + ".");
      }
    }
  }
}

/// Texels of the three corners of every level of chart c inside their image: the texel map is
/// affine and the sample triangle convex, so every sample is then inside.
void checkChartTexels(const Atlas& atlas, size_t c)
{
  const AtlasChart& chart = atlas.charts[c];
  for (int32_t d = 0; d <= chart.maxLevel; ++d)
  {
    const AtlasImage& image = atlas.images[static_cast<size_t>(chart.maxLevel - d)];
    const int32_t big = int32_t(1) << d;
    for (const std::array<int32_t, 2>& ij : { std::array<int32_t, 2>{ 0, 0 },
           std::array<int32_t, 2>{ big, 0 }, std::array<int32_t, 2>{ 0, big } })
    {
      // Widened: an origin near INT32_MAX must not wrap around into the image.
      const std::array<int32_t, 2>& o = chart.origin[static_cast<size_t>(chart.maxLevel - d)];
      const int64_t x = chart.rotated ? int64_t(o[0]) - ij[0] : int64_t(o[0]) + ij[0];
      const int64_t y = chart.rotated ? int64_t(o[1]) - ij[1] : int64_t(o[1]) + ij[1];
      if (x < 0 || y < 0 || x >= image.width || y >= image.height)
      {
        throw InputError(chartName(c) + ", level " + std::to_string(d) + ": sample (" +
          std::to_string(ij[0]) + ", " + std::to_string(ij[1]) + ") falls on texel (" +
          std::to_string(x) + ", " + std::to_string(y) + "), outside image " +
          std::to_string(chart.maxLevel - d) + " (" + std::to_string(image.width) + " x " +
          std::to_string(image.height) + "); fix the chart's origin or the image size.");
      }
    }
  }
}

/// Chart c's own fields: level, origins, rotation, texels, three distinct corners and
/// neighbours that exist.
void checkChart(const Atlas& atlas, size_t c)
{
  const size_t numCharts = atlas.charts.size();
  const AtlasChart& chart = atlas.charts[c];
  // Level 30 is where 2^level stops fitting the int32 grid coordinates; the image checks below
  // bound real atlases far lower.
  if (chart.maxLevel < 0 || chart.maxLevel > 30)
  {
    throw InputError(chartName(c) + " has maxLevel " + std::to_string(chart.maxLevel) +
      "; it must lie in [0, 30].");
  }
  if (chart.origin.size() != static_cast<size_t>(chart.maxLevel) + 1 ||
    atlas.images.size() <= static_cast<size_t>(chart.maxLevel))
  {
    throw InputError(chartName(c) + " has maxLevel " + std::to_string(chart.maxLevel) + ", " +
      std::to_string(chart.origin.size()) + " origins and the atlas " +
      std::to_string(atlas.images.size()) + " images; it needs maxLevel + 1 of each.");
  }
  if (chart.rotated > 1)
  {
    throw InputError(
      chartName(c) + " has rotated = " + std::to_string(chart.rotated) + "; it must be 0 or 1.");
  }
  checkChartTexels(atlas, c);
  for (int k = 0; k < 3; ++k)
  {
    if (chart.cornerVertex[k] < 0 || chart.cornerVertex[k] == chart.cornerVertex[(k + 1) % 3])
    {
      throw InputError(chartName(c) + " has corner vertices " +
        std::to_string(chart.cornerVertex[0]) + ", " + std::to_string(chart.cornerVertex[1]) +
        ", " + std::to_string(chart.cornerVertex[2]) +
        "; they must be three distinct base-vertex ids >= 0.");
    }
    const int32_t nb = chart.neighborChart[k], ns = chart.neighborSide[k];
    if (nb < 0 || static_cast<size_t>(nb) >= numCharts || ns < 0 || ns > 2)
    {
      throw InputError(chartName(c) + ", side " + std::to_string(k) + ": neighbour (chart " +
        std::to_string(nb) + ", side " + std::to_string(ns) + ") does not exist; the atlas has " +
        std::to_string(numCharts) + " charts of 3 sides and must be closed.");
    }
  }
}

/// The neighbours of chart c (which exist: checkChart) name it back and run each shared side
/// between the same corners the other way.
void checkNeighbours(const Atlas& atlas, size_t c)
{
  const AtlasChart& chart = atlas.charts[c];
  for (int k = 0; k < 3; ++k)
  {
    const int32_t nb = chart.neighborChart[k], ns = chart.neighborSide[k];
    const std::string where = chartName(c) + ", side " + std::to_string(k) + ": ";
    const AtlasChart& other = atlas.charts[static_cast<size_t>(nb)];
    if (other.neighborChart[ns] != static_cast<int32_t>(c) || other.neighborSide[ns] != k ||
      (static_cast<size_t>(nb) == c && ns == k))
    {
      throw InputError(where + "its neighbour, chart " + std::to_string(nb) + " side " +
        std::to_string(ns) + ", names chart " + std::to_string(other.neighborChart[ns]) + " side " +
        std::to_string(other.neighborSide[ns]) +
        " back; neighbours must name each other (run validateAtlas on the producer's output).");
    }
    // The neighbour runs the side the other way: its side starts at this side's end corner.
    if (other.cornerVertex[ns] != chart.cornerVertex[(k + 1) % 3] ||
      other.cornerVertex[(ns + 1) % 3] != chart.cornerVertex[k])
    {
      throw InputError(where + "runs from base vertex " + std::to_string(chart.cornerVertex[k]) +
        " to " + std::to_string(chart.cornerVertex[(k + 1) % 3]) + " but its neighbour, chart " +
        std::to_string(nb) + " side " + std::to_string(ns) + ", from " +
        std::to_string(other.cornerVertex[ns]) + " to " +
        std::to_string(other.cornerVertex[(ns + 1) % 3]) +
        "; a shared side must join the same base vertices, in opposite directions.");
    }
  }
}

void checkCharts(const Atlas& atlas)
{
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    checkChart(atlas, c);
  }
  // Every neighbour exists (above), so these reads stay inside the chart table.
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    checkNeighbours(atlas, c);
  }
}

/// Where every output point goes; see the point order in the header.
struct Plan
{
  std::vector<int32_t> levels;       ///< #C clamped levels
  std::vector<int32_t> cornerPoint;  ///< #C x 3 point of corner k
  std::vector<int32_t> edgeOf;       ///< #C x 3 base edge of side k
  std::vector<uint8_t> owns;         ///< #C x 3: 1 where (c, k) is its edge's owner
  std::vector<int32_t> edgeLevel;    ///< #E lower level of the edge's two charts
  std::vector<int64_t> edgeBase;     ///< #E point of the edge's first inner sample
  std::vector<int64_t> interiorBase; ///< #C point of the chart's first interior sample
  int64_t numCornerPoints = 0;
  int64_t numPoints = 0;
};

Plan makePlan(const Atlas& atlas, const std::vector<int32_t>& levels)
{
  const size_t numCharts = atlas.charts.size();
  Plan plan;
  plan.levels.resize(numCharts);
  for (size_t c = 0; c < numCharts; ++c)
  {
    plan.levels[c] = std::min(levels[c], atlas.charts[c].maxLevel);
  }

  std::vector<int32_t> baseVertices;
  baseVertices.reserve(3 * numCharts);
  for (const AtlasChart& chart : atlas.charts)
  {
    baseVertices.insert(baseVertices.end(), chart.cornerVertex.begin(), chart.cornerVertex.end());
  }
  std::sort(baseVertices.begin(), baseVertices.end());
  baseVertices.erase(std::unique(baseVertices.begin(), baseVertices.end()), baseVertices.end());
  plan.numCornerPoints = static_cast<int64_t>(baseVertices.size());
  plan.cornerPoint.resize(3 * numCharts);
  for (size_t c = 0; c < numCharts; ++c)
  {
    for (int k = 0; k < 3; ++k)
    {
      plan.cornerPoint[3 * c + k] =
        static_cast<int32_t>(std::lower_bound(baseVertices.begin(), baseVertices.end(),
                               atlas.charts[c].cornerVertex[k]) -
          baseVertices.begin());
    }
  }

  // Charts and sides in ascending order meet every edge first at its owner.
  int64_t next = plan.numCornerPoints;
  plan.edgeOf.assign(3 * numCharts, -1);
  plan.owns.assign(3 * numCharts, 0);
  for (size_t c = 0; c < numCharts; ++c)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int32_t nb = atlas.charts[c].neighborChart[k], ns = atlas.charts[c].neighborSide[k];
      const bool owner = std::make_pair(static_cast<int32_t>(c), k) < std::make_pair(nb, ns);
      if (!owner)
      {
        plan.edgeOf[3 * c + k] = plan.edgeOf[3 * static_cast<size_t>(nb) + ns];
        continue;
      }
      plan.owns[3 * c + k] = 1;
      plan.edgeOf[3 * c + k] = static_cast<int32_t>(plan.edgeLevel.size());
      const int32_t m = std::min(plan.levels[c], plan.levels[static_cast<size_t>(nb)]);
      plan.edgeLevel.push_back(m);
      plan.edgeBase.push_back(next);
      next += (int64_t(1) << m) - 1;
    }
  }
  plan.interiorBase.resize(numCharts);
  for (size_t c = 0; c < numCharts; ++c)
  {
    const int64_t big = int64_t(1) << plan.levels[c];
    plan.interiorBase[c] = next;
    next += (big - 1) * (big - 2) / 2;
  }
  plan.numPoints = next;
  if (plan.numPoints > std::numeric_limits<int32_t>::max())
  {
    throw InputError("The rebuilt mesh would have " + std::to_string(plan.numPoints) +
      " points, more than 32-bit point ids hold; choose lower levels.");
  }
  return plan;
}

/// Output point of stitched grid point (i, j) of chart c at level n.
inline int32_t pointOf(const Plan& plan, size_t c, int32_t n, int32_t i, int32_t j)
{
  const int32_t big = int32_t(1) << n;
  if (j == 0 && i == 0)
  {
    return plan.cornerPoint[3 * c];
  }
  if (j == 0 && i == big)
  {
    return plan.cornerPoint[3 * c + 1];
  }
  if (i == 0 && j == big)
  {
    return plan.cornerPoint[3 * c + 2];
  }
  const std::array<int32_t, 2> side = gridSide(i, j, big);
  const int32_t k = side[0], t = side[1];
  if (k < 0)
  {
    return static_cast<int32_t>(
      plan.interiorBase[c] + int64_t(j - 1) * (big - 1) - int64_t(j - 1) * j / 2 + (i - 1));
  }
  // After stitching t is a multiple of 2^(n - m): the sample of the edge at its lower level m.
  const int32_t e = plan.edgeOf[3 * c + k];
  const int32_t m = plan.edgeLevel[static_cast<size_t>(e)];
  const int32_t s = t >> (n - m);
  const int32_t index = plan.owns[3 * c + k] ? s : (int32_t(1) << m) - s;
  return static_cast<int32_t>(plan.edgeBase[static_cast<size_t>(e)] + index - 1);
}
/// @throws InputError for an atlas without charts, or levels that are not one >= 0 per chart
void checkLevels(const Atlas& atlas, const std::vector<int32_t>& levels)
{
  if (atlas.charts.empty())
  {
    throw InputError("The atlas has no charts; there is nothing to rebuild.");
  }
  if (levels.size() != atlas.charts.size())
  {
    throw InputError("rebuildMesh got " + std::to_string(levels.size()) +
      " levels for an atlas of " + std::to_string(atlas.charts.size()) +
      " charts; pass one level per chart.");
  }
  for (size_t c = 0; c < levels.size(); ++c)
  {
    if (levels[c] < 0)
    {
      throw InputError("rebuildMesh got level " + std::to_string(levels[c]) + " for chart " +
        std::to_string(c) + "; levels must be >= 0 (0 draws a chart as one triangle).");
    }
  }
}

/// The output's per-chart arrays sized by the plan, and the sources of the base vertices, read
/// from the lowest chart that has them (the chart pass writes only the points one chart owns).
RebuiltMesh startMesh(const Plan& plan)
{
  const size_t numCharts = plan.levels.size();
  RebuiltMesh out;
  out.chartLevel = plan.levels;
  out.chartVertexOffsets.resize(numCharts + 1, 0);
  for (size_t c = 0; c < numCharts; ++c)
  {
    out.chartVertexOffsets[c + 1] = out.chartVertexOffsets[c] + gridVertexCount(plan.levels[c]);
  }
  out.chartVertexPoint.resize(static_cast<size_t>(out.chartVertexOffsets[numCharts]));
  out.pointSource.assign(static_cast<size_t>(3 * plan.numPoints), -1);
  for (size_t c = 0; c < numCharts; ++c)
  {
    const int32_t big = int32_t(1) << plan.levels[c];
    const std::array<std::array<int32_t, 2>, 3> corners{ { { 0, 0 }, { big, 0 }, { 0, big } } };
    for (int k = 0; k < 3; ++k)
    {
      int32_t* source = &out.pointSource[3 * static_cast<size_t>(plan.cornerPoint[3 * c + k])];
      if (source[0] < 0)
      {
        source[0] = static_cast<int32_t>(c);
        source[1] = corners[k][0];
        source[2] = corners[k][1];
      }
    }
  }
  return out;
}

/// The levels of the charts across chart c's sides 0, 1, 2.
std::array<int32_t, 3> levelsAcross(const Atlas& atlas, const Plan& plan, size_t c)
{
  const AtlasChart& chart = atlas.charts[c];
  return { plan.levels[static_cast<size_t>(chart.neighborChart[0])],
    plan.levels[static_cast<size_t>(chart.neighborChart[1])],
    plan.levels[static_cast<size_t>(chart.neighborChart[2])] };
}

/// The vertex rule on every grid vertex of chart c, mapped to its output point.
void mapChartVertices(const Atlas& atlas, const Plan& plan, size_t c, int32_t* vertexPoint)
{
  const int32_t n = plan.levels[c];
  const int32_t big = int32_t(1) << n;
  const std::array<int32_t, 3> neighborLevels = levelsAcross(atlas, plan, c);
  for (int32_t j = 0, v = 0; j <= big; ++j)
  {
    for (int32_t i = 0; i + j <= big; ++i, ++v)
    {
      const std::array<int32_t, 2> g = stitchedGridPoint(n, neighborLevels, i, j);
      vertexPoint[v] = pointOf(plan, c, n, g[0], g[1]);
    }
  }
}

/// Sources of the points chart c owns: its interior and the sides it owns, read at the side's
/// own samples (multiples of 2^(n - m)), which stitching never moves.
void setOwnedSources(const Plan& plan, size_t c, std::vector<int32_t>& pointSource)
{
  const int32_t n = plan.levels[c];
  const int32_t big = int32_t(1) << n;
  const auto setSource = [&](int32_t i, int32_t j)
  {
    int32_t* source = &pointSource[3 * static_cast<size_t>(pointOf(plan, c, n, i, j))];
    source[0] = static_cast<int32_t>(c);
    source[1] = i;
    source[2] = j;
  };
  for (int32_t j = 1; j < big; ++j)
  {
    for (int32_t i = 1; i + j < big; ++i)
    {
      setSource(i, j);
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    if (!plan.owns[3 * c + k])
    {
      continue;
    }
    const int32_t m = plan.edgeLevel[static_cast<size_t>(plan.edgeOf[3 * c + k])];
    for (int32_t s = 1; s < (int32_t(1) << m); ++s)
    {
      const std::array<int32_t, 2> g = sidePoint(k, s << (n - m), big);
      setSource(g[0], g[1]);
    }
  }
}

/// The grid triangles of a chart at level n in row order, those that keep three distinct points;
/// rows j and j + 1 are consecutive runs of vertexPoint.
std::vector<int32_t> chartTriangles(int32_t n, const int32_t* vertexPoint)
{
  const int32_t big = int32_t(1) << n;
  std::vector<int32_t> tris;
  tris.reserve(3 * static_cast<size_t>(big) * static_cast<size_t>(big));
  const auto emit = [&tris](int32_t a, int32_t b, int32_t d)
  {
    if (a != b && b != d && d != a)
    {
      tris.insert(tris.end(), { a, b, d });
    }
  };
  for (int32_t j = 0, row = 0; j < big; ++j)
  {
    const int32_t* lo = vertexPoint + row;  // row j: big + 1 - j vertices
    const int32_t* hi = lo + (big + 1 - j); // row j + 1
    for (int32_t i = 0; i + j < big; ++i)
    {
      emit(lo[i], lo[i + 1], hi[i]);
      if (i + j + 2 <= big)
      {
        emit(lo[i + 1], hi[i + 1], hi[i]);
      }
    }
    row += big + 1 - j;
  }
  return tris;
}

/// The charts' triangles one after the other, with their chart and level; counts the dropped
/// ones. Frees the per-chart lists.
void gatherTriangles(
  const Plan& plan, std::vector<std::vector<int32_t>>& perChart, RebuiltMesh& out)
{
  const size_t numCharts = perChart.size();
  size_t numTriangleIds = 0;
  int64_t gridTriangles = 0;
  for (size_t c = 0; c < numCharts; ++c)
  {
    numTriangleIds += perChart[c].size();
    gridTriangles += int64_t(1) << (2 * plan.levels[c]);
  }
  out.mesh.triangles.reserve(numTriangleIds);
  out.chartId.reserve(numTriangleIds / 3);
  out.level.reserve(numTriangleIds / 3);
  for (size_t c = 0; c < numCharts; ++c)
  {
    std::vector<int32_t>& tris = perChart[c];
    out.mesh.triangles.insert(out.mesh.triangles.end(), tris.begin(), tris.end());
    out.chartId.insert(out.chartId.end(), tris.size() / 3, static_cast<int32_t>(c));
    out.level.insert(out.level.end(), tris.size() / 3, plan.levels[c]);
    std::vector<int32_t>().swap(tris);
  }
  out.droppedTriangles = gridTriangles - static_cast<int64_t>(numTriangleIds / 3);
}

/// Every attribute of every point from its one source sample, so points shared by charts are
/// bit-identical to what each chart's shader reads (the atlas invariants). In parallel.
void readPointAttributes(
  const Atlas& atlas, const Plan& plan, RebuiltMesh& out, const Progress& progress)
{
  const size_t numPoints = static_cast<size_t>(plan.numPoints);
  const size_t numAttributes = atlas.attributes.size();
  out.mesh.points.resize(3 * numPoints);
  out.attributes.resize(numAttributes - 1);
  for (size_t a = 1; a < numAttributes; ++a)
  {
    out.attributes[a - 1].resize(numPoints * static_cast<size_t>(atlas.attributes[a].components));
  }
  constexpr int64_t kBlock = 4096;
  parallel_for((plan.numPoints + kBlock - 1) / kBlock,
    [&](int64_t block)
    {
      const int64_t stop = std::min(plan.numPoints, (block + 1) * kBlock);
      for (int64_t p = block * kBlock; p < stop; ++p)
      {
        const int32_t* source = &out.pointSource[3 * static_cast<size_t>(p)];
        const int32_t d = plan.levels[static_cast<size_t>(source[0])];
        const float* xyz = atlasSample(atlas, source[0], 0, d, source[1], source[2]);
        for (int x = 0; x < 3; ++x)
        {
          out.mesh.points[3 * static_cast<size_t>(p) + x] = static_cast<double>(xyz[x]);
        }
        for (size_t a = 1; a < numAttributes; ++a)
        {
          const size_t comps = static_cast<size_t>(atlas.attributes[a].components);
          std::memcpy(&out.attributes[a - 1][static_cast<size_t>(p) * comps],
            atlasSample(atlas, source[0], static_cast<int32_t>(a), d, source[1], source[2]),
            comps * sizeof(float));
        }
      }
    },
    progress);
}

/// Whether values a and b of a seam attribute differ: by more than float noise (two charts
/// resample one side independently), less than any real seam (u = 0 against 1).
bool seamValuesDiffer(const float* a, const float* b, size_t comps)
{
  return !closeValues(a, b, comps, 1e-5f);
}

/// The attributes that may split a point (after Position and Normal), and whether chart c's own
/// sample (i, j) at level n holds other values of them than point p.
struct SeamAttributes
{
  const Atlas& atlas;
  const RebuiltMesh& mesh;

  bool differ(size_t c, int32_t n, int32_t i, int32_t j, int32_t p) const
  {
    for (size_t a = 2; a < atlas.attributes.size(); ++a)
    {
      const size_t comps = static_cast<size_t>(atlas.attributes[a].components);
      if (seamValuesDiffer(
            atlasSample(atlas, static_cast<int32_t>(c), static_cast<int32_t>(a), n, i, j),
            &mesh.attributes[a - 1][static_cast<size_t>(p) * comps], comps))
      {
        return true;
      }
    }
    return false;
  }
};

/// Appends point `from` again, read from chart c's sample (i, j) at level n; returns its index.
int32_t appendSeamCopy(
  const Atlas& atlas, RebuiltMesh& out, int32_t from, size_t c, int32_t n, int32_t i, int32_t j)
{
  const int32_t copy = static_cast<int32_t>(out.mesh.numPoints());
  for (int x = 0; x < 3; ++x)
  {
    out.mesh.points.push_back(out.mesh.points[3 * static_cast<size_t>(from) + x]);
  }
  out.pointSource.insert(out.pointSource.end(), { static_cast<int32_t>(c), i, j });
  for (size_t a = 1; a < atlas.attributes.size(); ++a)
  {
    const size_t comps = static_cast<size_t>(atlas.attributes[a].components);
    const float* v = atlasSample(atlas, static_cast<int32_t>(c), static_cast<int32_t>(a), n, i, j);
    out.attributes[a - 1].insert(out.attributes[a - 1].end(), v, v + comps);
  }
  return copy;
}

/// Chart c's side and corner vertices whose own values differ from their welded point's go to a
/// copy of the point with the chart's values (one copy per distinct value, shared by the charts
/// that agree); `remap` gets the replaced points.
void splitChartSeams(const Atlas& atlas, const Plan& plan, size_t c, RebuiltMesh& out,
  std::vector<std::vector<int32_t>>& copies, std::unordered_map<int32_t, int32_t>& remap)
{
  const int32_t n = plan.levels[c];
  const int32_t big = int32_t(1) << n;
  const std::array<int32_t, 3> neighborLevels = levelsAcross(atlas, plan, c);
  int32_t* vertexPoint = out.chartVertexPoint.data() + out.chartVertexOffsets[c];
  for (int32_t k = 0; k < 3; ++k)
  {
    for (int32_t t = 0; t < big; ++t)
    {
      const std::array<int32_t, 2> ij = sidePoint(k, t, big);
      const std::array<int32_t, 2> g = stitchedGridPoint(n, neighborLevels, ij[0], ij[1]);
      int32_t& point = vertexPoint[gridVertexIndex(n, ij[0], ij[1])];
      const SeamAttributes seams{ atlas, out };
      if (!seams.differ(c, n, g[0], g[1], point))
      {
        continue;
      }
      std::vector<int32_t>& known = copies[static_cast<size_t>(point)];
      const auto same = std::find_if(
        known.begin(), known.end(), [&](int32_t q) { return !seams.differ(c, n, g[0], g[1], q); });
      const int32_t copy =
        same != known.end() ? *same : appendSeamCopy(atlas, out, point, c, n, g[0], g[1]);
      if (same == known.end())
      {
        known.push_back(copy);
        copies.emplace_back(); // the copy's own list, last: `known` is not used after it
      }
      remap[point] = copy;
      point = copy;
    }
  }
}

/// Points on a seam of an attribute after Position and Normal (a texture seam the atlas keeps
/// per chart) split into one copy per distinct value, so that each chart's triangles carry its
/// own values, as its shader draws them; the triangles follow.
void splitSeams(const Atlas& atlas, const Plan& plan, RebuiltMesh& out)
{
  if (atlas.attributes.size() <= 2)
  {
    return;
  }
  std::vector<std::vector<int32_t>> copies(static_cast<size_t>(out.mesh.numPoints()));
  size_t t = 0;
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    std::unordered_map<int32_t, int32_t> remap;
    splitChartSeams(atlas, plan, c, out, copies, remap);
    for (; t < out.chartId.size() && out.chartId[t] == static_cast<int32_t>(c); ++t)
    {
      for (size_t x = 3 * t; x < 3 * t + 3 && !remap.empty(); ++x)
      {
        const auto it = remap.find(out.mesh.triangles[x]);
        out.mesh.triangles[x] = it == remap.end() ? out.mesh.triangles[x] : it->second;
      }
    }
  }
}
} // namespace

RebuiltMesh rebuildMesh(
  const Atlas& atlas, const std::vector<int32_t>& levels, const Progress& progress)
{
  checkLevels(atlas, levels);
  checkImages(atlas);
  checkCharts(atlas);
  progress.report(0.0);

  // Every output point's index from the counts, then one pass over the charts: the vertex rule,
  // the sources of the points each chart owns, and its triangles.
  const Plan plan = makePlan(atlas, levels);
  RebuiltMesh out = startMesh(plan);
  std::vector<std::vector<int32_t>> perChart(atlas.charts.size());
  parallel_for(
    static_cast<int64_t>(atlas.charts.size()),
    [&](int64_t ci)
    {
      const size_t c = static_cast<size_t>(ci);
      int32_t* vertexPoint = out.chartVertexPoint.data() + out.chartVertexOffsets[c];
      mapChartVertices(atlas, plan, c, vertexPoint);
      setOwnedSources(plan, c, out.pointSource);
      perChart[c] = chartTriangles(plan.levels[c], vertexPoint);
    },
    progress.sub(0.0, 0.6));
  gatherTriangles(plan, perChart, out);
  progress.report(0.65);

  // Every point's attributes from its source sample.
  readPointAttributes(atlas, plan, out, progress.sub(0.65, 1.0));
  splitSeams(atlas, plan, out);
  return out;
}

RebuiltMesh rebuildMesh(const Atlas& atlas, int32_t level, const Progress& progress)
{
  if (level < 0)
  {
    throw InputError("rebuildMesh got level " + std::to_string(level) +
      "; levels must be >= 0 (0 draws every chart as one triangle).");
  }
  return rebuildMesh(atlas, std::vector<int32_t>(atlas.charts.size(), level), progress);
}
} // namespace tc
