// SPDX-License-Identifier: BSD-3-Clause
// M0's faces while M0 is contracted into M1, and the link condition of Dey, Edelsbrunner, Guha
// and Nekhayev (1998) that keeps M1 homeomorphic to M0 (Kircher and Garland 2005, section 4.2).
#include "multilevel/multilevel_internal.h"

namespace tc
{
namespace detail
{
namespace multilevel
{
LiveFaces::LiveFaces(const TriMesh& mesh)
  : Tri_(mesh.triangles)
  , Alive_(mesh.numTriangles(), 1)
  , Head_(mesh.numPoints(), -1)
  , Next_(mesh.triangles.size(), -1)
  , MarkA_(mesh.numPoints(), 0)
  , MarkB_(mesh.numPoints(), 0)
  , UseA_(mesh.numPoints(), 0)
  , UseB_(mesh.numPoints(), 0)
{
  for (int32_t k = 0; k < static_cast<int32_t>(Tri_.size()); ++k)
  {
    Next_[k] = Head_[Tri_[k]];
    Head_[Tri_[k]] = k;
  }
}

void LiveFaces::gather(int32_t v)
{
  Faces_.clear();
  int32_t* link = &Head_[v];
  while (*link >= 0)
  {
    const int32_t k = *link;
    if (!Alive_[k / 3])
    {
      *link = Next_[k]; // unlink a dead face as it is met
      continue;
    }
    Faces_.push_back(k / 3);
    link = &Next_[k];
  }
}

void LiveFaces::gatherRing(
  int32_t v, std::vector<int32_t>& mark, std::vector<int32_t>& use, std::vector<int32_t>& ring)
{
  this->gather(v);
  ring.clear();
  for (const int32_t f : Faces_)
  {
    for (int i = 0; i < 3; ++i)
    {
      const int32_t x = Tri_[3 * f + i];
      if (x == v)
      {
        continue;
      }
      if (mark[x] != Stamp_)
      {
        mark[x] = Stamp_;
        use[x] = 0;
        ring.push_back(x);
      }
      ++use[x];
    }
  }
}

bool LiveFaces::hasFace(int32_t a, int32_t x, int32_t y)
{
  this->gather(a);
  for (const int32_t f : Faces_)
  {
    const int32_t* t = &Tri_[3 * f];
    const bool hasX = t[0] == x || t[1] == x || t[2] == x;
    const bool hasY = t[0] == y || t[1] == y || t[2] == y;
    if (hasX && hasY)
    {
      return true;
    }
  }
  return false;
}

bool LiveFaces::oneSidedEdge(const std::vector<int32_t>& ring, const std::vector<int32_t>& use)
{
  for (const int32_t x : ring)
  {
    if (use[x] == 1)
    {
      return true;
    }
  }
  return false;
}

/// Lk(a) n Lk(b) = Lk(ab) on a surface whose boundary is coned off to a virtual vertex w: the
/// common neighbours of a and b are exactly the vertices opposite ab, the two faces beside ab
/// are not closed off by faces acd and bcd (a tetrahedron), w is common only if ab is on the
/// boundary, and then the boundary is not the triangle abc.
bool LiveFaces::linkConditionHolds(int32_t a, int32_t b)
{
  ++Stamp_;
  this->gatherRing(a, MarkA_, UseA_, RingA_);
  this->gatherRing(b, MarkB_, UseB_, RingB_);
  if (MarkB_[a] != Stamp_ || UseB_[a] > 2)
  {
    return false; // not an edge of the surface, or a non-manifold one
  }
  int32_t opposite[2] = { -1, -1 };
  int nOpposite = 0;
  for (const int32_t f : Faces_) // b's faces, from the last gather
  {
    const int32_t* t = &Tri_[3 * f];
    if (t[0] == a || t[1] == a || t[2] == a)
    {
      opposite[nOpposite++] = t[0] + t[1] + t[2] - a - b;
    }
  }
  int nCommon = 0;
  for (const int32_t x : RingB_)
  {
    nCommon += (x != a && MarkA_[x] == Stamp_) ? 1 : 0;
  }
  if (nCommon != nOpposite)
  {
    return false;
  }
  if (nOpposite == 2 && this->hasFace(a, opposite[0], opposite[1]) &&
    this->hasFace(b, opposite[0], opposite[1]))
  {
    return false;
  }
  const bool abOnBoundary = UseB_[a] == 1;
  if (!abOnBoundary)
  {
    return !(oneSidedEdge(RingA_, UseA_) && oneSidedEdge(RingB_, UseB_));
  }
  const int32_t c = opposite[0];
  return !(UseA_[c] == 1 && UseB_[c] == 1);
}

void LiveFaces::contract(int32_t a, int32_t b)
{
  int32_t k = Head_[b];
  while (k >= 0)
  {
    const int32_t next = Next_[k];
    const int32_t f = k / 3;
    const int32_t* t = &Tri_[3 * f];
    if (Alive_[f] && (t[0] == a || t[1] == a || t[2] == a))
    {
      Alive_[f] = 0; // the face of edge ab degenerates
    }
    else if (Alive_[f])
    {
      Tri_[k] = a;
      Next_[k] = Head_[a];
      Head_[a] = k;
    }
    k = next;
  }
  Head_[b] = -1;
}
} // namespace multilevel
} // namespace detail
} // namespace tc
