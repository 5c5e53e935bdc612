// SPDX-License-Identifier: BSD-3-Clause
/// @file multilevel_mesh.h
/// The multilevel mesh of Kircher and Garland (2005), section 3: levels M0 .. Mn of one
/// surface, M0 the input and each coarser level made from the one below by QSlim (Garland and
/// Heckbert 1997: quadric-error pair contractions along the level's edges) down to about
/// 1 / branchingFactor of its vertices. Contraction edges give every vertex of level k its
/// parent in level k + 1; the vertices of M0 under one vertex of level k form its cluster.
/// Each level's connectivity is derived from M0 and the clusters (a face of M0 survives at
/// level k when its corners lie in three distinct level-k clusters), so levels above M0 need
/// not be manifold; with the link condition (Dey et al. 1998) M1 is homeomorphic to M0.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tc
{
struct MultilevelOptions
{
  /// Each level has about 1 / branchingFactor of the vertices of the one below (>= 2; the
  /// paper uses 8).
  int branchingFactor = 8;
  /// Levels above M0 at most; 0: as many as coarsestVertices allows.
  int maxLevels = 0;
  /// A level is built only if it is to have at least this many vertices (>= 1).
  int coarsestVertices = 16;
  /// Contract M0 into M1 only where the link condition holds, so that M1 is homeomorphic to
  /// M0 (which must then be a manifold, with or without boundary). Coarser levels never check
  /// it: they may be non-manifold.
  bool linkCondition = true;
};

/// How a vertex's position was chosen from its quadric Q (minimized over the cluster).
enum class Placement : uint8_t
{
  Input = 0,   ///< a vertex of M0: its input position
  Optimal = 1, ///< the minimizer of Q (Q's 3 x 3 part is well conditioned)
  /// Q is singular (a flat or cylindrical cluster): the minimizer of Q nearest the mean of the
  /// cluster's M0 positions, its eigenvalues below 1e-3 of the largest dropped (Lindstrom 2000)
  Singular = 2,
  /// a vertex of the cluster in M0, where Q is lower than at the Singular position
  ClusterVertex = 3,
};

/// One level Mk. Vertex ids of a level are 0 .. #Vk - 1; those of level 0 are the input's.
struct MultilevelLevel
{
  std::vector<double> points; ///< #Vk x 3: M0's positions at level 0, optimal ones above
  /// #Fk x 3 derived faces: each M0 face whose corners map to three distinct level-k vertices,
  /// in those vertices, once per vertex triple (the lowest M0 face id's orientation)
  std::vector<int32_t> triangles;
  std::vector<int32_t> sourceFaces; ///< #Fk: the M0 face each triangle was derived from
  /// #Ek x 2 derived edges (a < b, sorted): the M0 edges whose ends map to distinct vertices,
  /// the edges QSlim contracts; they include every side of `triangles`
  std::vector<int32_t> edges;
  std::vector<int32_t> parents;      ///< #Vk: parent in level k + 1; -1 at the coarsest level
  std::vector<int32_t> clusterSizes; ///< #Vk: M0 vertices in the cluster (1 at level 0)
  /// #Vk x 10: summed quadric of the cluster, upper triangle of A then b then c
  /// (a00 a01 a02 a11 a12 a22 b0 b1 b2 c; Q(p) = p^T A p + 2 b.p + c), in area x length^2
  std::vector<double> quadrics;
  std::vector<double> errors;        ///< #Vk: E_a = Q_a(a) at the vertex's position
  std::vector<Placement> placements; ///< #Vk: how each position was chosen

  int64_t numVertices() const { return static_cast<int64_t>(clusterSizes.size()); }
  int64_t numTriangles() const { return static_cast<int64_t>(triangles.size() / 3); }
};

struct MultilevelMesh
{
  std::vector<MultilevelLevel> levels; ///< levels[0] = M0 (the input), then coarser

  /// #V0: the level-k vertex each M0 vertex lies under (the identity for k = 0).
  std::vector<int32_t> clusterOf(int level) const;
};

/// Builds the multilevel mesh of `mesh` (Kircher and Garland 2005, section 3).
///
/// Each M0 vertex gets the area-weighted plane quadrics of its faces plus a plane through each
/// boundary edge perpendicular to its face (Garland and Heckbert 1997); a level-k vertex gets
/// the sum over its cluster. Level k + 1 contracts the cheapest edge of level k (cost: the
/// merged quadric at its position, ties by vertex ids) until about #Vk / branchingFactor
/// vertices remain or no edge can be contracted (a mesh of several components keeps at least
/// one vertex each). Levels stop at maxLevels, before a level of fewer than coarsestVertices
/// vertices, or when a level cannot be reduced. Deterministic: the same input gives the same
/// result.
///
/// @param[in] mesh      M0: #V x 3 finite positions, #F x 3 triangles of three distinct ids
/// @param[in] progress  reported per level and during contraction; may abort (tc::Aborted)
/// @throws InputError   for a mesh without triangles, an id out of range, a repeated corner, a
///   non-finite coordinate, options out of range, or, with linkCondition, an M0 that is not a
///   manifold (an edge of more than two faces, or a vertex whose faces are not one fan)
MultilevelMesh buildMultilevelMesh(
  const TriMesh& mesh, const MultilevelOptions& options = {}, const Progress& progress = {});

/// What checkMultilevelMesh measured on one level.
struct MultilevelLevelCheck
{
  int64_t vertices = 0;  ///< of the level (also those no triangle uses)
  int64_t edges = 0;     ///< unique edges of the level's triangles
  int64_t triangles = 0; ///< derived faces
  /// of the level's triangles: the vertices they use - their edges + triangles
  int64_t eulerCharacteristic = 0;
  int64_t boundaryEdges = 0;    ///< edges of one triangle
  int64_t nonManifoldEdges = 0; ///< edges of more than two triangles
  /// level-k vertices whose cluster is not connected through M0's edges (the paper's validity)
  int64_t disconnectedClusters = 0;
  int64_t emptyClusters = 0;   ///< level-k vertices that no M0 vertex lies under
  int64_t invalidParents = 0;  ///< parents out of range (or set at the coarsest level)
  int64_t mismatchedFaces = 0; ///< triangles that differ from a derivation from M0
  /// (2 components - Euler characteristic - boundary loops) / 2, the genus of a manifold
  /// orientable level; -1 where the level is not edge-manifold
  int64_t genus = -1;
};

/// What checkMultilevelMesh found.
struct MultilevelCheck
{
  std::vector<MultilevelLevelCheck> levels;
  std::string firstProblem; ///< "" when valid(); else the first problem found, in one sentence

  bool valid() const { return firstProblem.empty(); }
};
/// Checks the structure of `multilevel` against `mesh` (its M0): every parent in range, every
/// cluster non-empty and connected in M0, every level's triangles those derived from M0, and
/// each level's Euler characteristic and genus (to compare M1 with M0 under the link condition).
/// A `mesh` of another vertex count than level 0 is a problem too.
MultilevelCheck checkMultilevelMesh(const TriMesh& mesh, const MultilevelMesh& multilevel);

/// Q(p) for a quadric in the layout of MultilevelLevel::quadrics (10 values).
double evaluateQuadric(const double* quadric, const double p[3]);
} // namespace tc
