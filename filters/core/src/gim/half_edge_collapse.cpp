// SPDX-License-Identifier: BSD-3-Clause
// Steps 3 and 4 of the base complex (simplifier.h), one half-edge collapse u -> v:
//  - prepare(): the rules of Feng et al. section 5.1 (no feature / non-feature collapse; a
//    feature vertex only moves along its own curve), the link condition, normals and shapes of
//    the new triangles, and the MAPS flattening of u's ring by z^a, in which the fan from v must
//    be a valid triangulation. At a feature vertex each side of the curve is flattened onto a
//    half plane, so the curve is straight in both.
//  - apply(): MAPS reassignment. Every removed vertex stored in u's faces (and u) is placed in
//    the flat ring and located in the new fan; points on the curve through u go onto the new
//    curve edge by arc length (one barycentric exactly 0); a point outside every new triangle by
//    round-off is snapped into the nearest one. Then the corner table is updated.
//  - undo(): everything apply() changed, restored, for a collapse the bijection check rejects.
#include "gim/simplifier.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tc
{
namespace detail
{
namespace base_complex
{
namespace
{
/// Triangle shape 4 sqrt(3) area / (sum of squared sides): 1 equilateral, 0 degenerate.
inline double shapeQuality(const V3& a, const V3& b, const V3& c, const V3& n)
{
  const V3 ab = sub(b, a), bc = sub(c, b), ca = sub(a, c);
  const double s = dot(ab, ab) + dot(bc, bc) + dot(ca, ca);
  return s > 0 ? 2.0 * std::sqrt(3.0) * norm(n) / s : 0.0;
}

/// Closest point of triangle (a, b, c) to p, as barycentrics, and its squared distance.
double closestBarycentric(const P2& p, const P2& a, const P2& b, const P2& c, double w[3])
{
  double inside[3];
  if (barycentric(p, a, b, c, inside) && inside[0] >= 0 && inside[1] >= 0 && inside[2] >= 0)
  {
    std::copy(inside, inside + 3, w);
    return 0.0;
  }
  const P2 corner[3] = { a, b, c };
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i)
  {
    const P2& s = corner[i];
    const P2& t = corner[(i + 1) % 3];
    const double ex = t.x - s.x, ey = t.y - s.y;
    const double len2 = ex * ex + ey * ey;
    double u = len2 > 0 ? ((p.x - s.x) * ex + (p.y - s.y) * ey) / len2 : 0.0;
    u = std::min(1.0, std::max(0.0, u));
    const double dx = s.x + u * ex - p.x, dy = s.y + u * ey - p.y;
    const double d2 = dx * dx + dy * dy;
    if (d2 < best)
    {
      best = d2;
      w[i] = 1.0 - u;
      w[(i + 1) % 3] = u;
      w[(i + 2) % 3] = 0.0;
    }
  }
  return best;
}
} // namespace

/// Gathers the ring of u for the collapse along h0 = u -> v and tests every rule that depends
/// on the current mesh: link condition, valences, feature sides, normals and shapes of the new
/// triangles, and that the new fan from v is a valid triangulation of the flattened ring (the
/// flat polygon is star-shaped from v), which is what makes the MAPS reassignment a bijection.
bool Simplifier::prepare(int32_t u, int32_t h0)
{
  this->gatherRing(u, h0);
  if (K_ < 3 || FaceCount_ <= 4)
  {
    return false;
  }
  if (!this->linkConditionHolds() || !this->findCurveSides())
  {
    return false;
  }
  const double worstOld = this->measureRing();
  return this->newTrianglesAllowed(worstOld) && this->flattenRing() && this->fanTilesRing();
}

/// U_, V_, K_ and the ring: RingHe_[j] = u -> x_j, RingV_[j] = x_j, RingF_[j] its face.
void Simplifier::gatherRing(int32_t u, int32_t h0)
{
  U_ = u;
  V_ = F_[nextHe(h0)];
  RingHe_.clear();
  RingV_.clear();
  RingF_.clear();
  int32_t h = h0;
  do
  {
    RingHe_.push_back(h);
    RingV_.push_back(F_[nextHe(h)]);
    RingF_.push_back(h / 3);
    h = this->nextOutgoing(h);
  } while (h != h0);
  K_ = static_cast<int>(RingV_.size());
}

/// Every vertex keeps valence >= 3 (no tetrahedron collapses into a flat pair of triangles), and
/// the link condition (Dey et al. 1999): u and v share exactly the neighbours x_1 and x_{k-1}.
bool Simplifier::linkConditionHolds()
{
  const int k = K_;
  const int32_t v = V_, x1 = RingV_[1], xl = RingV_[k - 1];
  if (Valence_[v] + k - 4 < 3 || Valence_[x1] - 1 < 3 || Valence_[xl] - 1 < 3)
  {
    return false;
  }
  ++MarkCounter_;
  const int32_t start = Out_[v];
  int32_t g = start;
  do
  {
    Mark_[F_[nextHe(g)]] = MarkCounter_;
    g = this->nextOutgoing(g);
  } while (g != start);
  for (int j = 2; j <= k - 2; ++j)
  {
    if (Mark_[RingV_[j]] == MarkCounter_)
    {
      return false;
    }
  }
  return true;
}

/// M_: at a feature vertex, the ring index of the other curve neighbour w; else K_. Each side of
/// the curve needs two faces (the collapse deletes one on each side); a single face between the
/// two curve edges would be flattened onto the new curve edge.
bool Simplifier::findCurveSides()
{
  const int k = K_;
  M_ = k;
  if (!Feature_[U_])
  {
    return true;
  }
  for (int j = 1; j < k; ++j)
  {
    if (FeatureHe_[RingHe_[j]])
    {
      M_ = j;
      break;
    }
  }
  return M_ >= 2 && M_ <= k - 2;
}

/// Theta_ and Radius_: the 3D angle of every ring face at u and the distance to every ring
/// vertex. Returns the worst shape among the ring faces.
double Simplifier::measureRing()
{
  const int k = K_;
  const V3 pu = this->pos(U_);
  Theta_.resize(k);
  Radius_.resize(k);
  double worstOld = 1.0;
  for (int j = 0; j < k; ++j)
  {
    const V3 a = sub(this->pos(RingV_[j]), pu);
    const V3 b = sub(this->pos(RingV_[(j + 1) % k]), pu);
    const V3 n = cross(a, b);
    Theta_[j] = std::atan2(norm(n), dot(a, b));
    Radius_[j] = norm(a);
    worstOld =
      std::min(worstOld, shapeQuality(pu, this->pos(RingV_[j]), this->pos(RingV_[(j + 1) % k]), n));
  }
  return worstOld;
}

/// 3D: no normal flip, no degenerate triangle. The shape bound is relative: a new triangle may
/// not be worse than minTriangleQuality nor than the worst triangle it replaces.
bool Simplifier::newTrianglesAllowed(double worstOld) const
{
  const int k = K_;
  const V3 pu = this->pos(U_), pv = this->pos(V_);
  const double minQuality = std::min(Options_.minTriangleQuality, worstOld);
  const double minCos = std::cos(Options_.maxNormalChange * kPi / 180.0);
  for (int j = 1; j <= k - 2; ++j)
  {
    const V3 pa = this->pos(RingV_[j]), pb = this->pos(RingV_[j + 1]);
    const V3 nOld = cross(sub(pa, pu), sub(pb, pu));
    const V3 nNew = cross(sub(pa, pv), sub(pb, pv));
    const double lo = norm(nOld), ln = norm(nNew);
    if (!(dot(nOld, nNew) > minCos * lo * ln) || !(ln > 0))
    {
      return false;
    }
    if (shapeQuality(pv, pa, pb, nNew) < minQuality)
    {
      return false;
    }
  }
  return true;
}

/// The flat domain: the whole ring in ZA_ (v at index 0 and k), or, for a feature collapse, side
/// A (x_0 .. x_m) in ZA_ and side B (x_m .. x_k) in ZB_, each on a half plane; L1_ and L2_.
bool Simplifier::flattenRing()
{
  const int k = K_;
  ZA_.resize(k + 1);
  ZB_.resize(k + 1);
  if (M_ == k)
  {
    if (!this->flattenChain(0, k, 2.0 * kPi, true, ZA_))
    {
      return false;
    }
    ZA_[k] = ZA_[0];
    return true;
  }
  if (!this->flattenChain(0, M_, kPi, false, ZA_) || !this->flattenChain(M_, k, kPi, false, ZB_))
  {
    return false;
  }
  L1_ = Radius_[0];
  L2_ = Radius_[M_];
  return true;
}

/// Maps ring vertices x_begin..x_end (faces begin..end-1) into the plane with the conformal map
/// z^a of Lee et al. (MAPS, section 3.2): polar angles are scaled by a = span / (their total
/// 3D angle) and radii raised to the power a. span = 2 pi closes the full ring. At a feature
/// vertex each side of the curve is mapped onto the upper half plane (span = pi, the curve on
/// the real axis) with radii kept (power 1): both sides then put a curve point at the same
/// place, the arc-length position that placeOnFeature gives it, so curve points and the points
/// beside the curve move together. Returns false when a face would fold over (its scaled angle
/// reaches pi).
bool Simplifier::flattenChain(
  int begin, int end, double span, bool conformal, std::vector<P2>& z) const
{
  double total = 0.0, meanRadius = 0.0;
  for (int j = begin; j < end; ++j)
  {
    total += Theta_[j];
  }
  for (int j = begin; j <= end; ++j)
  {
    meanRadius += Radius_[j % K_];
  }
  meanRadius /= (end - begin + 1);
  if (!(total > 0) || !(meanRadius > 0))
  {
    return false;
  }
  const double a = span / total;
  double phi = 0.0;
  for (int j = begin; j <= end; ++j)
  {
    if (j < end && !(a * Theta_[j] < kPi * (1.0 - 1e-9)))
    {
      return false;
    }
    const double rho =
      conformal ? std::pow(Radius_[j % K_] / meanRadius, a) : Radius_[j % K_] / meanRadius;
    const double angle = j == end ? span : a * phi;
    z[j] = { rho * std::cos(angle), rho * std::sin(angle) };
    if (j < end)
    {
      phi += Theta_[j];
    }
  }
  return true;
}

/// The fan from v must tile the flat polygon: every new flat triangle counter-clockwise, with a
/// margin so that later barycentric solves stay well conditioned.
bool Simplifier::fanTilesRing() const
{
  const int k = K_;
  const double minSine = 1e-6;
  for (int j = 1; j <= k - 2; ++j)
  {
    const bool sideB = j >= M_;
    const std::vector<P2>& z = sideB ? ZB_ : ZA_;
    const P2 zv = sideB ? ZB_[k] : ZA_[0];
    const P2& za = z[j];
    const P2& zb = z[j + 1];
    const double la = std::hypot(za.x - zv.x, za.y - zv.y);
    const double lb = std::hypot(zb.x - zv.x, zb.y - zv.y);
    if (!(orient(zv, za, zb) > minSine * la * lb))
    {
      return false;
    }
  }
  return true;
}

/// Stores point p in new face j = (v, x_j, x_{j+1}) with these barycentrics (corner order of the
/// face follows the old one: u's corner now holds v).
void Simplifier::store(int32_t p, int j, double bv, double bj, double bj1)
{
  const int32_t f = RingF_[j];
  this->setPoint(p, RingHe_[j], bv, bj, bj1);
  Next_[p] = Head_[f];
  Head_[f] = p;
}

/// A point of the feature curve through u goes onto the new curve edge (v, w), at arc-length
/// parameter t from v (MAPS's 1-D parameterization of feature curves): exactly on the base edge.
void Simplifier::placeOnFeature(int32_t p, double t)
{
  t = std::min(1.0, std::max(0.0, t));
  // Side A's last new face (v, x_{m-1}, w) carries the edge v -> ... -> w.
  this->store(p, M_ - 1, 1.0 - t, 0.0, t);
}

/// Locates a flat point among the new faces of one side (fan from v) and stores it there. A point
/// outside all of them (round-off in the z^a map or in earlier steps) is snapped to the nearest
/// new triangle and nudged a hair inside: the flip repair of MAPS.
void Simplifier::locateFlat(int32_t p, const P2& P, int side, int guess)
{
  const int k = K_;
  const int lo = side == 0 ? 1 : M_;
  const int hi = side == 0 ? std::min(M_, k - 1) - 1 : k - 2;
  const std::vector<P2>& z = side == 0 ? ZA_ : ZB_;
  const P2 zv = side == 0 ? ZA_[0] : ZB_[k];
  guess = std::min(hi, std::max(lo, guess));
  double w[3];
  double bestMin = -std::numeric_limits<double>::infinity();
  int best = -1;
  double bestW[3] = { 1, 0, 0 };
  for (int n = 0; n <= hi - lo; ++n)
  {
    const int i = n == 0 ? guess : (lo + n - 1 < guess ? lo + n - 1 : lo + n);
    if (!barycentric(P, zv, z[i], z[i + 1], w))
    {
      continue;
    }
    const double m = std::min(w[0], std::min(w[1], w[2]));
    if (m > bestMin)
    {
      bestMin = m;
      best = i;
      std::copy(w, w + 3, bestW);
      if (m >= 0.0)
      {
        break;
      }
    }
  }
  if (best >= 0 && bestMin >= -kInsideSlack)
  {
    this->store(p, best, std::max(0.0, bestW[0]), std::max(0.0, bestW[1]), std::max(0.0, bestW[2]));
    return;
  }
  ++Snapped_;
  double bestD = std::numeric_limits<double>::infinity();
  for (int i = lo; i <= hi; ++i)
  {
    const double d = closestBarycentric(P, zv, z[i], z[i + 1], w);
    if (d < bestD)
    {
      bestD = d;
      best = i;
      std::copy(w, w + 3, bestW);
    }
  }
  const double nudge = 1e-9;
  this->store(p, best, (1 - nudge) * bestW[0] + nudge / 3, (1 - nudge) * bestW[1] + nudge / 3,
    (1 - nudge) * bestW[2] + nudge / 3);
}

/// New (face, barycentric) of point p, which lay in old face j of the ring (j = -1: p is u).
void Simplifier::relocate(int32_t p, int j)
{
  const int k = K_;
  const bool featureCollapse = M_ < k;
  const double t0 = L1_ / (L1_ + L2_);
  if (j < 0)
  {
    if (featureCollapse)
    {
      this->placeOnFeature(p, t0);
    }
    else
    {
      this->locateFlat(p, P2{ 0.0, 0.0 }, 0, 1);
    }
    return;
  }
  const int c = RingHe_[j] % 3;
  const double* b = &PointBary_[3 * p];
  const double bu = b[c], bj = b[(c + 1) % 3], bj1 = b[(c + 2) % 3];
  if (bu == 0.0)
  {
    // On the link edge (x_j, x_{j+1}), which survives: keep its 1-D coordinate exactly.
    if (j == 0)
    {
      this->store(p, 1, bj, bj1, 0.0);
    }
    else if (j == k - 1)
    {
      this->store(p, k - 2, bj1, 0.0, bj);
    }
    else
    {
      this->store(p, j, 0.0, bj, bj1);
    }
    return;
  }
  if (featureCollapse && Feature_[p] && (bj == 0.0 || bj1 == 0.0))
  {
    // On curve edge (u, x): x = v sits at ring index 0 (= k), w at index m.
    const int xi = bj == 0.0 ? j + 1 : j;
    const double bx = bj == 0.0 ? bj1 : bj;
    if (xi % k == 0)
    {
      this->placeOnFeature(p, bu * t0);
      return;
    }
    if (xi == M_)
    {
      this->placeOnFeature(p, t0 + bx * (1.0 - t0));
      return;
    }
  }
  const int side = featureCollapse && j >= M_ ? 1 : 0;
  const std::vector<P2>& z = side == 0 ? ZA_ : ZB_;
  const P2 P{ bj * z[j].x + bj1 * z[j + 1].x, bj * z[j].y + bj1 * z[j + 1].y };
  this->locateFlat(p, P, side, j);
}

/// Performs the collapse prepared for u: MAPS reassignment of every point in the ring's faces (and
/// of u), then the corner-table update. Everything it changes can be restored by undo().
void Simplifier::apply(int32_t u)
{
  this->reassignPoints(u);
  this->removeFaces();
}

/// MAPS: takes every point out of the ring's faces (keeping its old barycentrics in OldBary_ for
/// undo), then puts it, and u, into the new faces.
void Simplifier::reassignPoints(int32_t u)
{
  Points_.clear();
  OldBary_.clear();
  for (int j = 0; j < K_; ++j)
  {
    const int32_t f = RingF_[j];
    for (int32_t p = Head_[f]; p >= 0; p = Next_[p])
    {
      Points_.emplace_back(p, j);
      OldBary_.push_back(PointBary_[3 * p]);
      OldBary_.push_back(PointBary_[3 * p + 1]);
      OldBary_.push_back(PointBary_[3 * p + 2]);
    }
    Head_[f] = -1;
  }
  Points_.emplace_back(u, -1);
  for (const auto& pj : Points_)
  {
    this->relocate(pj.first, pj.second);
  }
  Removed_[u] = 1;
}

/// Corner table: drops faces 0 and k-1, glues their outer twins, renames u to v; what it
/// overwrites goes to UndoOpp_, UndoFeature_ and UndoOut_.
void Simplifier::removeFaces()
{
  const int k = K_;
  const int32_t u = U_, v = V_;
  const int32_t h0 = RingHe_[0];
  const int32_t h1 = Opp_[h0];
  const int32_t A = Opp_[nextHe(h0)], B = Opp_[prevHe(h0)];
  const int32_t C = Opp_[nextHe(h1)], D = Opp_[prevHe(h1)];
  UndoFeature_[0] = FeatureHe_[A];
  UndoFeature_[1] = FeatureHe_[B];
  UndoFeature_[2] = FeatureHe_[C];
  UndoFeature_[3] = FeatureHe_[D];
  UndoOpp_[0] = A;
  UndoOpp_[1] = B;
  UndoOpp_[2] = C;
  UndoOpp_[3] = D;
  Opp_[A] = B;
  Opp_[B] = A;
  Opp_[C] = D;
  Opp_[D] = C;
  FeatureHe_[A] = FeatureHe_[B] = FeatureHe_[A] | FeatureHe_[B];
  FeatureHe_[C] = FeatureHe_[D] = FeatureHe_[C] | FeatureHe_[D];
  for (int j = 1; j <= k - 2; ++j)
  {
    F_[RingHe_[j]] = v;
  }
  FaceAlive_[RingF_[0]] = 0;
  FaceAlive_[RingF_[k - 1]] = 0;
  FaceCount_ -= 2;
  const int32_t x1 = RingV_[1], xl = RingV_[k - 1];
  UndoOut_[0] = Out_[v];
  UndoOut_[1] = Out_[x1];
  UndoOut_[2] = Out_[xl];
  Out_[v] = B;
  Out_[x1] = A;
  Out_[xl] = C;
  Valence_[v] += k - 4;
  --Valence_[x1];
  --Valence_[xl];
  Valence_[u] = 0;
  StarValid_[u] = 0;
  for (int j = 0; j < k; ++j)
  {
    StarValid_[RingV_[j]] = 0;
  }
}

void Simplifier::undo()
{
  this->restoreFaces();
  this->restorePoints();
}

/// The corner table as it was before removeFaces.
void Simplifier::restoreFaces()
{
  const int k = K_;
  const int32_t u = U_, v = V_;
  const int32_t h0 = RingHe_[0];
  const int32_t h1 = Opp_[h0];
  const int32_t A = UndoOpp_[0], B = UndoOpp_[1], C = UndoOpp_[2], D = UndoOpp_[3];
  Opp_[A] = nextHe(h0);
  Opp_[B] = prevHe(h0);
  Opp_[C] = nextHe(h1);
  Opp_[D] = prevHe(h1);
  FeatureHe_[A] = UndoFeature_[0];
  FeatureHe_[B] = UndoFeature_[1];
  FeatureHe_[C] = UndoFeature_[2];
  FeatureHe_[D] = UndoFeature_[3];
  for (int j = 1; j <= k - 2; ++j)
  {
    F_[RingHe_[j]] = u;
  }
  FaceAlive_[RingF_[0]] = 1;
  FaceAlive_[RingF_[k - 1]] = 1;
  FaceCount_ += 2;
  const int32_t x1 = RingV_[1], xl = RingV_[k - 1];
  Out_[v] = UndoOut_[0];
  Out_[x1] = UndoOut_[1];
  Out_[xl] = UndoOut_[2];
  Valence_[v] -= k - 4;
  ++Valence_[x1];
  ++Valence_[xl];
  Valence_[u] = k;
  StarValid_[u] = 0;
  for (int j = 0; j < k; ++j)
  {
    StarValid_[RingV_[j]] = 0;
  }
}

/// Every point back in its old face with its old barycentrics; u is a base vertex again.
void Simplifier::restorePoints()
{
  const int32_t u = U_;
  Removed_[u] = 0;
  for (int j = 0; j < K_; ++j)
  {
    Head_[RingF_[j]] = -1;
  }
  for (size_t i = 0; i + 1 < Points_.size(); ++i)
  {
    const int32_t p = Points_[i].first;
    const int32_t f = RingF_[Points_[i].second];
    PointFace_[p] = f;
    std::copy(&OldBary_[3 * i], &OldBary_[3 * i] + 3, &PointBary_[3 * p]);
    Next_[p] = Head_[f];
    Head_[f] = p;
  }
  PointFace_[u] = -1;
}
} // namespace base_complex
} // namespace detail
} // namespace tc
