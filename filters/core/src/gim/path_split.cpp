// SPDX-License-Identifier: BSD-3-Clause
// Step 2 of the path tracer (path_tracer.h): an input triangle cut along the base edges that
// cross it. The routes of its sides and the base faces its corners span give the cyclic word of
// transitions round its boundary; the word reduces like nested brackets into chords, the chords
// cut the triangle into convex pieces, one base face each, and each piece is triangulated by a
// fan. A triangle that cannot be cut has one of its sides drawn in another chart (repair).
#include "gim/path_tracer.h"

namespace tc
{
namespace detail
{
namespace tracing
{
namespace
{
/// Cuts the polygon of `polys` (indices into the boundary) that holds boundary points ip and iq
/// in two along the chord ip-iq; the error, or nullptr.
const char* cutPolygon(std::vector<std::vector<size_t>>& polys, size_t ip, size_t iq)
{
  for (size_t k = 0; k < polys.size(); ++k)
  {
    std::vector<size_t>& poly = polys[k];
    const auto ia = std::find(poly.begin(), poly.end(), ip);
    const auto ib = std::find(poly.begin(), poly.end(), iq);
    if (ia == poly.end() || ib == poly.end())
    {
      continue;
    }
    const size_t n = poly.size();
    const size_t i = static_cast<size_t>(ia - poly.begin());
    const size_t j = static_cast<size_t>(ib - poly.begin());
    if ((i + 1) % n == j || (j + 1) % n == i)
    {
      return "a path would run along its side";
    }
    std::vector<size_t> first, second;
    for (size_t x = i;; x = (x + 1) % n)
    {
      first.push_back(poly[x]);
      if (x == j)
      {
        break;
      }
    }
    for (size_t x = j;; x = (x + 1) % n)
    {
      second.push_back(poly[x]);
      if (x == i)
      {
        break;
      }
    }
    poly = std::move(first);
    polys.push_back(std::move(second));
    return nullptr;
  }
  return "two paths cross inside it";
}

/// The corner of convex polygon `poly` (indices into at) whose fan has the largest smallest
/// triangle (by twice its area): no needle where a wider fan exists.
size_t fanApex(const std::vector<size_t>& poly, const std::vector<V3>& at)
{
  const size_t n = poly.size();
  size_t apex = 0;
  double bestMin = -1.0;
  for (size_t a = 0; a < n && n > 3; ++a)
  {
    double smallest = std::numeric_limits<double>::infinity();
    for (size_t k = 1; k + 1 < n; ++k)
    {
      const V3& pa = at[poly[a]];
      smallest = std::min(
        smallest, norm(cross(sub(at[poly[(a + k) % n]], pa), sub(at[poly[(a + k + 1) % n]], pa))));
    }
    if (smallest > bestMin)
    {
      bestMin = smallest;
      apex = a;
    }
  }
  return apex;
}
} // namespace

/// The boundary of an input triangle, counter-clockwise, and what cuts it.
struct Tracer::Boundary
{
  /// A chord between boundary points p and q (indices into cycle).
  struct Chord
  {
    size_t p, q;
    int32_t left, right; ///< left: face of the piece holding directed p -> q
  };

  std::vector<int64_t> cycle;   ///< corners and Steiner points (points as in Transition)
  std::vector<V3> at;           ///< their positions
  std::vector<int32_t> arc;     ///< the base face of the arc after each
  std::vector<Transition> word; ///< the transitions between base faces, in order

  /// Pairs each transition with the one that undoes it (same base edge, faces swapped), like
  /// brackets; the word of a disk without a base vertex inside reduces to nothing. Returns the
  /// index in `word` of a transition left without its pair, -1 if none is.
  int reduce(std::vector<std::pair<int, int>>& pairs) const
  {
    auto undoes = [](const Transition& a, const Transition& b)
    { return a.edge == b.edge && a.from == b.to && a.to == b.from && a.point != b.point; };
    std::vector<int> stack;
    for (int j = 0; j < static_cast<int>(word.size()); ++j)
    {
      if (!stack.empty() && undoes(word[stack.back()], word[j]))
      {
        pairs.emplace_back(stack.back(), j);
        stack.pop_back();
      }
      else
      {
        stack.push_back(j);
      }
    }
    size_t lo = 0, hi = stack.size();
    while (hi - lo >= 2 && undoes(word[stack[hi - 1]], word[stack[lo]]))
    {
      pairs.emplace_back(stack[hi - 1], stack[lo]);
      ++lo;
      --hi;
    }
    return lo != hi ? stack[lo] : -1;
  }

  /// Cuts the triangle along the chord of every pair, into polygons of indices into `cycle`. A
  /// chord from transition P (X -> Y) to Q (Y -> X) has face Y on the side of the boundary from P
  /// counter-clockwise to Q, and X on the other side. The chords go to out.links. Returns the
  /// error, or nullptr.
  const char* cut(const std::vector<std::pair<int, int>>& pairs, std::vector<Chord>& chords,
    std::vector<std::vector<size_t>>& polys, Pieces& out) const
  {
    const size_t m = cycle.size();
    auto indexOf = [&](int64_t point)
    { return static_cast<size_t>(std::find(cycle.begin(), cycle.end(), point) - cycle.begin()); };
    polys.assign(1, std::vector<size_t>());
    for (size_t k = 0; k < m; ++k)
    {
      polys[0].push_back(k);
    }
    for (const auto& pq : pairs)
    {
      const Transition& P = word[pq.first];
      const Transition& Q = word[pq.second];
      const size_t ip = indexOf(P.point), iq = indexOf(Q.point);
      chords.push_back({ ip, iq, P.from, P.to });
      out.links.push_back({ P.edge, P.point, Q.point });
      if (const char* error = cutPolygon(polys, ip, iq))
      {
        return error;
      }
    }
    return nullptr;
  }

  /// The base face of polygon `poly`, from every boundary arc and chord side around it; -1 if
  /// they disagree.
  int32_t pieceFace(const std::vector<size_t>& poly, const std::vector<Chord>& chords) const
  {
    const size_t m = cycle.size();
    int32_t label = -1;
    const size_t n = poly.size();
    for (size_t k = 0; k < n; ++k)
    {
      const size_t x = poly[k], y = poly[(k + 1) % n];
      int32_t l = (x + 1) % m == y ? arc[x] : -1;
      for (const Chord& c : chords)
      {
        l = c.p == x && c.q == y ? c.left : (c.p == y && c.q == x ? c.right : l);
      }
      if (l < 0 || (label >= 0 && l != label))
      {
        return -1;
      }
      label = l;
    }
    return label;
  }
};

/// The one base face that holds the images of the three corners of input triangle f, -1 if none
/// does, -2 if two do (all three images on one base edge).
int32_t Tracer::commonFace(int32_t f) const
{
  Support s[3];
  int best = 0;
  for (int i = 0; i < 3; ++i)
  {
    s[i] = this->support(Mesh_.triangles[3 * f + i]);
    best = s[i].n > s[best].n ? i : best;
  }
  int32_t candidates[2] = { -1, -1 };
  if (s[best].n == 3)
  {
    candidates[0] = Base_.vertexBaseFace[Mesh_.triangles[3 * f + best]];
  }
  else if (s[best].n == 2)
  {
    candidates[0] = this->faceOf(s[best].v[0], s[best].v[1]);
    candidates[1] = this->faceOf(s[best].v[1], s[best].v[0]);
  }
  else
  {
    candidates[0] = this->faceOf(s[0].v[0], s[1].v[0]);
    candidates[1] = this->faceOf(s[1].v[0], s[0].v[0]);
  }
  int32_t found = -1;
  int count = 0;
  for (int32_t g : candidates)
  {
    if (g >= 0 && this->faceHolds(g, s[0]) && this->faceHolds(g, s[1]) && this->faceHolds(g, s[2]))
    {
      found = g;
      ++count;
    }
  }
  return count == 2 ? -2 : found;
}

/// Cuts input triangle f along the base edges that cross it; out.error says why it cannot be.
void Tracer::split(int32_t f, Pieces& out) const
{
  out = Pieces();
  Route routes[3];
  for (int i = 0; i < 3; ++i)
  {
    this->routeOf(3 * f + i, routes[i]);
    if (routes[i].kind == Route::kNoChart)
    {
      out.error = "no chart holds its side " + std::to_string(this->from(3 * f + i)) + "-" +
        std::to_string(this->to(3 * f + i));
      return;
    }
  }
  Boundary b;
  if (!this->traceBoundary(f, routes, b, out))
  {
    return;
  }
  this->orderCuts(f, out);
  std::vector<std::pair<int, int>> pairs;
  const int open = b.reduce(pairs);
  if (open >= 0)
  {
    out.error = "base edge " + this->edgeName(b.word[open].edge) +
      " enters it and does not leave it (it would hold a base vertex)";
    return;
  }
  std::vector<Boundary::Chord> chords;
  std::vector<std::vector<size_t>> polys;
  if (const char* error = b.cut(pairs, chords, polys, out))
  {
    out.error = error;
    return;
  }
  for (const std::vector<size_t>& poly : polys)
  {
    const int32_t label = b.pieceFace(poly, chords);
    if (label < 0)
    {
      out.error = "a piece of it lies in two base faces";
      return;
    }
    // A convex piece: the fan whose smallest triangle is largest.
    const size_t n = poly.size();
    const size_t apex = fanApex(poly, b.at);
    for (size_t k = 1; k + 1 < n; ++k)
    {
      out.triangles.push_back(b.cycle[poly[apex]]);
      out.triangles.push_back(b.cycle[poly[(apex + k) % n]]);
      out.triangles.push_back(b.cycle[poly[(apex + k + 1) % n]]);
      out.patch.push_back(label);
    }
  }
}

/// The boundary of f, counter-clockwise, from the routes of its sides: each corner with the
/// transitions it spans, then the crossings of the side after it. False (out.error set) where a
/// corner and its sides disagree.
inline bool Tracer::traceBoundary(int32_t f, const Route routes[3], Boundary& b, Pieces& out) const
{
  for (int i = 0; i < 3; ++i)
  {
    const int32_t c = Mesh_.triangles[3 * f + i];
    if (!this->addCorner(c, routes[(i + 2) % 3].last, routes[i].first, b, out) ||
      !this->addSide(3 * f + i, routes[i], b, out))
    {
      return false;
    }
  }
  return true;
}

/// Corner c, entered from base face `in` (the side before it) and left into `outFace` (the side
/// after it), with the transitions between those faces round its image.
inline bool Tracer::addCorner(
  int32_t c, int32_t in, int32_t outFace, Boundary& b, Pieces& out) const
{
  const Support s = this->support(c);
  if (s.n == 3)
  {
    if (in != Base_.vertexBaseFace[c] || outFace != in)
    {
      out.error = "its sides leave point " + std::to_string(c) + " in other base faces";
      return false;
    }
  }
  else if (s.n == 2)
  {
    const int32_t g1 = this->faceOf(s.v[0], s.v[1]), g2 = this->faceOf(s.v[1], s.v[0]);
    if ((in != g1 && in != g2) || (outFace != g1 && outFace != g2))
    {
      out.error = "its sides leave point " + std::to_string(c) + " in other base faces";
      return false;
    }
    if (in != outFace)
    {
      b.word.push_back({ c, this->edgeIndex(s.v[0], s.v[1]), in, outFace });
    }
  }
  else
  {
    // At a base vertex the corner spans the sectors from `in` clockwise to `out`: walking
    // round the boundary, the corner is passed from the incoming side to the outgoing one.
    const StarChart& st = Stars_[s.v[0]];
    const int d = static_cast<int>(st.ring.size());
    const int jin =
      static_cast<int>(std::find(st.sector.begin(), st.sector.end(), in) - st.sector.begin());
    const int jout =
      static_cast<int>(std::find(st.sector.begin(), st.sector.end(), outFace) - st.sector.begin());
    if (jin == d || jout == d)
    {
      out.error = "its sides leave base vertex " + std::to_string(c) + " through other faces";
      return false;
    }
    for (int j = jin; j != jout; j = (j - 1 + d) % d)
    {
      b.word.push_back(
        { c, this->edgeIndex(s.v[0], st.ring[j]), st.sector[j], st.sector[(j - 1 + d) % d] });
    }
  }
  b.cycle.push_back(c);
  b.at.push_back(this->pos(c));
  b.arc.push_back(outFace);
  return true;
}

/// The crossings of side h (route r, from its start to its end) as Steiner points of the
/// boundary; those of the side whose lower half-edge is h also go to out.cuts.
inline bool Tracer::addSide(int32_t h, const Route& r, Boundary& b, Pieces& out) const
{
  const int32_t key = this->lowerHalfEdge(h);
  const int32_t lo = this->lower(h), hi = this->upper(h);
  const bool forward = this->from(h) == lo;
  const V3 plo = this->pos(lo), phi = this->pos(hi);
  for (int k = 0; k < r.n; ++k)
  {
    const int kc = forward ? k : r.n - 1 - k;
    const double t = forward ? r.c[k].t : 1.0 - r.c[k].t;
    if (r.c[k].from != b.arc.back())
    {
      out.error = "its side " + std::to_string(this->from(h)) + "-" + std::to_string(this->to(h)) +
        " is not one route";
      return false;
    }
    if (h == key)
    {
      out.cuts.emplace_back(key, t);
    }
    b.cycle.push_back(provisional(key, kc));
    b.at.push_back(pointAt(plo, phi, t));
    b.arc.push_back(r.c[k].to);
    b.word.push_back({ provisional(key, kc), r.c[k].edge, r.c[k].from, r.c[k].to });
  }
  return true;
}

/// The cuts of an owned side are kept from the lower vertex to the higher.
inline void Tracer::orderCuts(int32_t f, Pieces& out) const
{
  for (int i = 0; i < 3; ++i)
  {
    const int32_t h = 3 * f + i;
    if (h < Opp_[h] && this->from(h) > this->to(h))
    {
      auto first = std::find_if(out.cuts.begin(), out.cuts.end(),
        [&](const std::pair<int32_t, double>& c) { return c.first == h; });
      std::reverse(first,
        std::find_if(first, out.cuts.end(),
          [&](const std::pair<int32_t, double>& c) { return c.first != h; }));
    }
  }
}

/// Makes input triangle f cuttable by drawing one of its sides (not the edge `keep`, a lower
/// half-edge) in another chart, where the triangle across that side stays cuttable or, down to
/// `depth` levels, can be made so in turn. A thin triangle at a base vertex can be positive in two
/// charts that pass the vertex on opposite sides (the bijection check of buildBaseComplex draws
/// each triangle in one chart only); the first chart of a side may be the wrong one. Triangles
/// whose sides change are added to `changed`; false (charts restored) if nothing works.
bool Tracer::repair(int32_t f, int32_t keep, int depth, std::vector<int32_t>& changed)
{
  auto cuttable = [&](int32_t t)
  {
    Pieces p;
    this->split(t, p);
    return p.error.empty();
  };
  for (int k = 0; k < 3; ++k)
  {
    const int32_t h = 3 * f + k, key = this->lowerHalfEdge(h), g = Opp_[h] / 3;
    if (key == keep || Slot_[g] < 0)
    {
      continue; // the other triangle is inside one base face: the side has no other chart
    }
    const uint8_t old = Choice_[key];
    for (int c = 0; c < 64; ++c)
    {
      if (c == old)
      {
        continue;
      }
      Route r;
      this->route(h, c, r);
      if (r.kind == Route::kNoChart)
      {
        break;
      }
      Choice_[key] = static_cast<uint8_t>(c);
      const size_t mark = changed.size();
      if (cuttable(f) && (cuttable(g) || (depth > 1 && this->repair(g, key, depth - 1, changed))))
      {
        changed.push_back(f);
        changed.push_back(g);
        return true;
      }
      changed.resize(mark);
    }
    Choice_[key] = old;
  }
  return false;
}
} // namespace tracing
} // namespace detail
} // namespace tc
