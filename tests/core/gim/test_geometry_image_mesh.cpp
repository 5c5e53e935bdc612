// SPDX-License-Identifier: BSD-3-Clause
// rebuildMesh: the mesh an atlas draws at a level per chart, stitched by eq. (8) of Feng et al.
// and welded. Two analytic atlases: a unit sphere over an icosahedron (20 charts, maxLevel 2..6,
// rotated partner pairs) and a torus over a 4 x 3 grid (24 charts, maxLevel 2..5).
#include "tc/gim/geometry_image_mesh.h"

#include "tc/gim/atlas.h"
#include "tc/common/errors.h"

#include "mesh_checks.h"
#include "test_progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace
{
constexpr double kPi = 3.14159265358979323846;
using Param = std::array<double, 3>;

/// A closed base complex and its map onto an analytic surface.
struct AnalyticBase
{
  std::vector<std::array<int32_t, 3>> faces; ///< counter-clockwise seen from outside
  std::vector<Param> vertexParam;            ///< canonical parameter of every base vertex
  /// Per face, the parameters of its three corners in one frame (the torus unwraps its seams, so
  /// a corner's frame parameter may differ from the canonical one by a period).
  std::vector<std::array<Param, 3>> frame;
  /// Position, unit normal and one scalar of the surface at a parameter.
  std::function<void(const Param&, float*, float*, float*)> eval;
  std::vector<int32_t> maxLevel; ///< per face
  std::vector<int32_t> partner;  ///< per face, -1 for none; partners have the same maxLevel
  int eulerCharacteristic = 0;
};

/// Parameter of sample (i, j) of chart c at level d. Corners come from the base vertex and side
/// samples from the side's owner (the lower (chart, side)) at the exact dyadic fraction, so
/// shared sides and corners are bit-identical and a coarse side's samples are a subset of a
/// finer one's.
Param sampleParam(const AnalyticBase& base, const std::vector<tc::AtlasChart>& charts, int32_t c,
  int32_t d, int32_t i, int32_t j)
{
  const int32_t big = 1 << d;
  const tc::AtlasChart& chart = charts[static_cast<size_t>(c)];
  const std::array<std::array<int32_t, 2>, 3> corners{ { { 0, 0 }, { big, 0 }, { 0, big } } };
  for (int k = 0; k < 3; ++k)
  {
    if (corners[k][0] == i && corners[k][1] == j)
    {
      return base.vertexParam[static_cast<size_t>(chart.cornerVertex[k])];
    }
  }
  int side = -1;
  int32_t t = 0;
  if (j == 0)
  {
    side = 0;
    t = i;
  }
  else if (i + j == big)
  {
    side = 1;
    t = j;
  }
  else if (i == 0)
  {
    side = 2;
    t = big - j;
  }
  const std::array<Param, 3>& f = base.frame[static_cast<size_t>(c)];
  Param p{};
  if (side < 0)
  {
    const double s = static_cast<double>(i) / big, r = static_cast<double>(j) / big;
    for (int x = 0; x < 3; ++x)
    {
      p[x] = f[0][x] + (f[1][x] - f[0][x]) * s + (f[2][x] - f[0][x]) * r;
    }
    return p;
  }
  int32_t oc = c, os = side;
  double fraction = static_cast<double>(t) / big;
  const int32_t nb = chart.neighborChart[side], ns = chart.neighborSide[side];
  if (std::make_pair(nb, ns) < std::make_pair(c, side))
  {
    oc = nb;
    os = ns;
    fraction = static_cast<double>(big - t) / big;
  }
  const Param& a = base.frame[static_cast<size_t>(oc)][os];
  const Param& b = base.frame[static_cast<size_t>(oc)][(os + 1) % 3];
  for (int x = 0; x < 3; ++x)
  {
    p[x] = a[x] + (b[x] - a[x]) * fraction;
  }
  return p;
}

/// The atlas of an analytic base: Position, Normal and a scalar "Height", one chart per face,
/// partner pairs sharing rectangles (the second of a pair rotated), rectangles in a row per image
/// with a one-texel margin.
tc::Atlas buildAtlas(const AnalyticBase& base)
{
  const size_t nc = base.faces.size();
  tc::Atlas atlas;
  atlas.attributes = { { tc::kAtlasPosition, 3 }, { tc::kAtlasNormal, 3 }, { "Height", 1 } };
  atlas.charts.resize(nc);
  std::map<std::pair<int32_t, int32_t>, std::pair<int32_t, int32_t>> sideOf;
  for (size_t c = 0; c < nc; ++c)
  {
    for (int k = 0; k < 3; ++k)
    {
      const auto key = std::make_pair(base.faces[c][k], base.faces[c][(k + 1) % 3]);
      EXPECT_TRUE(sideOf.count(key) == 0) << "the base complex repeats a directed edge";
      sideOf[key] = { static_cast<int32_t>(c), k };
    }
  }
  for (size_t c = 0; c < nc; ++c)
  {
    tc::AtlasChart& chart = atlas.charts[c];
    chart.maxLevel = base.maxLevel[c];
    chart.partner = base.partner[c];
    chart.rotated = static_cast<uint8_t>(chart.partner >= 0 && chart.partner < int32_t(c));
    for (int k = 0; k < 3; ++k)
    {
      chart.cornerVertex[k] = base.faces[c][k];
      const auto it = sideOf.find({ base.faces[c][(k + 1) % 3], base.faces[c][k] });
      if (it != sideOf.end())
      {
        chart.neighborChart[k] = it->second.first;
        chart.neighborSide[k] = it->second.second;
      }
    }
  }

  const int32_t top = atlas.maxLevel();
  atlas.images.resize(static_cast<size_t>(top) + 1);
  for (int32_t k = 0; k <= top; ++k)
  {
    int32_t x = 1, height = 1;
    for (size_t c = 0; c < nc; ++c)
    {
      tc::AtlasChart& chart = atlas.charts[c];
      if (chart.maxLevel < k || chart.rotated)
      {
        continue;
      }
      const int32_t big = 1 << (chart.maxLevel - k);
      chart.origin.push_back({ x, 1 });
      if (chart.partner >= 0)
      {
        atlas.charts[static_cast<size_t>(chart.partner)].origin.push_back({ x + big + 1, 1 + big });
      }
      x += big + 3;
      height = std::max(height, big + 3);
    }
    tc::AtlasImage& image = atlas.images[static_cast<size_t>(k)];
    image.width = x;
    image.height = height;
    for (const tc::AtlasAttribute& a : atlas.attributes)
    {
      image.data.emplace_back(static_cast<size_t>(x * height * a.components), 0.0f);
    }
  }
  for (size_t c = 0; c < nc; ++c)
  {
    const tc::AtlasChart& chart = atlas.charts[c];
    for (int32_t d = 0; d <= chart.maxLevel; ++d)
    {
      tc::AtlasImage& image = atlas.images[static_cast<size_t>(chart.maxLevel - d)];
      for (int32_t j = 0; j <= (1 << d); ++j)
      {
        for (int32_t i = 0; i + j <= (1 << d); ++i)
        {
          const std::array<int32_t, 2> xy = tc::atlasTexel(chart, d, i, j);
          const size_t texel = static_cast<size_t>(xy[1] * image.width + xy[0]);
          base.eval(sampleParam(base, atlas.charts, static_cast<int32_t>(c), d, i, j),
            &image.data[0][3 * texel], &image.data[1][3 * texel], &image.data[2][texel]);
        }
      }
    }
  }
  return atlas;
}

/// The unit sphere over an icosahedron: sample = normalize(point of the flat base face).
AnalyticBase sphereBase()
{
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  AnalyticBase base;
  for (const double s : { -1.0, 1.0 })
  {
    for (const double t : { -1.0, 1.0 })
    {
      base.vertexParam.push_back({ 0.0, s, t * phi });
      base.vertexParam.push_back({ s, t * phi, 0.0 });
      base.vertexParam.push_back({ t * phi, 0.0, s });
    }
  }
  const auto dist2 = [&](size_t a, size_t b)
  {
    double s = 0;
    for (int x = 0; x < 3; ++x)
    {
      s += (base.vertexParam[a][x] - base.vertexParam[b][x]) *
        (base.vertexParam[a][x] - base.vertexParam[b][x]);
    }
    return s;
  };
  for (size_t a = 0; a < 12; ++a)
  {
    for (size_t b = a + 1; b < 12; ++b)
    {
      for (size_t c = b + 1; c < 12; ++c)
      {
        if (std::abs(dist2(a, b) - 4) > 1e-9 || std::abs(dist2(b, c) - 4) > 1e-9 ||
          std::abs(dist2(a, c) - 4) > 1e-9)
        {
          continue;
        }
        const Param &pa = base.vertexParam[a], &pb = base.vertexParam[b], &pc = base.vertexParam[c];
        const double u[3] = { pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2] };
        const double v[3] = { pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2] };
        const double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
          u[0] * v[1] - u[1] * v[0] };
        const bool outward = n[0] * pa[0] + n[1] * pa[1] + n[2] * pa[2] > 0;
        base.faces.push_back({ int32_t(a), int32_t(outward ? b : c), int32_t(outward ? c : b) });
      }
    }
  }
  for (const std::array<int32_t, 3>& f : base.faces)
  {
    base.frame.push_back({ base.vertexParam[static_cast<size_t>(f[0])],
      base.vertexParam[static_cast<size_t>(f[1])], base.vertexParam[static_cast<size_t>(f[2])] });
  }
  base.eval = [](const Param& p, float* position, float* normal, float* height)
  {
    const double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (int x = 0; x < 3; ++x)
    {
      position[x] = normal[x] = static_cast<float>(p[x] / len);
    }
    height[0] = static_cast<float>(p[2] / len);
  };
  // Pairs (2p, 2p + 1) share maxLevel 2 .. 6; every third pair is packed as two single charts.
  for (size_t c = 0; c < base.faces.size(); ++c)
  {
    const int32_t pair = static_cast<int32_t>(c / 2);
    base.maxLevel.push_back(2 + (pair * 3) % 5);
    base.partner.push_back(pair % 3 == 2 ? -1 : static_cast<int32_t>(c ^ 1));
  }
  base.eulerCharacteristic = 2;
  return base;
}

constexpr double kTorusR = 1.0, kTorusr = 0.4;
constexpr int kTorusNu = 4, kTorusNv = 3;

/// A torus over a 4 x 3 grid of parameter cells, each split into two base faces.
AnalyticBase torusBase()
{
  AnalyticBase base;
  const auto id = [](int a, int b) { return ((b % kTorusNv) * kTorusNu + a % kTorusNu); };
  for (int b = 0; b < kTorusNv; ++b)
  {
    for (int a = 0; a < kTorusNu; ++a)
    {
      base.vertexParam.push_back({ double(a), double(b), 0.0 });
    }
  }
  for (int b = 0; b < kTorusNv; ++b)
  {
    for (int a = 0; a < kTorusNu; ++a)
    {
      const Param p00{ double(a), double(b), 0 }, p10{ double(a + 1), double(b), 0 },
        p11{ double(a + 1), double(b + 1), 0 }, p01{ double(a), double(b + 1), 0 };
      base.faces.push_back({ id(a, b), id(a + 1, b), id(a + 1, b + 1) });
      base.frame.push_back({ p00, p10, p11 });
      base.faces.push_back({ id(a, b), id(a + 1, b + 1), id(a, b + 1) });
      base.frame.push_back({ p00, p11, p01 });
    }
  }
  base.eval = [](const Param& p, float* position, float* normal, float* height)
  {
    const double u = 2 * kPi * p[0] / kTorusNu, v = 2 * kPi * p[1] / kTorusNv;
    const double ring = kTorusR + kTorusr * std::cos(v);
    position[0] = static_cast<float>(ring * std::cos(u));
    position[1] = static_cast<float>(ring * std::sin(u));
    position[2] = static_cast<float>(kTorusr * std::sin(v));
    normal[0] = static_cast<float>(std::cos(v) * std::cos(u));
    normal[1] = static_cast<float>(std::cos(v) * std::sin(u));
    normal[2] = static_cast<float>(std::sin(v));
    height[0] = static_cast<float>(kTorusr * std::sin(v));
  };
  for (size_t c = 0; c < base.faces.size(); ++c)
  {
    const int32_t pair = static_cast<int32_t>(c / 2);
    base.maxLevel.push_back(2 + (pair * 3) % 4);
    base.partner.push_back(pair % 3 == 1 ? -1 : static_cast<int32_t>(c ^ 1));
  }
  base.eulerCharacteristic = 0;
  return base;
}

struct Fixture
{
  std::string name;
  AnalyticBase base;
  tc::Atlas atlas;
};

const Fixture& sphere()
{
  static const Fixture f{ "sphere", sphereBase(), buildAtlas(sphereBase()) };
  return f;
}

const Fixture& torus()
{
  static const Fixture f{ "torus", torusBase(), buildAtlas(torusBase()) };
  return f;
}

/// Distinct AtlasChart::cornerVertex ids, inner samples of every shared side at the lower
/// level of its two charts, and interior samples of every chart.
int64_t expectedPointCount(const tc::Atlas& atlas, const std::vector<int32_t>& levels)
{
  std::vector<int32_t> corners;
  int64_t count = 0;
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    const tc::AtlasChart& chart = atlas.charts[c];
    corners.insert(corners.end(), chart.cornerVertex.begin(), chart.cornerVertex.end());
    const int64_t big = int64_t(1) << levels[c];
    count += (big - 1) * (big - 2) / 2;
    for (int k = 0; k < 3; ++k)
    {
      if (std::make_pair(int32_t(c), k) <
        std::make_pair(chart.neighborChart[k], chart.neighborSide[k]))
      {
        count +=
          (int64_t(1) << std::min(levels[c], levels[static_cast<size_t>(chart.neighborChart[k])])) -
          1;
      }
    }
  }
  std::sort(corners.begin(), corners.end());
  return count + (std::unique(corners.begin(), corners.end()) - corners.begin());
}

bool sameBits(const float* a, const float* b, int n)
{
  return std::memcmp(a, b, sizeof(float) * static_cast<size_t>(n)) == 0;
}

std::array<float, 3> pointAsFloat(const tc::TriMesh& mesh, int64_t p)
{
  return { static_cast<float>(mesh.points[3 * p]), static_cast<float>(mesh.points[3 * p + 1]),
    static_cast<float>(mesh.points[3 * p + 2]) };
}

struct StitchFigures
{
  int64_t moved = 0;
  int64_t distinctSamples = 0;
};

/// Checks every chart vertex against eq. (8) as the brief states it, written out per side:
/// vertex t of side k moves to t - (t mod 2^(n - m)) when the neighbour's level m is below n,
/// every other vertex stays; what the output point holds must be that sample of the chart's own
/// level, bit for bit, in every attribute; a moved point must be the coarse neighbour's sample.
StitchFigures checkStitching(
  const tc::Atlas& atlas, const std::vector<int32_t>& levels, const tc::RebuiltMesh& out)
{
  StitchFigures figures;
  std::vector<std::array<uint32_t, 3>> drawn;
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    const tc::AtlasChart& chart = atlas.charts[c];
    const int32_t ci = static_cast<int32_t>(c);
    const int32_t n = levels[c], big = 1 << n;
    std::vector<std::array<int32_t, 2>> target;
    std::vector<int32_t> movedOnSide, movedParameter;
    for (int32_t j = 0; j <= big; ++j)
    {
      for (int32_t i = 0; i + j <= big; ++i)
      {
        target.push_back({ i, j });
        movedOnSide.push_back(-1);
        movedParameter.push_back(0);
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      const int32_t m = levels[static_cast<size_t>(chart.neighborChart[k])];
      if (m >= n)
      {
        continue;
      }
      const int32_t step = 1 << (n - m);
      for (int32_t t = 1; t < big; ++t)
      {
        const std::array<int32_t, 2> ij = tc::sidePoint(k, t, big);
        const size_t v = static_cast<size_t>(tc::gridVertexIndex(n, ij[0], ij[1]));
        target[v] = tc::sidePoint(k, t - t % step, big);
        movedOnSide[v] = t % step ? k : -1;
        movedParameter[v] = t;
      }
    }
    for (size_t v = 0; v < target.size(); ++v)
    {
      const int32_t p = out.chartVertexPoint[static_cast<size_t>(out.chartVertexOffsets[c]) + v];
      const std::array<float, 3> xyz = pointAsFloat(out.mesh, p);
      drawn.push_back({});
      std::memcpy(drawn.back().data(), xyz.data(), sizeof(xyz));
      const std::array<int32_t, 2>& g = target[v];
      bool ok = sameBits(xyz.data(), tc::atlasSample(atlas, ci, 0, n, g[0], g[1]), 3);
      for (size_t a = 1; a < atlas.attributes.size(); ++a)
      {
        const int comps = atlas.attributes[a].components;
        ok = ok &&
          sameBits(&out.attributes[a - 1][static_cast<size_t>(p) * static_cast<size_t>(comps)],
            tc::atlasSample(atlas, ci, static_cast<int32_t>(a), n, g[0], g[1]), comps);
      }
      if (!ok)
      {
        ADD_FAILURE() << "chart " << c << " vertex " << v << " does not hold sample (" << g[0]
                      << ", " << g[1] << ") of level " << n;
        return figures;
      }
      const int k = movedOnSide[v];
      if (k < 0)
      {
        continue;
      }
      ++figures.moved;
      const int32_t t = movedParameter[v];
      const int32_t nb = chart.neighborChart[k], ns = chart.neighborSide[k];
      const int32_t m = levels[static_cast<size_t>(nb)];
      // Parameter t - t mod 2^(n - m) here is parameter 2^m - (t >> (n - m)) of the neighbour.
      const std::array<int32_t, 2> coarse = tc::sidePoint(ns, (1 << m) - (t >> (n - m)), 1 << m);
      EXPECT_TRUE(sameBits(xyz.data(), tc::atlasSample(atlas, nb, 0, m, coarse[0], coarse[1]), 3))
        << "chart " << c << " side " << k << ": a moved vertex is not on the coarse side";
      const std::array<int32_t, 2> before = tc::sidePoint(k, t, big);
      EXPECT_FALSE(sameBits(xyz.data(), tc::atlasSample(atlas, ci, 0, n, before[0], before[1]), 3))
        << "chart " << c << " side " << k << " t " << t << " did not move";
    }
  }
  std::sort(drawn.begin(), drawn.end());
  figures.distinctSamples = std::unique(drawn.begin(), drawn.end()) - drawn.begin();
  return figures;
}

/// Every property of one rebuild; returns the number of moved vertices.
int64_t checkRebuild(
  const Fixture& fx, const std::vector<int32_t>& requested, const std::string& what)
{
  SCOPED_TRACE(fx.name + " " + what);
  const tc::Atlas& atlas = fx.atlas;
  const tc::RebuiltMesh out = tc::rebuildMesh(atlas, requested);
  std::vector<int32_t> levels(requested.size());
  for (size_t c = 0; c < levels.size(); ++c)
  {
    levels[c] = std::min(requested[c], atlas.charts[c].maxLevel);
  }
  EXPECT_EQ(out.chartLevel, levels);

  int64_t euler = -99;
  EXPECT_EQ(tctest::manifoldDefect(out.mesh, euler), "");
  EXPECT_EQ(euler, fx.base.eulerCharacteristic);
  EXPECT_EQ(out.mesh.numPoints(), expectedPointCount(atlas, levels));

  int64_t grid = 0;
  for (const int32_t n : levels)
  {
    grid += int64_t(1) << (2 * n);
  }
  EXPECT_EQ(out.mesh.numTriangles() + out.droppedTriangles, grid);
  EXPECT_EQ(out.chartId.size(), static_cast<size_t>(out.mesh.numTriangles()));
  EXPECT_EQ(out.level.size(), out.chartId.size());
  for (size_t f = 0; f < out.chartId.size(); ++f)
  {
    if (out.level[f] != levels[static_cast<size_t>(out.chartId[f])] ||
      (f > 0 && out.chartId[f] < out.chartId[f - 1]))
    {
      ADD_FAILURE() << "triangle " << f << " has chart " << out.chartId[f] << " and level "
                    << out.level[f];
      break;
    }
  }

  // Every point holds its source sample; no two points share a position (the weld is complete).
  EXPECT_EQ(out.pointSource.size(), static_cast<size_t>(3 * out.mesh.numPoints()));
  std::vector<std::array<float, 3>> positions;
  for (int64_t p = 0; p < out.mesh.numPoints(); ++p)
  {
    const int32_t* s = &out.pointSource[static_cast<size_t>(3 * p)];
    const std::array<float, 3> xyz = pointAsFloat(out.mesh, p);
    positions.push_back(xyz);
    if (!sameBits(xyz.data(),
          tc::atlasSample(atlas, s[0], 0, levels[static_cast<size_t>(s[0])], s[1], s[2]), 3))
    {
      ADD_FAILURE() << "point " << p << " is not its source sample";
      break;
    }
  }
  std::sort(positions.begin(), positions.end());
  EXPECT_EQ(
    std::unique(positions.begin(), positions.end()) - positions.begin(), out.mesh.numPoints());

  const StitchFigures figures = checkStitching(atlas, levels, out);
  EXPECT_EQ(figures.distinctSamples, out.mesh.numPoints());
  // Each moved vertex collapses one boundary edge of its chart, which takes exactly one grid
  // triangle with it: F = sum_c (4^n - sum over coarser neighbours (2^n - 2^m)).
  int64_t expectedTriangles = 0;
  for (size_t c = 0; c < levels.size(); ++c)
  {
    const int32_t n = levels[c];
    expectedTriangles += int64_t(1) << (2 * n);
    for (const int32_t nb : atlas.charts[c].neighborChart)
    {
      const int32_t m = levels[static_cast<size_t>(nb)];
      expectedTriangles -= m < n ? (int64_t(1) << n) - (int64_t(1) << m) : 0;
    }
  }
  EXPECT_EQ(out.mesh.numTriangles(), expectedTriangles);
  EXPECT_EQ(out.droppedTriangles, figures.moved);
  return figures.moved;
}

/// Random levels per chart, seeded: every fourth assignment puts each chart at 0 or its maxLevel
/// (neighbours 3 and more levels apart); levels above maxLevel test the clamp.
std::vector<std::vector<int32_t>> assignments(const tc::Atlas& atlas, uint32_t seed)
{
  std::mt19937 rng(seed);
  std::vector<std::vector<int32_t>> all;
  all.push_back(std::vector<int32_t>(atlas.charts.size(), 0));
  while (all.size() < 100)
  {
    std::vector<int32_t> levels;
    const bool extremes = all.size() % 4 == 1;
    for (const tc::AtlasChart& chart : atlas.charts)
    {
      levels.push_back(extremes
          ? (std::bernoulli_distribution(0.5)(rng) ? chart.maxLevel : 0)
          : std::uniform_int_distribution<int32_t>(0, chart.maxLevel + 1)(rng));
    }
    all.push_back(levels);
  }
  return all;
}

void checkRandomAssignments(const Fixture& fx, uint32_t seed)
{
  int64_t farApart = 0, moved = 0;
  const auto all = assignments(fx.atlas, seed);
  for (size_t a = 0; a < all.size(); ++a)
  {
    moved += checkRebuild(fx, all[a], "assignment " + std::to_string(a));
    for (size_t c = 0; c < fx.atlas.charts.size(); ++c)
    {
      for (const int32_t nb : fx.atlas.charts[c].neighborChart)
      {
        const int32_t l = std::min(all[a][c], fx.atlas.charts[c].maxLevel);
        const int32_t m = std::min(
          all[a][static_cast<size_t>(nb)], fx.atlas.charts[static_cast<size_t>(nb)].maxLevel);
        farApart += l - m >= 3;
      }
    }
    if (::testing::Test::HasFailure())
    {
      return;
    }
  }
  // The assignments must exercise what they claim to.
  EXPECT_GT(farApart, 100);
  EXPECT_GT(moved, 1000);
}
} // namespace

TEST(GeometryImageMesh, TestAtlasesAreValid)
{
  EXPECT_NO_THROW(tc::validateAtlas(sphere().atlas));
  EXPECT_NO_THROW(tc::validateAtlas(torus().atlas));
  EXPECT_EQ(sphere().atlas.charts.size(), 20u);
  EXPECT_EQ(torus().atlas.charts.size(), 24u);
  int rotated = 0;
  for (const tc::AtlasChart& c : sphere().atlas.charts)
  {
    rotated += c.rotated;
  }
  EXPECT_GT(rotated, 4);
}

TEST(GeometryImageMesh, VertexRuleSnapsAlongTheSideParameter)
{
  // Level 3 (N = 8), neighbours at levels 1 (side 0), 3 (side 1) and 0 (side 2).
  const std::array<int32_t, 3> nl{ 1, 3, 0 };
  EXPECT_EQ(tc::stitchedGridPoint(3, nl, 5, 0), (std::array<int32_t, 2>{ 4, 0 }));
  EXPECT_EQ(tc::stitchedGridPoint(3, nl, 3, 0), (std::array<int32_t, 2>{ 0, 0 }));
  EXPECT_EQ(tc::stitchedGridPoint(3, nl, 4, 0), (std::array<int32_t, 2>{ 4, 0 }));
  EXPECT_EQ(tc::stitchedGridPoint(3, nl, 8, 0), (std::array<int32_t, 2>{ 8, 0 }));
  EXPECT_EQ(tc::stitchedGridPoint(3, nl, 5, 3), (std::array<int32_t, 2>{ 5, 3 }));
  // Side 2 runs from (0, 8) down to (0, 0): (0, 3) is t = 5, which snaps to t = 0, i.e. (0, 8).
  EXPECT_EQ(tc::stitchedGridPoint(3, nl, 0, 3), (std::array<int32_t, 2>{ 0, 8 }));
  EXPECT_EQ(tc::stitchedGridPoint(3, nl, 0, 0), (std::array<int32_t, 2>{ 0, 0 }));
  EXPECT_EQ(tc::stitchedGridPoint(3, nl, 2, 2), (std::array<int32_t, 2>{ 2, 2 }));
  // Side 1 (i + j = N), neighbour two levels down: t = j rounds down to a multiple of 4.
  EXPECT_EQ(tc::stitchedGridPoint(3, { 3, 1, 3 }, 1, 7), (std::array<int32_t, 2>{ 4, 4 }));
  EXPECT_EQ(tc::stitchedGridPoint(3, { 3, 1, 3 }, 5, 3), (std::array<int32_t, 2>{ 8, 0 }));
  EXPECT_EQ(tc::gridVertexCount(3), 45);
  EXPECT_EQ(tc::gridVertexIndex(3, 0, 1), 9);
  EXPECT_EQ(tc::gridVertexIndex(3, 0, 8), 44);
}

TEST(GeometryImageMesh, UniformLevelsGiveTheClosedFormCounts)
{
  for (const Fixture* fx : { &sphere(), &torus() })
  {
    const int64_t nf = static_cast<int64_t>(fx->atlas.charts.size());
    const int64_t ne = 3 * nf / 2;
    const int64_t nv = fx->base.eulerCharacteristic + ne - nf;
    for (int32_t n = 0; n <= 2; ++n)
    {
      // V = V_b + E_b (N - 1) + F_b (N - 1)(N - 2) / 2 and F = F_b N^2.
      const int64_t big = int64_t(1) << n;
      const tc::RebuiltMesh out = tc::rebuildMesh(fx->atlas, n);
      EXPECT_EQ(out.mesh.numPoints(), nv + ne * (big - 1) + nf * (big - 1) * (big - 2) / 2)
        << fx->name << " level " << n;
      EXPECT_EQ(out.mesh.numTriangles(), nf * big * big) << fx->name << " level " << n;
      EXPECT_EQ(out.droppedTriangles, 0);
      checkRebuild(*fx, std::vector<int32_t>(static_cast<size_t>(nf), n),
        "uniform level " + std::to_string(n));
    }
    // Above some charts' maxLevel the one-level overload clamps each chart like the array one.
    const tc::RebuiltMesh one = tc::rebuildMesh(fx->atlas, 4);
    const tc::RebuiltMesh many =
      tc::rebuildMesh(fx->atlas, std::vector<int32_t>(static_cast<size_t>(nf), 4));
    EXPECT_EQ(one.mesh.points, many.mesh.points);
    EXPECT_EQ(one.mesh.triangles, many.mesh.triangles);
    EXPECT_EQ(one.chartLevel, many.chartLevel);
    EXPECT_GT(one.droppedTriangles, 0);
  }
  const tc::RebuiltMesh coarse = tc::rebuildMesh(sphere().atlas, 0);
  EXPECT_EQ(coarse.mesh.numPoints(), 12);
  EXPECT_EQ(coarse.mesh.numTriangles(), 20);
}

TEST(GeometryImageMesh, SphereIsClosedAndStitchedForRandomLevels)
{
  checkRandomAssignments(sphere(), 20100601u);
}

TEST(GeometryImageMesh, TorusIsClosedAndStitchedForRandomLevels)
{
  checkRandomAssignments(torus(), 20100602u);
}

TEST(GeometryImageMesh, SphereIsOrientedOutwardAndInscribed)
{
  const tc::Atlas& atlas = sphere().atlas;
  std::vector<int32_t> levels;
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    levels.push_back(c % 3 == 0 ? 0 : atlas.charts[c].maxLevel);
  }
  const tc::RebuiltMesh out = tc::rebuildMesh(atlas, levels);
  double volume = 0;
  for (int64_t f = 0; f < out.mesh.numTriangles(); ++f)
  {
    const auto a = out.mesh.point(out.mesh.triangles[3 * f]),
               b = out.mesh.point(out.mesh.triangles[3 * f + 1]),
               c = out.mesh.point(out.mesh.triangles[3 * f + 2]);
    volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                a[2] * (b[0] * c[1] - b[1] * c[0])) /
      6.0;
  }
  // Outward triangles give a positive volume; every vertex on the unit sphere keeps it inside
  // the ball; the icosahedron alone (level 0) encloses 2.536.
  EXPECT_GT(volume, 2.6);
  EXPECT_LT(volume, 4.0 * kPi / 3.0);
  std::printf("[ figures  ] sphere, every third chart at level 0, others at maxLevel: %lld points, "
              "%lld triangles (%lld dropped by stitching), volume %.4f (ball %.4f)\n",
    static_cast<long long>(out.mesh.numPoints()), static_cast<long long>(out.mesh.numTriangles()),
    static_cast<long long>(out.droppedTriangles), volume, 4.0 * kPi / 3.0);
}

TEST(GeometryImageMesh, PrintsTheCountsOfOneAssignment)
{
  const Fixture& fx = torus();
  const std::vector<int32_t> levels = assignments(fx.atlas, 7u)[5];
  const tc::RebuiltMesh out = tc::rebuildMesh(fx.atlas, levels);
  const int64_t moved = checkRebuild(fx, levels, "printed assignment");
  std::string text;
  for (const int32_t n : out.chartLevel)
  {
    text += (text.empty() ? "" : " ") + std::to_string(n);
  }
  std::printf("[ figures  ] torus levels %s: %lld points, %lld triangles, %lld grid triangles "
              "dropped, %lld vertices moved by eq. 8\n",
    text.c_str(), static_cast<long long>(out.mesh.numPoints()),
    static_cast<long long>(out.mesh.numTriangles()), static_cast<long long>(out.droppedTriangles),
    static_cast<long long>(moved));
  EXPECT_GT(moved, 0);
}

TEST(GeometryImageMesh, RefusesBadInputWithAMessage)
{
  const tc::Atlas& good = sphere().atlas;
  const auto refusal = [](const tc::Atlas& atlas, const std::vector<int32_t>& levels)
  {
    try
    {
      tc::rebuildMesh(atlas, levels);
    }
    catch (const tc::InputError& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::vector<int32_t> twos(good.charts.size(), 2);
  EXPECT_NE(refusal(good, std::vector<int32_t>(19, 2)).find("20 charts"), std::string::npos);
  std::vector<int32_t> negative = twos;
  negative[7] = -1;
  EXPECT_NE(refusal(good, negative).find("chart 7"), std::string::npos);
  EXPECT_THROW(tc::rebuildMesh(good, -2), tc::InputError);
  EXPECT_NE(refusal(tc::Atlas(), {}).find("no charts"), std::string::npos);

  tc::Atlas atlas = good;
  atlas.charts[4].neighborSide[1] = (atlas.charts[4].neighborSide[1] + 1) % 3;
  EXPECT_NE(refusal(atlas, twos).find("name each other"), std::string::npos)
    << refusal(atlas, twos);

  atlas = good;
  atlas.charts[4].neighborChart[0] = 99;
  EXPECT_NE(refusal(atlas, twos).find("does not exist"), std::string::npos);

  atlas = good;
  std::swap(atlas.charts[9].cornerVertex[0], atlas.charts[9].cornerVertex[1]);
  EXPECT_NE(refusal(atlas, twos).find("same base vertices"), std::string::npos)
    << refusal(atlas, twos);

  atlas = good;
  atlas.charts[9].cornerVertex[2] = atlas.charts[9].cornerVertex[0];
  EXPECT_NE(refusal(atlas, twos).find("distinct"), std::string::npos) << refusal(atlas, twos);

  atlas = good;
  atlas.charts[5].origin[1][0] = atlas.images[1].width - 1;
  EXPECT_NE(refusal(atlas, twos).find("outside image"), std::string::npos) << refusal(atlas, twos);

  atlas = good;
  atlas.images.pop_back();
  EXPECT_NE(refusal(atlas, twos).find("images"), std::string::npos) << refusal(atlas, twos);

  atlas = good;
  atlas.images[2].data[1].pop_back();
  EXPECT_NE(refusal(atlas, twos).find("floats"), std::string::npos) << refusal(atlas, twos);

  atlas = good;
  atlas.attributes[0].components = 4;
  EXPECT_NE(refusal(atlas, twos).find("Position"), std::string::npos) << refusal(atlas, twos);
}

TEST(GeometryImageMesh, ReportsProgressAndHonoursAbort)
{
  const tc::Atlas& atlas = sphere().atlas;
  std::vector<int32_t> levels;
  for (const tc::AtlasChart& c : atlas.charts)
  {
    levels.push_back(c.maxLevel);
  }
  tctest::expectProgressAndAbort([&](const tc::Progress& p) { tc::rebuildMesh(atlas, levels, p); },
    10, [](double f) { return f < 0.3; });
}
