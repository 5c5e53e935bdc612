// SPDX-License-Identifier: BSD-3-Clause
/// @file spectrum.h
/// The largest eigenpairs of the normalized similarity D^-1/2 W D^-1/2 (Feng et al. 2010,
/// section 4.1, eq. 2) of one mesh component: from the exact sparse matrix (Spectra), or from
/// the Nystrom approximation (Fowlkes et al. 2004) above a face-count threshold. Every Eigen and
/// Spectra solve of spectral clustering is behind this header, so that one translation unit
/// compiles them.
#pragma once

#include "tc/common/progress.h"
#include "tc/features/spectral_clustering.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
namespace spectral
{
/// exp() of anything below this is still a normal double: a face whose curvature is far above
/// sigma_k keeps a tiny positive similarity instead of becoming an isolated node (D = 0).
constexpr double kMinExponent = -600.0;
/// The same for the float kernel blocks of the Nystrom method (and no denormals in the GEMMs).
constexpr float kMinExponentFloat = -60.0f;

/// Sparse symmetric matrix in CSR form over a component's faces (local ids).
struct LocalMatrix
{
  std::vector<int64_t> offsets; ///< rows + 1
  std::vector<int32_t> ids;
  std::vector<double> values;
  int64_t rows() const { return static_cast<int64_t>(offsets.size()) - 1; }
};

/// Eigenpairs of D^-1/2 W D^-1/2 of one component and the degrees D.
struct Spectrum
{
  std::vector<double> values;  ///< Ne, descending
  std::vector<double> vectors; ///< n x Ne row-major, local face order
  std::vector<double> degree;  ///< n
};

/// The ne largest eigenpairs of n (at most its size), eigenvalues descending: a dense solve for
/// small components, else shift-invert Lanczos on the normalized Laplacian I - n (sparse LDLT),
/// with Lanczos on n itself as the fallback.
/// @param[out] values   Ne eigenvalues
/// @param[out] vectors  rows x Ne eigenvectors, row-major
/// @throws std::runtime_error when no eigensolver converges
void largestEigenpairs(const LocalMatrix& n, int ne, const Progress& progress,
  std::vector<double>& values, std::vector<double>& vectors);

/// The Nystrom approximation of the spectrum of one component (see spectrum.cpp for the kernel
/// and the rank-r extension).
/// @param[in] faces  global ids of the component's faces, ascending
/// @param[in] cen    #F x 3 centroids
/// @param[in] nrm    #F x 3 unit normals
/// @param[in] ce     #F |kappa| / sigma_k
/// @param[in] seed   of the sample choice
Spectrum nystromSpectrum(const std::vector<int32_t>& faces, const std::vector<double>& cen,
  const std::vector<double>& nrm, const std::vector<double>& ce, int ne,
  const SpectralClusteringOptions& options, uint64_t seed, const Progress& progress);
} // namespace spectral
} // namespace detail
} // namespace tc
