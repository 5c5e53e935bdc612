// SPDX-License-Identifier: BSD-3-Clause
#include "tc/gim/base_complex.h"

#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"
#include "tc/io/off_io.h"

#include "pipeline_fixture.h"
#include "test_data.h"
#include "test_progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace
{
constexpr double kPi = 3.14159265358979323846;

int64_t eulerCharacteristic(const std::vector<int32_t>& triangles, int64_t numPoints)
{
  const tc::EdgeTable et = tc::buildEdgeTable(triangles);
  return numPoints - et.numEdges() + static_cast<int64_t>(triangles.size() / 3);
}

/// The base vertices (indices into baseVertices) with a non-zero barycentric for vertex v: its
/// base vertex, base edge or base face.
std::vector<std::pair<int32_t, double>> support(const tc::BaseComplexResult& r, int64_t v)
{
  std::vector<std::pair<int32_t, double>> s;
  const int32_t f = r.vertexBaseFace[v];
  for (int i = 0; i < 3; ++i)
  {
    if (r.vertexBarycentric[3 * v + i] != 0.0)
    {
      s.emplace_back(r.baseTriangles[3 * f + i], r.vertexBarycentric[3 * v + i]);
    }
  }
  return s;
}

/// Stars of the base vertices: the ring of each one counter-clockwise, and a flattening of the
/// star in which s sits at the origin.
struct BaseStars
{
  std::vector<std::vector<int32_t>> ring;
  std::vector<std::vector<std::array<double, 2>>> flat;
  bool manifold = true; ///< every directed edge once, with its twin; every link one cycle
};

BaseStars baseStars(const tc::TriMesh& mesh, const tc::BaseComplexResult& r)
{
  BaseStars stars;
  const int64_t nb = static_cast<int64_t>(r.baseVertices.size());
  const int64_t nf = static_cast<int64_t>(r.baseTriangles.size() / 3);
  std::map<std::pair<int32_t, int32_t>, int32_t> next; // directed edge (s, a) -> c of face (s,a,c)
  std::vector<int> facesAt(nb, 0);
  for (int64_t f = 0; f < nf; ++f)
  {
    for (int i = 0; i < 3; ++i)
    {
      const int32_t s = r.baseTriangles[3 * f + i], a = r.baseTriangles[3 * f + (i + 1) % 3],
                    c = r.baseTriangles[3 * f + (i + 2) % 3];
      stars.manifold &= next.emplace(std::make_pair(s, a), c).second;
      ++facesAt[s];
    }
  }
  for (const auto& e : next)
  {
    stars.manifold &= next.count({ e.first.second, e.first.first }) == 1;
  }
  stars.ring.resize(nb);
  stars.flat.resize(nb);
  for (int64_t s = 0; s < nb && stars.manifold; ++s)
  {
    auto it = next.lower_bound({ static_cast<int32_t>(s), -1 });
    if (it == next.end() || it->first.first != s)
    {
      stars.manifold = false;
      break;
    }
    std::vector<int32_t>& ring = stars.ring[s];
    const int32_t first = it->first.second;
    int32_t a = first;
    do
    {
      ring.push_back(a);
      a = next.at({ static_cast<int32_t>(s), a });
    } while (a != first && ring.size() <= next.size());
    stars.manifold &= static_cast<int>(ring.size()) == facesAt[s];

    // The conformal flattening z^a of MAPS (3D angles at s scaled to sum to 2 pi, radii to the
    // power a); if a face would fold (one angle over half the total), the uniform one instead
    // (ring on the unit circle at equal angles). Both are linear on every base face and agree
    // with the barycentrics on shared edges, so either is a common chart of the star.
    const auto ps = mesh.point(r.baseVertices[s]);
    const size_t d = ring.size();
    std::vector<double> theta(d), radius(d);
    double total = 0.0;
    for (size_t i = 0; i < d; ++i)
    {
      const auto pa = mesh.point(r.baseVertices[ring[i]]);
      const auto pb = mesh.point(r.baseVertices[ring[(i + 1) % d]]);
      const double u[3] = { pa[0] - ps[0], pa[1] - ps[1], pa[2] - ps[2] };
      const double v[3] = { pb[0] - ps[0], pb[1] - ps[1], pb[2] - ps[2] };
      const double c[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0] };
      theta[i] = std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
        u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
      radius[i] = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      total += theta[i];
    }
    const double power = 2.0 * kPi / total;
    const bool embeds =
      std::all_of(theta.begin(), theta.end(), [&](double t) { return power * t < kPi; });
    double phi = 0.0;
    for (size_t i = 0; i < d; ++i)
    {
      const double angle = embeds ? power * phi : 2.0 * kPi * i / d;
      const double rho = embeds ? std::pow(radius[i] / radius[0], power) : 1.0;
      stars.flat[s].push_back({ rho * std::cos(angle), rho * std::sin(angle) });
      phi += theta[i];
    }
  }
  return stars;
}

/// Position of a point with this support in the flattened star of s, or false when the point
/// is not in the closed star of s.
bool inStar(const BaseStars& stars, int32_t s, const std::vector<std::pair<int32_t, double>>& sup,
  std::array<double, 2>& p)
{
  const std::vector<int32_t>& ring = stars.ring[s];
  const int d = static_cast<int>(ring.size());
  p = { 0.0, 0.0 };
  std::vector<int> index;
  for (const auto& vw : sup)
  {
    if (vw.first == s)
    {
      continue;
    }
    const auto it = std::find(ring.begin(), ring.end(), vw.first);
    if (it == ring.end())
    {
      return false;
    }
    const int i = static_cast<int>(it - ring.begin());
    index.push_back(i);
    p[0] += vw.second * stars.flat[s][i][0];
    p[1] += vw.second * stars.flat[s][i][1];
  }
  // Three ring vertices: a face without s. Two: they must span a face (s, ring[i], ring[i+1]).
  return index.size() < 2 ||
    (index.size() == 2 &&
      ((index[1] - index[0] + d) % d == 1 || (index[0] - index[1] + d) % d == 1));
}

struct FlipCount
{
  int64_t straddling = 0;   ///< input triangles not inside the closed star of any base vertex
  int64_t flipped = 0;      ///< input triangles with non-positive area in their common chart
  std::vector<int64_t> bad; ///< ids of both kinds
};

/// Vertices of the base faces in the ordered form the charts need.
struct BaseFaces
{
  const tc::BaseComplexResult& r;
  std::map<std::pair<int32_t, int32_t>, int64_t> faceOfEdge; ///< directed edge -> face

  explicit BaseFaces(const tc::BaseComplexResult& result)
    : r(result)
  {
    for (size_t c = 0; c < r.baseTriangles.size(); ++c)
    {
      faceOfEdge[{ r.baseTriangles[c], r.baseTriangles[c - c % 3 + (c % 3 + 1) % 3] }] =
        static_cast<int64_t>(c / 3);
    }
  }
  bool faceHas(int64_t f, int32_t b) const
  {
    return r.baseTriangles[3 * f] == b || r.baseTriangles[3 * f + 1] == b ||
      r.baseTriangles[3 * f + 2] == b;
  }
};

/// Bijection test. A map from the input mesh onto the base complex is one-to-one and onto when
/// every input triangle, drawn with straight sides between the images of its corners, keeps its
/// orientation: then, on a closed surface, the images tile the base complex exactly once.
/// "Straight" needs a chart, and the charts of neighbouring base faces bend against each other
/// along base edges, so each triangle is drawn in the one chart that the later stages use for
/// it (Feng et al. section 5.1: base triangles unfolded into the plane):
///  - corners whose images all lie in one closed base face (a corner's face, or the base face
///    their supports span, e.g. three base vertices): the barycentric plane of that face (sign
///    of the 3x3 barycentric determinant; every chart agrees);
///  - each image in one of two base faces sharing an edge: those two 3D triangles unfolded
///    about the edge (the quadrilateral in which the path of that base edge is traced), unless
///    a corner is at an end of the edge where the two faces turn by pi or more;
///  - otherwise images around one base vertex s: the star of s flattened by z^a (MAPS).
/// A triangle that fits none of these straddles the base complex and fails too.
FlipCount countFlips(
  const tc::TriMesh& mesh, const tc::BaseComplexResult& r, const BaseStars& stars)
{
  FlipCount out;
  const BaseFaces faces(r);
  auto basePoint = [&](int32_t b) { return mesh.point(r.baseVertices[b]); };
  auto dist = [&](int32_t a, int32_t b)
  {
    const auto p = basePoint(a), q = basePoint(b);
    return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
      (p[2] - q[2]) * (p[2] - q[2]));
  };
  for (int64_t t = 0; t < mesh.numTriangles(); ++t)
  {
    std::vector<std::pair<int32_t, double>> sup[3];
    std::set<int32_t> all;
    for (int i = 0; i < 3; ++i)
    {
      sup[i] = support(r, mesh.triangles[3 * t + i]);
      for (const auto& vw : sup[i])
      {
        all.insert(vw.first);
      }
    }
    // One face: some corner's face, or the base face spanned by the images' supports, holds
    // every image.
    bool decided = false;
    std::vector<int64_t> candidateFaces;
    for (int i = 0; i < 3; ++i)
    {
      candidateFaces.push_back(r.vertexBaseFace[mesh.triangles[3 * t + i]]);
    }
    if (all.size() == 3)
    {
      const auto it = faces.faceOfEdge.find({ *all.begin(), *std::next(all.begin()) });
      const auto jt = faces.faceOfEdge.find({ *std::next(all.begin()), *all.begin() });
      for (const auto& e : { it, jt })
      {
        if (e != faces.faceOfEdge.end() && faces.faceHas(e->second, *all.rbegin()))
        {
          candidateFaces.push_back(e->second);
        }
      }
    }
    for (size_t i = 0; i < candidateFaces.size() && !decided; ++i)
    {
      const int64_t f = candidateFaces[i];
      if (std::all_of(all.begin(), all.end(), [&](int32_t b) { return faces.faceHas(f, b); }))
      {
        double m[3][3];
        for (int j = 0; j < 3; ++j)
        {
          for (int k = 0; k < 3; ++k)
          {
            m[j][k] = 0.0;
            for (const auto& vw : sup[j])
            {
              m[j][k] += vw.first == r.baseTriangles[3 * f + k] ? vw.second : 0.0;
            }
          }
        }
        const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
          m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
          m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        out.flipped += !(det > 0.0);
        decided = true;
      }
    }
    // Two faces about an edge (a, b): f = (a, b, c) above the x axis, g = (b, a, d) below.
    for (int i = 0; i < 3 && !decided; ++i)
    {
      const int64_t f = r.vertexBaseFace[mesh.triangles[3 * t + i]];
      for (int e = 0; e < 3 && !decided; ++e)
      {
        const int32_t a = r.baseTriangles[3 * f + e], b = r.baseTriangles[3 * f + (e + 1) % 3],
                      c = r.baseTriangles[3 * f + (e + 2) % 3];
        const int64_t g = faces.faceOfEdge.at({ b, a });
        // Every corner's image in the closed face f or in the closed face g (sharing their four
        // vertices is not enough: another pair of faces may span the same four).
        auto inHinge = [&](const std::vector<std::pair<int32_t, double>>& sp)
        {
          auto within = [&](int64_t h)
          {
            return std::all_of(sp.begin(), sp.end(),
              [&](const std::pair<int32_t, double>& vw) { return faces.faceHas(h, vw.first); });
          };
          return within(f) || within(g);
        };
        if (!inHinge(sup[0]) || !inHinge(sup[1]) || !inHinge(sup[2]))
        {
          continue;
        }
        int32_t d = -1;
        for (int k = 0; k < 3; ++k)
        {
          d = r.baseTriangles[3 * g + k] != a && r.baseTriangles[3 * g + k] != b
            ? r.baseTriangles[3 * g + k]
            : d;
        }
        const double L = dist(a, b);
        auto apex = [&](int32_t x, double sign)
        {
          const double ax = dist(a, x), bx = dist(b, x);
          const double px = (ax * ax - bx * bx + L * L) / (2 * L);
          return std::array<double, 2>{ px, sign * std::sqrt(std::max(0.0, ax * ax - px * px)) };
        };
        std::map<int32_t, std::array<double, 2>> at = { { a, { 0.0, 0.0 } }, { b, { L, 0.0 } },
          { c, apex(c, 1.0) }, { d, apex(d, -1.0) } };
        // Not when a corner is at an end of the edge where f and g turn by pi or more: the
        // triangle may lie outside the unfolding there; the star of that corner decides.
        auto turn = [&](int32_t o, int32_t u, int32_t v)
        {
          const auto &po = at.at(o), &pu = at.at(u), &pv = at.at(v);
          return (pu[0] - po[0]) * (pv[1] - po[1]) - (pu[1] - po[1]) * (pv[0] - po[0]);
        };
        bool reflex = false;
        for (int j = 0; j < 3; ++j)
        {
          if (sup[j].size() == 1 && sup[j][0].first == a)
          {
            reflex |= !(turn(a, d, c) > 0.0);
          }
          if (sup[j].size() == 1 && sup[j][0].first == b)
          {
            reflex |= !(turn(b, c, d) > 0.0);
          }
        }
        if (reflex)
        {
          continue;
        }
        std::array<double, 2> p[3];
        for (int j = 0; j < 3; ++j)
        {
          p[j] = { 0.0, 0.0 };
          for (const auto& vw : sup[j])
          {
            p[j][0] += vw.second * at.at(vw.first)[0];
            p[j][1] += vw.second * at.at(vw.first)[1];
          }
        }
        const double area =
          (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
        out.flipped += !(area > 0.0);
        decided = true;
      }
    }
    // The star of a base vertex (the lowest-numbered one that holds all three images).
    for (int32_t s : all)
    {
      std::array<double, 2> p[3];
      if (decided || !inStar(stars, s, sup[0], p[0]) || !inStar(stars, s, sup[1], p[1]) ||
        !inStar(stars, s, sup[2], p[2]))
      {
        continue;
      }
      const double area =
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
      out.flipped += !(area > 0.0);
      decided = true;
    }
    out.straddling += !decided;
    if (!decided || out.flipped + out.straddling > static_cast<int64_t>(out.bad.size()))
    {
      out.bad.push_back(t);
    }
  }
  return out;
}

class BaseComplexOnMesh : public ::testing::TestWithParam<std::string>
{
protected:
  void SetUp() override
  {
    Case_ = tctest::pipelineCase(tctest::pipelineMeshPath(GetParam()));
    if (!Case_)
    {
      GTEST_SKIP() << GetParam() << " is not in the shared data";
    }
  }
  const tctest::PipelineCase* Case_ = nullptr;
};
} // namespace

TEST_P(BaseComplexOnMesh, KeepsTheEulerCharacteristic)
{
  const auto& r = Case_->result;
  EXPECT_EQ(eulerCharacteristic(r.baseTriangles, static_cast<int64_t>(r.baseVertices.size())),
    eulerCharacteristic(Case_->mesh.triangles, Case_->mesh.numPoints()));
}

TEST_P(BaseComplexOnMesh, IsAClosedManifold)
{
  const BaseStars stars = baseStars(Case_->mesh, Case_->result);
  EXPECT_TRUE(stars.manifold);
  EXPECT_EQ(Case_->result.baseEdgeIsFeature.size(), Case_->result.baseTriangles.size());
}

TEST_P(BaseComplexOnMesh, BaseVerticesAreSortedOriginalVertices)
{
  const auto& r = Case_->result;
  ASSERT_GE(r.baseVertices.size(), 4u);
  EXPECT_TRUE(std::is_sorted(r.baseVertices.begin(), r.baseVertices.end()));
  EXPECT_EQ(std::adjacent_find(r.baseVertices.begin(), r.baseVertices.end()), r.baseVertices.end());
  EXPECT_GE(r.baseVertices.front(), 0);
  EXPECT_LT(r.baseVertices.back(), Case_->mesh.numPoints());
}

TEST_P(BaseComplexOnMesh, IsOrientedLikeTheInput)
{
  // Signed volume (divergence theorem) of the base complex and of the input have the same sign.
  auto volume = [&](const std::vector<int32_t>& tris, auto&& point)
  {
    double vol = 0.0;
    for (size_t t = 0; t < tris.size(); t += 3)
    {
      const auto a = point(tris[t]), b = point(tris[t + 1]), c = point(tris[t + 2]);
      vol += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
        a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return vol / 6.0;
  };
  const auto& m = Case_->mesh;
  const auto& r = Case_->result;
  const double input = volume(m.triangles, [&](int32_t v) { return m.point(v); });
  const double base =
    volume(r.baseTriangles, [&](int32_t b) { return m.point(r.baseVertices[b]); });
  EXPECT_GT(input * base, 0.0);
}

TEST_P(BaseComplexOnMesh, EveryVertexHasABaseFaceAndBarycentrics)
{
  const auto& r = Case_->result;
  const int64_t nv = Case_->mesh.numPoints();
  const int64_t nf = static_cast<int64_t>(r.baseTriangles.size() / 3);
  ASSERT_EQ(static_cast<int64_t>(r.vertexBaseFace.size()), nv);
  ASSERT_EQ(static_cast<int64_t>(r.vertexBarycentric.size()), 3 * nv);
  int64_t bad = 0;
  for (int64_t v = 0; v < nv; ++v)
  {
    const double* b = &r.vertexBarycentric[3 * v];
    const bool ok = r.vertexBaseFace[v] >= 0 && r.vertexBaseFace[v] < nf &&
      std::all_of(b, b + 3, [](double x) { return x >= -1e-9 && x <= 1.0; }) &&
      std::abs(b[0] + b[1] + b[2] - 1.0) <= 1e-9;
    bad += !ok;
  }
  EXPECT_EQ(bad, 0);
}

TEST_P(BaseComplexOnMesh, BaseVerticesSitOnTheirOwnCorner)
{
  const auto& r = Case_->result;
  for (size_t b = 0; b < r.baseVertices.size(); ++b)
  {
    const int32_t v = r.baseVertices[b];
    const auto sup = support(r, v);
    ASSERT_EQ(sup.size(), 1u) << "base vertex " << v;
    EXPECT_EQ(sup[0].first, static_cast<int32_t>(b));
    EXPECT_EQ(sup[0].second, 1.0);
  }
}

TEST_P(BaseComplexOnMesh, MapsTheInputOneToOne)
{
  const BaseStars stars = baseStars(Case_->mesh, Case_->result);
  ASSERT_TRUE(stars.manifold);
  const FlipCount flips = countFlips(Case_->mesh, Case_->result, stars);
  EXPECT_EQ(flips.straddling, 0);
  EXPECT_EQ(flips.flipped, 0);
}

TEST_P(BaseComplexOnMesh, FeatureEdgesLieOnFeatureBaseEdges)
{
  const auto& r = Case_->result;
  const auto& fe = Case_->features.featureEdges;
  std::map<std::pair<int32_t, int32_t>, int32_t> edgeFeature;
  for (size_t c = 0; c < r.baseTriangles.size(); ++c)
  {
    const int32_t a = r.baseTriangles[c], b = r.baseTriangles[c - c % 3 + (c % 3 + 1) % 3];
    edgeFeature[{ std::min(a, b), std::max(a, b) }] |= r.baseEdgeIsFeature[c];
  }
  int64_t inside = 0, unflagged = 0;
  for (size_t i = 0; i < fe.size(); i += 2)
  {
    std::set<int32_t> ends;
    for (const auto& vw : support(r, fe[i]))
    {
      ends.insert(vw.first);
    }
    for (const auto& vw : support(r, fe[i + 1]))
    {
      ends.insert(vw.first);
    }
    if (ends.size() > 2)
    {
      ++inside;
      continue;
    }
    if (ends.size() == 2)
    {
      const auto it = edgeFeature.find({ *ends.begin(), *ends.rbegin() });
      inside += it == edgeFeature.end();
      unflagged += it != edgeFeature.end() && !it->second;
    }
  }
  EXPECT_EQ(inside, 0) << "feature edges inside a base triangle";
  EXPECT_EQ(unflagged, 0) << "feature edges on a base edge not marked as feature";
}

TEST_P(BaseComplexOnMesh, CornersAreBaseVertices)
{
  const auto& r = Case_->result;
  const auto& corner = Case_->features.cornerVertex;
  int64_t missing = 0;
  for (size_t v = 0; v < corner.size(); ++v)
  {
    missing += corner[v] &&
      !std::binary_search(r.baseVertices.begin(), r.baseVertices.end(), static_cast<int32_t>(v));
  }
  EXPECT_EQ(missing, 0);
}

TEST_P(BaseComplexOnMesh, BaseTrianglesAreNotDegenerate)
{
  // The shape rule is relative (a collapse may create a triangle as good as the worst one it
  // replaces), so by induction no base triangle is worse than min(0.1, worst input triangle).
  auto quality = [&](const std::array<double, 3>& a, const std::array<double, 3>& b,
                   const std::array<double, 3>& c)
  {
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    const double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
      u[0] * v[1] - u[1] * v[0] };
    const double w[3] = { c[0] - b[0], c[1] - b[1], c[2] - b[2] };
    const double s = u[0] * u[0] + u[1] * u[1] + u[2] * u[2] + v[0] * v[0] + v[1] * v[1] +
      v[2] * v[2] + w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    return 2.0 * std::sqrt(3.0) * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / s;
  };
  const auto& m = Case_->mesh;
  const auto& r = Case_->result;
  double worstInput = 1.0;
  for (int64_t f = 0; f < m.numTriangles(); ++f)
  {
    worstInput = std::min(worstInput,
      quality(m.point(m.triangles[3 * f]), m.point(m.triangles[3 * f + 1]),
        m.point(m.triangles[3 * f + 2])));
  }
  const double bound = std::min(tc::BaseComplexOptions().minTriangleQuality, worstInput);
  for (size_t f = 0; f < r.baseTriangles.size(); f += 3)
  {
    EXPECT_GE(quality(m.point(r.baseVertices[r.baseTriangles[f]]),
                m.point(r.baseVertices[r.baseTriangles[f + 1]]),
                m.point(r.baseVertices[r.baseTriangles[f + 2]])),
      bound * (1 - 1e-9))
      << "base triangle " << f / 3;
  }
}

TEST_P(BaseComplexOnMesh, ReportsNoInvalidTriangle)
{
  EXPECT_EQ(Case_->result.invalidTriangles, 0);
  EXPECT_GT(Case_->result.collapses, 0);
}

INSTANTIATE_TEST_SUITE_P(BaseComplex, BaseComplexOnMesh,
  // The cube: every vertex is a corner, so nothing collapses.
  ::testing::ValuesIn(tctest::pipelineMeshesWithout("cube")),
  [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

namespace
{
/// The surface of the cube [0, n]^3 with an n x n grid of squares on each side, each square cut
/// into 2 triangles, counter-clockwise seen from outside.
tc::TriMesh gridCube(int n)
{
  tc::TriMesh mesh;
  std::map<std::array<int, 3>, int32_t> ids;
  auto id = [&](std::array<int, 3> p)
  {
    const auto it = ids.find(p);
    if (it != ids.end())
    {
      return it->second;
    }
    const int32_t v = static_cast<int32_t>(ids.size());
    ids.emplace(p, v);
    for (int c : p)
    {
      mesh.points.push_back(c);
    }
    return v;
  };
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int side = 0; side < 2; ++side)
    {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      for (int i = 0; i < n; ++i)
      {
        for (int j = 0; j < n; ++j)
        {
          std::array<int32_t, 4> q;
          const int di[4] = { 0, 1, 1, 0 }, dj[4] = { 0, 0, 1, 1 };
          for (int k = 0; k < 4; ++k)
          {
            std::array<int, 3> p;
            p[axis] = side * n;
            p[a] = i + di[k];
            p[b] = j + dj[k];
            q[k] = id(p);
          }
          // (a, b, axis) is right-handed, so (0,0) (1,0) (1,1) faces +axis.
          const std::array<int32_t, 6> t = side == 1
            ? std::array<int32_t, 6>{ q[0], q[1], q[2], q[0], q[2], q[3] }
            : std::array<int32_t, 6>{ q[0], q[2], q[1], q[0], q[3], q[2] };
          mesh.triangles.insert(mesh.triangles.end(), t.begin(), t.end());
        }
      }
    }
  }
  return mesh;
}
} // namespace

TEST(BaseComplex, CubeEdgesSimplifyAlongThemselvesIntoTwelveBaseEdges)
{
  // Each of the 12 sharp edges of a finely gridded cube is one feature curve between two
  // corners. Curves simplify along themselves down to one base edge each; the grid inside each
  // side can only collapse into itself (never into its border curve), which leaves one vertex
  // per side: 8 + 6 base vertices, 24 base triangles.
  const tc::TriMesh cube = gridCube(8);
  const tctest::Features features = tctest::sharpFeatures(cube);
  ASSERT_EQ(features.featureEdges.size(), 2u * 12 * 8);
  tc::BaseComplexOptions options;
  options.targetFaces = 4;
  const tc::BaseComplexResult r = tc::buildBaseComplex(
    cube, features.featureVertex, features.cornerVertex, features.featureEdges, options);
  EXPECT_FALSE(r.reachedTarget);
  EXPECT_EQ(r.baseVertices.size(), 14u);
  EXPECT_EQ(r.baseTriangles.size(), 3u * 24);
  std::set<std::pair<int32_t, int32_t>> featureBaseEdges;
  for (size_t c = 0; c < r.baseTriangles.size(); ++c)
  {
    const int32_t a = r.baseTriangles[c], b = r.baseTriangles[c - c % 3 + (c % 3 + 1) % 3];
    if (r.baseEdgeIsFeature[c])
    {
      featureBaseEdges.insert({ std::min(a, b), std::max(a, b) });
    }
  }
  EXPECT_EQ(featureBaseEdges.size(), 12u);
  for (int64_t v = 0; v < cube.numPoints(); ++v)
  {
    if (features.cornerVertex[v])
    {
      EXPECT_TRUE(std::binary_search(r.baseVertices.begin(), r.baseVertices.end(), v));
    }
  }
  const FlipCount flips = countFlips(cube, r, baseStars(cube, r));
  EXPECT_EQ(flips.flipped + flips.straddling, 0);
  EXPECT_EQ(r.invalidTriangles, 0);
}

TEST(BaseComplex, Bunny00ReachesATargetOf100)
{
  const std::string path = tctest::sharedData("static_medium/bunny00.off");
  if (path.empty())
  {
    GTEST_SKIP() << "static_medium/bunny00.off is not in the shared data";
  }
  const tc::TriMesh mesh = tctest::loadMesh(path);
  const tctest::Features features = tctest::sharpFeatures(mesh);
  tc::BaseComplexOptions options;
  options.targetFaces = 100;
  options.maxError = 0.0; // the count alone: target control
  const tc::BaseComplexResult r = tc::buildBaseComplex(
    mesh, features.featureVertex, features.cornerVertex, features.featureEdges, options);
  const size_t faces = r.baseTriangles.size() / 3;
  EXPECT_TRUE(r.reachedTarget);
  EXPECT_GE(faces, 60u);
  EXPECT_LE(faces, 200u);
  EXPECT_EQ(r.invalidTriangles, 0);
  EXPECT_EQ(eulerCharacteristic(r.baseTriangles, static_cast<int64_t>(r.baseVertices.size())),
    eulerCharacteristic(mesh.triangles, mesh.numPoints()));
  const BaseStars stars = baseStars(mesh, r);
  EXPECT_TRUE(stars.manifold);
  const FlipCount flips = countFlips(mesh, r, stars);
  EXPECT_EQ(flips.flipped + flips.straddling, 0);
}

TEST(BaseComplex, MaxErrorStopsTheSimplificationEarly)
{
  // The bound stops nothing above one face per 32 input points (1839 / 32 = 57 faces here),
  // then the first collapse above it ends the simplification.
  const tc::TriMesh mesh = tctest::loadMesh(tctest::testingData("meshes/bunny_npm.off"));
  ASSERT_EQ(mesh.numPoints(), 1839);
  tc::BaseComplexOptions options;
  options.targetFaces = 20;
  options.maxError = 1e-6;
  const tc::BaseComplexResult bounded = tc::buildBaseComplex(mesh, {}, {}, {}, options);
  EXPECT_FALSE(bounded.reachedTarget);
  EXPECT_LE(bounded.baseTriangles.size() / 3, 57u);
  EXPECT_GT(bounded.baseTriangles.size() / 3, 50u);
  options.maxError = 0.0;
  const tc::BaseComplexResult free = tc::buildBaseComplex(mesh, {}, {}, {}, options);
  EXPECT_TRUE(free.reachedTarget);
  EXPECT_GT(free.maxCollapseError, 1e-6);
  EXPECT_GT(free.maxCollapseError, bounded.maxCollapseError);
}

TEST(BaseComplex, IsDeterministic)
{
  const tc::TriMesh mesh = tctest::loadMesh(tctest::testingData("meshes/fandisk.off"));
  const tctest::Features f = tctest::sharpFeatures(mesh);
  const auto a = tc::buildBaseComplex(mesh, f.featureVertex, f.cornerVertex, f.featureEdges);
  const auto b = tc::buildBaseComplex(mesh, f.featureVertex, f.cornerVertex, f.featureEdges);
  EXPECT_EQ(a.baseVertices, b.baseVertices);
  EXPECT_EQ(a.baseTriangles, b.baseTriangles);
  EXPECT_EQ(a.vertexBaseFace, b.vertexBaseFace);
  EXPECT_EQ(a.vertexBarycentric, b.vertexBarycentric);
  EXPECT_EQ(a.baseEdgeIsFeature, b.baseEdgeIsFeature);
}

TEST(BaseComplex, ReportsProgressAndHonoursAbort)
{
  const tc::TriMesh mesh = tctest::loadMesh(tctest::testingData("meshes/bunny_npm.off"));
  tctest::expectProgressAndAbort([&](const tc::Progress& p)
    { tc::buildBaseComplex(mesh, {}, {}, {}, {}, p); },
    1, [calls = 0](double) mutable { return ++calls < 2; });
}

TEST(BaseComplex, RejectsInputThatIsNotAClosedManifoldOrDoesNotMatch)
{
  tc::TriMesh mesh = tctest::loadMesh(tctest::testingData("meshes/bunny_npm.off"));
  const int64_t nv = mesh.numPoints();
  tc::TriMesh open = mesh;
  open.triangles.resize(open.triangles.size() - 3);
  EXPECT_THROW(tc::buildBaseComplex(open, {}, {}, {}), tc::InputError);
  EXPECT_THROW(tc::buildBaseComplex(mesh, std::vector<uint8_t>(nv - 1, 0), {}, {}), tc::InputError);
  EXPECT_THROW(tc::buildBaseComplex(mesh, {}, std::vector<uint8_t>(nv + 1, 0), {}), tc::InputError);
  // A feature "edge" between two vertices of the same triangle is fine; one across the mesh
  // is not an edge.
  const int32_t a = mesh.triangles[0], b = mesh.triangles[1];
  EXPECT_NO_THROW(tc::buildBaseComplex(mesh, {}, {}, { a, b }));
  int32_t far = 0;
  const tc::VertexRing ring = tc::buildVertexRing(tc::buildEdgeTable(mesh.triangles), nv);
  while (far == a ||
    std::binary_search(
      ring.ids.begin() + ring.offsets[a], ring.ids.begin() + ring.offsets[a + 1], far))
  {
    ++far;
  }
  EXPECT_THROW(tc::buildBaseComplex(mesh, {}, {}, { a, far }), tc::InputError);
  tc::TriMesh flipped = mesh;
  std::swap(flipped.triangles[0], flipped.triangles[1]);
  EXPECT_THROW(tc::buildBaseComplex(flipped, {}, {}, {}), tc::InputError);
}
