// SPDX-License-Identifier: BSD-3-Clause
/// @file curvature.h
/// Robust per-vertex principal curvatures of a triangle mesh, the curvature estimate that
/// Section 4.2 of Feng et al. 2010 (triangle-chart geometry images) builds its feature
/// detection on. The paper uses the robust statistical estimator of Kalogerakis et al. 2007;
/// this is an estimator in its spirit: per vertex, a weighted least-squares fit of a height
/// function over an adaptive k-ring neighbourhood, re-weighted by a robust M-estimator (IRLS)
/// so that outliers and points across sharp creases lose their influence. The shape operator
/// comes from the first and second fundamental forms of the fitted graph, so the fitted normal
/// (not the initial frame) defines the tangent plane.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"

#include <vector>

namespace tc
{
struct CurvatureOptions
{
  /// Adaptive neighbourhood: rings around the vertex are added until it has at least this many
  /// neighbours (the vertex itself not counted) and at least 2 rings, up to maxRings.
  int minNeighbors = 20;
  /// Largest ring count of the neighbourhood (bounds the cost on very irregular meshes).
  int maxRings = 6;
  /// Degree of the fitted height function z = poly(x, y): 2 or 3. A vertex whose
  /// neighbourhood is too small for the cubic falls back to 2, then to a 1-ring quadric.
  int degree = 3;
  /// Iteratively reweighted least squares with Tukey's biweight on the fit residuals.
  bool robust = true;
  /// Number of reweighting passes after the first (plain weighted) fit.
  int robustIterations = 2;
  /// Standard deviation of the Gaussian distance weights, as a fraction of the neighbourhood
  /// radius (distance of its farthest vertex).
  double weightSigma = 0.5;
  /// Fit in the frame of a normal refined by a first, plain quadric fit instead of the
  /// area-weighted vertex normal's (helps where that normal is poor: boundaries, creases,
  /// irregular sampling).
  bool refit = true;
};

struct CurvatureResult
{
  std::vector<double> k1;       ///< #V maximal principal curvature (signed, convex > 0)
  std::vector<double> k2;       ///< #V minimal principal curvature, k2 <= k1
  std::vector<double> d1;       ///< #V x 3 unit direction of k1, tangent to the fitted surface
  std::vector<double> d2;       ///< #V x 3 unit direction of k2; (d1, d2, normal) right-handed
  std::vector<double> normals;  ///< #V x 3 fitted unit normals (outward for CCW faces)
  std::vector<double> mean;     ///< #V (k1 + k2) / 2
  std::vector<double> gaussian; ///< #V k1 * k2
  std::vector<double> faceMean; ///< #F mean of the mean curvature of the three corners
};

/// Principal curvatures, directions and normals at every vertex.
///
/// Sign convention: curvature is positive where the surface is convex w.r.t. the outward
/// normal, i.e. where triangles are counter-clockwise seen from outside; a sphere of radius 2
/// gives k1 = k2 = +0.5, the same sphere with reversed triangles -0.5. The estimate is scale
/// covariant: all tolerances are relative to local lengths, so scaling the mesh by s divides
/// every curvature by s. Isolated vertices get zero curvature and the +z normal. The output
/// is deterministic (independent of the number of threads).
///
/// @param[in] mesh      #V x 3 points, #F x 3 triangles (vertex ids in [0, #V))
/// @param[in] options   neighbourhood and fit settings
/// @param[in] progress  progress and abort
/// @throws InputError when a triangle references a vertex that does not exist
CurvatureResult computeCurvature(
  const TriMesh& mesh, const CurvatureOptions& options = {}, const Progress& progress = {});
} // namespace tc
