// SPDX-License-Identifier: BSD-3-Clause
// The output of the path tracer (PatchMesh): the Steiner points numbered by input edge and
// placed, the chords and the input edges on base edges chained into one path per base edge
// (step 3 of path_tracer.h), and the triangles in input order.
#include "gim/path_tracer.h"

#include "tc/common/errors.h"
#include "tc/common/parallel.h"

#include <array>

namespace tc
{
namespace detail
{
namespace tracing
{
/// SteinerStart_ from the cuts of every piece; returns the number of Steiner points.
int64_t Tracer::numberSteinerPoints()
{
  const int32_t nh = 3 * NF_;
  std::vector<int32_t> count(nh, 0);
  for (const Pieces& p : Pieces_)
  {
    for (const auto& c : p.cuts)
    {
      ++count[c.first];
    }
  }
  SteinerStart_.assign(nh, 0);
  int64_t ns = 0;
  for (int32_t h = 0; h < nh; ++h)
  {
    SteinerStart_[h] = static_cast<int32_t>(ns);
    ns += count[h];
    if (ns + NV_ >= std::numeric_limits<int32_t>::max())
    {
      throw InputError("tracePaths: too many Steiner points for 32-bit point ids");
    }
  }
  return ns;
}

/// The output points (the input's, then the ns Steiner points) and the input edge and parameter
/// of each Steiner point.
void Tracer::placeSteinerPoints(int64_t ns, const Progress& progress)
{
  PatchMesh& out = Result_;
  out.steinerEdge.resize(2 * ns);
  out.steinerParameter.resize(ns);
  out.mesh.points.resize(3 * (static_cast<size_t>(NV_) + ns));
  std::copy(Mesh_.points.begin(), Mesh_.points.end(), out.mesh.points.begin());
  tc::parallel_for(
    static_cast<int64_t>(Cut_.size()),
    [&](int64_t i)
    {
      const std::vector<std::pair<int32_t, double>>& cuts = Pieces_[i].cuts;
      for (size_t k = 0; k < cuts.size();)
      {
        const int32_t h = cuts[k].first;
        const int32_t u = this->lower(h);
        const int32_t v = this->upper(h);
        const V3 pu = this->pos(u), pv = this->pos(v);
        for (int32_t j = 0; k < cuts.size() && cuts[k].first == h; ++k, ++j)
        {
          const int64_t s = SteinerStart_[h] + j;
          const double t = cuts[k].second;
          out.steinerEdge[2 * s] = u;
          out.steinerEdge[2 * s + 1] = v;
          out.steinerParameter[s] = t;
          const V3 x = pointAt(pu, pv, t);
          double* p = &out.mesh.points[3 * (NV_ + s)];
          p[0] = x.x;
          p[1] = x.y;
          p[2] = x.z;
        }
      }
    },
    progress);
}

/// PatchMesh::pathOffsets and pathPoints: the links of every base edge chained from its lower
/// base vertex to its higher one.
void Tracer::chainPaths(const Progress& progress)
{
  PatchMesh& out = Result_;
  const int32_t ne = static_cast<int32_t>(out.baseEdges.size() / 2);
  const std::vector<Link> links = this->pathLinks();
  std::vector<int64_t> linkStart(static_cast<size_t>(ne) + 1, 0);
  for (const Link& l : links)
  {
    ++linkStart[l.edge + 1];
  }
  for (int32_t e = 0; e < ne; ++e)
  {
    linkStart[e + 1] += linkStart[e];
  }
  std::vector<std::vector<int32_t>> paths(ne);
  std::vector<std::string> pathError(ne);
  tc::parallel_for(
    ne,
    [&](int64_t ei)
    {
      const int32_t e = static_cast<int32_t>(ei);
      pathError[e] =
        this->chainPath(e, links.data() + linkStart[e], linkStart[e + 1] - linkStart[e], paths[e]);
    },
    progress);
  for (int32_t e = 0; e < ne; ++e)
  {
    if (!pathError[e].empty())
    {
      throw UntraceableError(
        "the path of base edge " + this->edgeName(e) + " cannot be traced: " + pathError[e],
        kNotOneToOne);
    }
  }
  out.pathOffsets.assign(1, 0);
  out.pathPoints.clear();
  for (int32_t e = 0; e < ne; ++e)
  {
    out.pathPoints.insert(out.pathPoints.end(), paths[e].begin(), paths[e].end());
    out.pathOffsets.push_back(static_cast<int64_t>(out.pathPoints.size()));
  }
}

/// The pieces of all paths, by base edge and then by their points (output point ids): the chords
/// of the cut triangles and the input edges on base edges (from the lower vertex id).
std::vector<Link> Tracer::pathLinks() const
{
  std::vector<Link> links;
  for (const Pieces& p : Pieces_)
  {
    for (const Link& l : p.links)
    {
      links.push_back({ l.edge, this->pointId(l.p), this->pointId(l.q) });
    }
  }
  const int32_t nh = 3 * NF_;
  for (int32_t h = 0; h < nh; ++h)
  {
    if (AlongEdge_[h] >= 0)
    {
      links.push_back({ AlongEdge_[h], this->lower(h), this->upper(h) });
    }
  }
  std::sort(links.begin(), links.end(),
    [](const Link& a, const Link& b)
    { return a.edge < b.edge || (a.edge == b.edge && (a.p < b.p || (a.p == b.p && a.q < b.q))); });
  return links;
}

/// Chains the nl links of base edge e into `path`, from its lower base vertex to its higher one;
/// returns why it cannot be, or "".
std::string Tracer::chainPath(
  int32_t e, const Link* links, int64_t nl, std::vector<int32_t>& path) const
{
  // Ends of every link, sorted by point: each point of the path has 2 (its ends 1).
  std::vector<std::pair<int64_t, int64_t>> ends;
  for (int64_t k = 0; k < nl; ++k)
  {
    ends.emplace_back(links[k].p, k);
    ends.emplace_back(links[k].q, k);
  }
  std::sort(ends.begin(), ends.end());
  auto linksAt = [&](int64_t p)
  {
    return std::equal_range(ends.begin(), ends.end(), std::make_pair(p, int64_t(-1)),
      [](const std::pair<int64_t, int64_t>& x, const std::pair<int64_t, int64_t>& y)
      { return x.first < y.first; });
  };
  const int32_t A = Base_.baseVertices[Result_.baseEdges[2 * e]];
  const int32_t B = Base_.baseVertices[Result_.baseEdges[2 * e + 1]];
  path.push_back(A);
  int64_t cur = A, came = -1;
  for (int64_t used = 0; cur != B; ++used)
  {
    const auto range = linksAt(cur);
    const int64_t degree = range.second - range.first;
    if (degree != (cur == A ? 1 : 2) || used >= nl)
    {
      return degree == 0 ? "it stops at " + this->pointName(static_cast<int32_t>(cur))
                         : "it branches at " + this->pointName(static_cast<int32_t>(cur));
    }
    const int64_t k = range.first->second != came ? range.first->second : (range.first + 1)->second;
    cur = links[k].p == cur ? links[k].q : links[k].p;
    came = k;
    path.push_back(static_cast<int32_t>(cur));
  }
  const auto range = linksAt(B);
  if (range.second - range.first != 1 || static_cast<int64_t>(path.size()) != nl + 1)
  {
    return "it has pieces that are not on its way from end to end";
  }
  return std::string();
}

/// The output triangles in input order (each input triangle kept whole, or its pieces), their
/// patch and input triangle, and the input point of every output point.
void Tracer::writeTriangles(int64_t ns, const Progress& progress)
{
  PatchMesh& out = Result_;
  std::vector<int64_t> offset(static_cast<size_t>(NF_) + 1, 0);
  for (int32_t f = 0; f < NF_; ++f)
  {
    offset[f + 1] =
      offset[f] + (Slot_[f] < 0 ? 1 : static_cast<int64_t>(Pieces_[Slot_[f]].patch.size()));
  }
  const int64_t nOut = offset[NF_];
  out.mesh.triangles.resize(3 * nOut);
  out.patchId.resize(nOut);
  out.inputTriangle.resize(nOut);
  tc::parallel_for(
    NF_,
    [&](int64_t i)
    {
      const int32_t f = static_cast<int32_t>(i);
      const int64_t o = offset[f];
      if (Slot_[f] >= 0)
      {
        const Pieces& p = Pieces_[Slot_[f]];
        for (size_t k = 0; k < p.triangles.size(); ++k)
        {
          out.mesh.triangles[3 * o + k] = this->pointId(p.triangles[k]);
        }
        std::copy(p.patch.begin(), p.patch.end(), out.patchId.begin() + o);
        std::fill(out.inputTriangle.begin() + o,
          out.inputTriangle.begin() + o + static_cast<int64_t>(p.patch.size()), f);
        return;
      }
      std::copy(&Mesh_.triangles[3 * static_cast<size_t>(f)],
        &Mesh_.triangles[3 * static_cast<size_t>(f)] + 3, out.mesh.triangles.begin() + 3 * o);
      out.patchId[o] = Label_[f];
      out.inputTriangle[o] = f;
    },
    progress);
  out.inputPointId.resize(static_cast<size_t>(NV_) + ns);
  for (int32_t v = 0; v < NV_; ++v)
  {
    out.inputPointId[v] = v;
  }
  std::fill(out.inputPointId.begin() + NV_, out.inputPointId.end(), -1);
}

/// "7 (points 12 and 40)": base edge e and the input points at its ends, for messages.
std::string Tracer::edgeName(int32_t e) const
{
  return std::to_string(e) + " (points " +
    std::to_string(Base_.baseVertices[Result_.baseEdges[2 * e]]) + " and " +
    std::to_string(Base_.baseVertices[Result_.baseEdges[2 * e + 1]]) + ")";
}

/// An output point for messages: an input point, or the input edge a Steiner point lies on.
std::string Tracer::pointName(int32_t p) const
{
  if (p < NV_)
  {
    return "point " + std::to_string(p);
  }
  const int64_t s = p - NV_;
  return "the Steiner point on input edge " + std::to_string(Result_.steinerEdge[2 * s]) + "-" +
    std::to_string(Result_.steinerEdge[2 * s + 1]);
}
} // namespace tracing
} // namespace detail
} // namespace tc

namespace tc
{
namespace
{
/// Weights of point p of the traced mesh over the corners of input triangle `tri`: 1 at its own
/// corner, or (1 - t, t) at the ends of the side its Steiner point lies on.
std::array<double, 3> cornerWeights(
  const PatchMesh& patches, int64_t inputPoints, const int32_t* tri, int64_t p)
{
  std::array<double, 3> w{ 0.0, 0.0, 0.0 };
  auto corner = [&](int64_t v)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] == v)
      {
        return k;
      }
    }
    throw InputError("pieceCornerValues: a piece has a corner outside its input triangle; pass "
                     "the mesh that tracePaths was given");
  };
  if (p < inputPoints)
  {
    w[static_cast<size_t>(corner(p))] = 1.0;
    return w;
  }
  const size_t s = static_cast<size_t>(p - inputPoints);
  const double t = patches.steinerParameter[s];
  w[static_cast<size_t>(corner(patches.steinerEdge[2 * s]))] += 1.0 - t;
  w[static_cast<size_t>(corner(patches.steinerEdge[2 * s + 1]))] += t;
  return w;
}
} // namespace

std::vector<double> pieceCornerValues(const PatchMesh& patches, const TriMesh& mesh,
  const std::vector<double>& values, int32_t components)
{
  const size_t n = static_cast<size_t>(components);
  if (components < 1 || values.size() != mesh.triangles.size() * n ||
    patches.inputTriangle.size() != patches.mesh.triangles.size() / 3)
  {
    throw InputError("pieceCornerValues: the corner values must hold 3 x " +
      std::to_string(components) + " values per triangle of the traced mesh");
  }
  const int64_t inputPoints =
    patches.mesh.numPoints() - static_cast<int64_t>(patches.steinerParameter.size());
  std::vector<double> out(patches.mesh.triangles.size() * n, 0.0);
  for (size_t f = 0; f < patches.inputTriangle.size(); ++f)
  {
    const size_t t = static_cast<size_t>(patches.inputTriangle[f]);
    const int32_t* tri = &mesh.triangles[3 * t];
    for (size_t k = 0; k < 3; ++k)
    {
      const std::array<double, 3> w =
        cornerWeights(patches, inputPoints, tri, patches.mesh.triangles[3 * f + k]);
      for (size_t r = 0; r < 3; ++r)
      {
        for (size_t x = 0; w[r] != 0.0 && x < n; ++x)
        {
          out[(3 * f + k) * n + x] += w[r] * values[(3 * t + r) * n + x];
        }
      }
    }
  }
  return out;
}
} // namespace tc
