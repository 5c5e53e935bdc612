// SPDX-License-Identifier: BSD-3-Clause
#include "features/spectrum.h"

#include "features/seeded_random.h"

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
#include <stdexcept>
#include <string>

namespace tc
{
namespace detail
{
namespace spectral
{
namespace
{
// Components up to this size are solved with a dense eigensolver (cheaper and always
// convergent there).
constexpr int64_t kDenseEigenLimit = 400;
// Faces per block of the Nystrom passes: a float block of nystromSamples x this stays small.
constexpr int64_t kNystromBlock = 1024;

// exp() of anything below this is still a normal double: a face whose curvature is far above
// sigma_k keeps a tiny positive similarity instead of becoming an isolated node (D = 0).
constexpr double kMinExponent = -600.0;
// The same for the float kernel blocks of the Nystrom method (and no denormals in the GEMMs).
constexpr float kMinExponentFloat = -60.0f;

using RowMajorXf = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Sparse symmetric matrix in CSR form over a component's faces (local ids).
struct LocalMatrix
{
  std::vector<int64_t> offsets; // rows + 1
  std::vector<int32_t> ids;
  std::vector<double> values;
  int64_t rows() const { return static_cast<int64_t>(offsets.size()) - 1; }
};

// ---------------------------------------------------------------------------------------------
// Eq. 3 on the dual graph

// W over the component's faces (local ids), weight(k, f, g) on the graph's entry k from face f
// to face g, and the degrees D = W 1 (at least 1e-300).
template <typename Weight>
LocalMatrix similarityRows(const std::vector<int32_t>& faces, const DualGraph& graph,
  const std::vector<int32_t>& localId, const Weight& weight, std::vector<double>& degree)
{
  const int64_t n = static_cast<int64_t>(faces.size());
  LocalMatrix W;
  W.offsets.resize(n + 1);
  W.offsets[0] = 0;
  for (int64_t i = 0; i < n; ++i)
  {
    const int32_t f = faces[i];
    W.offsets[i + 1] = W.offsets[i] + (graph.offsets[f + 1] - graph.offsets[f]);
  }
  W.ids.resize(W.offsets[n]);
  W.values.resize(W.offsets[n]);
  degree.assign(n, 0.0);
  parallel_for(n,
    [&](int64_t i)
    {
      const int32_t f = faces[i];
      int64_t slot = W.offsets[i];
      double sum = 0.0;
      for (int64_t k = graph.offsets[f]; k < graph.offsets[f + 1]; ++k, ++slot)
      {
        const int32_t g = graph.ids[k];
        const double w = weight(k, f, g);
        W.ids[slot] = localId[g];
        W.values[slot] = w;
        sum += w;
      }
      degree[i] = std::max(sum, 1e-300);
    });
  return W;
}

// N = D^-1/2 W D^-1/2 (eq. 2), in place.
void normalize(LocalMatrix& W, const std::vector<double>& degree)
{
  parallel_for(W.rows(),
    [&](int64_t i)
    {
      for (int64_t k = W.offsets[i]; k < W.offsets[i + 1]; ++k)
      {
        W.values[k] /= std::sqrt(degree[i] * degree[W.ids[k]]);
      }
    });
}

// N = D^-1/2 W D^-1/2 (eq. 2) of eq. 3 over the component's faces, and the degrees D.
LocalMatrix normalizedSimilarity(const std::vector<int32_t>& faces, const ExactGraph& exact,
  const std::vector<int32_t>& localId, const std::vector<double>& curvExp,
  const std::vector<double>& normals, const SpectralClusteringOptions& options,
  std::vector<double>& degree)
{
  const DualGraph& graph = exact.graph;
  const double invNormalSigma =
    options.exactNormalSigma > 0.0 ? 1.0 / options.exactNormalSigma : 0.0;
  const auto eq3 = [&](int64_t k, int32_t f, int32_t g)
  {
    // Eq. 3: w = beta exp(-(|k_i| + |k_j|) / sigma_k) exp(-dist / sigma_d).
    // With exactNormalSigma, times exp(-(1 - n_i . n_j) / exactNormalSigma).
    const double beta = graph.crest[k] ? options.crestBeta : 1.0;
    const double bend = invNormalSigma > 0.0
      ? (1.0 - normals[3 * f] * normals[3 * g] - normals[3 * f + 1] * normals[3 * g + 1] -
          normals[3 * f + 2] * normals[3 * g + 2]) *
        invNormalSigma
      : 0.0;
    return beta *
      std::exp(std::max(
        kMinExponent, -(curvExp[f] + curvExp[g]) - graph.dist[k] * exact.invSigmaD - bend));
  };
  LocalMatrix N = similarityRows(faces, graph, localId, eq3, degree);
  normalize(N, degree);
  return N;
}

// ---------------------------------------------------------------------------------------------
// Dense eigenpairs

// The count largest eigenpairs of the symmetric matrix a by a full decomposition, eigenvalues
// descending.
void denseLargest(
  const Eigen::MatrixXd& a, int64_t count, Eigen::VectorXd& values, Eigen::MatrixXd& vectors)
{
  const int64_t m = a.rows();
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

// The count largest eigenpairs of the symmetric matrix a, eigenvalues descending. Lanczos
// (Spectra) when few are wanted from a large matrix: a full dense decomposition costs m^3, a
// few hundred products m^2 each.
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
  denseLargest(a, count, values, vectors);
}

// ---------------------------------------------------------------------------------------------
// Exact sparse eigenpairs

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

Eigen::MatrixXd toDense(const LocalMatrix& n)
{
  const int64_t rows = n.rows();
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(rows, rows);
  for (int64_t i = 0; i < rows; ++i)
  {
    for (int64_t k = n.offsets[i]; k < n.offsets[i + 1]; ++k)
    {
      dense(i, n.ids[k]) = n.values[k];
    }
  }
  return dense;
}

// The lower triangle of L + eps I = (1 + eps) I - N.
Eigen::SparseMatrix<double> shiftedLaplacian(const LocalMatrix& n, double eps)
{
  const int64_t rows = n.rows();
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
  return shifted;
}

// The largest eigenvalues of N = D^-1/2 W D^-1/2 crowd just below 1 on a mesh graph
// (1 - O(h^2)), so Lanczos on N itself needs thousands of products. They are the smallest of
// the Laplacian L = I - N (eq. 2), which shift-invert spreads apart: Lanczos on (L + eps I)^-1
// (sparse LDLT, AMD ordering) converges in a few dozen solves. eps > 0 makes L + eps I positive
// definite (L is singular: L D^1/2 1 = 0) and is far below the gaps that matter.
// @return false when the factorization or Lanczos fails
bool shiftInvertLanczos(const LocalMatrix& n, int ne, const Progress& progress,
  std::vector<double>& values, Eigen::MatrixXd& vectors)
{
  constexpr double eps = 1e-6;
  const int64_t rows = n.rows();
  const SparseLDLT factor(shiftedLaplacian(n, eps));
  progress.report(0.3);
  if (factor.info() != Eigen::Success)
  {
    return false;
  }
  const int ncv = static_cast<int>(std::min<int64_t>(rows, std::max(2 * ne + 1, ne + 20)));
  ProductCounter counter(progress.sub(0.3, 1.0), 4 * ncv);
  ShiftInvertProduct op(factor, rows, counter);
  Spectra::SymEigsSolver<ShiftInvertProduct> eigs(op, ne, ncv);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestAlge, 1000, 1e-10, Spectra::SortRule::LargestAlge);
  if (eigs.info() != Spectra::CompInfo::Successful)
  {
    return false;
  }
  // nu = 1 / (mu + eps) with mu = 1 - lambda.
  const Eigen::VectorXd nu = eigs.eigenvalues();
  values.resize(nu.size());
  for (Eigen::Index j = 0; j < nu.size(); ++j)
  {
    values[j] = 1.0 - (1.0 / nu(j) - eps);
  }
  vectors = eigs.eigenvectors();
  return true;
}

// The fallback: Lanczos on N itself.
void plainLanczos(const LocalMatrix& n, int ne, const Progress& progress,
  std::vector<double>& values, Eigen::MatrixXd& vectors)
{
  const int64_t rows = n.rows();
  const int ncv = static_cast<int>(std::min<int64_t>(rows, std::max(2 * ne + 1, ne + 40)));
  ProductCounter counter(progress, 100 * ncv);
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
}

// ---------------------------------------------------------------------------------------------
// Nystrom approximation (Fowlkes, Belongie, Chung and Malik 2004)

// The sampled faces of a component and the rest, local ids ascending.
struct SampleSplit
{
  std::vector<int64_t> samples;
  std::vector<int64_t> rest;
};

SampleSplit splitSamples(int64_t n, int64_t m, uint64_t seed)
{
  SampleSplit split;
  split.samples = sampleIndices(n, m, seed);
  split.rest.reserve(n - m);
  size_t s = 0;
  for (int64_t i = 0; i < n; ++i)
  {
    if (s < split.samples.size() && split.samples[s] == i)
    {
      ++s;
    }
    else
    {
      split.rest.push_back(i);
    }
  }
  return split;
}

// Centroids, curvature exponents |kappa| / sigma_k and unit normals of the samples.
struct SampleData
{
  Eigen::MatrixXd points;  // m x 3
  Eigen::VectorXd kappa;   // m
  Eigen::MatrixXd normals; // m x 3
};

SampleData gatherSamples(const std::vector<int32_t>& faces, const std::vector<int64_t>& samples,
  const std::vector<double>& cen, const std::vector<double>& nrm, const std::vector<double>& ce)
{
  const int64_t m = static_cast<int64_t>(samples.size());
  SampleData s{ Eigen::MatrixXd(m, 3), Eigen::VectorXd(m), Eigen::MatrixXd(m, 3) };
  for (int64_t i = 0; i < m; ++i)
  {
    const int32_t f = faces[samples[i]];
    s.points.row(i) << cen[3 * f], cen[3 * f + 1], cen[3 * f + 2];
    s.kappa(i) = ce[f];
    s.normals.row(i) << nrm[3 * f], nrm[3 * f + 1], nrm[3 * f + 2];
  }
  return s;
}

// The same in float, one array per coordinate, for the blocked kernel pass.
struct SampleFloats
{
  Eigen::ArrayXf x, y, z, kappa, nx, ny, nz;
};

SampleFloats toFloats(const SampleData& s)
{
  return { s.points.col(0).cast<float>().array(), s.points.col(1).cast<float>().array(),
    s.points.col(2).cast<float>().array(), s.kappa.cast<float>().array(),
    s.normals.col(0).cast<float>().array(), s.normals.col(1).cast<float>().array(),
    s.normals.col(2).cast<float>().array() };
}

// The kernel's exponent scales: 1 / sigma_d and 1 / nystromNormalSigma (0: no normal term).
struct KernelScales
{
  double invSigma = 0.0;
  double invSigmaN = 0.0;
};

// Pairwise sample distances (m x m) and sigma_d: nystromKernelScale times the mean distance
// from a sample to its nearest other sample.
Eigen::MatrixXd sampleDistances(
  const SampleData& s, const SpectralClusteringOptions& options, KernelScales& scales)
{
  const int64_t m = s.points.rows();
  Eigen::MatrixXd sd(m, m);
  double nnSum = 0.0;
  int64_t nnCount = 0;
  for (int64_t i = 0; i < m; ++i)
  {
    double nn = std::numeric_limits<double>::infinity();
    for (int64_t j = 0; j < m; ++j)
    {
      sd(i, j) = (s.points.row(i) - s.points.row(j)).norm();
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
  scales.invSigma = 1.0 / sigma;
  scales.invSigmaN = options.nystromNormalSigma > 0.0 ? 1.0 / options.nystromNormalSigma : 0.0;
  return sd;
}

// A: the kernel between the samples, m x m.
Eigen::MatrixXd sampleKernel(const SampleData& s, const Eigen::MatrixXd& sd, const KernelScales& k)
{
  const int64_t m = s.points.rows();
  Eigen::MatrixXd A(m, m);
  for (int64_t i = 0; i < m; ++i)
  {
    for (int64_t j = 0; j < m; ++j)
    {
      A(i, j) = std::exp(std::max(kMinExponent,
        -(s.kappa(i) + s.kappa(j)) - sd(i, j) * k.invSigma -
          (1.0 - s.normals.row(i).dot(s.normals.row(j))) * k.invSigmaN));
    }
  }
  return A;
}

// The r largest eigenpairs of A, descending, of those that are numerically positive (A is
// positive definite in exact arithmetic; tiny or negative eigenvalues are rounding and would
// blow up L^-1).
struct TopEigenpairs
{
  Eigen::MatrixXd U; // m x r
  Eigen::VectorXd L; // r
};

TopEigenpairs positiveTopEigenpairs(const Eigen::MatrixXd& A, int64_t rMax)
{
  Eigen::VectorXd topValues;
  Eigen::MatrixXd topVectors;
  largestDenseEigenpairs(A, rMax, topValues, topVectors);
  int64_t r = 0;
  while (r < topValues.size() && topValues(r) > 1e-9 * topValues(0))
  {
    ++r;
  }
  return { topVectors.leftCols(r), topValues.head(r) };
}

// The rest faces in blocks of kNystromBlock, with their rows of the row-major nr x r matrix C.
struct Blocks
{
  int64_t rows = 0;
  int64_t count() const { return (rows + kNystromBlock - 1) / kNystromBlock; }
  int64_t begin(int64_t b) const { return b * kNystromBlock; }
  int64_t size(int64_t b) const { return std::min(rows, begin(b) + kNystromBlock) - begin(b); }
  Eigen::Map<RowMajorXf> of(std::vector<float>& C, int64_t b, int64_t r) const
  {
    return Eigen::Map<RowMajorXf>(C.data() + begin(b) * r, size(b), r);
  }
};

// Kt = B^T for one block of rest faces: bs x m, one sample per column.
void blockKernel(const std::vector<int32_t>& faces, const std::vector<int64_t>& rest, int64_t begin,
  int64_t bs, const std::vector<double>& cen, const std::vector<double>& nrm,
  const std::vector<double>& ce, const SampleFloats& s, const KernelScales& k, Eigen::MatrixXf& Kt)
{
  const int64_t m = s.x.size();
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
  Kt.resize(bs, m);
  const float inv = static_cast<float>(k.invSigma);
  const float invN = static_cast<float>(k.invSigmaN);
  for (int64_t i = 0; i < m; ++i)
  {
    const Eigen::ArrayXf d =
      ((px - s.x(i)).square() + (py - s.y(i)).square() + (pz - s.z(i)).square()).sqrt();
    const Eigen::ArrayXf c = nx * s.nx(i) + ny * s.ny(i) + nz * s.nz(i);
    Kt.col(i) =
      (-(pa + s.kappa(i)) - d * inv - (1.0f - c) * invN).max(kMinExponentFloat).exp().matrix();
  }
}

// One blocked pass over the rest faces: B 1 per block (summed in order later), B^T 1 and
// C = B^T U. B itself is never stored.
struct RestPass
{
  Eigen::MatrixXd blockRowSums; // m x #blocks
  std::vector<double> colSum;   // nr
  std::vector<float> C;         // nr x r, row-major
};

RestPass restPass(const std::vector<int32_t>& faces, const std::vector<int64_t>& rest,
  const std::vector<double>& cen, const std::vector<double>& nrm, const std::vector<double>& ce,
  const SampleFloats& s, const KernelScales& k, const Eigen::MatrixXd& U, const Blocks& blocks,
  const Progress& progress)
{
  const int64_t m = s.x.size();
  const int64_t r = U.cols();
  const Eigen::MatrixXf Uf = U.cast<float>();
  RestPass pass{ Eigen::MatrixXd::Zero(m, blocks.count()), std::vector<double>(blocks.rows),
    std::vector<float>(static_cast<size_t>(blocks.rows) * r) };
  tbb::enumerable_thread_specific<Eigen::MatrixXf> kernelBlocks;
  parallel_for(
    blocks.count(),
    [&](int64_t b)
    {
      const int64_t begin = blocks.begin(b);
      const int64_t bs = blocks.size(b);
      Eigen::MatrixXf& Kt = kernelBlocks.local();
      blockKernel(faces, rest, begin, bs, cen, nrm, ce, s, k, Kt);
      pass.blockRowSums.col(b) = Kt.colwise().sum().transpose().cast<double>();
      const Eigen::VectorXf rs = Kt.rowwise().sum();
      for (int64_t j = 0; j < bs; ++j)
      {
        pass.colSum[begin + j] = rs(j);
      }
      blocks.of(pass.C, b, r).noalias() = Kt * Uf;
    },
    progress);
  return pass;
}

// Rows of G for the rest faces, D^-1/2 C L^-1/2, in place in C, with their approximate degrees
// B^T 1 + C L^-1 U^T B 1 (t = L^-1 U^T B 1); the Gram matrix G^T G of each block.
std::vector<Eigen::MatrixXd> restRowsOfG(RestPass& pass, const Eigen::VectorXf& tf,
  const Eigen::VectorXf& lInvSqrt, const std::vector<int64_t>& rest, const Blocks& blocks,
  std::vector<double>& degree, const Progress& progress)
{
  const int64_t r = lInvSqrt.size();
  std::vector<Eigen::MatrixXd> blockGram(blocks.count());
  parallel_for(
    blocks.count(),
    [&](int64_t b)
    {
      const int64_t begin = blocks.begin(b);
      Eigen::Map<RowMajorXf> Cb = blocks.of(pass.C, b, r);
      for (int64_t j = 0; j < blocks.size(b); ++j)
      {
        // The approximate correction can be negative; the true degree is at least B^T 1.
        const double d2 =
          std::max(pass.colSum[begin + j] + static_cast<double>(Cb.row(j).dot(tf.transpose())),
            std::max(pass.colSum[begin + j], 1e-300));
        degree[rest[begin + j]] = d2;
        Cb.row(j) =
          Cb.row(j).cwiseProduct(lInvSqrt.transpose()) / static_cast<float>(std::sqrt(d2));
      }
      blockGram[b] = (Cb.transpose() * Cb).cast<double>();
    },
    progress);
  return blockGram;
}

// Eigenvectors G R S^-1/2 of G G^T from G^T G = R S R^T, the ne largest: samples from Gs, the
// rest from the rows of G in C.
void extendEigenvectors(const Eigen::MatrixXd& Gs, const Eigen::MatrixXd& gram, RestPass& pass,
  const SampleSplit& split, const Blocks& blocks, int ne, Spectrum& out, const Progress& progress)
{
  const int64_t m = Gs.rows();
  const int64_t r = Gs.cols();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigG(gram);
  ne = static_cast<int>(std::min<int64_t>(ne, r));
  Eigen::MatrixXd proj(r, ne); // R S^-1/2 for the ne largest
  out.values.resize(ne);
  for (int j = 0; j < ne; ++j)
  {
    const double s = eigG.eigenvalues()(r - 1 - j);
    out.values[j] = s;
    proj.col(j) = eigG.eigenvectors().col(r - 1 - j) / std::sqrt(std::max(s, 1e-300));
  }
  std::vector<double>& vectors = out.vectors;
  vectors.resize(static_cast<size_t>(m + blocks.rows) * ne);
  const Eigen::MatrixXd vs = Gs * proj;
  for (int64_t i = 0; i < m; ++i)
  {
    for (int j = 0; j < ne; ++j)
    {
      vectors[split.samples[i] * ne + j] = vs(i, j);
    }
  }
  const Eigen::MatrixXf projf = proj.cast<float>();
  parallel_for(
    blocks.count(),
    [&](int64_t b)
    {
      const Eigen::MatrixXf vb = blocks.of(pass.C, b, r) * projf;
      for (int64_t j = 0; j < blocks.size(b); ++j)
      {
        for (int c = 0; c < ne; ++c)
        {
          vectors[split.rest[blocks.begin(b) + j] * ne + c] = vb(j, c);
        }
      }
    },
    progress);
}
// The ne largest eigenpairs of n, eigenvalues descending, eigenvectors rows x Ne row-major.
void largestEigenpairs(const LocalMatrix& n, int ne, const Progress& progress,
  std::vector<double>& values, std::vector<double>& rowMajorVectors)
{
  const int64_t rows = n.rows();
  ne = static_cast<int>(std::min<int64_t>(ne, rows));
  Eigen::MatrixXd vectors;
  if (rows <= kDenseEigenLimit || 2 * static_cast<int64_t>(ne) + 1 >= rows)
  {
    Eigen::VectorXd dense;
    denseLargest(toDense(n), ne, dense, vectors);
    values.assign(dense.data(), dense.data() + dense.size());
  }
  else if (!shiftInvertLanczos(n, ne, progress, values, vectors))
  {
    plainLanczos(n, ne, progress.sub(0.3, 1.0), values, vectors);
  }
  progress.report(1.0);
  const int dim = static_cast<int>(values.size());
  rowMajorVectors.resize(static_cast<size_t>(rows) * dim);
  for (int64_t i = 0; i < rows; ++i)
  {
    for (int j = 0; j < dim; ++j)
    {
      rowMajorVectors[i * dim + j] = vectors(i, j);
    }
  }
}
} // namespace

Spectrum exactSpectrum(const std::vector<int32_t>& faces, const ExactGraph& exact,
  const std::vector<int32_t>& localId, const std::vector<double>& curvExp,
  const std::vector<double>& normals, int ne, const SpectralClusteringOptions& options,
  const Progress& progress)
{
  Spectrum out;
  const LocalMatrix N =
    normalizedSimilarity(faces, exact, localId, curvExp, normals, options, out.degree);
  largestEigenpairs(N, ne, progress, out.values, out.vectors);
  return out;
}

Spectrum weightedSpectrum(const std::vector<int32_t>& faces, const DualGraph& graph,
  const std::vector<double>& weights, const std::vector<int32_t>& localId, int ne,
  const Progress& progress)
{
  Spectrum out;
  LocalMatrix N = similarityRows(
    faces, graph, localId, [&](int64_t k, int32_t, int32_t) { return weights[k]; }, out.degree);
  normalize(N, out.degree);
  largestEigenpairs(N, ne, progress, out.values, out.vectors);
  return out;
}

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
Spectrum nystromSpectrum(const std::vector<int32_t>& faces, const std::vector<double>& cen,
  const std::vector<double>& nrm, const std::vector<double>& ce, int ne,
  const SpectralClusteringOptions& options, uint64_t seed, const Progress& progress)
{
  const int64_t n = static_cast<int64_t>(faces.size());
  const int64_t m = std::min<int64_t>(std::max(2, options.nystromSamples), n);

  // 1. Samples, and the kernel A between them with its width from the sample spacing.
  const SampleSplit split = splitSamples(n, m, mixSeed(seed, 3));
  const SampleData samples = gatherSamples(faces, split.samples, cen, nrm, ce);
  KernelScales scales;
  Eigen::MatrixXd sd = sampleDistances(samples, options, scales);
  Eigen::MatrixXd A = sampleKernel(samples, sd, scales);
  sd.resize(0, 0);

  // 2. The rank-r truncation A ~ U L U^T.
  const TopEigenpairs top =
    positiveTopEigenpairs(A, std::min<int64_t>(m, std::max(ne, options.nystromRank)));
  progress.report(0.1);
  const Eigen::MatrixXd& U = top.U;
  const Eigen::VectorXd& L = top.L;

  // 3. B 1, B^T 1 and C = B^T U over the rest faces.
  const Blocks blocks{ static_cast<int64_t>(split.rest.size()) };
  RestPass pass = restPass(
    faces, split.rest, cen, nrm, ce, toFloats(samples), scales, U, blocks, progress.sub(0.1, 0.75));

  // 4. Approximate degrees of the samples, A 1 + B 1, and t = L^-1 U^T B 1 for the rest.
  Eigen::VectorXd b1 = Eigen::VectorXd::Zero(m);
  for (int64_t b = 0; b < blocks.count(); ++b)
  {
    b1 += pass.blockRowSums.col(b);
  }
  const Eigen::VectorXd d1 = A * Eigen::VectorXd::Ones(m) + b1;
  const Eigen::VectorXd t = (U.transpose() * b1).cwiseQuotient(L);
  A.resize(0, 0);

  // 5. G: sample rows D^-1/2 U L^1/2, rest rows D^-1/2 C L^-1/2 (in place in C), and G^T G.
  const Eigen::VectorXd lSqrt = L.cwiseSqrt();
  Spectrum out;
  out.degree.resize(n);
  Eigen::MatrixXd Gs(m, U.cols());
  for (int64_t i = 0; i < m; ++i)
  {
    out.degree[split.samples[i]] = std::max(d1(i), 1e-300);
    Gs.row(i) = U.row(i).cwiseProduct(lSqrt.transpose()) / std::sqrt(out.degree[split.samples[i]]);
  }
  std::vector<Eigen::MatrixXd> blockGram = restRowsOfG(pass, t.cast<float>(),
    lSqrt.cwiseInverse().cast<float>(), split.rest, blocks, out.degree, progress.sub(0.75, 0.9));
  Eigen::MatrixXd gram = Gs.transpose() * Gs;
  for (int64_t b = 0; b < blocks.count(); ++b)
  {
    gram += blockGram[b];
  }
  blockGram.clear();

  // 6. The ne largest eigenvectors of G G^T.
  extendEigenvectors(Gs, gram, pass, split, blocks, ne, out, progress.sub(0.9, 1.0));
  return out;
}
} // namespace spectral
} // namespace detail
} // namespace tc
