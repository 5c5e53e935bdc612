// SPDX-License-Identifier: BSD-3-Clause
// Step 5 of the base complex (simplifier.h), the bijection check: every input triangle at a
// point a collapse moved, or at a base vertex whose star it changed, must keep its orientation
// in the chart of its corners' images (one base face, two faces unfolded about an edge, or a
// base vertex's star flattened by z^a); otherwise the collapse is undone and rejected, so the
// map from the mesh to the base complex stays a bijection (Feng et al. section 5.1).
#include "gim/simplifier.h"

#include "detail/star_map.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace tc
{
namespace detail
{
namespace base_complex
{
namespace
{
/// Whether flat triangle p is counter-clockwise with an area that clears a relative margin, so
/// that any evaluation of the charts agrees on its sign.
bool clearlyPositive(const P2 p[3])
{
  constexpr double kMargin = 1e-12;
  const double a = orient(p[0], p[1], p[2]);
  const double s = (p[1].x - p[0].x) * (p[1].x - p[0].x) + (p[1].y - p[0].y) * (p[1].y - p[0].y) +
    (p[2].x - p[1].x) * (p[2].x - p[1].x) + (p[2].y - p[1].y) * (p[2].y - p[1].y) +
    (p[0].x - p[2].x) * (p[0].x - p[2].x) + (p[0].y - p[2].y) * (p[0].y - p[2].y);
  return a > kMargin * s;
}

/// Whether n ring indices (n <= 3, found[0..n)) of a ring of d put a point outside the closed
/// star: a point inside a face must be in a face of the star (the centre is a corner); one on
/// an edge that misses the centre must be on the far side of a face of the star.
bool outsideStar(int n, const int found[3], int d)
{
  return n == 3 ||
    (n == 2 && (found[1] - found[0] + d) % d != 1 && (found[0] - found[1] + d) % d != 1);
}
} // namespace

/// Whether every input triangle at a point the collapse moved, or at a base vertex whose star it
/// changed, is still valid (triangleValid): a collapse that would fold or stretch one is
/// rejected, so the map stays a bijection at every level instead of being untangled at the end.
bool Simplifier::movedTrianglesValid()
{
  ++TriCounter_;
  PendingStar_.clear();
  return this->movedPointsValid() && this->changedStarsValid();
}

/// The triangles at every point the collapse moved (u among them).
bool Simplifier::movedPointsValid()
{
  for (const auto& pj : Points_)
  {
    const int32_t p = pj.first;
    for (int32_t s = InOffsets_[p]; s < InOffsets_[p + 1]; ++s)
    {
      const int32_t t = InHe_[s] / 3;
      if (!this->seen(t) && !this->checkTriangle(t))
      {
        return false;
      }
    }
  }
  return true;
}

/// The star charts of u, v and the ring changed: the triangles drawn in them, and those at these
/// base vertices (a star that now holds them may come first), are drawn anew, unless their other
/// corners did not move and lie in one face with the vertex (that face's barycentric plane did
/// not change).
bool Simplifier::changedStarsValid()
{
  auto inFaceWith = [&](int32_t p, int32_t x)
  {
    if (!Removed_[p])
    {
      return p == x;
    }
    return this->faceHas(PointFace_[p], x);
  };
  for (int j = -1; j < K_; ++j)
  {
    const int32_t x = j < 0 ? U_ : RingV_[j];
    for (int32_t t = StarHead_[x]; t >= 0; t = TriStarNext_[t])
    {
      if (!this->seen(t) && !this->checkTriangle(t))
      {
        return false;
      }
    }
    if (j < 0)
    {
      continue;
    }
    for (int32_t s = InOffsets_[x]; s < InOffsets_[x + 1]; ++s)
    {
      const int32_t h = InHe_[s];
      const int32_t t = h / 3;
      if (this->seen(t))
      {
        continue;
      }
      const int32_t p = Tri_[nextHe(h)], q = Tri_[prevHe(h)];
      if (Removed_[p] && Removed_[q] && PointFace_[p] == PointFace_[q] && inFaceWith(p, x))
      {
        continue;
      }
      if (!this->checkTriangle(t))
      {
        return false;
      }
    }
  }
  return true;
}

/// triangleValid for the check of a collapse; notes a change of the star t is drawn in.
bool Simplifier::checkTriangle(int32_t t)
{
  int32_t centre = -1;
  const bool valid = this->triangleValid(t, &centre);
  if (centre != TriStar_[t])
  {
    PendingStar_.emplace_back(t, centre);
  }
  return valid;
}

/// Files the triangles checked by an accepted collapse under the star they were drawn in.
void Simplifier::commitStarUsers()
{
  for (const auto& tc : PendingStar_)
  {
    const int32_t t = tc.first;
    const int32_t old = TriStar_[t];
    if (old >= 0)
    {
      const int32_t prev = TriStarPrev_[t], next = TriStarNext_[t];
      (prev >= 0 ? TriStarNext_[prev] : StarHead_[old]) = next;
      if (next >= 0)
      {
        TriStarPrev_[next] = prev;
      }
    }
    TriStar_[t] = tc.second;
    if (tc.second >= 0)
    {
      TriStarPrev_[t] = -1;
      TriStarNext_[t] = StarHead_[tc.second];
      if (StarHead_[tc.second] >= 0)
      {
        TriStarPrev_[StarHead_[tc.second]] = t;
      }
      StarHead_[tc.second] = t;
    }
  }
  PendingStar_.clear();
}

Simplifier::Support Simplifier::supportOf(int32_t p) const
{
  Support s;
  if (!Removed_[p])
  {
    s.n = 1;
    s.face = Out_[p] / 3;
    s.v[0] = p;
    s.w[0] = 1.0;
    return s;
  }
  s.face = PointFace_[p];
  for (int i = 0; i < 3; ++i)
  {
    if (PointBary_[3 * p + i] != 0.0)
    {
      s.v[s.n] = F_[3 * s.face + i];
      s.w[s.n] = PointBary_[3 * p + i];
      ++s.n;
    }
  }
  return s;
}

/// The chart of the star of base vertex s: its ring flattened by z^a (3D angles at s scaled to
/// sum to 2 pi, radii to the power a), or, where one angle is more than half the total and a
/// face would fold, the ring on the unit circle at equal angles. Cached until the star changes;
/// the ring alone (chart = false) is cheap, the flat positions are computed when first needed.
const Simplifier::StarChart& Simplifier::star(int32_t s, bool chart) const
{
  if (StarSlot_[s] < 0)
  {
    StarSlot_[s] = static_cast<int32_t>(Stars_.size());
    Stars_.emplace_back();
  }
  StarChart& star = Stars_[StarSlot_[s]];
  if (StarValid_[s] == 0)
  {
    StarValid_[s] = 1;
    star.he.clear();
    star.ring.clear();
    const int32_t start = Out_[s];
    int32_t h = start;
    do
    {
      star.he.push_back(h);
      star.ring.push_back(F_[nextHe(h)]);
      h = this->nextOutgoing(h);
    } while (h != start);
  }
  if (!chart || StarValid_[s] == 2)
  {
    return star;
  }
  StarValid_[s] = 2;
  star.z.clear();
  flattenStar(
    this->pos(s), star.ring.size(), [&](size_t i) { return this->pos(star.ring[i]); }, StarTheta_,
    StarRadius_, star.z);
  return star;
}

/// Position of a point with this support in the chart of the star of s, or false when the point
/// is outside the closed star of s.
bool Simplifier::inStar(int32_t s, const Support& sup, P2* at) const
{
  const StarChart& star = this->star(s, at != nullptr);
  const int d = static_cast<int>(star.ring.size());
  int index[3], n = 0;
  P2 p{ 0.0, 0.0 };
  for (int i = 0; i < sup.n; ++i)
  {
    if (sup.v[i] == s)
    {
      continue;
    }
    const auto it = std::find(star.ring.begin(), star.ring.end(), sup.v[i]);
    if (it == star.ring.end())
    {
      return false;
    }
    index[n] = static_cast<int>(it - star.ring.begin());
    if (at)
    {
      p.x += sup.w[i] * star.z[index[n]].x;
      p.y += sup.w[i] * star.z[index[n]].y;
    }
    ++n;
  }
  if (outsideStar(n, index, d))
  {
    return false;
  }
  if (at)
  {
    *at = p;
  }
  return true;
}

/// inStar for the three corners of a triangle at once: the ring is looked up once per support
/// vertex, and the chart is only computed when all three are in the closed star.
bool Simplifier::inStar(int32_t s, const Support sup[3], P2 at[3]) const
{
  const StarChart& ring = this->star(s, false);
  const int32_t* ids = ring.ring.data();
  const int d = static_cast<int>(ring.ring.size());
  int index[3][3];
  for (int j = 0; j < 3; ++j)
  {
    int n = 0, found[3];
    for (int i = 0; i < sup[j].n; ++i)
    {
      index[j][i] = -1;
      if (sup[j].v[i] == s)
      {
        continue;
      }
      int r = 0;
      while (r < d && ids[r] != sup[j].v[i])
      {
        ++r;
      }
      if (r == d)
      {
        return false;
      }
      index[j][i] = found[n++] = r;
    }
    if (outsideStar(n, found, d))
    {
      return false;
    }
  }
  const StarChart& star = this->star(s, true);
  for (int j = 0; j < 3; ++j)
  {
    at[j] = { 0.0, 0.0 };
    for (int i = 0; i < sup[j].n; ++i)
    {
      if (index[j][i] >= 0)
      {
        at[j].x += sup[j].w[i] * star.z[index[j][i]].x;
        at[j].y += sup[j].w[i] * star.z[index[j][i]].y;
      }
    }
  }
  return true;
}

/// Whether input triangle t keeps its orientation in the base domain, drawn with straight sides
/// in the chart the later stages use for it (Feng et al. section 5.1: base triangles unfolded
/// into the plane): corners in one closed base face (a corner's face, or the face their
/// supports span) -> that face's barycentric plane; each in one of two faces about a base edge
/// -> the two 3D triangles unfolded about the edge; otherwise the star chart of the
/// lowest-numbered base vertex whose closed star holds all three (its id in *starCentre, else
/// -1). A triangle no chart holds straddles the base complex and is invalid too.
bool Simplifier::triangleValid(int64_t t, int32_t* starCentre) const
{
  if (starCentre)
  {
    *starCentre = -1;
  }
  // Fast paths. Three base vertices that still make face t, as in the input (a fine base
  // complex): the rules below would find t and draw it as its own barycentric triangle, area
  // 1/2. Three removed vertices stored in the same face, by far the most common case on a coarse
  // base complex: the rules below would pick that face's barycentric plane too.
  const int32_t a = Tri_[3 * t], b = Tri_[3 * t + 1], c = Tri_[3 * t + 2];
  if (!Removed_[a] && !Removed_[b] && !Removed_[c] && FaceAlive_[t] && F_[3 * t] == a &&
    F_[3 * t + 1] == b && F_[3 * t + 2] == c)
  {
    return true;
  }
  if (Removed_[a] && Removed_[b] && Removed_[c] && PointFace_[a] == PointFace_[b] &&
    PointFace_[a] == PointFace_[c])
  {
    const P2 p[3] = { { PointBary_[3 * a + 1], PointBary_[3 * a + 2] },
      { PointBary_[3 * b + 1], PointBary_[3 * b + 2] },
      { PointBary_[3 * c + 1], PointBary_[3 * c + 2] } };
    return clearlyPositive(p);
  }
  TriangleImages im;
  this->gatherImages(t, im);
  bool valid = false;
  if (this->drawnInFace(im, &valid) || this->drawnInHinge(im, &valid))
  {
    return valid;
  }
  return this->drawnInStar(im, starCentre);
}

/// The supports of t's corners and the base vertices they name, sorted by input id without
/// repeats (insertion sort: at most 9 ids).
inline void Simplifier::gatherImages(int64_t t, TriangleImages& im) const
{
  int na = 0;
  for (int i = 0; i < 3; ++i)
  {
    im.sup[i] = this->supportOf(Tri_[3 * t + i]);
    for (int j = 0; j < im.sup[i].n; ++j)
    {
      im.all[na++] = im.sup[i].v[j];
    }
  }
  // Swapped down one step at a time: a shifting loop would become a call to memmove.
  int32_t* all = im.all;
  int32_t rank[9];
  int n = 0;
  for (int i = 0; i < na; ++i)
  {
    const int32_t x = all[i], r = VertexRank_[x];
    bool repeat = false;
    for (int m = 0; m < n; ++m)
    {
      repeat |= rank[m] == r;
    }
    if (repeat)
    {
      continue;
    }
    all[n] = x;
    rank[n] = r;
    for (int j = n; j > 0 && rank[j - 1] > rank[j]; --j)
    {
      std::swap(all[j - 1], all[j]);
      std::swap(rank[j - 1], rank[j]);
    }
    ++n;
  }
  im.na = n;
}

/// The base face spanned by three distinct images when no corner's face holds them all (-1:
/// none): no support spans a face then; one on an edge leaves only the face across that edge,
/// else the faces around all[0] are searched.
inline int32_t Simplifier::spannedFace(const TriangleImages& im) const
{
  int edgeSupport = -1;
  for (int i = 0; i < 3; ++i)
  {
    edgeSupport = im.sup[i].n == 2 ? i : edgeSupport;
  }
  int32_t face = -1;
  if (edgeSupport >= 0)
  {
    const Support& q = im.sup[edgeSupport];
    for (int e = 0; e < 3; ++e)
    {
      const int32_t a = F_[3 * q.face + e], b = F_[3 * q.face + (e + 1) % 3];
      if ((a == q.v[0] && b == q.v[1]) || (a == q.v[1] && b == q.v[0]))
      {
        face = Opp_[3 * q.face + e] / 3;
      }
    }
    return face;
  }
  const int32_t start = Out_[im.all[0]];
  int32_t h = start;
  do
  {
    if (this->faceHas(h / 3, im.all[1]) && this->faceHas(h / 3, im.all[2]))
    {
      face = h / 3;
    }
    h = this->nextOutgoing(h);
  } while (h != start);
  return face;
}

/// The face that holds every image, a corner's face or else the face the images span, drawn as
/// its barycentric plane (the right triangle (0,0) (1,0) (0,1)); false when there is none.
inline bool Simplifier::drawnInFace(const TriangleImages& im, bool* valid) const
{
  // Whether face f holds every image: na <= 3 distinct vertices, all among its corners.
  auto holdsAll = [&](int32_t f)
  {
    if (im.na > 3)
    {
      return false;
    }
    const int32_t c0 = F_[3 * f], c1 = F_[3 * f + 1], c2 = F_[3 * f + 2];
    for (int i = 0; i < im.na; ++i)
    {
      if (im.all[i] != c0 && im.all[i] != c1 && im.all[i] != c2)
      {
        return false;
      }
    }
    return true;
  };
  for (int i = 0; i < 4; ++i)
  {
    const int32_t f = i < 3 ? im.sup[i].face : (im.na == 3 ? this->spannedFace(im) : -1);
    if (f < 0 || !holdsAll(f))
    {
      continue;
    }
    P2 p[3];
    for (int j = 0; j < 3; ++j)
    {
      p[j] = { 0.0, 0.0 };
      for (int m = 0; m < im.sup[j].n; ++m)
      {
        p[j].x += im.sup[j].v[m] == F_[3 * f + 1] ? im.sup[j].w[m] : 0.0;
        p[j].y += im.sup[j].v[m] == F_[3 * f + 2] ? im.sup[j].w[m] : 0.0;
      }
    }
    *valid = clearlyPositive(p);
    return true;
  }
  return false;
}

/// The first hinge that holds every image (at most 4 distinct ones), among the edges of the
/// corners' faces: two base faces f = (a, b, c) and g = (b, a, d) about their edge (a, b), with
/// each image in the closed face f or g. The triangle is drawn in the two 3D faces unfolded
/// about (a, b); false when no hinge holds it.
inline bool Simplifier::drawnInHinge(const TriangleImages& im, bool* valid) const
{
  const Support* sup = im.sup;
  for (int i = 0; i < 3 && im.na <= 4; ++i)
  {
    const int32_t f = sup[i].face;
    for (int e = 0; e < 3; ++e)
    {
      const int32_t h = Opp_[3 * f + e];
      const int32_t a = F_[3 * f + e], b = F_[3 * f + (e + 1) % 3], c = F_[3 * f + (e + 2) % 3];
      const int32_t d = F_[prevHe(h)];
      // Four shared vertices are not enough when another pair of faces spans them too.
      auto inHinge = [&](const Support& q)
      {
        bool inF = true, inG = true;
        for (int m = 0; m < q.n; ++m)
        {
          inF &= q.v[m] == a || q.v[m] == b || q.v[m] == c;
          inG &= q.v[m] == a || q.v[m] == b || q.v[m] == d;
        }
        return inF || inG;
      };
      if (!inHinge(sup[0]) || !inHinge(sup[1]) || !inHinge(sup[2]))
      {
        continue;
      }
      P2 p[3];
      if (this->unfoldHinge(sup, a, b, c, d, p))
      {
        *valid = clearlyPositive(p);
        return true;
      }
    }
  }
  return false;
}

/// The images drawn in base faces (a, b, c) and (b, a, d) unfolded about (a, b): a at the
/// origin, b on the positive x axis, c above it, d below. False when a corner at a or b sits
/// where the two faces together turn by pi or more: a triangle there can be positive in the
/// unfolding and yet lie outside it (its angle at that end is the reflex rest of the plane), so
/// the hinge does not hold it. tracePaths draws the side opposite such a corner in the corner's
/// star, whose z^a angles differ from the 3D ones; the star chart decides, as it does there.
inline bool Simplifier::unfoldHinge(
  const Support sup[3], int32_t a, int32_t b, int32_t c, int32_t d, P2 p[3]) const
{
  const V3 pa = this->pos(a), pb = this->pos(b);
  const double L = norm(sub(pb, pa));
  auto apex = [&](int32_t x, double sign)
  {
    const double ax = norm(sub(this->pos(x), pa)), bx = norm(sub(this->pos(x), pb));
    const double px = (ax * ax - bx * bx + L * L) / (2 * L);
    return P2{ px, sign * std::sqrt(std::max(0.0, ax * ax - px * px)) };
  };
  const int32_t ids[4] = { a, b, c, d };
  const P2 at[4] = { { 0.0, 0.0 }, { L, 0.0 }, apex(c, 1.0), apex(d, -1.0) };
  bool reflexCorner = false;
  for (int j = 0; j < 3; ++j)
  {
    if (sup[j].n == 1 && (sup[j].v[0] == a || sup[j].v[0] == b))
    {
      // Convex at a when d, a, c turn left; at b when c, b, d do.
      reflexCorner |= sup[j].v[0] == a ? !(orient(at[0], at[3], at[2]) > 0.0)
                                       : !(orient(at[1], at[2], at[3]) > 0.0);
    }
  }
  if (reflexCorner)
  {
    return false;
  }
  for (int j = 0; j < 3; ++j)
  {
    p[j] = { 0.0, 0.0 };
    for (int m = 0; m < sup[j].n; ++m)
    {
      const int k = static_cast<int>(std::find(ids, ids + 4, sup[j].v[m]) - ids);
      p[j].x += sup[j].w[m] * at[k].x;
      p[j].y += sup[j].w[m] * at[k].y;
    }
  }
  return true;
}

/// The star chart of the lowest-numbered base vertex whose closed star holds every image; false
/// when none does (the triangle straddles the base complex).
inline bool Simplifier::drawnInStar(const TriangleImages& im, int32_t* starCentre) const
{
  const Support* sup = im.sup;
  for (int i = 0; i < im.na; ++i)
  {
    // A corner inside a face is only in the stars of that face's vertices: no ring needed.
    const int32_t c = im.all[i];
    auto corner = [&](const Support& q)
    { return q.n < 3 || q.v[0] == c || q.v[1] == c || q.v[2] == c; };
    if (!corner(sup[0]) || !corner(sup[1]) || !corner(sup[2]))
    {
      continue;
    }
    P2 p[3];
    if (this->inStar(c, sup, p))
    {
      if (starCentre)
      {
        *starCentre = c;
      }
      return clearlyPositive(p);
    }
  }
  return false;
}
} // namespace base_complex
} // namespace detail
} // namespace tc
