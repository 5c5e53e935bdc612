// SPDX-License-Identifier: BSD-3-Clause
// tracePaths (Feng et al. 2010, section 5.1, Fig. 9): the steps of the path tracer in order, and
// which input triangles are cut. How the tracing works: the top of path_tracer.h.
#include "tc/gim/path_tracing.h"

#include "gim/path_tracer.h"

#include "tc/common/errors.h"
#include "tc/common/parallel.h"

namespace tc
{
namespace detail
{
namespace tracing
{
PatchMesh Tracer::run(const Progress& progress)
{
  // The input, its half-edge twins, the base complex and the star charts of its vertices.
  this->validate(progress.sub(0.0, 0.05));
  this->buildTopology(progress.sub(0.05, 0.2));
  this->buildBase();
  this->buildStars();
  if (static_cast<int64_t>(3 * NF_) * kMaxCrossings >= std::numeric_limits<int64_t>::max() / 2)
  {
    throw InputError("tracePaths: the mesh is too large");
  }
  // 1. The input edges that lie on a base edge, and the triangles inside one base face, which
  // keep it; the others are cut.
  this->findEdgesOnBase(progress.sub(0.2, 0.3));
  this->findWholeTriangles(progress.sub(0.3, 0.4));
  // 2. Cut them along the routes of their sides (steps 1 and 2 of path_tracer.h).
  this->cutTriangles(progress.sub(0.4, 0.7));
  // 3. Steiner points, numbered by input edge (its lower half-edge) and along it.
  const int64_t ns = this->numberSteinerPoints();
  this->placeSteinerPoints(ns, progress.sub(0.7, 0.75));
  // 4. One path per base edge: its chords and the input edges on it, chained from end to end.
  this->chainPaths(progress.sub(0.75, 0.8));
  // 5. Output triangles in input order: each input triangle, or its pieces.
  this->writeTriangles(ns, progress.sub(0.8, 1.0));
  return std::move(Result_);
}

/// AlongEdge_: the base edge each input edge lies on.
void Tracer::findEdgesOnBase(const Progress& progress)
{
  const int32_t nh = 3 * NF_;
  AlongEdge_.assign(nh, -1);
  tc::parallel_for(
    nh,
    [&](int64_t i)
    {
      const int32_t h = static_cast<int32_t>(i);
      Route r;
      if (h < Opp_[h] &&
        this->direct(this->support(this->from(h)), this->support(this->to(h)), r) &&
        r.kind == Route::kAlong)
      {
        AlongEdge_[h] = r.along;
      }
    },
    progress);
}

/// Label_: the base face of each input triangle that lies inside one and has no side on a base
/// edge; Cut_ and Slot_: the others, which are cut.
void Tracer::findWholeTriangles(const Progress& progress)
{
  Label_.assign(NF_, -1);
  tc::parallel_for(
    NF_,
    [&](int64_t i)
    {
      const int32_t f = static_cast<int32_t>(i);
      const int32_t g = this->commonFace(f);
      bool along = false;
      for (int k = 0; k < 3; ++k)
      {
        along |= AlongEdge_[this->lowerHalfEdge(3 * f + k)] >= 0;
      }
      Label_[f] = g >= 0 && !along ? g : -1;
    },
    progress);
  Cut_.clear();
  Slot_.assign(NF_, -1);
  for (int32_t f = 0; f < NF_; ++f)
  {
    if (Label_[f] < 0)
    {
      Slot_[f] = static_cast<int32_t>(Cut_.size());
      Cut_.push_back(f);
    }
  }
}

/// Pieces_ of every triangle of Cut_, each side in its first chart; repair() handles the few that
/// cannot be cut so.
void Tracer::cutTriangles(const Progress& progress)
{
  Choice_.assign(3 * static_cast<size_t>(NF_), 0);
  Pieces_.clear();
  Pieces_.resize(Cut_.size());
  tc::parallel_for(
    static_cast<int64_t>(Cut_.size()), [&](int64_t i) { this->split(Cut_[i], Pieces_[i]); },
    progress);
  std::vector<int32_t> changed;
  for (size_t i = 0; i < Cut_.size(); ++i)
  {
    if (!Pieces_[i].error.empty())
    {
      // An earlier repair may have fixed it.
      this->split(Cut_[i], Pieces_[i]);
      if (!Pieces_[i].error.empty())
      {
        this->repair(Cut_[i], -1, 3, changed);
      }
    }
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  for (int32_t f : changed)
  {
    this->split(f, Pieces_[Slot_[f]]);
  }
  for (size_t i = 0; i < Cut_.size(); ++i)
  {
    if (!Pieces_[i].error.empty())
    {
      throw UntraceableError("input triangle " + std::to_string(Cut_[i]) +
          " cannot be cut along the base edges: " + Pieces_[i].error,
        kNotOneToOne);
    }
  }
}
} // namespace tracing
} // namespace detail

PatchMesh tracePaths(const TriMesh& mesh, const BaseComplexResult& base, const Progress& progress)
{
  detail::tracing::Tracer tracer(mesh, base);
  return tracer.run(progress);
}
} // namespace tc
