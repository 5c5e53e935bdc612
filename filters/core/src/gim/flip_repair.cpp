// SPDX-License-Identifier: BSD-3-Clause
// Step 6 of the base complex (simplifier.h), flip repair (Lee et al. 1998; Feng et al. section
// 5.1 "we detect and fix any triangle flips in the parametric domain"): a last check of every
// input triangle, and parameter-domain smoothing of the rare leftovers.
#include "gim/simplifier.h"

#include <algorithm>

namespace tc
{
namespace detail
{
namespace base_complex
{
/// The z^a maps of successive collapses bend straight lines, so a thin input triangle can come
/// out folded, or, where the base complex is still about as fine as the input, stretched over
/// more than one star. Every invalid triangle is found, and the non-feature vertices of invalid
/// triangles are smoothed in the parameter domain, sweep after sweep, widening to their
/// neighbours when a sweep makes no progress. Returns how many triangles are still invalid.
int64_t Simplifier::repairFlips(const Progress& progress)
{
  std::vector<uint8_t> invalid(NumFaces_, 0);
  std::vector<int32_t> badList;
  for (int32_t t = 0; t < NumFaces_; ++t)
  {
    if (!this->triangleValid(t))
    {
      invalid[t] = 1;
      badList.push_back(t);
    }
  }
  progress.report(0.5);
  std::vector<int32_t> movable;
  std::vector<uint8_t> inSet(NumVertices_, 0);
  int ring = 0;
  const int kSweeps = 40;
  for (int sweep = 0; sweep < kSweeps && !badList.empty(); ++sweep)
  {
    this->gatherMovable(badList, ring, inSet, movable);
    bool moved = false;
    for (int32_t p : movable)
    {
      moved |= this->smooth(p);
      inSet[p] = 0;
    }
    const size_t before = badList.size();
    this->reevaluate(movable, invalid, badList);
    ring = (moved && badList.size() < before) ? 0 : std::min(ring + 1, 4);
  }
  progress.report(1.0);
  return static_cast<int64_t>(badList.size());
}

/// The points one sweep smooths, by input id: the removed non-feature corners of the invalid
/// triangles, widened by `ring` rings of neighbours; inSet marks them.
void Simplifier::gatherMovable(const std::vector<int32_t>& badList, int ring,
  std::vector<uint8_t>& inSet, std::vector<int32_t>& movable) const
{
  auto add = [&](int32_t p)
  {
    if (Removed_[p] && !Feature_[p] && !inSet[p])
    {
      inSet[p] = 1;
      movable.push_back(p);
    }
  };
  movable.clear();
  for (int32_t t : badList)
  {
    for (int i = 0; i < 3; ++i)
    {
      add(Tri_[3 * t + i]);
    }
  }
  for (int r = 0; r < ring; ++r)
  {
    const size_t n = movable.size();
    for (size_t i = 0; i < n; ++i)
    {
      for (int32_t s = InOffsets_[movable[i]]; s < InOffsets_[movable[i] + 1]; ++s)
      {
        add(Tri_[nextHe(InHe_[s])]);
      }
    }
  }
  std::sort(movable.begin(), movable.end(),
    [&](int32_t a, int32_t b) { return VertexRank_[a] < VertexRank_[b]; });
}

/// The triangles around the movable points checked again; badList keeps the invalid ones,
/// ascending, once each.
void Simplifier::reevaluate(const std::vector<int32_t>& movable, std::vector<uint8_t>& invalid,
  std::vector<int32_t>& badList) const
{
  for (int32_t p : movable)
  {
    for (int32_t s = InOffsets_[p]; s < InOffsets_[p + 1]; ++s)
    {
      const int32_t t = InHe_[s] / 3;
      const uint8_t now = !this->triangleValid(t);
      if (now && !invalid[t])
      {
        badList.push_back(t);
      }
      invalid[t] = now;
    }
  }
  badList.erase(
    std::remove_if(badList.begin(), badList.end(), [&](int32_t t) { return !invalid[t]; }),
    badList.end());
  std::sort(badList.begin(), badList.end());
  badList.erase(std::unique(badList.begin(), badList.end()), badList.end());
}

int Simplifier::countInvalidAround(int32_t p) const
{
  int bad = 0;
  for (int32_t s = InOffsets_[p]; s < InOffsets_[p + 1]; ++s)
  {
    bad += !this->triangleValid(InHe_[s] / 3);
  }
  return bad;
}

/// One step of parameter-domain smoothing (the untangling half of MAPS's flip repair): moves p
/// to the mean of its mesh neighbours in the star chart that holds them (Tutte's barycentric
/// embedding, locally), and keeps the move only if fewer triangles around p are invalid.
bool Simplifier::smooth(int32_t p)
{
  const int before = this->countInvalidAround(p);
  if (before == 0)
  {
    return false;
  }
  int32_t centre = -1;
  P2 mean{ 0, 0 };
  if (!this->smoothingChart(p, &centre, &mean))
  {
    return false;
  }
  const StarChart& star = this->star(centre, true);
  const int d = static_cast<int>(star.ring.size());
  for (int i = 0; i < d; ++i)
  {
    double w[3];
    if (!barycentric(mean, P2{ 0, 0 }, star.z[i], star.z[(i + 1) % d], w) ||
      std::min(w[0], std::min(w[1], w[2])) < -kInsideSlack)
    {
      continue;
    }
    const int32_t oldFace = PointFace_[p];
    const double oldBary[3] = { PointBary_[3 * p], PointBary_[3 * p + 1], PointBary_[3 * p + 2] };
    this->setPoint(p, star.he[i], std::max(0.0, w[0]), std::max(0.0, w[1]), std::max(0.0, w[2]));
    if (this->countInvalidAround(p) < before)
    {
      return true;
    }
    PointFace_[p] = oldFace;
    std::copy(oldBary, oldBary + 3, &PointBary_[3 * p]);
    return false;
  }
  return false;
}

/// The chart for smoothing p: the lowest-numbered base vertex whose closed star holds the most
/// of p's mesh neighbours, and their mean position in it; false when no star holds any.
bool Simplifier::smoothingChart(int32_t p, int32_t* centre, P2* mean) const
{
  int32_t candidates[64];
  int nc = 0;
  for (int32_t s = InOffsets_[p]; s < InOffsets_[p + 1] && nc < 61; ++s)
  {
    const Support q = this->supportOf(Tri_[nextHe(InHe_[s])]);
    for (int j = 0; j < q.n; ++j)
    {
      candidates[nc++] = q.v[j];
    }
  }
  std::sort(candidates, candidates + nc,
    [&](int32_t a, int32_t b) { return VertexRank_[a] < VertexRank_[b]; });
  nc = static_cast<int>(std::unique(candidates, candidates + nc) - candidates);
  int32_t bestS = -1;
  int bestCount = 0;
  P2 bestMean{ 0, 0 };
  for (int c = 0; c < nc; ++c)
  {
    int count = 0;
    P2 sum{ 0, 0 };
    for (int32_t s = InOffsets_[p]; s < InOffsets_[p + 1]; ++s)
    {
      P2 at;
      if (this->inStar(candidates[c], this->supportOf(Tri_[nextHe(InHe_[s])]), &at))
      {
        ++count;
        sum.x += at.x;
        sum.y += at.y;
      }
    }
    if (count > bestCount)
    {
      bestCount = count;
      bestS = candidates[c];
      bestMean = { sum.x / count, sum.y / count };
    }
  }
  *centre = bestS;
  *mean = bestMean;
  return bestS >= 0;
}
} // namespace base_complex
} // namespace detail
} // namespace tc
