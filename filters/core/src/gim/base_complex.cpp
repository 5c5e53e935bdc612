// SPDX-License-Identifier: BSD-3-Clause
// The base complex of Feng et al. 2010 section 5.1: quadric half-edge collapses with the MAPS
// parameterization of Lee et al. 1998. run() makes these steps, each in its own file
// (simplifier.h):
//  1. Validate and link (corner_table.cpp): corner table of the input, closed-manifold checks,
//     feature flags. Vertices and faces are renumbered in a spatially coherent order; ties and
//     "lowest-numbered" rules still compare input ids, so the result does not depend on it.
//  2. Quadrics and queue (collapse_queue.cpp): Garland-Heckbert quadrics, area-weighted, plus
//     feature-edge planes; a lazy priority queue of half-edge collapses u -> v, cheapest first,
//     ties by input vertex id (deterministic).
//  3. prepare() (half_edge_collapse.cpp): the rules of section 5.1, the link condition, normals
//     and shapes of the new triangles, and the flat ring of u by z^a, in which the fan from v
//     must be a valid triangulation.
//  4. apply() (half_edge_collapse.cpp): MAPS reassignment of every point stored in u's faces,
//     and of u, into the new fan; then the corner table is updated.
//  5. movedTrianglesValid() (bijection_check.cpp): every input triangle the collapse touched
//     keeps its orientation in the charts of the base domain, or the collapse is undone.
//     Steps 3-5 repeat (collapseLoop, below) until targetFaces is reached or every remaining
//     collapse is refused.
//  6. repairFlips() (flip_repair.cpp): a last check of every input triangle, with
//     parameter-domain smoothing of the rare leftovers; then output(), in input ids.
#include "tc/gim/base_complex.h"

#include "gim/simplifier.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace tc
{
namespace detail
{
namespace base_complex
{
namespace
{
/// BaseComplexOptions::maxError stops the simplification only once the base complex has at most
/// one face per this many input points (64 input triangles each on average): under the geometry
/// images' default budget of one sample per point, a chart then averages 32 samples (level 3
/// has 45), where smaller charts would be left with a few samples each.
constexpr int64_t kPointsPerBoundedFace = 32;
} // namespace

BaseComplexResult Simplifier::run(const Progress& progress)
{
  const Progress setup = progress.sub(0.0, 0.1);
  const Progress simplify = progress.sub(0.1, 0.9);
  const Progress repair = progress.sub(0.9, 1.0);
  // 1. Validate and link: done by the constructor.
  // 2. Quadrics, the state of the collapses, and the queue.
  this->initQuadrics();
  this->initState();
  this->buildQueue();
  setup.report(1.0);
  // 3-5. Collapses, cheapest first: prepare, apply, check the bijection (or undo).
  BaseComplexResult result;
  this->collapseLoop(simplify, result);
  simplify.report(1.0);
  // 6. Flip repair, then the output in input ids.
  const int64_t invalid = this->repairFlips(repair);
  BaseComplexResult out = this->output();
  out.collapses = result.collapses;
  out.maxCollapseError = result.maxCollapseError;
  out.reachedTarget = FaceCount_ <= Options_.targetFaces;
  out.snappedPoints = Snapped_;
  out.invalidTriangles = invalid;
  progress.report(1.0);
  return out;
}

/// Every vertex a base vertex with no queue entry, no point stored in any face, no star chart.
void Simplifier::initState()
{
  FaceAlive_.assign(NumFaces_, 1);
  FaceCount_ = NumFaces_;
  Removed_.assign(NumVertices_, 0);
  Key_.assign(NumVertices_, std::numeric_limits<double>::infinity());
  Mark_.assign(NumVertices_, 0);
  Head_.assign(NumFaces_, -1);
  Next_.assign(NumVertices_, -1);
  PointFace_.assign(NumVertices_, -1);
  PointBary_.assign(3 * static_cast<size_t>(NumVertices_), 0.0);
  TriMark_.assign(NumFaces_, 0);
  StarHead_.assign(NumVertices_, -1);
  TriStar_.assign(NumFaces_, -1);
  TriStarPrev_.assign(NumFaces_, -1);
  TriStarNext_.assign(NumFaces_, -1);
  StarSlot_.assign(NumVertices_, -1);
  StarValid_.assign(NumVertices_, 0);
}

/// Pops vertices until the base complex has targetFaces faces or the queue is empty. The error
/// bound never leaves more than one face per kPointsPerBoundedFace input points: on a coarse
/// input it would leave charts of a few samples each. Vertices whose collapses it refused wait
/// in `deferred`; should the simplification end above that count, the bound is lifted until the
/// count is reached, and they are queued again.
void Simplifier::collapseLoop(const Progress& progress, BaseComplexResult& result)
{
  const int64_t target = std::max<int64_t>(4, Options_.targetFaces);
  const int64_t boundedFaces = NumVertices_ / kPointsPerBoundedFace;
  bool bounded = Options_.maxError > 0;
  std::vector<int32_t> deferred;
  const double toRemove = std::max<double>(1.0, static_cast<double>(NumFaces_ - target));
  int64_t pops = 0;
  while (FaceCount_ > target)
  {
    if (Heap_.empty())
    {
      if (!bounded || FaceCount_ <= boundedFaces || deferred.empty())
      {
        break;
      }
      bounded = false;
      this->requeueDeferred(deferred);
      continue;
    }
    if (!bounded && Options_.maxError > 0 && FaceCount_ <= boundedFaces)
    {
      bounded = true; // the count is reached: the bound stops the rest
    }
    if ((++pops & 4095) == 0)
    {
      progress.report(std::min(1.0, (NumFaces_ - FaceCount_) / toRemove));
    }
    const HeapEntry top = Heap_.top();
    Heap_.pop();
    const int32_t u = top.vertex;
    if (Removed_[u] || top.cost != Key_[u])
    {
      continue;
    }
    Key_[u] = std::numeric_limits<double>::infinity();
    if (this->collapseCheapest(u, top.cost, bounded, deferred, result))
    {
      this->requeueAfter(V_);
    }
  }
}

/// Makes the cheapest collapse of u, popped at `key`, that is within the bound and passes every
/// check; false when none is made (u is then queued again at its next cost, or deferred).
bool Simplifier::collapseCheapest(
  int32_t u, double key, bool bounded, std::vector<int32_t>& deferred, BaseComplexResult& result)
{
  this->gatherCandidates(u);
  for (size_t c = 0; c < Candidates_.size(); ++c)
  {
    const Candidate cand = Candidates_[c];
    if (cand.cost > key)
    {
      // The key was a lower bound, or cheaper collapses of u were rejected: wait for the turn of
      // this one.
      this->push(u, cand.cost);
      return false;
    }
    const double error = cand.cost /
      std::max(Area_[u] + Area_[cand.target], std::numeric_limits<double>::min()) / Diag2_;
    if (bounded && error > Options_.maxError)
    {
      deferred.push_back(u);
      continue;
    }
    if (!this->tryCollapse(u, cand.halfEdge))
    {
      continue;
    }
    ++result.collapses;
    result.maxCollapseError = std::max(result.maxCollapseError, error);
    return true;
  }
  return false;
}

/// Steps 3 and 4 for the collapse along h = u -> v: prepare, apply, check the bijection and
/// undo, or commit (the star users, v's quadric and area).
bool Simplifier::tryCollapse(int32_t u, int32_t h)
{
  if (!this->prepare(u, h))
  {
    return false;
  }
  this->apply(u);
  if (Options_.checkBijection && !this->movedTrianglesValid())
  {
    this->undo();
    return false;
  }
  this->commitStarUsers();
  Quadric_[V_].add(Quadric_[u]);
  Area_[V_] += Area_[u];
  return true;
}

/// The deferred vertices queued again (the bound is lifted), each once: a vertex is deferred
/// again each time it is popped and refused.
void Simplifier::requeueDeferred(std::vector<int32_t>& deferred)
{
  std::sort(deferred.begin(), deferred.end());
  deferred.erase(std::unique(deferred.begin(), deferred.end()), deferred.end());
  for (int32_t v : deferred)
  {
    if (!Removed_[v] && !Pinned_[v])
    {
      this->queueCheapest(v);
    }
  }
  deferred.clear();
}

/// Everything in input order and input ids.
BaseComplexResult Simplifier::output() const
{
  BaseComplexResult r;
  std::vector<int32_t> baseIndex(NumVertices_, -1);
  for (int32_t input = 0; input < NumVertices_; ++input)
  {
    const int32_t v = VertexOf_[input];
    if (!Removed_[v])
    {
      baseIndex[v] = static_cast<int32_t>(r.baseVertices.size());
      r.baseVertices.push_back(input);
    }
  }
  std::vector<int32_t> faceIndex(NumFaces_, -1);
  for (int32_t input = 0; input < NumFaces_; ++input)
  {
    const int32_t f = FaceOf_[input];
    if (!FaceAlive_[f])
    {
      continue;
    }
    faceIndex[f] = static_cast<int32_t>(r.baseTriangles.size() / 3);
    for (int i = 0; i < 3; ++i)
    {
      r.baseTriangles.push_back(baseIndex[F_[3 * f + i]]);
      r.baseEdgeIsFeature.push_back(FeatureHe_[3 * f + i]);
    }
  }
  r.vertexBaseFace.resize(NumVertices_);
  r.vertexBarycentric.assign(3 * static_cast<size_t>(NumVertices_), 0.0);
  for (int32_t input = 0; input < NumVertices_; ++input)
  {
    const int32_t v = VertexOf_[input];
    if (Removed_[v])
    {
      r.vertexBaseFace[input] = faceIndex[PointFace_[v]];
      std::copy(&PointBary_[3 * v], &PointBary_[3 * v] + 3, &r.vertexBarycentric[3 * input]);
    }
    else
    {
      const int32_t h = Out_[v];
      r.vertexBaseFace[input] = faceIndex[h / 3];
      r.vertexBarycentric[3 * input + h % 3] = 1.0;
    }
  }
  return r;
}
} // namespace base_complex
} // namespace detail

BaseComplexResult buildBaseComplex(const TriMesh& mesh, const std::vector<uint8_t>& featureVertex,
  const std::vector<uint8_t>& cornerVertex, const std::vector<int32_t>& featureEdges,
  const BaseComplexOptions& options, const Progress& progress)
{
  detail::base_complex::Simplifier simplifier(
    mesh, featureVertex, cornerVertex, featureEdges, options);
  return simplifier.run(progress);
}
} // namespace tc
