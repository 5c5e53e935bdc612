// SPDX-License-Identifier: BSD-3-Clause
// Step 1 of the base complex (simplifier.h): the input checked for a closed oriented manifold,
// renumbered in a spatially coherent order, and linked into a corner table with the feature
// flags of Feng et al. section 5.1.
#include "gim/simplifier.h"

#include "tc/common/errors.h"

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

namespace tc
{
namespace detail
{
namespace base_complex
{
namespace
{
/// Morton (Z-order) code of point p, 21 bits per axis over the box [lo, hi].
uint64_t mortonCode(const double* p, const double lo[3], const double hi[3])
{
  uint32_t q[3];
  for (int c = 0; c < 3; ++c)
  {
    const double t = hi[c] > lo[c] ? (p[c] - lo[c]) / (hi[c] - lo[c]) : 0.0;
    q[c] = t > 0 ? static_cast<uint32_t>(std::min(t, 1.0) * 2097151.0) : 0u;
  }
  uint64_t code = 0;
  for (int b = 20; b >= 0; --b)
  {
    for (int c = 0; c < 3; ++c)
    {
      code = (code << 1) | ((q[c] >> b) & 1u);
    }
  }
  return code;
}
} // namespace

/// Twins are found through per-vertex lists (no sort). A vertex is on a feature when flagged or
/// when a feature edge ends there, and pinned (never removed) at a corner or where a number of
/// feature edges other than 2 meet (junctions, curve ends).
void Simplifier::validateAndLink(const std::vector<uint8_t>& featureVertex,
  const std::vector<uint8_t>& cornerVertex, const std::vector<int32_t>& featureEdges)
{
  this->checkSizes(featureVertex, cornerVertex, featureEdges);
  this->checkTriangles();
  this->reorder();
  F_ = Tri_;
  std::vector<int32_t> outTarget;
  this->linkOutgoing(outTarget);
  this->linkTwins(outTarget);
  this->linkFans();
  this->flagFeatures(featureVertex, cornerVertex, featureEdges, outTarget);
}

/// Array shapes and sizes; sets NumVertices_ and NumFaces_.
void Simplifier::checkSizes(const std::vector<uint8_t>& featureVertex,
  const std::vector<uint8_t>& cornerVertex, const std::vector<int32_t>& featureEdges)
{
  if (Mesh_.points.size() % 3 != 0 || Mesh_.triangles.size() % 3 != 0)
  {
    throw InputError(
      "buildBaseComplex: points and triangles must be flat #V x 3 and #F x 3 arrays");
  }
  if (Mesh_.numPoints() >= std::numeric_limits<int32_t>::max() / 2 ||
    Mesh_.triangles.size() >= static_cast<size_t>(std::numeric_limits<int32_t>::max()))
  {
    throw InputError("buildBaseComplex: the mesh is too large for 32-bit half-edge ids");
  }
  NumVertices_ = static_cast<int32_t>(Mesh_.numPoints());
  NumFaces_ = static_cast<int32_t>(Mesh_.numTriangles());
  if (NumFaces_ < 4)
  {
    throw InputError("buildBaseComplex: the mesh needs at least 4 triangles (a closed surface)");
  }
  if (!featureVertex.empty() && featureVertex.size() != static_cast<size_t>(NumVertices_))
  {
    throw InputError("buildBaseComplex: featureVertex must be empty or have one entry per point");
  }
  if (!cornerVertex.empty() && cornerVertex.size() != static_cast<size_t>(NumVertices_))
  {
    throw InputError("buildBaseComplex: cornerVertex must be empty or have one entry per point");
  }
  if (featureEdges.size() % 2 != 0)
  {
    throw InputError("buildBaseComplex: featureEdges must be a flat #E x 2 array");
  }
}

/// Every corner an existing point, no corner repeated.
void Simplifier::checkTriangles() const
{
  for (int32_t f = 0; f < NumFaces_; ++f)
  {
    const int32_t a = Mesh_.triangles[3 * f], b = Mesh_.triangles[3 * f + 1],
                  c = Mesh_.triangles[3 * f + 2];
    if (a < 0 || b < 0 || c < 0 || a >= NumVertices_ || b >= NumVertices_ || c >= NumVertices_)
    {
      throw InputError(
        "buildBaseComplex: triangle " + std::to_string(f) + " refers to a missing point");
    }
    if (a == b || b == c || c == a)
    {
      throw InputError("buildBaseComplex: triangle " + std::to_string(f) +
        " repeats a corner; run tcMeshPreparation to drop degenerate triangles");
    }
  }
}

/// Vertices sorted along a Morton (Z-order) curve of their positions, faces by their lowest
/// internal vertex (a stable counting sort), ties by input id.
void Simplifier::reorder()
{
  const int32_t nv = NumVertices_, nf = NumFaces_;
  const std::vector<double>& P = Mesh_.points;
  double lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 };
  boundingBox(P.data(), nv, lo, hi);
  std::vector<std::pair<uint64_t, int32_t>> key(nv);
  for (int32_t v = 0; v < nv; ++v)
  {
    key[v] = { mortonCode(&P[3 * v], lo, hi), v };
  }
  std::sort(key.begin(), key.end());
  VertexRank_.resize(nv);
  VertexOf_.resize(nv);
  Points3_.resize(3 * static_cast<size_t>(nv));
  for (int32_t v = 0; v < nv; ++v)
  {
    const int32_t input = key[v].second;
    VertexRank_[v] = input;
    VertexOf_[input] = v;
    std::copy(&P[3 * input], &P[3 * input] + 3, &Points3_[3 * v]);
  }
  std::vector<int32_t> first(nv + 1, 0);
  std::vector<int32_t> lowest(nf);
  for (int32_t f = 0; f < nf; ++f)
  {
    const int32_t* t = &Mesh_.triangles[3 * f];
    lowest[f] = std::min(VertexOf_[t[0]], std::min(VertexOf_[t[1]], VertexOf_[t[2]]));
    ++first[lowest[f] + 1];
  }
  for (int32_t v = 0; v < nv; ++v)
  {
    first[v + 1] += first[v];
  }
  FaceOf_.resize(nf);
  Tri_.resize(3 * static_cast<size_t>(nf));
  for (int32_t input = 0; input < nf; ++input)
  {
    const int32_t f = first[lowest[input]]++;
    FaceOf_[input] = f;
    for (int c = 0; c < 3; ++c)
    {
      Tri_[3 * f + c] = VertexOf_[Mesh_.triangles[3 * input + c]];
    }
  }
}

/// Outgoing half-edges of every vertex in CSR form (InOffsets_, InHe_), in input order, and the
/// end of each in outTarget; every point must be in a triangle.
void Simplifier::linkOutgoing(std::vector<int32_t>& outTarget)
{
  const int32_t nh = 3 * NumFaces_;
  std::vector<int32_t>& offsets = InOffsets_;
  offsets.assign(NumVertices_ + 1, 0);
  for (int32_t h = 0; h < nh; ++h)
  {
    ++offsets[F_[h] + 1];
  }
  for (int32_t input = 0; input < NumVertices_; ++input)
  {
    if (offsets[VertexOf_[input] + 1] == 0)
    {
      throw InputError("buildBaseComplex: point " + std::to_string(input) +
        " is in no triangle; run tcMeshPreparation to drop unused points");
    }
  }
  for (int32_t v = 0; v < NumVertices_; ++v)
  {
    offsets[v + 1] += offsets[v];
  }
  InHe_.resize(nh);
  outTarget.assign(nh, 0);
  std::vector<int32_t> fill(offsets.begin(), offsets.end() - 1);
  for (int32_t i = 0; i < nh; ++i)
  {
    const int32_t h = this->inputHe(i);
    const int32_t slot = fill[F_[h]]++;
    InHe_[slot] = h;
    outTarget[slot] = F_[nextHe(h)];
  }
}

/// The half-edge a -> b listed last among a's outgoing ones (-1: none), and how many there are.
int32_t Simplifier::findHe(
  int32_t a, int32_t b, const std::vector<int32_t>& outTarget, int* count) const
{
  int32_t found = -1;
  *count = 0;
  for (int32_t s = InOffsets_[a]; s < InOffsets_[a + 1]; ++s)
  {
    if (outTarget[s] == b)
    {
      found = InHe_[s];
      ++*count;
    }
  }
  return found;
}

/// Opp_ by scanning the (short) list of the other end: O(#F * valence), no sort. Every edge must
/// have exactly one twin, of opposite direction.
void Simplifier::linkTwins(const std::vector<int32_t>& outTarget)
{
  const int32_t nh = 3 * NumFaces_;
  Opp_.assign(nh, -1);
  for (int32_t i = 0; i < nh; ++i)
  {
    const int32_t h = this->inputHe(i);
    const int32_t a = F_[h], b = F_[nextHe(h)];
    int same = 0, twin = 0;
    this->findHe(a, b, outTarget, &same);
    const int32_t o = this->findHe(b, a, outTarget, &twin);
    auto edge = [&]
    { return "(" + std::to_string(VertexRank_[a]) + ", " + std::to_string(VertexRank_[b]) + ")"; };
    if (same != 1 || twin > 1)
    {
      throw InputError("buildBaseComplex: edge " + edge() +
        " has more than 2 triangles or inconsistent orientation (split non-manifold edges and "
        "orient the mesh in the preparation: SplitNonManifold and Orient, trichart build "
        "--split-non-manifold)");
    }
    if (twin == 0)
    {
      throw InputError("buildBaseComplex: edge " + edge() +
        " is on a boundary; the base complex needs a closed surface (close the holes in the "
        "preparation: FillHoles, trichart build --fill-holes)");
    }
    Opp_[h] = o;
  }
}

/// Out_ and Valence_; the triangles around every vertex must make one fan.
void Simplifier::linkFans()
{
  Out_.resize(NumVertices_);
  Valence_.resize(NumVertices_);
  for (int32_t input = 0; input < NumVertices_; ++input)
  {
    const int32_t v = VertexOf_[input];
    const int32_t start = InHe_[InOffsets_[v]];
    const int32_t valence = InOffsets_[v + 1] - InOffsets_[v];
    int32_t h = start, steps = 0;
    do
    {
      h = this->nextOutgoing(h);
      ++steps;
    } while (h != start && steps <= valence);
    if (steps != valence)
    {
      throw InputError("buildBaseComplex: the triangles around point " + std::to_string(input) +
        " form more than one fan (split non-manifold vertices in the preparation: "
        "SplitNonManifold, trichart build --split-non-manifold)");
    }
    Out_[v] = start;
    Valence_[v] = valence;
  }
}

/// FeatureHe_ (both twins of every feature edge), Feature_ and Pinned_.
void Simplifier::flagFeatures(const std::vector<uint8_t>& featureVertex,
  const std::vector<uint8_t>& cornerVertex, const std::vector<int32_t>& featureEdges,
  const std::vector<int32_t>& outTarget)
{
  FeatureHe_.assign(3 * NumFaces_, 0);
  std::vector<int32_t> featureCount(NumVertices_, 0);
  for (size_t i = 0; i < featureEdges.size(); i += 2)
  {
    const int32_t ia = featureEdges[i], ib = featureEdges[i + 1];
    if (ia < 0 || ib < 0 || ia >= NumVertices_ || ib >= NumVertices_)
    {
      throw InputError(
        "buildBaseComplex: feature edge " + std::to_string(i / 2) + " refers to a missing point");
    }
    const int32_t a = VertexOf_[ia], b = VertexOf_[ib];
    int count = 0;
    const int32_t h = this->findHe(a, b, outTarget, &count);
    if (h < 0)
    {
      throw InputError("buildBaseComplex: feature edge (" + std::to_string(ia) + ", " +
        std::to_string(ib) + ") is not an edge of the mesh");
    }
    if (!FeatureHe_[h])
    {
      FeatureHe_[h] = FeatureHe_[Opp_[h]] = 1;
      ++featureCount[a];
      ++featureCount[b];
    }
  }
  Feature_.assign(NumVertices_, 0);
  Pinned_.assign(NumVertices_, 0);
  for (int32_t v = 0; v < NumVertices_; ++v)
  {
    const int32_t input = VertexRank_[v];
    Feature_[v] = (!featureVertex.empty() && featureVertex[input]) || featureCount[v] > 0;
    Pinned_[v] =
      (!cornerVertex.empty() && cornerVertex[input]) || (Feature_[v] && featureCount[v] != 2);
  }
}
} // namespace base_complex
} // namespace detail
} // namespace tc
