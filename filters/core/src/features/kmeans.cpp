// SPDX-License-Identifier: BSD-3-Clause
#include "features/kmeans.h"

#include "features/seeded_random.h"

#include "tc/common/parallel.h"

#include <Eigen/Core>

#include <algorithm>
#include <limits>
#include <random>

namespace tc
{
namespace detail
{
namespace spectral
{
namespace
{
// Rows per chunk of the blocked k-means passes (fixed, so sums do not depend on the threads).
constexpr int64_t kKMeansChunk = 4096;
// Lloyd stops once at most 1 / this of the rows changed cluster in an iteration.
constexpr int64_t kKMeansStableFraction = 2000;

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

// The nearest center of every row, and the per-cluster coordinate sums, counts and inertia
// that follow; assignRows() adds them over fixed chunks, in the same order with any number of
// threads.
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

// The rows that the restarts run on: a seeded sample of sampleSize rows (row-major copy).
std::vector<double> sampleRows(
  const std::vector<double>& x, int64_t n, int dim, int64_t sampleSize, uint64_t seed)
{
  const std::vector<int64_t> rows = sampleIndices(n, sampleSize, mixSeed(seed, 1));
  std::vector<double> sample(static_cast<size_t>(sampleSize) * dim);
  for (int64_t i = 0; i < sampleSize; ++i)
  {
    std::copy(x.begin() + rows[i] * dim, x.begin() + (rows[i] + 1) * dim, sample.begin() + i * dim);
  }
  return sample;
}

// The centers of the restart of lowest inertia (the lowest restart on ties), each restart
// seeded by k-means++ with its own generator and refined by Lloyd on the ns rows of data.
std::vector<double> bestRestart(const double* data, int64_t ns, int dim, int k,
  const SpectralClusteringOptions& options, uint64_t seed, const Progress& progress)
{
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
    progress, 1);
  int best = 0;
  for (int r = 1; r < restarts; ++r)
  {
    if (runs[r].inertia < runs[best].inertia)
    {
      best = r;
    }
  }
  return runs[best].centers;
}
} // namespace

std::vector<int32_t> kmeans(const std::vector<double>& x, int64_t n, int dim, int k,
  const SpectralClusteringOptions& options, uint64_t seed, const Progress& progress)
{
  // The sample keeps at least 50 rows per cluster, so that small clusters are seen.
  const int64_t sampleSize = std::max<int64_t>(options.kmeansSampleSize, 50 * int64_t(k));
  const bool sampled = options.kmeansSampleSize > 0 && n > sampleSize;
  const std::vector<double> sample =
    sampled ? sampleRows(x, n, dim, sampleSize, seed) : std::vector<double>();
  std::vector<double> centers = bestRestart(sampled ? sample.data() : x.data(),
    sampled ? sampleSize : n, dim, k, options, seed, progress.sub(0.0, sampled ? 0.5 : 0.9));
  // Without a sample the restarts saw every row: only the final assignment is left.
  std::vector<int32_t> labels;
  lloyd(x.data(), n, dim, k, sampled ? options.kmeansIterations : 0, centers, labels, true);
  progress.report(1.0);
  return labels;
}
} // namespace spectral
} // namespace detail
} // namespace tc
