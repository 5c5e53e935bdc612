// SPDX-License-Identifier: BSD-3-Clause
// The input of the path tracer checked and read: the shapes and ids of the arrays, the image of
// every input vertex in the base complex (snapped onto base edges where round-off put it beside
// one), and the twin of every half-edge of the mesh.
#include "gim/path_tracer.h"

#include "tc/common/errors.h"
#include "tc/common/parallel.h"

#include <atomic>
#include <cmath>

namespace tc
{
namespace detail
{
namespace tracing
{
namespace
{
/// No bad item found yet.
constexpr int32_t kNone = std::numeric_limits<int32_t>::max();

/// Lowers `first` to x: the lowest bad item is the one reported, whatever the thread count.
void keepLowest(std::atomic<int32_t>& first, int32_t x)
{
  int32_t cur = first.load();
  while (x < cur && !first.compare_exchange_weak(cur, x))
  {
  }
}
} // namespace

void Tracer::validate(const Progress& progress)
{
  this->checkShapes();
  this->checkIds();
  BaseIndex_.assign(NV_, -1);
  for (int32_t i = 0; i < NB_; ++i)
  {
    BaseIndex_[Base_.baseVertices[i]] = i;
  }
  NoSnap_.assign(NV_, 0);
  this->checkImages(progress);
  this->keepOffEdges();
}

/// Array sizes; sets the counts NV_, NF_, NB_, NFB_.
void Tracer::checkShapes()
{
  if (Mesh_.points.size() % 3 != 0 || Mesh_.triangles.size() % 3 != 0)
  {
    throw InputError("tracePaths: points and triangles must be flat #V x 3 and #F x 3 arrays");
  }
  if (Mesh_.triangles.size() >= static_cast<size_t>(std::numeric_limits<int32_t>::max()) ||
    Mesh_.numPoints() >= std::numeric_limits<int32_t>::max() / 2)
  {
    throw InputError("tracePaths: the mesh is too large for 32-bit half-edge ids");
  }
  NV_ = static_cast<int32_t>(Mesh_.numPoints());
  NF_ = static_cast<int32_t>(Mesh_.numTriangles());
  NB_ = static_cast<int32_t>(Base_.baseVertices.size());
  NFB_ = static_cast<int32_t>(Base_.baseTriangles.size() / 3);
  if (NF_ < 4)
  {
    throw InputError("tracePaths: the mesh needs at least 4 triangles (a closed surface)");
  }
  if (Base_.vertexBaseFace.size() != static_cast<size_t>(NV_) ||
    Base_.vertexBarycentric.size() != 3 * static_cast<size_t>(NV_))
  {
    throw InputError("tracePaths: the base complex does not match the mesh (vertexBaseFace and "
                     "vertexBarycentric need one entry per point); pass the mesh that "
                     "buildBaseComplex was given");
  }
  if (NB_ < 4 || NFB_ < 4 || Base_.baseTriangles.size() % 3 != 0 ||
    Base_.baseEdgeIsFeature.size() != Base_.baseTriangles.size())
  {
    throw InputError("tracePaths: the base complex needs at least 4 vertices and 4 triangles, and "
                     "baseEdgeIsFeature one entry per triangle side");
  }
}

/// Every id in range; base vertices ascending.
void Tracer::checkIds() const
{
  for (int32_t i = 0; i < NB_; ++i)
  {
    const int32_t v = Base_.baseVertices[i];
    if (v < 0 || v >= NV_ || (i > 0 && v <= Base_.baseVertices[i - 1]))
    {
      throw InputError("tracePaths: baseVertices must be ascending point ids of the mesh");
    }
  }
  for (int32_t x : Base_.baseTriangles)
  {
    if (x < 0 || x >= NB_)
    {
      throw InputError("tracePaths: baseTriangles refers to a base vertex that does not exist");
    }
  }
  for (int32_t x : Mesh_.triangles)
  {
    if (x < 0 || x >= NV_)
    {
      throw InputError("tracePaths: a triangle refers to a point that does not exist");
    }
  }
}

/// Every image must be a point of its base face; a vertex other than a base vertex must not
/// land on a base vertex (two input vertices at one point of the base complex cannot be cut
/// apart).
void Tracer::checkImages(const Progress& progress)
{
  std::atomic<int32_t> firstBad{ kNone };
  tc::parallel_for(
    NV_,
    [&](int64_t i)
    {
      const int32_t v = static_cast<int32_t>(i);
      const int32_t g = Base_.vertexBaseFace[v];
      const double* w = &Base_.vertexBarycentric[3 * static_cast<size_t>(v)];
      bool ok = g >= 0 && g < NFB_;
      double sum = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        ok &= std::isfinite(w[k]) && w[k] >= -1e-9;
        sum += w[k];
      }
      ok &= std::abs(sum - 1.0) <= 1e-6;
      if (ok)
      {
        const Support s = this->support(v);
        ok = BaseIndex_[v] >= 0 ? (s.n == 1 && s.v[0] == BaseIndex_[v]) : s.n >= 2;
      }
      if (!ok)
      {
        keepLowest(firstBad, v);
      }
    },
    progress);
  if (firstBad.load() != kNone)
  {
    const int32_t v = firstBad.load();
    throw InputError("tracePaths: point " + std::to_string(v) +
      " has no valid image in the base complex (base face and barycentrics summing to 1; a base "
      "vertex on its own corner, no other point on a base vertex); rebuild the base complex "
      "from this mesh");
  }
}

/// Forbids the snaps that would flatten or flip an input triangle. For a triangle whose corners'
/// exact images lie in one base face g with positive area, the snapped images must keep a
/// positive area in g; where they do not, its snapped corners keep their exact images. A
/// removed snap can turn another triangle (one corner still snapped) over, so the check runs
/// until nothing changes; snaps are only ever removed, so that ends.
void Tracer::keepOffEdges()
{
  std::vector<uint8_t> snapped(NV_, 0);
  tc::parallel_for(NV_,
    [&](int64_t i)
    {
      const int32_t v = static_cast<int32_t>(i);
      snapped[v] = BaseIndex_[v] < 0 && this->image(v, true).n < this->image(v, false).n ? 1 : 0;
    });
  // The signed area in base face g of the images of the corners of f (0 when g misses one).
  auto area = [&](int32_t g, const Support* s)
  {
    double l[3][3];
    for (int i = 0; i < 3; ++i)
    {
      if (!this->faceHolds(g, s[i]))
      {
        return 0.0;
      }
      for (int k = 0; k < 3; ++k)
      {
        l[i][k] = s[i].weight(Base_.baseTriangles[3 * g + k]);
      }
    }
    return l[0][0] * (l[1][1] * l[2][2] - l[1][2] * l[2][1]) -
      l[0][1] * (l[1][0] * l[2][2] - l[1][2] * l[2][0]) +
      l[0][2] * (l[1][0] * l[2][1] - l[1][1] * l[2][0]);
  };
  std::vector<int32_t> candidates;
  for (int32_t f = 0; f < NF_; ++f)
  {
    const int32_t* c = &Mesh_.triangles[3 * static_cast<size_t>(f)];
    if (snapped[c[0]] || snapped[c[1]] || snapped[c[2]])
    {
      candidates.push_back(f);
    }
  }
  for (bool changed = true; changed;)
  {
    changed = false;
    for (int32_t f : candidates)
    {
      const int32_t* c = &Mesh_.triangles[3 * static_cast<size_t>(f)];
      Support exact[3], now[3];
      for (int i = 0; i < 3; ++i)
      {
        exact[i] = this->image(c[i], false);
        now[i] = this->support(c[i]);
      }
      for (int i = 0; i < 3; ++i)
      {
        const int32_t g = Base_.vertexBaseFace[c[i]];
        if (area(g, exact) > 0.0 && !(area(g, now) > 0.0))
        {
          for (int j = 0; j < 3; ++j)
          {
            changed |= snapped[c[j]] && !NoSnap_[c[j]];
            NoSnap_[c[j]] |= snapped[c[j]];
          }
          break;
        }
      }
    }
  }
}

/// Outgoing half-edges of every vertex (CSR), then each twin is found in the list of the
/// half-edge's end: linear time, no sort, and parallel.
void Tracer::buildTopology(const Progress& progress)
{
  const int32_t nh = 3 * NF_;
  std::vector<int32_t> offsets(static_cast<size_t>(NV_) + 1, 0);
  for (int32_t h = 0; h < nh; ++h)
  {
    ++offsets[Mesh_.triangles[h] + 1];
  }
  for (int32_t v = 0; v < NV_; ++v)
  {
    offsets[v + 1] += offsets[v];
  }
  std::vector<int32_t> outgoing(nh);
  {
    std::vector<int32_t> fill(offsets.begin(), offsets.end() - 1);
    for (int32_t h = 0; h < nh; ++h)
    {
      outgoing[fill[Mesh_.triangles[h]]++] = h;
    }
  }
  this->findTwins(offsets, outgoing, progress.sub(0.0, 0.5));
  this->checkFans(offsets, outgoing, progress.sub(0.5, 1.0));
}

/// Opp_ from the outgoing half-edges of every vertex (offsets into outgoing, CSR).
void Tracer::findTwins(const std::vector<int32_t>& offsets, const std::vector<int32_t>& outgoing,
  const Progress& progress)
{
  const int32_t nh = 3 * NF_;
  Opp_.assign(nh, -1);
  std::atomic<int32_t> firstBad{ kNone };
  tc::parallel_for(
    nh,
    [&](int64_t i)
    {
      const int32_t h = static_cast<int32_t>(i);
      const int32_t u = this->from(h), v = this->to(h);
      int found = 0;
      for (int32_t k = offsets[v]; k < offsets[v + 1]; ++k)
      {
        const int32_t g = outgoing[k];
        if (this->to(g) == u)
        {
          Opp_[h] = g;
          ++found;
        }
      }
      // A repeated u -> v shows as two twins of v -> u, a missing twin or a reversed triangle
      // as none.
      if (found != 1 || u == v)
      {
        keepLowest(firstBad, h);
      }
    },
    progress);
  if (firstBad.load() != kNone)
  {
    const int32_t h = firstBad.load();
    throw InputError("tracePaths: the mesh is not a closed oriented manifold (edge " +
      std::to_string(this->from(h)) + "-" + std::to_string(this->to(h)) +
      " has no single opposite twin); pass the mesh that buildBaseComplex was given");
  }
}

/// One fan per vertex: turning around v through the twins visits all its half-edges.
void Tracer::checkFans(const std::vector<int32_t>& offsets, const std::vector<int32_t>& outgoing,
  const Progress& progress) const
{
  std::atomic<int32_t> firstBad{ kNone };
  tc::parallel_for(
    NV_,
    [&](int64_t i)
    {
      const int32_t v = static_cast<int32_t>(i);
      const int32_t count = offsets[v + 1] - offsets[v];
      if (count == 0)
      {
        return;
      }
      const int32_t start = outgoing[offsets[v]];
      int32_t h = start, steps = 0;
      do
      {
        h = Opp_[prevHe(h)];
        ++steps;
      } while (h != start && steps <= count);
      if (steps != count)
      {
        keepLowest(firstBad, start);
      }
    },
    progress);
  if (firstBad.load() != kNone)
  {
    throw InputError("tracePaths: the triangles around point " +
      std::to_string(this->from(firstBad.load())) +
      " do not form one fan (non-manifold vertex); pass the mesh that buildBaseComplex was given");
  }
}
} // namespace tracing
} // namespace detail
} // namespace tc
