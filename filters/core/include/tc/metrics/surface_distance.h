// SPDX-License-Identifier: BSD-3-Clause
/// @file surface_distance.h
/// Metro-style distance between two triangle meshes (Cignoni, Rocchini and Scopigno 1998,
/// "Metro: measuring error on simplified surfaces"), the error measure of Section 7 and Table II
/// of Feng et al. 2010: dense samples on each surface, the unsigned distance of every sample to
/// the other surface, and the maximum (one-sided and symmetric Hausdorff distance), the
/// area-weighted mean and the area-weighted root mean square of those distances.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"

#include <cstdint>
#include <vector>

namespace tc
{
struct SurfaceDistanceOptions
{
  /// Target number of area samples on each mesh, besides its vertices (every vertex is always
  /// a sample). 0 picks max(10 x #F, 100000) for each mesh, at most 4000000 (but never fewer
  /// than one per triangle). Must be in [0, 10^12].
  int64_t samplesPerMesh = 0;
  /// Seed of the sample positions inside the triangles; the result depends only on the meshes,
  /// the options and this seed (not on the thread count): equal inputs give bitwise equal
  /// results.
  uint32_t seed = 1;
  /// Fill SurfaceDistanceResult::pointDistance.
  bool perPointDistance = true;
};

/// All distances are unsigned Euclidean distances to the closest point of the other surface
/// (the union of its triangles), in the units of the input coordinates. Divide by `diagonal`
/// for the relative errors that Metro and Table II of Feng et al. report.
///
/// With d_R(p) the distance of a point p to `reference`, d_M(q) that of q to `mesh`, and
/// A_M, A_R the areas of the two meshes:
///   forwardMax  = max over the samples p of `mesh` of d_R(p)
///   forwardMean = (integral over `mesh` of d_R dA) / A_M
///   forwardRms  = sqrt((integral over `mesh` of d_R^2 dA) / A_M)
///   backward*   = the same with the roles swapped (samples q of `reference`, d_M(q), A_R)
///   hausdorff   = max(forwardMax, backwardMax)
///   meanDistance = (A_M forwardMean + A_R backwardMean) / (A_M + A_R)
///   rmsDistance  = sqrt((A_M forwardRms^2 + A_R backwardRms^2) / (A_M + A_R))
/// i.e. the symmetric mean and RMS are taken over the union of both surfaces (both sample
/// sets), weighted by area. The integrals are estimated by stratified sampling: each triangle
/// is cut into k x k congruent sub-triangles (k^2 proportional to its area, k >= 1), weighted
/// by their area. Pairs of them that form a rhombus get one uniformly random point and its
/// mirror image through the rhombus centre (antithetic samples, placed by the seed); the k
/// along one side get their centroid. The estimate is thus exact wherever the distance is
/// linear over a triangle (e.g. to a plane). Vertex samples enter the maxima only. The maxima
/// are lower bounds of the true one-sided Hausdorff distances that converge as the sampling
/// gets denser.
///
/// Distances below 1e-12 times the largest absolute coordinate of the two meshes are rounding
/// noise of the closest-point computation and are reported as 0, so identical surfaces give
/// exactly 0.
struct SurfaceDistanceResult
{
  double hausdorff = 0.0;    ///< symmetric Hausdorff distance: max(forwardMax, backwardMax)
  double meanDistance = 0.0; ///< symmetric area-weighted mean over both surfaces
  double rmsDistance = 0.0;  ///< symmetric area-weighted root mean square over both surfaces
  double forwardMax = 0.0;   ///< samples of `mesh` to `reference`: maximum
  double forwardMean = 0.0;  ///< samples of `mesh` to `reference`: area-weighted mean
  double forwardRms = 0.0;   ///< samples of `mesh` to `reference`: area-weighted RMS
  double backwardMax = 0.0;  ///< samples of `reference` to `mesh`: maximum
  double backwardMean = 0.0; ///< samples of `reference` to `mesh`: area-weighted mean
  double backwardRms = 0.0;  ///< samples of `reference` to `mesh`: area-weighted RMS
  double diagonal = 0.0;     ///< diagonal of the bounding box of the reference's points
  int64_t samples = 0;       ///< samples measured, both directions: area samples + used points
  /// #V of `mesh` (empty if !perPointDistance): distance of each of its points to `reference`,
  /// also of points that no triangle uses (those do not enter the maxima).
  std::vector<double> pointDistance;
};

/// Measures how far `mesh` (e.g. a reconstruction) and `reference` (e.g. the original) are
/// from each other, in both directions (see SurfaceDistanceResult for the definitions).
/// Closest points come from an AABB tree over each mesh's triangles; the queries run in
/// parallel. Cost: one closest-point query per sample, O(log #F) each.
///
/// @param[in] mesh       #V points, #F x 3 triangles with ids in [0, #V)
/// @param[in] reference  #V' points, #F' x 3 triangles with ids in [0, #V')
/// @param[in] options    see SurfaceDistanceOptions
/// @param[in] progress   reported about 130 times; may abort (tc::Aborted)
/// @throws tc::InputError  a mesh without points or triangles, a point array whose length is
///   not a multiple of 3, a triangle array whose length is not a multiple of 3, a NaN or
///   infinite coordinate, a triangle index out of range, a mesh with zero total area (only
///   degenerate triangles), or samplesPerMesh outside [0, 10^12]
SurfaceDistanceResult surfaceDistance(const TriMesh& mesh, const TriMesh& reference,
  const SurfaceDistanceOptions& options = {}, const Progress& progress = {});
} // namespace tc
