// SPDX-License-Identifier: BSD-3-Clause
// Step 1 of the path tracer (path_tracer.h): the route of an input edge over the base complex.
// Its ends' images are joined by a straight segment in one chart that holds both: their common
// base face or base edge (direct), two base faces unfolded about their common edge (hingeRoute,
// Feng et al. Fig. 9), or the star of a base vertex flattened by z^a, possibly with the faces
// across its link (starRoute). route() tries the charts in a fixed order and returns the
// choice-th that holds the segment, so that a side whose first chart leaves its triangle uncut
// can be drawn in the next one (Tracer::repair).
#include "gim/path_tracer.h"

#include <cmath>

namespace tc
{
namespace detail
{
namespace tracing
{
namespace
{
/// Barycentrics of p in the triangle at, each from the side opposite its corner (so that a point
/// on the line of a side gets exactly 0 there, unlike 1 - the others); false if the triangle is
/// degenerate or clockwise (b is then meaningless).
bool placedBarycentric(const P2& p, const P2 at[3], double b[3])
{
  const double area = orient(at[0], at[1], at[2]);
  for (int m = 0; m < 3; ++m)
  {
    b[m] = orient(at[(m + 1) % 3], at[(m + 2) % 3], p) / area;
  }
  return area > 0;
}

/// The side through which the segment from barycentrics bp (t = 0) to bq (t = 1) leaves a
/// triangle first, other than the side `entry` it came in by: the index of the corner opposite
/// it, -1 if none; its parameter in tExit (infinite for none).
int exitSide(const double bp[3], const double bq[3], int entry, double& tExit)
{
  int exit = -1;
  tExit = std::numeric_limits<double>::infinity();
  for (int m = 0; m < 3; ++m)
  {
    const double slope = bq[m] - bp[m];
    if (m == entry || !(slope < 0))
    {
      continue;
    }
    const double tm = bp[m] / (bp[m] - bq[m]);
    if (tm < tExit)
    {
      tExit = tm;
      exit = m;
    }
  }
  return exit;
}

/// The index of the corner of c other than a and b.
int cornerOpposite(const int32_t c[3], int32_t a, int32_t b)
{
  int m = -1;
  for (int i = 0; i < 3; ++i)
  {
    m = c[i] != a && c[i] != b ? i : m;
  }
  return m;
}
} // namespace

/// The star of base vertex s flattened by z^a, with the faces across its link unfolded onto it
/// ("placed faces"): placed face k < d is sector k, (s, ring[k], ring[k + 1]); placed face d + j
/// is the outer face across link edge j.
struct Tracer::PlacedFaces
{
  const StarChart& st;
  int32_t s;
  int d; ///< valence of s

  /// Corners and chart positions of placed face k; returns its base face (-1: an outer face that
  /// is in the star itself, not placed).
  int32_t corners(int k, int32_t c[3], P2 at[3]) const
  {
    if (k < d)
    {
      c[0] = s;
      c[1] = st.ring[k];
      c[2] = st.ring[(k + 1) % d];
      at[0] = { 0, 0 };
      at[1] = st.z[k];
      at[2] = st.z[(k + 1) % d];
      return st.sector[k];
    }
    const int j = k - d;
    c[0] = st.ring[(j + 1) % d];
    c[1] = st.ring[j];
    c[2] = st.outerApex[j];
    at[0] = st.z[(j + 1) % d];
    at[1] = st.z[j];
    at[2] = st.apexAt[j];
    return st.outer[j];
  }
  /// The placed face across the side opposite corner m of placed face k (-1: outside the chart).
  int across(int k, int m) const
  {
    if (k < d)
    {
      return m == 0 ? (st.outer[k] >= 0 ? d + k : -1) : (m == 1 ? (k + 1) % d : (k - 1 + d) % d);
    }
    return m == 2 ? k - d : -1;
  }
  /// Whether placed face k holds the image sp; if so, sp's barycentrics b in it and its position.
  bool holds(int k, const Support& sp, double b[3], P2& at) const
  {
    int32_t c[3];
    P2 pos[3];
    if (corners(k, c, pos) < 0)
    {
      return false;
    }
    b[0] = b[1] = b[2] = 0.0;
    at = { 0, 0 };
    for (int i = 0; i < sp.n; ++i)
    {
      const int m = sp.v[i] == c[0] ? 0 : (sp.v[i] == c[1] ? 1 : (sp.v[i] == c[2] ? 2 : -1));
      if (m < 0)
      {
        return false;
      }
      b[m] = sp.w[i];
      at.x += sp.w[i] * pos[m].x;
      at.y += sp.w[i] * pos[m].y;
    }
    return true;
  }
  /// Whether the segment from a point of placed face `start` (barycentrics bs there) to q enters
  /// that face: decided on the exact zeros of the image's barycentrics.
  bool enters(int start, const double bs[3], const P2& q) const
  {
    int32_t c[3];
    P2 at[3];
    corners(start, c, at);
    double bq[3];
    if (!placedBarycentric(q, at, bq))
    {
      return false;
    }
    bool in = true;
    for (int m = 0; m < 3; ++m)
    {
      in &= bs[m] > 0 || bq[m] - bs[m] > 0;
    }
    return in;
  }
};

/// Routes that need no chart: both images in one base face, or on one base edge. False if not.
bool Tracer::direct(const Support& su, const Support& sv, Route& r) const
{
  r.kind = Route::kNoChart;
  r.n = 0;
  r.first = r.last = r.along = -1;
  int32_t all[6];
  int na = 0;
  for (const Support* s : { &su, &sv })
  {
    for (int i = 0; i < s->n; ++i)
    {
      if (std::find(all, all + na, s->v[i]) == all + na)
      {
        all[na++] = s->v[i];
      }
    }
  }
  // Both images on one base edge: the input edge lies on it. The face on its left is fA when
  // it runs from the edge's lower base vertex a towards b, fB when back.
  if (na == 2 && this->faceOf(all[0], all[1]) >= 0)
  {
    const int32_t e = this->edgeIndex(all[0], all[1]);
    const int32_t a = Result_.baseEdges[2 * e], b = Result_.baseEdges[2 * e + 1];
    const double pu = su.weight(b), pv = sv.weight(b);
    if (pu != pv)
    {
      r.kind = Route::kAlong;
      r.along = e;
      r.first = r.last = pv > pu ? this->faceOf(a, b) : this->faceOf(b, a);
    }
    return true; // kNoChart if both are the same point of the edge
  }
  if (na == 3)
  {
    for (const int32_t g : { this->faceOf(all[0], all[1]), this->faceOf(all[1], all[0]) })
    {
      if (g >= 0 && this->faceHas(g, all[2]))
      {
        r.kind = Route::kInFace;
        r.first = r.last = g;
        return true;
      }
    }
  }
  return false;
}

/// Route of the input edge of half-edge h from its lower vertex id u to the higher v (see the
/// top of path_tracer.h), in the choice-th chart that holds it (0: the first; kNoChart when there
/// are not that many). Charts in order: the star of a base vertex that is the third corner of a
/// triangle of the edge (the triangle's corner and its opposite side then turn round that vertex
/// in the same chart); the two faces about a base edge; the star of a base vertex near an end;
/// the other stars, lowest vertex first; those stars again with the faces outside them.
void Tracer::route(int32_t h, int choice, Route& r) const
{
  const int32_t u = this->lower(h), v = this->upper(h);
  const Support su = this->support(u), sv = this->support(v);
  if (this->direct(su, sv, r))
  {
    r.kind = choice == 0 ? r.kind : Route::kNoChart; // the only way
    return;
  }
  int32_t nearby[8];
  int napex = 0;
  const int nnear = this->nearStars(h, su, sv, nearby, napex);
  // The stars of a base vertex at the third corner of a triangle of the edge.
  if (this->tryStars(su, sv, nearby, napex, choice, r))
  {
    return;
  }
  // Two faces unfolded about their common edge.
  if (this->tryHinges(u, su, sv, choice, r))
  {
    return;
  }
  // Stars of a base vertex near an end only when no two faces about a base edge hold both ends.
  // A triangle whose corners lie in two such faces is checked in their unfolding by
  // buildBaseComplex (triangleValid), so its sides must be drawn there too. The z^a star of a
  // base vertex with a narrow cone (a low valence, a stretched ring) can be far from that
  // unfolding, and a side drawn straight in it can pass the vertex through its third face
  // instead of crossing the edge next to it; the triangle then looks as if it held the vertex
  // and cannot be cut.
  if (this->tryStars(su, sv, nearby + napex, nnear - napex, choice, r))
  {
    return;
  }
  // The other stars: one of the images' base vertices or a neighbour of u's.
  if (this->tryOtherStars(su, sv, nearby, nnear, choice, r))
  {
    return;
  }
  r.kind = Route::kNoChart;
  r.n = 0;
}

/// Stars that decide on which side the segment passes a base vertex it comes close to: those of
/// a base vertex at the third corner of a triangle of h's edge (the first napex, ascending), then
/// those of a base vertex with weight 1/2 or more at either end, heaviest first. Returns how many.
inline int Tracer::nearStars(
  int32_t h, const Support& su, const Support& sv, int32_t stars[8], int& napex) const
{
  int n = 0;
  for (const int32_t s : { BaseIndex_[this->to(nextHe(h))], BaseIndex_[this->to(nextHe(Opp_[h]))] })
  {
    if (s >= 0 && std::find(stars, stars + n, s) == stars + n)
    {
      stars[n++] = s;
    }
  }
  std::sort(stars, stars + n);
  napex = n;
  for (const Support* sp : { &su, &sv })
  {
    for (int i = 0; i < sp->n; ++i)
    {
      if (sp->w[i] >= 0.5 && std::find(stars, stars + n, sp->v[i]) == stars + n)
      {
        stars[n++] = sp->v[i];
      }
    }
  }
  std::sort(stars + napex, stars + n,
    [&](int32_t a, int32_t b)
    {
      const double wa = std::max(su.weight(a), sv.weight(a));
      const double wb = std::max(su.weight(b), sv.weight(b));
      return wa > wb || (wa == wb && a < b);
    });
  return n;
}

/// The star charts of stars[0 .. n), each without then with the faces outside it; true once the
/// choice-th chart that holds the segment is found (in r).
inline bool Tracer::tryStars(
  const Support& su, const Support& sv, const int32_t* stars, int n, int& choice, Route& r) const
{
  for (int i = 0; i < n; ++i)
  {
    for (int outside = 0; outside < 2; ++outside)
    {
      if (this->starRoute(su, sv, stars[i], outside == 1, r) && choice-- == 0)
      {
        return true;
      }
    }
  }
  return false;
}

/// Two faces unfolded about their common edge: each base face that holds the image of u (the
/// lower end) with each of its sides; true once the choice-th chart is found.
inline bool Tracer::tryHinges(
  int32_t u, const Support& su, const Support& sv, int& choice, Route& r) const
{
  int32_t faces[64];
  int nf = 0;
  if (su.n == 3)
  {
    faces[nf++] = Base_.vertexBaseFace[u];
  }
  else if (su.n == 2)
  {
    faces[nf++] = this->faceOf(su.v[0], su.v[1]);
    faces[nf++] = this->faceOf(su.v[1], su.v[0]);
  }
  else
  {
    for (int32_t g : Stars_[su.v[0]].sector)
    {
      if (nf < 64)
      {
        faces[nf++] = g;
      }
    }
  }
  for (int i = 0; i < nf; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (this->hingeRoute(su, sv, faces[i], k, r) && choice-- == 0)
      {
        return true;
      }
    }
  }
  return false;
}

/// The other stars, lowest vertex first, all without the faces outside them, then all with
/// them: those of one of the images' base vertices or of a neighbour of u's, except those in
/// tried[0 .. ntried); true once the choice-th chart is found.
inline bool Tracer::tryOtherStars(const Support& su, const Support& sv, const int32_t* tried,
  int ntried, int& choice, Route& r) const
{
  int32_t centres[128];
  int nc = 0;
  for (const Support* sp : { &su, &sv })
  {
    for (int i = 0; i < sp->n; ++i)
    {
      centres[nc++] = sp->v[i];
    }
  }
  for (int i = 0; i < su.n; ++i)
  {
    for (int32_t x : Stars_[su.v[i]].ring)
    {
      if (nc < 128)
      {
        centres[nc++] = x;
      }
    }
  }
  std::sort(centres, centres + nc);
  nc = static_cast<int>(std::unique(centres, centres + nc) - centres);
  for (int outside = 0; outside < 2; ++outside)
  {
    for (int i = 0; i < nc; ++i)
    {
      if (std::find(tried, tried + ntried, centres[i]) == tried + ntried &&
        this->starRoute(su, sv, centres[i], outside == 1, r) && choice-- == 0)
      {
        return true;
      }
    }
  }
  return false;
}

/// Route through base face f (holding u) and the face across its side k (holding v), unfolded
/// into the plane (Feng et al. Fig. 9): one crossing, if the segment meets that side.
inline bool Tracer::hingeRoute(
  const Support& su, const Support& sv, int32_t f, int k, Route& r) const
{
  const std::vector<int32_t>& bt = Base_.baseTriangles;
  const int32_t x = bt[3 * f + k], y = bt[3 * f + (k + 1) % 3], c = bt[3 * f + (k + 2) % 3];
  const int32_t g = this->faceOf(y, x);
  if (!this->faceHolds(g, sv))
  {
    return false;
  }
  const int32_t d = this->thirdCorner(g, x, y);
  // x at 0, y at (L, 0), c above, d below, with the 3D side lengths.
  const V3 px = this->basePos(x), py = this->basePos(y);
  const double L = norm(sub(py, px));
  auto apex = [&](int32_t w, double sign)
  {
    const V3 pw = this->basePos(w);
    const double ax = norm(sub(pw, px)), bx = norm(sub(pw, py));
    const double along = (ax * ax - bx * bx + L * L) / (2 * L);
    return P2{ along, sign * std::sqrt(std::max(0.0, ax * ax - along * along)) };
  };
  const P2 pc = apex(c, 1.0), pd = apex(d, -1.0);
  auto place = [&](const Support& s)
  {
    P2 p{ 0, 0 };
    for (int i = 0; i < s.n; ++i)
    {
      const P2 at = s.v[i] == x ? P2{ 0, 0 } : (s.v[i] == y ? P2{ L, 0 } : (s.v[i] == c ? pc : pd));
      p.x += s.w[i] * at.x;
      p.y += s.w[i] * at.y;
    }
    return p;
  };
  const P2 p = place(su), q = place(sv);
  if (!(p.y > 0 && q.y < 0 && L > 0))
  {
    return false;
  }
  const double t = p.y / (p.y - q.y);
  const double at = p.x + t * (q.x - p.x);
  if (!(at > 0 && at < L && t > 0 && t < 1))
  {
    return false;
  }
  r.kind = Route::kCrossing;
  r.n = 1;
  r.c[0] = { t, this->edgeIndex(x, y), f, g };
  r.first = f;
  r.last = g;
  return true;
}

/// Route through the star of base vertex s flattened by z^a, with the faces across its link
/// unfolded onto it (PlacedFaces). Without `outside`, both ends in the star; with it, at least
/// one outside (tried only when no star holds both ends: the faces outside are unfolded one by
/// one and may overlap, so they are the weaker chart). The segment between the images must not
/// pass through a base vertex nor leave the chart (walkStar).
bool Tracer::starRoute(
  const Support& su, const Support& sv, int32_t s, bool outside, Route& r) const
{
  const StarChart& st = Stars_[s];
  const PlacedFaces chart{ st, s, static_cast<int>(st.ring.size()) };
  const int d = chart.d;
  // The placed faces that hold each end (a few: more than one only on a side or a corner).
  int starts[16], ends[16], ns = 0, nd = 0;
  for (int k = 0; k < 2 * d; ++k)
  {
    double b[3];
    P2 at;
    if (ns < 16 && chart.holds(k, su, b, at))
    {
      starts[ns++] = k;
    }
    if (nd < 16 && chart.holds(k, sv, b, at))
    {
      ends[nd++] = k;
    }
  }
  // Ends in the star, or (outside) at least one end in a face outside it.
  for (int pair = 0; pair < ns * nd; ++pair)
  {
    const int start = starts[pair / nd], end = ends[pair % nd];
    double bs[3], be[3];
    P2 p, q;
    if ((start >= d || end >= d) != outside || end == start)
    {
      continue;
    }
    chart.holds(start, su, bs, p);
    chart.holds(end, sv, be, q);
    if (chart.enters(start, bs, q) && this->walkStar(chart, start, end, sv, p, q, r))
    {
      return true;
    }
  }
  r.n = 0;
  return false;
}

/// Follows the segment from p (in placed face `start`) to q (the image sv, in placed face `end`)
/// from placed face to placed face across their common sides, each crossing into r.c. True (r a
/// kCrossing route) if it reaches a placed face that holds the end, through sides only, after at
/// least one crossing; false if it passes through a corner, leaves the chart or turns back.
inline bool Tracer::walkStar(const PlacedFaces& chart, int start, int end, const Support& sv,
  const P2& p, const P2& q, Route& r) const
{
  int32_t c[3];
  P2 at[3];
  int k = start, n = 0, entry = -1;
  double t = 0.0;
  bool ok = false;
  r.first = chart.corners(start, c, at);
  for (int steps = 0; steps <= 2 * chart.d && n < kMaxCrossings; ++steps)
  {
    const int32_t face = chart.corners(k, c, at);
    // Done in the first placed face that holds the end at the same position.
    double bk[3];
    P2 qk;
    if (k == end || (chart.holds(k, sv, bk, qk) && qk.x == q.x && qk.y == q.y))
    {
      ok = true;
      break;
    }
    double bp[3], bq[3];
    if (!placedBarycentric(p, at, bp) || !placedBarycentric(q, at, bq))
    {
      break;
    }
    double tExit;
    const int exit = exitSide(bp, bq, entry, tExit);
    const int next = exit >= 0 ? chart.across(k, exit) : -1;
    if (next < 0 || !(tExit > t && tExit < 1))
    {
      break;
    }
    // Through a side, not a corner.
    const double b1 = bp[(exit + 1) % 3] + tExit * (bq[(exit + 1) % 3] - bp[(exit + 1) % 3]);
    const double b2 = bp[(exit + 2) % 3] + tExit * (bq[(exit + 2) % 3] - bp[(exit + 2) % 3]);
    int32_t nc[3];
    P2 nat[3];
    const int32_t nextFace = chart.corners(next, nc, nat);
    if (!(b1 > 0 && b2 > 0) || nextFace < 0)
    {
      break;
    }
    r.c[n++] = { tExit, this->edgeIndex(c[(exit + 1) % 3], c[(exit + 2) % 3]), face, nextFace };
    t = tExit;
    // The side we came in by, as a corner index of the next face.
    entry = cornerOpposite(nc, c[(exit + 1) % 3], c[(exit + 2) % 3]);
    k = next;
  }
  if (ok && n > 0)
  {
    r.kind = Route::kCrossing;
    r.n = n;
    r.last = r.c[n - 1].to;
    return true;
  }
  return false;
}

/// Route of half-edge h, from its start to its end, in the chart chosen for its edge.
void Tracer::routeOf(int32_t h, Route& r) const
{
  this->route(h, Choice_[this->lowerHalfEdge(h)], r);
  if (this->from(h) < this->to(h))
  {
    return;
  }
  if (r.kind == Route::kAlong)
  {
    const int32_t a = Result_.baseEdges[2 * r.along], b = Result_.baseEdges[2 * r.along + 1];
    const int32_t fA = this->faceOf(a, b);
    r.first = r.last = r.first == fA ? this->faceOf(b, a) : fA;
    return;
  }
  r.reverse();
}
} // namespace tracing
} // namespace detail
} // namespace tc
