// SPDX-License-Identifier: BSD-3-Clause
#include "tc/features/spectral_clustering.h"

#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"
#include "tc/common/parallel.h"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <Spectra/MatOp/DenseSymMatProd.h>
#include <Spectra/SymEigsSolver.h>

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <utility>

namespace tc
{
namespace
{
// exp() of anything below this is still a normal double: a face whose curvature is far above
// sigma_k keeps a tiny positive similarity instead of becoming an isolated node (D = 0).
constexpr double kMinExponent = -600.0;
// The same for the float kernel blocks of the Nystrom method (and no denormals in the GEMMs).
constexpr float kMinExponentFloat = -60.0f;
// Components up to this size are solved with a dense eigensolver (cheaper and always
// convergent there).
constexpr int64_t kDenseEigenLimit = 400;
// Faces per block of the Nystrom passes: a float block of nystromSamples x this stays small.
constexpr int64_t kNystromBlock = 1024;
// Rows per chunk of the blocked k-means passes (fixed, so sums do not depend on the threads).
constexpr int64_t kKMeansChunk = 4096;
// Lloyd stops once at most 1 / this of the rows changed cluster in an iteration.
constexpr int64_t kKMeansStableFraction = 2000;

// --------------------------------------------------------------------------------------------
// Deterministic randomness

// SplitMix64 finalizer: independent seeds for every (component, purpose, restart).
uint64_t mixSeed(uint64_t seed, uint64_t a, uint64_t b = 0)
{
  uint64_t z = seed + 0x9E3779B97F4A7C15ull * (a + 1) + 0xBF58476D1CE4E5B9ull * (b + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Uniform in [0, 1) from the top 53 bits: the same numbers with every standard library
// (std::uniform_real_distribution is implementation-defined).
double uniform01(std::mt19937_64& rng)
{
  return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0);
}

int64_t uniformIndex(std::mt19937_64& rng, int64_t n)
{
  return std::min<int64_t>(n - 1, static_cast<int64_t>(uniform01(rng) * static_cast<double>(n)));
}

// m distinct indices of [0, n), ascending (partial Fisher-Yates).
std::vector<int64_t> sampleIndices(int64_t n, int64_t m, uint64_t seed)
{
  std::vector<int64_t> all(n);
  std::iota(all.begin(), all.end(), 0);
  std::mt19937_64 rng(seed);
  for (int64_t i = 0; i < m; ++i)
  {
    std::swap(all[i], all[i + uniformIndex(rng, n - i)]);
  }
  all.resize(m);
  std::sort(all.begin(), all.end());
  return all;
}

// --------------------------------------------------------------------------------------------
// Dual graph

// Symmetric graph over faces in CSR form: the neighbours of f are ids[offsets[f] ..
// offsets[f+1]), sorted, with the dual-path length and whether a crest separates the two.
struct DualGraph
{
  std::vector<int64_t> offsets;
  std::vector<int32_t> ids;
  std::vector<double> dist;
  std::vector<uint8_t> crest;
};

// Faces sharing a mesh edge (every pair of the fan of a non-manifold edge). The length is
// |c_i - m_e| + |m_e - c_j| through the midpoint m_e of the shared edge, so that sums along
// dual paths are geodesic lengths on the surface (section 4.2, dist(f_i, f_j)). A crest
// separates the two faces when both ends of the shared edge are crest vertices.
DualGraph buildAdjacentDual(const TriMesh& mesh, const std::vector<double>& centroids,
  const std::vector<uint8_t>& crestVertex, const Progress& progress)
{
  const int64_t nf = mesh.numTriangles();
  const EdgeTable edges = buildEdgeTable(mesh.triangles);
  const int64_t ne = edges.numEdges();
  progress.report(0.4);

  DualGraph g;
  g.offsets.assign(nf + 1, 0);
  for (int64_t e = 0; e < ne; ++e)
  {
    const int64_t valence = edges.valence(e);
    if (valence < 2 || edges.vertices[2 * e] == edges.vertices[2 * e + 1])
    {
      continue;
    }
    for (int64_t k = edges.faceOffsets[e]; k < edges.faceOffsets[e + 1]; ++k)
    {
      g.offsets[edges.edgeFaces[k] + 1] += valence - 1;
    }
  }
  std::partial_sum(g.offsets.begin(), g.offsets.end(), g.offsets.begin());
  const int64_t total = g.offsets[nf];
  g.ids.resize(total);
  g.dist.resize(total);
  g.crest.resize(total);
  std::vector<int64_t> fill(g.offsets.begin(), g.offsets.end() - 1);
  const bool haveCrest = !crestVertex.empty();
  for (int64_t e = 0; e < ne; ++e)
  {
    const int32_t a = edges.vertices[2 * e];
    const int32_t b = edges.vertices[2 * e + 1];
    if (edges.valence(e) < 2 || a == b)
    {
      continue;
    }
    double mid[3];
    for (int c = 0; c < 3; ++c)
    {
      mid[c] = 0.5 * (mesh.points[3 * a + c] + mesh.points[3 * b + c]);
    }
    const uint8_t crest = haveCrest && crestVertex[a] && crestVertex[b] ? 1 : 0;
    for (int64_t i = edges.faceOffsets[e]; i < edges.faceOffsets[e + 1]; ++i)
    {
      const int32_t fi = edges.edgeFaces[i];
      double di = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        const double d = centroids[3 * fi + c] - mid[c];
        di += d * d;
      }
      di = std::sqrt(di);
      for (int64_t j = edges.faceOffsets[e]; j < edges.faceOffsets[e + 1]; ++j)
      {
        const int32_t fj = edges.edgeFaces[j];
        if (j == i)
        {
          continue;
        }
        double dj = 0.0;
        for (int c = 0; c < 3; ++c)
        {
          const double d = centroids[3 * fj + c] - mid[c];
          dj += d * d;
        }
        const int64_t slot = fill[fi]++;
        g.ids[slot] = fj;
        g.dist[slot] = di + std::sqrt(dj);
        g.crest[slot] = crest;
      }
    }
  }
  progress.report(0.7);

  // Sort every row; a pair of faces that shares two edges (a fold) or appears twice in a fan
  // keeps one dual edge: the shorter length, crest if either shared edge is one. A face paired
  // with itself (a degenerate triangle with two equal sides) is dropped.
  std::vector<int64_t> kept(nf, 0);
  parallel_for(nf,
    [&](int64_t f)
    {
      const int64_t begin = g.offsets[f];
      const int64_t end = g.offsets[f + 1];
      // Rows are short (3 for a manifold mesh): insertion sort without allocation.
      for (int64_t i = begin + 1; i < end; ++i)
      {
        for (int64_t j = i; j > begin && g.ids[j] < g.ids[j - 1]; --j)
        {
          std::swap(g.ids[j], g.ids[j - 1]);
          std::swap(g.dist[j], g.dist[j - 1]);
          std::swap(g.crest[j], g.crest[j - 1]);
        }
      }
      int64_t out = begin;
      for (int64_t i = begin; i < end; ++i)
      {
        if (g.ids[i] == static_cast<int32_t>(f))
        {
          continue;
        }
        if (out > begin && g.ids[out - 1] == g.ids[i])
        {
          g.dist[out - 1] = std::min(g.dist[out - 1], g.dist[i]);
          g.crest[out - 1] = g.crest[out - 1] | g.crest[i];
          continue;
        }
        g.ids[out] = g.ids[i];
        g.dist[out] = g.dist[i];
        g.crest[out] = g.crest[i];
        ++out;
      }
      kept[f] = out - begin;
    });

  // Compact the rows.
  int64_t write = 0;
  for (int64_t f = 0; f < nf; ++f)
  {
    const int64_t begin = g.offsets[f];
    g.offsets[f] = write;
    for (int64_t i = begin; i < begin + kept[f]; ++i, ++write)
    {
      g.ids[write] = g.ids[i];
      g.dist[write] = g.dist[i];
      g.crest[write] = g.crest[i];
    }
  }
  g.offsets[nf] = write;
  g.ids.resize(write);
  g.dist.resize(write);
  g.crest.resize(write);
  g.ids.shrink_to_fit();
  g.dist.shrink_to_fit();
  g.crest.shrink_to_fit();
  progress.report(1.0);
  return g;
}

// Connected components of the adjacent dual graph, numbered in the order of their first face.
// @return number of components; componentOf is #F
int64_t findComponents(const DualGraph& g, int64_t nf, std::vector<int32_t>& componentOf)
{
  componentOf.assign(nf, -1);
  std::vector<int32_t> stack;
  int32_t count = 0;
  for (int64_t seed = 0; seed < nf; ++seed)
  {
    if (componentOf[seed] >= 0)
    {
      continue;
    }
    componentOf[seed] = count;
    stack.push_back(static_cast<int32_t>(seed));
    while (!stack.empty())
    {
      const int32_t f = stack.back();
      stack.pop_back();
      for (int64_t k = g.offsets[f]; k < g.offsets[f + 1]; ++k)
      {
        const int32_t n = g.ids[k];
        if (componentOf[n] < 0)
        {
          componentOf[n] = count;
          stack.push_back(n);
        }
      }
    }
    ++count;
  }
  return count;
}

// Clusters per component, in proportion to its face count (largest remainder). A component
// whose share rounds to zero still gets one cluster (clusters never span components); those
// extra clusters are taken back from components that got a rounding bonus (share rounded up),
// so every component keeps at least floor(its share) and the total is numClusters whenever the
// rounding leaves room. Never more clusters than faces.
std::vector<int> allocateClusters(const std::vector<int64_t>& sizes, int numClusters)
{
  const size_t nc = sizes.size();
  const double total = static_cast<double>(std::accumulate(sizes.begin(), sizes.end(), int64_t(0)));
  std::vector<double> quota(nc);
  std::vector<int> alloc(nc);
  int assigned = 0;
  for (size_t c = 0; c < nc; ++c)
  {
    quota[c] = numClusters * static_cast<double>(sizes[c]) / total;
    alloc[c] = static_cast<int>(std::floor(quota[c]));
    assigned += alloc[c];
  }
  std::vector<size_t> order(nc);
  std::iota(order.begin(), order.end(), 0);
  auto fraction = [&](size_t c) { return quota[c] - std::floor(quota[c]); };
  std::stable_sort(
    order.begin(), order.end(), [&](size_t a, size_t b) { return fraction(a) > fraction(b); });
  for (size_t i = 0; assigned < numClusters && i < nc; ++i, ++assigned)
  {
    ++alloc[order[i]];
  }
  int excess = 0;
  for (size_t c = 0; c < nc; ++c)
  {
    if (alloc[c] == 0)
    {
      alloc[c] = 1;
      ++excess;
    }
  }
  // Take back from the smallest rounding bonuses first.
  for (auto it = order.rbegin(); excess > 0 && it != order.rend(); ++it)
  {
    const size_t c = *it;
    if (alloc[c] > std::max(1, static_cast<int>(std::floor(quota[c]))))
    {
      --alloc[c];
      --excess;
    }
  }
  for (size_t c = 0; c < nc; ++c)
  {
    alloc[c] = static_cast<int>(std::min<int64_t>(alloc[c], sizes[c]));
  }
  return alloc;
}

struct DijkstraScratch
{
  std::vector<double> best;
  std::vector<uint8_t> crest;
  std::vector<int32_t> touched;
  std::vector<std::pair<double, int32_t>> heap;
};

struct ExtraEdges
{
  std::vector<int32_t> source;
  std::vector<int32_t> target;
  std::vector<double> dist;
  std::vector<uint8_t> crest;
};

// Section 4.2: "we add an additional dual edge between f_i, f_j if dist(f_i, f_j) < 2 dist-bar"
// for non-adjacent faces, dist the dual-path (geodesic) length. A bounded Dijkstra from every
// face of `active` finds them; each pair is recorded once, from its lower face id, so the
// graph is symmetric whatever the tie-breaking. The crest flag of an extra edge is that of the
// shortest dual path: set when the path crosses a mesh edge that runs along a crest line
// (beta = crestBeta in eq. 3 for the pair, as for adjacent faces across a crest).
DualGraph addExtraEdges(
  const DualGraph& adj, const std::vector<uint8_t>& active, double radius, const Progress& progress)
{
  const int64_t nf = static_cast<int64_t>(adj.offsets.size()) - 1;
  const int64_t chunk = 2048;
  const int64_t numChunks = (nf + chunk - 1) / chunk;
  std::vector<ExtraEdges> found(numChunks);
  tbb::enumerable_thread_specific<DijkstraScratch> scratch(
    [nf]()
    {
      DijkstraScratch s;
      s.best.assign(nf, std::numeric_limits<double>::infinity());
      s.crest.assign(nf, 0);
      return s;
    });
  auto greater = [](const std::pair<double, int32_t>& a, const std::pair<double, int32_t>& b)
  { return a.first > b.first || (a.first == b.first && a.second > b.second); };

  parallel_for(
    numChunks,
    [&](int64_t c)
    {
      DijkstraScratch& s = scratch.local();
      ExtraEdges& out = found[c];
      const int64_t stop = std::min(nf, (c + 1) * chunk);
      for (int64_t src = c * chunk; src < stop; ++src)
      {
        if (!active[src])
        {
          continue;
        }
        const int32_t* adjBegin = adj.ids.data() + adj.offsets[src];
        const int32_t* adjEnd = adj.ids.data() + adj.offsets[src + 1];
        s.best[src] = 0.0;
        s.crest[src] = 0;
        s.touched.push_back(static_cast<int32_t>(src));
        s.heap.emplace_back(0.0, static_cast<int32_t>(src));
        while (!s.heap.empty())
        {
          std::pop_heap(s.heap.begin(), s.heap.end(), greater);
          const auto [d, u] = s.heap.back();
          s.heap.pop_back();
          if (d > s.best[u])
          {
            continue;
          }
          if (u > src && !std::binary_search(adjBegin, adjEnd, u))
          {
            out.source.push_back(static_cast<int32_t>(src));
            out.target.push_back(u);
            out.dist.push_back(d);
            out.crest.push_back(s.crest[u]);
          }
          for (int64_t k = adj.offsets[u]; k < adj.offsets[u + 1]; ++k)
          {
            const int32_t v = adj.ids[k];
            const double nd = d + adj.dist[k];
            if (nd < radius && nd < s.best[v])
            {
              if (s.best[v] == std::numeric_limits<double>::infinity())
              {
                s.touched.push_back(v);
              }
              s.best[v] = nd;
              s.crest[v] = s.crest[u] | adj.crest[k];
              s.heap.emplace_back(nd, v);
              std::push_heap(s.heap.begin(), s.heap.end(), greater);
            }
          }
        }
        for (int32_t t : s.touched)
        {
          s.best[t] = std::numeric_limits<double>::infinity();
        }
        s.touched.clear();
      }
    },
    progress.sub(0.0, 0.8));

  // Merge: adjacency rows plus the extra edges in both directions.
  DualGraph g;
  g.offsets.assign(nf + 1, 0);
  for (int64_t f = 0; f < nf; ++f)
  {
    g.offsets[f + 1] = adj.offsets[f + 1] - adj.offsets[f];
  }
  for (const ExtraEdges& e : found)
  {
    for (size_t i = 0; i < e.source.size(); ++i)
    {
      ++g.offsets[e.source[i] + 1];
      ++g.offsets[e.target[i] + 1];
    }
  }
  std::partial_sum(g.offsets.begin(), g.offsets.end(), g.offsets.begin());
  const int64_t total = g.offsets[nf];
  g.ids.resize(total);
  g.dist.resize(total);
  g.crest.resize(total);
  std::vector<int64_t> fill(g.offsets.begin(), g.offsets.end() - 1);
  for (int64_t f = 0; f < nf; ++f)
  {
    for (int64_t k = adj.offsets[f]; k < adj.offsets[f + 1]; ++k)
    {
      const int64_t slot = fill[f]++;
      g.ids[slot] = adj.ids[k];
      g.dist[slot] = adj.dist[k];
      g.crest[slot] = adj.crest[k];
    }
  }
  for (ExtraEdges& e : found)
  {
    for (size_t i = 0; i < e.source.size(); ++i)
    {
      for (int side = 0; side < 2; ++side)
      {
        const int32_t a = side == 0 ? e.source[i] : e.target[i];
        const int32_t b = side == 0 ? e.target[i] : e.source[i];
        const int64_t slot = fill[a]++;
        g.ids[slot] = b;
        g.dist[slot] = e.dist[i];
        g.crest[slot] = e.crest[i];
      }
    }
    e = ExtraEdges();
  }
  progress.report(1.0);
  return g;
}

// --------------------------------------------------------------------------------------------
// Eigenvectors of the normalized similarity D^-1/2 W D^-1/2 (eq. 2)

// Sparse symmetric matrix in CSR form over a component's faces (local ids).
struct LocalMatrix
{
  std::vector<int64_t> offsets;
  std::vector<int32_t> ids;
  std::vector<double> values;
  int64_t rows() const { return static_cast<int64_t>(offsets.size()) - 1; }
};

// Counts the operator applications of an eigensolver and reports progress every few of them;
// the callback may abort (tc::Aborted passes through Spectra, which holds no resources).
class ProductCounter
{
public:
  ProductCounter(const Progress& progress, int64_t expected)
    : Progress_(progress)
    , Expected_(std::max<int64_t>(1, expected))
  {
  }
  void tick() const
  {
    if (++Count_ % 4 == 0)
    {
      Progress_.report(std::min(0.95, static_cast<double>(Count_) / Expected_));
    }
  }
  int64_t count() const { return Count_; }

private:
  Progress Progress_;
  int64_t Expected_;
  mutable int64_t Count_ = 0;
};

// y = N x for Spectra, rows in parallel (each row summed in order: deterministic).
class NormalizedProduct
{
public:
  using Scalar = double;

  NormalizedProduct(const LocalMatrix& n, const ProductCounter& counter)
    : N_(n)
    , Counter_(counter)
  {
  }
  Eigen::Index rows() const { return N_.rows(); }
  Eigen::Index cols() const { return N_.rows(); }
  void perform_op(const double* x, double* y) const
  {
    parallel_for(
      N_.rows(),
      [&](int64_t i)
      {
        double sum = 0.0;
        for (int64_t k = N_.offsets[i]; k < N_.offsets[i + 1]; ++k)
        {
          sum += N_.values[k] * x[N_.ids[k]];
        }
        y[i] = sum;
      },
      Progress(), 1);
    Counter_.tick();
  }

private:
  const LocalMatrix& N_;
  const ProductCounter& Counter_;
};

using SparseLDLT = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower>;

// y = (L + eps I)^-1 x for Spectra, L = I - N the normalized Laplacian of eq. 2.
class ShiftInvertProduct
{
public:
  using Scalar = double;

  ShiftInvertProduct(const SparseLDLT& factor, Eigen::Index n, const ProductCounter& counter)
    : Factor_(factor)
    , N_(n)
    , Counter_(counter)
  {
  }
  Eigen::Index rows() const { return N_; }
  Eigen::Index cols() const { return N_; }
  void perform_op(const double* x, double* y) const
  {
    Eigen::Map<Eigen::VectorXd>(y, N_) = Factor_.solve(Eigen::Map<const Eigen::VectorXd>(x, N_));
    Counter_.tick();
  }

private:
  const SparseLDLT& Factor_;
  Eigen::Index N_;
  const ProductCounter& Counter_;
};

// The ne largest eigenpairs of N, eigenvalues descending, eigenvectors n x ne column-major.
//
// The largest eigenvalues of N = D^-1/2 W D^-1/2 crowd below 1 on a mesh graph (1 - O(h^2):
// 0.99985 is the 16th on a 70K-face bunny), so Lanczos on N itself needs thousands of
// products. They are the smallest of the Laplacian L = I - N (eq. 2), which shift-invert
// spreads apart: Lanczos on (L + eps I)^-1 (sparse LDLT, AMD ordering) converges in a few
// dozen solves. eps > 0 makes L + eps I positive definite (L is singular: L D^1/2 1 = 0) and is
// far below the gaps that matter. Lanczos on N remains the fallback if the factorization fails.
void largestEigenpairs(const LocalMatrix& n, int ne, const Progress& progress,
  std::vector<double>& values, Eigen::MatrixXd& vectors)
{
  const int64_t rows = n.rows();
  ne = static_cast<int>(std::min<int64_t>(ne, rows));
  if (rows <= kDenseEigenLimit || 2 * static_cast<int64_t>(ne) + 1 >= rows)
  {
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(rows, rows);
    for (int64_t i = 0; i < rows; ++i)
    {
      for (int64_t k = n.offsets[i]; k < n.offsets[i + 1]; ++k)
      {
        dense(i, n.ids[k]) = n.values[k];
      }
    }
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense);
    values.resize(ne);
    vectors.resize(rows, ne);
    for (int j = 0; j < ne; ++j)
    {
      // Eigen sorts ascending.
      values[j] = eig.eigenvalues()(rows - 1 - j);
      vectors.col(j) = eig.eigenvectors().col(rows - 1 - j);
    }
    progress.report(1.0);
    return;
  }

  constexpr double eps = 1e-6;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(n.offsets[rows] / 2 + rows);
  for (int64_t i = 0; i < rows; ++i)
  {
    triplets.emplace_back(i, i, 1.0 + eps);
    for (int64_t k = n.offsets[i]; k < n.offsets[i + 1]; ++k)
    {
      if (n.ids[k] > i)
      {
        triplets.emplace_back(n.ids[k], i, -n.values[k]);
      }
    }
  }
  Eigen::SparseMatrix<double> shifted(rows, rows);
  shifted.setFromTriplets(triplets.begin(), triplets.end());
  triplets = {};
  SparseLDLT factor(shifted);
  progress.report(0.3);
  const Progress solveProgress = progress.sub(0.3, 1.0);
  if (factor.info() == Eigen::Success)
  {
    const int ncv = static_cast<int>(std::min<int64_t>(rows, std::max(2 * ne + 1, ne + 20)));
    ProductCounter counter(solveProgress, 4 * ncv);
    ShiftInvertProduct op(factor, rows, counter);
    Spectra::SymEigsSolver<ShiftInvertProduct> eigs(op, ne, ncv);
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestAlge, 1000, 1e-10, Spectra::SortRule::LargestAlge);
    if (eigs.info() == Spectra::CompInfo::Successful)
    {
      // nu = 1 / (mu + eps) with mu = 1 - lambda.
      const Eigen::VectorXd nu = eigs.eigenvalues();
      values.resize(nu.size());
      for (Eigen::Index j = 0; j < nu.size(); ++j)
      {
        values[j] = 1.0 - (1.0 / nu(j) - eps);
      }
      vectors = eigs.eigenvectors();
      progress.report(1.0);
      return;
    }
  }
  const int ncv = static_cast<int>(std::min<int64_t>(rows, std::max(2 * ne + 1, ne + 40)));
  ProductCounter counter(solveProgress, 100 * ncv);
  NormalizedProduct op(n, counter);
  Spectra::SymEigsSolver<NormalizedProduct> eigs(op, ne, ncv);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestAlge, 5000, 1e-8, Spectra::SortRule::LargestAlge);
  if (eigs.info() != Spectra::CompInfo::Successful)
  {
    throw std::runtime_error("spectralClustering: the eigensolver did not converge after " +
      std::to_string(counter.count()) + " products on a component of " + std::to_string(rows) +
      " faces");
  }
  const Eigen::VectorXd ev = eigs.eigenvalues();
  values.assign(ev.data(), ev.data() + ev.size());
  vectors = eigs.eigenvectors();
  progress.report(1.0);
}

// --------------------------------------------------------------------------------------------
// k-means with k-means++ seeding

struct KMeansRun
{
  std::vector<double> centers; // k x dim
  double inertia = std::numeric_limits<double>::infinity();
};

inline double squaredDistance(const double* a, const double* b, int dim)
{
  double s = 0.0;
  for (int d = 0; d < dim; ++d)
  {
    const double t = a[d] - b[d];
    s += t * t;
  }
  return s;
}

// Nearest center of every row of the rows listed in `rows` (all when empty), in fixed chunks
// so that the partial sums (per-cluster coordinate sums, counts, inertia) are added in the
// same order with any number of threads.
struct Assignment
{
  std::vector<int32_t> label;
  std::vector<double> sums;   // k x dim
  std::vector<int64_t> count; // k
  std::vector<double> dist2;  // per row
  double inertia = 0.0;
  int64_t changed = 0;
};

void assignRows(const double* x, int64_t n, int dim, const std::vector<double>& centers, int k,
  Assignment& a, bool parallel)
{
  const int64_t numChunks = (n + kKMeansChunk - 1) / kKMeansChunk;
  std::vector<double> chunkSums(static_cast<size_t>(numChunks) * k * dim, 0.0);
  std::vector<int64_t> chunkCounts(static_cast<size_t>(numChunks) * k, 0);
  std::vector<double> chunkInertia(numChunks, 0.0);
  std::vector<int64_t> chunkChanged(numChunks, 0);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::Map<const RowMajor> cm(centers.data(), k, dim);
  const Eigen::RowVectorXd centerNorms = cm.rowwise().squaredNorm().transpose();
  auto body = [&](int64_t c)
  {
    double* sums = chunkSums.data() + c * k * dim;
    int64_t* counts = chunkCounts.data() + c * k;
    const int64_t begin = c * kKMeansChunk;
    const int64_t rows = std::min(n, begin + kKMeansChunk) - begin;
    // |x - c|^2 = |x|^2 - 2 x.c + |c|^2: one small GEMM per chunk.
    const Eigen::Map<const RowMajor> xm(x + begin * dim, rows, dim);
    Eigen::MatrixXd score = -2.0 * (xm * cm.transpose());
    score.rowwise() += centerNorms;
    for (int64_t r = 0; r < rows; ++r)
    {
      const int64_t i = begin + r;
      Eigen::Index best = 0;
      const double bestScore = score.row(r).minCoeff(&best);
      const double bestD = std::max(0.0, bestScore + xm.row(r).squaredNorm());
      if (a.label[i] != best)
      {
        ++chunkChanged[c];
        a.label[i] = static_cast<int32_t>(best);
      }
      a.dist2[i] = bestD;
      chunkInertia[c] += bestD;
      ++counts[best];
      for (int d = 0; d < dim; ++d)
      {
        sums[best * dim + d] += xm(r, d);
      }
    }
  };
  if (parallel)
  {
    parallel_for(numChunks, body, Progress(), 1);
  }
  else
  {
    for (int64_t c = 0; c < numChunks; ++c)
    {
      body(c);
    }
  }
  a.sums.assign(static_cast<size_t>(k) * dim, 0.0);
  a.count.assign(k, 0);
  a.inertia = 0.0;
  a.changed = 0;
  for (int64_t c = 0; c < numChunks; ++c)
  {
    for (int j = 0; j < k * dim; ++j)
    {
      a.sums[j] += chunkSums[c * k * dim + j];
    }
    for (int j = 0; j < k; ++j)
    {
      a.count[j] += chunkCounts[c * k + j];
    }
    a.inertia += chunkInertia[c];
    a.changed += chunkChanged[c];
  }
}

// Lloyd iterations from `centers`; an emptied cluster moves to the row farthest from its
// center (the first such row), so no cluster is lost while distinct rows remain.
double lloyd(const double* x, int64_t n, int dim, int k, int iterations,
  std::vector<double>& centers, std::vector<int32_t>& labels, bool parallel)
{
  Assignment a;
  a.label.assign(n, -1);
  a.dist2.assign(n, 0.0);
  for (int it = 0; it < iterations; ++it)
  {
    assignRows(x, n, dim, centers, k, a, parallel);
    bool moved = false;
    for (int j = 0; j < k; ++j)
    {
      if (a.count[j] == 0)
      {
        const int64_t far = std::max_element(a.dist2.begin(), a.dist2.end()) - a.dist2.begin();
        if (a.dist2[far] <= 0.0)
        {
          continue;
        }
        std::copy(x + far * dim, x + (far + 1) * dim, centers.begin() + j * dim);
        a.dist2[far] = 0.0;
        moved = true;
        continue;
      }
      for (int d = 0; d < dim; ++d)
      {
        centers[j * dim + d] = a.sums[j * dim + d] / static_cast<double>(a.count[j]);
      }
    }
    // Converged when (almost) no row changes cluster: the last few border rows of a smooth
    // embedding can keep hopping for dozens of iterations without changing the clusters.
    if (!moved && a.changed <= n / kKMeansStableFraction)
    {
      break;
    }
  }
  // Final labels and inertia for the final centers.
  assignRows(x, n, dim, centers, k, a, parallel);
  labels = std::move(a.label);
  return a.inertia;
}

// k-means++ (Arthur and Vassilvitskii 2007): the first center uniformly, each next one with
// probability proportional to the squared distance to the nearest center so far.
std::vector<double> kmeansPlusPlus(const double* x, int64_t n, int dim, int k, std::mt19937_64& rng)
{
  std::vector<double> centers(static_cast<size_t>(k) * dim);
  std::vector<double> d2(n, std::numeric_limits<double>::infinity());
  int64_t pick = uniformIndex(rng, n);
  for (int j = 0; j < k; ++j)
  {
    std::copy(x + pick * dim, x + (pick + 1) * dim, centers.begin() + j * dim);
    double total = 0.0;
    for (int64_t i = 0; i < n; ++i)
    {
      d2[i] = std::min(d2[i], squaredDistance(x + i * dim, centers.data() + j * dim, dim));
      total += d2[i];
    }
    if (j + 1 == k)
    {
      break;
    }
    if (total <= 0.0)
    {
      // Fewer distinct rows than clusters: any row will do; Lloyd drops nothing.
      pick = uniformIndex(rng, n);
      continue;
    }
    double target = uniform01(rng) * total;
    pick = n - 1;
    for (int64_t i = 0; i < n; ++i)
    {
      target -= d2[i];
      if (target < 0.0 && d2[i] > 0.0)
      {
        pick = i;
        break;
      }
    }
  }
  return centers;
}

// Labels in [0, k) for the n x dim rows of x. Restarts run on a seeded sample of at most
// sampleSize rows (all rows when fewer), in parallel, each with its own generator; the best
// inertia wins (the lowest restart on ties), and its centers are refined on all rows.
std::vector<int32_t> kmeans(const std::vector<double>& x, int64_t n, int dim, int k,
  const SpectralClusteringOptions& options, uint64_t seed, const Progress& progress)
{
  std::vector<double> sample;
  const double* data = x.data();
  int64_t ns = n;
  // The sample keeps at least 50 rows per cluster, so that small clusters are seen.
  const int64_t sampleSize = std::max<int64_t>(options.kmeansSampleSize, 50 * int64_t(k));
  const bool sampled = options.kmeansSampleSize > 0 && n > sampleSize;
  if (sampled)
  {
    ns = sampleSize;
    const std::vector<int64_t> rows = sampleIndices(n, ns, mixSeed(seed, 1));
    sample.resize(static_cast<size_t>(ns) * dim);
    for (int64_t i = 0; i < ns; ++i)
    {
      std::copy(
        x.begin() + rows[i] * dim, x.begin() + (rows[i] + 1) * dim, sample.begin() + i * dim);
    }
    data = sample.data();
  }
  const int restarts = std::max(1, options.kmeansRestarts);
  std::vector<KMeansRun> runs(restarts);
  parallel_for(
    restarts,
    [&](int64_t r)
    {
      std::mt19937_64 rng(mixSeed(seed, 2, static_cast<uint64_t>(r)));
      runs[r].centers = kmeansPlusPlus(data, ns, dim, k, rng);
      std::vector<int32_t> labels;
      runs[r].inertia =
        lloyd(data, ns, dim, k, options.kmeansIterations, runs[r].centers, labels, false);
    },
    progress.sub(0.0, sampled ? 0.5 : 0.9), 1);
  int best = 0;
  for (int r = 1; r < restarts; ++r)
  {
    if (runs[r].inertia < runs[best].inertia)
    {
      best = r;
    }
  }
  std::vector<double> centers = runs[best].centers;
  std::vector<int32_t> labels;
  lloyd(x.data(), n, dim, k, sampled ? options.kmeansIterations : 0, centers, labels, true);
  progress.report(1.0);
  return labels;
}

// --------------------------------------------------------------------------------------------
// Spectral embedding

// Eigenpairs of D^-1/2 W D^-1/2 of one component and the degrees D.
struct Spectrum
{
  std::vector<double> values;  // ne, descending
  std::vector<double> vectors; // n x ne row-major, local face order
  std::vector<double> degree;  // n
};

// Eq. 3 on every edge of the dual graph of one component, N = D^-1/2 W D^-1/2 (eq. 2), and
// its largest eigenpairs.
Spectrum exactSpectrum(const std::vector<int32_t>& faces, const DualGraph& graph,
  const std::vector<int32_t>& localId, const std::vector<double>& curvExp, double invSigmaD,
  double crestBeta, const std::vector<double>& normals, double normalSigma, int ne,
  const Progress& progress)
{
  const double invNormalSigma = normalSigma > 0.0 ? 1.0 / normalSigma : 0.0;
  const int64_t n = static_cast<int64_t>(faces.size());
  LocalMatrix N;
  N.offsets.resize(n + 1);
  N.offsets[0] = 0;
  for (int64_t i = 0; i < n; ++i)
  {
    const int32_t f = faces[i];
    N.offsets[i + 1] = N.offsets[i] + (graph.offsets[f + 1] - graph.offsets[f]);
  }
  N.ids.resize(N.offsets[n]);
  N.values.resize(N.offsets[n]);
  Spectrum out;
  out.degree.assign(n, 0.0);
  parallel_for(n,
    [&](int64_t i)
    {
      const int32_t f = faces[i];
      int64_t slot = N.offsets[i];
      double sum = 0.0;
      for (int64_t k = graph.offsets[f]; k < graph.offsets[f + 1]; ++k, ++slot)
      {
        const int32_t g = graph.ids[k];
        // Eq. 3: w = beta exp(-(|k_i| + |k_j|) / sigma_k) exp(-dist / sigma_d).
        // With exactNormalSigma, times exp(-(1 - n_i . n_j) / exactNormalSigma).
        const double beta = graph.crest[k] ? crestBeta : 1.0;
        const double bend = invNormalSigma > 0.0
          ? (1.0 - normals[3 * f] * normals[3 * g] - normals[3 * f + 1] * normals[3 * g + 1] -
              normals[3 * f + 2] * normals[3 * g + 2]) *
            invNormalSigma
          : 0.0;
        const double w = beta *
          std::exp(
            std::max(kMinExponent, -(curvExp[f] + curvExp[g]) - graph.dist[k] * invSigmaD - bend));
        N.ids[slot] = localId[g];
        N.values[slot] = w;
        sum += w;
      }
      out.degree[i] = std::max(sum, 1e-300);
    });
  parallel_for(n,
    [&](int64_t i)
    {
      for (int64_t k = N.offsets[i]; k < N.offsets[i + 1]; ++k)
      {
        N.values[k] /= std::sqrt(out.degree[i] * out.degree[N.ids[k]]);
      }
    });
  Eigen::MatrixXd vectors;
  largestEigenpairs(N, ne, progress, out.values, vectors);
  const int dim = static_cast<int>(out.values.size());
  out.vectors.resize(static_cast<size_t>(n) * dim);
  for (int64_t i = 0; i < n; ++i)
  {
    for (int j = 0; j < dim; ++j)
    {
      out.vectors[i * dim + j] = vectors(i, j);
    }
  }
  return out;
}

// Section 4.1: row i of M_e, columns e_j / sqrt(lambda_j), embeds face i (then scaled per
// SpectralEmbedding). Columns with lambda <= 0 are left out: M_e M_e^T approximates the
// similarity only through positive eigenvalues.
// @return n x dim row-major
std::vector<double> embed(const Spectrum& s, SpectralEmbedding mode, int& dim)
{
  const int ne = static_cast<int>(s.values.size());
  const int64_t n = static_cast<int64_t>(s.degree.size());
  std::vector<int> keep;
  for (int j = 0; j < ne; ++j)
  {
    if (s.values[j] > 1e-12)
    {
      keep.push_back(j);
    }
  }
  dim = std::max(1, static_cast<int>(keep.size()));
  std::vector<double> x(static_cast<size_t>(n) * dim, 0.0);
  for (int64_t i = 0; i < n; ++i)
  {
    double* row = x.data() + i * dim;
    double norm2 = 0.0;
    for (size_t j = 0; j < keep.size(); ++j)
    {
      row[j] = s.vectors[i * ne + keep[j]] / std::sqrt(s.values[keep[j]]);
      norm2 += row[j] * row[j];
    }
    double scale = 1.0;
    if (mode == SpectralEmbedding::RandomWalk)
    {
      scale = 1.0 / std::sqrt(s.degree[i]);
    }
    else if (mode == SpectralEmbedding::RowNormalized && norm2 > 0.0)
    {
      scale = 1.0 / std::sqrt(norm2);
    }
    for (int j = 0; j < dim; ++j)
    {
      row[j] *= scale;
    }
  }
  return x;
}

// The count largest eigenpairs of the symmetric matrix a, eigenvalues descending. Lanczos
// (Spectra) when few are wanted from a large matrix: a full dense decomposition costs m^3
// (seconds for m = 1500), a few hundred products m^2 each.
void largestDenseEigenpairs(
  const Eigen::MatrixXd& a, int64_t count, Eigen::VectorXd& values, Eigen::MatrixXd& vectors)
{
  const int64_t m = a.rows();
  if (4 * count < m && m > 300)
  {
    Spectra::DenseSymMatProd<double> op(a);
    const Eigen::Index ncv = std::min<Eigen::Index>(m, 2 * count + 1);
    Spectra::SymEigsSolver<Spectra::DenseSymMatProd<double>> eigs(op, count, ncv);
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestAlge, 1000, 1e-8, Spectra::SortRule::LargestAlge);
    if (eigs.info() == Spectra::CompInfo::Successful)
    {
      values = eigs.eigenvalues();
      vectors = eigs.eigenvectors();
      return;
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(a);
  count = std::min(count, m);
  values.resize(count);
  vectors.resize(m, count);
  for (int64_t j = 0; j < count; ++j)
  {
    // Eigen sorts ascending.
    values(j) = eig.eigenvalues()(m - 1 - j);
    vectors.col(j) = eig.eigenvectors().col(m - 1 - j);
  }
}

// --------------------------------------------------------------------------------------------
// Nystrom approximation (Fowlkes, Belongie, Chung and Malik 2004)

// Eigenvectors of D^-1/2 W D^-1/2 for a kernel defined for every pair of faces: eq. 3 with
// dist = |c_i - c_j|, the Euclidean distance between centroids standing for the geodesic one
// (the only one available for pairs far apart without a graph search per sample), times
// exp(-(1 - n_i . n_j) / nystromNormalSigma) in place of beta: crest lines are not looked up
// per pair, and faces whose normals differ (the two sides of a crease, the two sides of a thin
// part that the Euclidean distance puts close together) are kept apart instead. sigma_d is
// tied to the sampling density (options.nystromKernelScale times the mean distance from a
// sample to its nearest other sample): a kernel much narrower than the sample spacing leaves
// faces unseen by every sample, a much wider one blurs features. The kernel is positive
// definite (a product of the exponential kernels of distance and of normal dot product, scaled
// by g_i g_j), as the extension needs.
//
// One-shot orthogonalized extension with approximate degrees (Fowlkes et al., section 3), in a
// rank-r form: with A = U L U^T (m x m, samples) truncated to its r largest eigenpairs and
// C = B^T U (n-m x r, B the sample-to-rest kernel), W ~ F U L^-1 U^T F^T for F = [A; B^T].
// Degrees d = W 1 ~ [A 1 + B 1; B^T 1 + C L^-1 U^T B 1]; G = D^-1/2 [U L; C] L^-1/2 gives
// D^-1/2 W D^-1/2 ~ G G^T, whose eigenvectors are G R S^-1/2 with G^T G = R S R^T. B is never
// stored: one blocked pass computes B 1, B^T 1 and C; G^T G is summed over blocks.
// @param[in] faces  global ids of the component's faces, ascending
// @param[in] cen    #F x 3 centroids;  nrm: #F x 3 unit normals;  ce: #F |kappa| / sigma_k
Spectrum nystromSpectrum(const std::vector<int32_t>& faces, const std::vector<double>& cen,
  const std::vector<double>& nrm, const std::vector<double>& ce, int ne,
  const SpectralClusteringOptions& options, uint64_t seed, const Progress& progress)
{
  const int64_t n = static_cast<int64_t>(faces.size());
  const int64_t m = std::min<int64_t>(std::max(2, options.nystromSamples), n);
  const std::vector<int64_t> samples = sampleIndices(n, m, mixSeed(seed, 3));
  std::vector<int64_t> rest;
  rest.reserve(n - m);
  {
    size_t s = 0;
    for (int64_t i = 0; i < n; ++i)
    {
      if (s < samples.size() && samples[s] == i)
      {
        ++s;
      }
      else
      {
        rest.push_back(i);
      }
    }
  }
  const int64_t nr = static_cast<int64_t>(rest.size());

  // Kernel width from the sample spacing.
  Eigen::MatrixXd sp(m, 3);
  Eigen::VectorXd sa(m);
  Eigen::MatrixXd sn(m, 3);
  for (int64_t i = 0; i < m; ++i)
  {
    const int32_t f = faces[samples[i]];
    sp.row(i) << cen[3 * f], cen[3 * f + 1], cen[3 * f + 2];
    sa(i) = ce[f];
    sn.row(i) << nrm[3 * f], nrm[3 * f + 1], nrm[3 * f + 2];
  }
  Eigen::MatrixXd sd(m, m);
  double nnSum = 0.0;
  int64_t nnCount = 0;
  for (int64_t i = 0; i < m; ++i)
  {
    double nn = std::numeric_limits<double>::infinity();
    for (int64_t j = 0; j < m; ++j)
    {
      sd(i, j) = (sp.row(i) - sp.row(j)).norm();
      if (j != i && sd(i, j) > 0.0)
      {
        nn = std::min(nn, sd(i, j));
      }
    }
    if (std::isfinite(nn))
    {
      nnSum += nn;
      ++nnCount;
    }
  }
  double sigma = nnCount > 0 ? options.nystromKernelScale * nnSum / nnCount : 0.0;
  if (!(sigma > 0.0))
  {
    sigma = 1.0; // all centroids coincide: any width gives the same (constant) kernel
  }
  const double invSigma = 1.0 / sigma;
  const double invSigmaN =
    options.nystromNormalSigma > 0.0 ? 1.0 / options.nystromNormalSigma : 0.0;

  Eigen::MatrixXd A(m, m);
  for (int64_t i = 0; i < m; ++i)
  {
    for (int64_t j = 0; j < m; ++j)
    {
      A(i, j) = std::exp(std::max(kMinExponent,
        -(sa(i) + sa(j)) - sd(i, j) * invSigma - (1.0 - sn.row(i).dot(sn.row(j))) * invSigmaN));
    }
  }
  sd.resize(0, 0);
  // The r largest eigenpairs of A, descending. Keep those that are numerically positive (A is
  // positive definite in exact arithmetic; tiny or negative eigenvalues are rounding and would
  // blow up L^-1).
  const int64_t rMax = std::min<int64_t>(m, std::max(ne, options.nystromRank));
  Eigen::VectorXd topValues;
  Eigen::MatrixXd topVectors;
  largestDenseEigenpairs(A, rMax, topValues, topVectors);
  progress.report(0.1);
  int64_t r = 0;
  while (r < topValues.size() && topValues(r) > 1e-9 * topValues(0))
  {
    ++r;
  }
  const Eigen::MatrixXd U = topVectors.leftCols(r);
  const Eigen::VectorXd L = topValues.head(r);
  const Eigen::MatrixXf Uf = U.cast<float>();

  // Pass over the rest in blocks: B 1 (per block, summed in order), B^T 1 and C = B^T U.
  const int64_t numBlocks = (nr + kNystromBlock - 1) / kNystromBlock;
  Eigen::MatrixXd blockRowSums = Eigen::MatrixXd::Zero(m, numBlocks);
  std::vector<double> colSum(nr);
  std::vector<float> C(static_cast<size_t>(nr) * r); // row-major nr x r
  const Eigen::ArrayXf sxf = sp.col(0).cast<float>().array();
  const Eigen::ArrayXf syf = sp.col(1).cast<float>().array();
  const Eigen::ArrayXf szf = sp.col(2).cast<float>().array();
  const Eigen::ArrayXf saf = sa.cast<float>().array();
  const Eigen::ArrayXf snx = sn.col(0).cast<float>().array();
  const Eigen::ArrayXf sny = sn.col(1).cast<float>().array();
  const Eigen::ArrayXf snz = sn.col(2).cast<float>().array();
  tbb::enumerable_thread_specific<Eigen::MatrixXf> kernelBlocks;
  parallel_for(
    numBlocks,
    [&](int64_t b)
    {
      const int64_t begin = b * kNystromBlock;
      const int64_t bs = std::min(nr, begin + kNystromBlock) - begin;
      Eigen::ArrayXf px(bs), py(bs), pz(bs), pa(bs), nx(bs), ny(bs), nz(bs);
      for (int64_t j = 0; j < bs; ++j)
      {
        const int32_t f = faces[rest[begin + j]];
        px(j) = static_cast<float>(cen[3 * f]);
        py(j) = static_cast<float>(cen[3 * f + 1]);
        pz(j) = static_cast<float>(cen[3 * f + 2]);
        pa(j) = static_cast<float>(ce[f]);
        nx(j) = static_cast<float>(nrm[3 * f]);
        ny(j) = static_cast<float>(nrm[3 * f + 1]);
        nz(j) = static_cast<float>(nrm[3 * f + 2]);
      }
      // Kt = B^T for this block, bs x m, one sample per column.
      Eigen::MatrixXf& Kt = kernelBlocks.local();
      Kt.resize(bs, m);
      const float inv = static_cast<float>(invSigma);
      const float invN = static_cast<float>(invSigmaN);
      for (int64_t i = 0; i < m; ++i)
      {
        const Eigen::ArrayXf d =
          ((px - sxf(i)).square() + (py - syf(i)).square() + (pz - szf(i)).square()).sqrt();
        const Eigen::ArrayXf c = nx * snx(i) + ny * sny(i) + nz * snz(i);
        Kt.col(i) =
          (-(pa + saf(i)) - d * inv - (1.0f - c) * invN).max(kMinExponentFloat).exp().matrix();
      }
      blockRowSums.col(b) = Kt.colwise().sum().transpose().cast<double>();
      const Eigen::VectorXf rs = Kt.rowwise().sum();
      for (int64_t j = 0; j < bs; ++j)
      {
        colSum[begin + j] = rs(j);
      }
      Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Cb(
        C.data() + begin * r, bs, r);
      Cb.noalias() = Kt * Uf;
    },
    progress.sub(0.1, 0.75));

  // Approximate degrees.
  Eigen::VectorXd b1 = Eigen::VectorXd::Zero(m);
  for (int64_t b = 0; b < numBlocks; ++b)
  {
    b1 += blockRowSums.col(b);
  }
  const Eigen::VectorXd d1 = A * Eigen::VectorXd::Ones(m) + b1;
  const Eigen::VectorXd t = (U.transpose() * b1).cwiseQuotient(L);
  const Eigen::VectorXf tf = t.cast<float>();
  A.resize(0, 0);

  // G rows: samples D^-1/2 U L^1/2, rest D^-1/2 C L^-1/2 (in place in C).
  const Eigen::VectorXd lSqrt = L.cwiseSqrt();
  const Eigen::VectorXf lInvSqrt = lSqrt.cwiseInverse().cast<float>();
  std::vector<double> degree(n);
  Eigen::MatrixXd Gs(m, r);
  for (int64_t i = 0; i < m; ++i)
  {
    degree[samples[i]] = std::max(d1(i), 1e-300);
    Gs.row(i) = U.row(i).cwiseProduct(lSqrt.transpose()) / std::sqrt(degree[samples[i]]);
  }
  std::vector<Eigen::MatrixXd> blockGram(numBlocks);
  parallel_for(
    numBlocks,
    [&](int64_t b)
    {
      const int64_t begin = b * kNystromBlock;
      const int64_t bs = std::min(nr, begin + kNystromBlock) - begin;
      Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Cb(
        C.data() + begin * r, bs, r);
      for (int64_t j = 0; j < bs; ++j)
      {
        // The approximate correction can be negative; the true degree is at least B^T 1.
        const double d2 =
          std::max(colSum[begin + j] + static_cast<double>(Cb.row(j).dot(tf.transpose())),
            std::max(colSum[begin + j], 1e-300));
        degree[rest[begin + j]] = d2;
        Cb.row(j) =
          Cb.row(j).cwiseProduct(lInvSqrt.transpose()) / static_cast<float>(std::sqrt(d2));
      }
      blockGram[b] = (Cb.transpose() * Cb).cast<double>();
    },
    progress.sub(0.75, 0.9));
  Eigen::MatrixXd gram = Gs.transpose() * Gs;
  for (int64_t b = 0; b < numBlocks; ++b)
  {
    gram += blockGram[b];
  }
  blockGram.clear();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigG(gram);
  ne = static_cast<int>(std::min<int64_t>(ne, r));
  Eigen::MatrixXd proj(r, ne); // R S^-1/2 for the ne largest
  Spectrum out;
  out.values.resize(ne);
  for (int j = 0; j < ne; ++j)
  {
    const double s = eigG.eigenvalues()(r - 1 - j);
    out.values[j] = s;
    proj.col(j) = eigG.eigenvectors().col(r - 1 - j) / std::sqrt(std::max(s, 1e-300));
  }
  std::vector<double>& vectors = out.vectors;
  vectors.resize(static_cast<size_t>(n) * ne);
  const Eigen::MatrixXd vs = Gs * proj;
  for (int64_t i = 0; i < m; ++i)
  {
    for (int j = 0; j < ne; ++j)
    {
      vectors[samples[i] * ne + j] = vs(i, j);
    }
  }
  const Eigen::MatrixXf projf = proj.cast<float>();
  parallel_for(
    numBlocks,
    [&](int64_t b)
    {
      const int64_t begin = b * kNystromBlock;
      const int64_t bs = std::min(nr, begin + kNystromBlock) - begin;
      Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Cb(
        C.data() + begin * r, bs, r);
      const Eigen::MatrixXf vb = Cb * projf;
      for (int64_t j = 0; j < bs; ++j)
      {
        for (int c = 0; c < ne; ++c)
        {
          vectors[rest[begin + j] * ne + c] = vb(j, c);
        }
      }
    },
    progress.sub(0.9, 1.0));
  out.degree = std::move(degree);
  return out;
}

// --------------------------------------------------------------------------------------------

// --------------------------------------------------------------------------------------------
// Cluster clean-up

// Every cluster keeps its largest edge-connected piece (the lowest-numbered one on ties); the
// faces of its other pieces join the clusters around them, grown breadth-first from the kept
// pieces (a face takes the cluster of the neighbour that reaches it first, in face order). Each
// cluster is then one connected region and no cluster disappears.
void keepLargestPieces(const DualGraph& adj, int32_t numClusters, std::vector<int32_t>& label)
{
  const int64_t nf = static_cast<int64_t>(label.size());
  std::vector<int32_t> piece(nf, -1);
  std::vector<int64_t> pieceSize;
  std::vector<int32_t> pieceCluster;
  std::vector<int32_t> stack;
  for (int64_t seed = 0; seed < nf; ++seed)
  {
    if (piece[seed] >= 0)
    {
      continue;
    }
    const int32_t id = static_cast<int32_t>(pieceSize.size());
    int64_t size = 0;
    piece[seed] = id;
    stack.push_back(static_cast<int32_t>(seed));
    while (!stack.empty())
    {
      const int32_t f = stack.back();
      stack.pop_back();
      ++size;
      for (int64_t k = adj.offsets[f]; k < adj.offsets[f + 1]; ++k)
      {
        const int32_t g = adj.ids[k];
        if (piece[g] < 0 && label[g] == label[f])
        {
          piece[g] = id;
          stack.push_back(g);
        }
      }
    }
    pieceSize.push_back(size);
    pieceCluster.push_back(label[seed]);
  }
  std::vector<int32_t> mainPiece(numClusters, -1);
  for (int32_t p = 0; p < static_cast<int32_t>(pieceSize.size()); ++p)
  {
    int32_t& best = mainPiece[pieceCluster[p]];
    if (best < 0 || pieceSize[p] > pieceSize[best])
    {
      best = p;
    }
  }
  if (pieceSize.size() == static_cast<size_t>(numClusters))
  {
    return; // every cluster is one piece already
  }
  std::vector<int32_t> queue;
  for (int64_t f = 0; f < nf; ++f)
  {
    if (mainPiece[label[f]] != piece[f])
    {
      label[f] = -1;
    }
  }
  for (int64_t f = 0; f < nf; ++f)
  {
    if (label[f] < 0)
    {
      continue;
    }
    for (int64_t k = adj.offsets[f]; k < adj.offsets[f + 1]; ++k)
    {
      if (label[adj.ids[k]] < 0)
      {
        queue.push_back(static_cast<int32_t>(f));
        break;
      }
    }
  }
  for (size_t head = 0; head < queue.size(); ++head)
  {
    const int32_t f = queue[head];
    for (int64_t k = adj.offsets[f]; k < adj.offsets[f + 1]; ++k)
    {
      const int32_t g = adj.ids[k];
      if (label[g] < 0)
      {
        label[g] = label[f];
        queue.push_back(g);
      }
    }
  }
}

// Cluster ids in the order of the lowest face of each cluster, with no gap.
// @return the number of clusters
int32_t renumberByFirstFace(std::vector<int32_t>& label)
{
  int32_t maxLabel = -1;
  for (int32_t l : label)
  {
    maxLabel = std::max(maxLabel, l);
  }
  std::vector<int32_t> renumber(maxLabel + 1, -1);
  int32_t next = 0;
  for (int32_t& l : label)
  {
    int32_t& id = renumber[l];
    if (id < 0)
    {
      id = next++;
    }
    l = id;
  }
  return next;
}

void validate(const TriMesh& mesh, const std::vector<double>& faceMeanCurvature,
  const std::vector<uint8_t>& crestVertex, const SpectralClusteringOptions& o)
{
  const int64_t nv = mesh.numPoints();
  const int64_t nf = mesh.numTriangles();
  const std::string where = "spectralClustering: ";
  if (mesh.triangles.size() % 3 != 0 || mesh.points.size() % 3 != 0)
  {
    throw InputError(where + "points and triangles must hold 3 numbers each");
  }
  if (o.numClusters < 1)
  {
    throw InputError(
      where + "numClusters is " + std::to_string(o.numClusters) + "; ask for at least 1 cluster");
  }
  if (nf < o.numClusters)
  {
    throw InputError(where + "the mesh has " + std::to_string(nf) + " faces, fewer than the " +
      std::to_string(o.numClusters) + " clusters asked for; lower numClusters to at most " +
      std::to_string(nf));
  }
  for (int32_t id : mesh.triangles)
  {
    if (id < 0 || id >= nv)
    {
      throw InputError(where + "a triangle references vertex " + std::to_string(id) +
        " of a mesh with " + std::to_string(nv) + " vertices; fix the connectivity");
    }
  }
  for (int64_t v = 0; v < nv; ++v)
  {
    if (!std::isfinite(mesh.points[3 * v]) || !std::isfinite(mesh.points[3 * v + 1]) ||
      !std::isfinite(mesh.points[3 * v + 2]))
    {
      throw InputError(where + "point " + std::to_string(v) +
        " has a non-finite coordinate; clean the mesh with tcMeshPreparation first");
    }
  }
  if (static_cast<int64_t>(faceMeanCurvature.size()) != nf)
  {
    throw InputError(where + "faceMeanCurvature has " + std::to_string(faceMeanCurvature.size()) +
      " values but the mesh " + std::to_string(nf) +
      " faces; pass computeCurvature()'s faceMean of the same mesh");
  }
  for (int64_t f = 0; f < nf; ++f)
  {
    if (!std::isfinite(faceMeanCurvature[f]))
    {
      throw InputError(where + "faceMeanCurvature of face " + std::to_string(f) +
        " is not finite; recompute the curvature of a mesh without degenerate faces");
    }
  }
  if (!crestVertex.empty() && static_cast<int64_t>(crestVertex.size()) != nv)
  {
    throw InputError(where + "crestVertex has " + std::to_string(crestVertex.size()) +
      " values but the mesh " + std::to_string(nv) + " vertices; pass crestVertices() of the " +
      "same mesh or an empty array");
  }
  if (o.numEigenvectors < 0 || !(o.crestBeta > 0.0) || !(o.extraEdgeFactor >= 0.0) ||
    !(o.exactNormalSigma >= 0.0) || o.nystromSamples < 2 || o.nystromRank < 1 ||
    !(o.nystromKernelScale > 0.0) || o.kmeansRestarts < 1 || o.kmeansIterations < 1 ||
    o.kmeansSampleSize < 0)
  {
    throw InputError(where +
      "invalid options: need numEigenvectors >= 0, crestBeta > 0, "
      "extraEdgeFactor >= 0, exactNormalSigma >= 0, nystromSamples >= 2, nystromRank >= 1, "
      "nystromKernelScale > 0, kmeansRestarts >= 1, kmeansIterations >= 1, "
      "kmeansSampleSize >= 0");
  }
}

/// Sum, sum of squares and number of the distances of the edges (each counted once) of `graph`
/// that leave the faces `use` marks.
struct DistanceMoments
{
  double sum = 0.0;
  double squares = 0.0;
  double count = 0.0;
};

DistanceMoments distanceMoments(const DualGraph& graph, const std::vector<uint8_t>& use)
{
  DistanceMoments m;
  const int64_t nf = static_cast<int64_t>(use.size());
  for (int64_t f = 0; f < nf; ++f)
  {
    if (!use[f])
    {
      continue;
    }
    for (int64_t k = graph.offsets[f]; k < graph.offsets[f + 1]; ++k)
    {
      if (graph.ids[k] > f)
      {
        m.sum += graph.dist[k];
        m.squares += graph.dist[k] * graph.dist[k];
        m.count += 1.0;
      }
    }
  }
  return m;
}

// Population standard deviation; 0 for fewer than two values.
double standardDeviation(double sum, double sumSquares, double count)
{
  if (count < 2.0)
  {
    return 0.0;
  }
  const double mean = sum / count;
  return std::sqrt(std::max(0.0, sumSquares / count - mean * mean));
}
} // namespace

SpectralClusteringResult spectralClustering(const TriMesh& mesh,
  const std::vector<double>& faceMeanCurvature, const std::vector<uint8_t>& crestVertex,
  const SpectralClusteringOptions& options, const Progress& progress)
{
  validate(mesh, faceMeanCurvature, crestVertex, options);
  const int64_t nf = mesh.numTriangles();

  std::vector<double> centroids(3 * nf);
  parallel_for(nf,
    [&](int64_t f)
    {
      for (int c = 0; c < 3; ++c)
      {
        centroids[3 * f + c] = (mesh.points[3 * mesh.triangles[3 * f] + c] +
                                 mesh.points[3 * mesh.triangles[3 * f + 1] + c] +
                                 mesh.points[3 * mesh.triangles[3 * f + 2] + c]) /
          3.0;
      }
    });
  // Unit face normals (zero for a degenerate face), for the Nystrom kernel.
  std::vector<double> normals(3 * nf, 0.0);
  parallel_for(nf,
    [&](int64_t f)
    {
      const double* a = &mesh.points[3 * mesh.triangles[3 * f]];
      const double* b = &mesh.points[3 * mesh.triangles[3 * f + 1]];
      const double* c = &mesh.points[3 * mesh.triangles[3 * f + 2]];
      const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
      const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
      const double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0] };
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int d = 0; d < 3 && len > 0.0; ++d)
      {
        normals[3 * f + d] = n[d] / len;
      }
    });
  const DualGraph adjacent =
    buildAdjacentDual(mesh, centroids, crestVertex, progress.sub(0.0, 0.05));

  // Components, their faces (ascending) and their share of the clusters.
  std::vector<int32_t> componentOf;
  const int64_t nc = findComponents(adjacent, nf, componentOf);
  std::vector<int64_t> sizes(nc, 0);
  for (int64_t f = 0; f < nf; ++f)
  {
    ++sizes[componentOf[f]];
  }
  std::vector<std::vector<int32_t>> componentFaces(nc);
  for (int64_t c = 0; c < nc; ++c)
  {
    componentFaces[c].reserve(sizes[c]);
  }
  for (int64_t f = 0; f < nf; ++f)
  {
    componentFaces[componentOf[f]].push_back(static_cast<int32_t>(f));
  }
  const std::vector<int> clustersOf = allocateClusters(sizes, options.numClusters);

  // Eq. 3: sigma_k is the standard deviation of |kappa| over all faces. A constant |kappa|
  // (a plane, a sphere) has sigma_k = 0; the factor is then the same for every pair and
  // cancels in D^-1/2 W D^-1/2, so it is left out (no 0/0).
  double ks = 0.0, kss = 0.0;
  for (double k : faceMeanCurvature)
  {
    ks += std::abs(k);
    kss += k * k;
  }
  const double sigmaK = standardDeviation(ks, kss, static_cast<double>(nf));
  std::vector<double> curvExp(nf, 0.0);
  if (sigmaK > 0.0)
  {
    for (int64_t f = 0; f < nf; ++f)
    {
      curvExp[f] = std::abs(faceMeanCurvature[f]) / sigmaK;
    }
  }

  // Which components need the exact sparse graph.
  std::vector<uint8_t> exactFace(nf, 0);
  bool anyExact = false;
  for (int64_t c = 0; c < nc; ++c)
  {
    if (clustersOf[c] >= 2 && sizes[c] <= options.nystromThreshold)
    {
      anyExact = true;
      for (int32_t f : componentFaces[c])
      {
        exactFace[f] = 1;
      }
    }
  }
  // Section 4.2: extra dual edges below extraEdgeFactor times the mean adjacent distance.
  DualGraph graph;
  double sigmaD = 0.0;
  if (anyExact)
  {
    const DistanceMoments near = distanceMoments(adjacent, exactFace);
    const double radius = options.extraEdgeFactor * (near.count > 0 ? near.sum / near.count : 0.0);
    if (radius > 0.0)
    {
      graph = addExtraEdges(adjacent, exactFace, radius, progress.sub(0.05, 0.2));
    }
    else
    {
      graph = adjacent;
    }
    // Eq. 3: sigma_d is the standard deviation of dist over the edges of the graph used.
    const DistanceMoments used = distanceMoments(graph, exactFace);
    sigmaD = standardDeviation(used.sum, used.squares, used.count);
  }
  // Equal distances everywhere (a regular mesh without extra edges): the factor is constant.
  const double invSigmaD = sigmaD > 0.0 ? 1.0 / sigmaD : 0.0;

  SpectralClusteringResult result;
  result.clusterId.assign(nf, -1);
  int64_t largest = 0;
  for (int64_t c = 1; c < nc; ++c)
  {
    if (sizes[c] > sizes[largest])
    {
      largest = c;
    }
  }
  std::vector<int32_t> localId(nf, 0);
  const Progress work = progress.sub(0.2, 1.0);
  int64_t done = 0;
  int32_t nextCluster = 0;
  for (int64_t c = 0; c < nc; ++c)
  {
    const std::vector<int32_t>& faces = componentFaces[c];
    const int64_t n = sizes[c];
    const Progress part =
      work.sub(static_cast<double>(done) / nf, static_cast<double>(done + n) / nf);
    done += n;
    const int k = clustersOf[c];
    if (k <= 1)
    {
      for (int32_t f : faces)
      {
        result.clusterId[f] = nextCluster;
      }
      ++nextCluster;
      part.report(1.0);
      continue;
    }
    if (k >= n)
    {
      // As many clusters as faces: nothing to embed (and a 2-face graph has eigenvalues 1
      // and -1, whose embedding could not tell the faces apart).
      for (int32_t f : faces)
      {
        result.clusterId[f] = nextCluster++;
      }
      part.report(1.0);
      continue;
    }
    const int neWanted = options.numEigenvectors > 0 ? options.numEigenvectors : k;
    Spectrum spectrum;
    if (n <= options.nystromThreshold)
    {
      for (int64_t i = 0; i < n; ++i)
      {
        localId[faces[i]] = static_cast<int32_t>(i);
      }
      spectrum = exactSpectrum(faces, graph, localId, curvExp, invSigmaD, options.crestBeta,
        normals, options.exactNormalSigma, neWanted, part.sub(0.0, 0.8));
    }
    else
    {
      result.usedNystrom = true;
      spectrum = nystromSpectrum(faces, centroids, normals, curvExp, neWanted, options,
        mixSeed(options.seed, 100, static_cast<uint64_t>(c)), part.sub(0.0, 0.8));
    }
    if (c == largest)
    {
      result.eigenvalues = spectrum.values;
    }
    int dim = 0;
    const std::vector<double> embedding = embed(spectrum, options.embedding, dim);
    const std::vector<int32_t> labels = kmeans(embedding, n, dim, k, options,
      mixSeed(options.seed, 200, static_cast<uint64_t>(c)), part.sub(0.8, 1.0));
    // Renumber by first face: cluster ids follow the order of the lowest face of each cluster,
    // and clusters left empty (fewer distinct rows than k) take no id.
    std::vector<int32_t> renumber(k, -1);
    for (int64_t i = 0; i < n; ++i)
    {
      int32_t& id = renumber[labels[i]];
      if (id < 0)
      {
        id = nextCluster++;
      }
      result.clusterId[faces[i]] = id;
    }
  }
  if (options.connectedClusters)
  {
    keepLargestPieces(adjacent, nextCluster, result.clusterId);
  }
  result.numClusters = renumberByFirstFace(result.clusterId);
  progress.report(1.0);
  return result;
}
} // namespace tc
