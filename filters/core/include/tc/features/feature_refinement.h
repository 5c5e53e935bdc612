// SPDX-License-Identifier: BSD-3-Clause
/// @file feature_refinement.h
/// Feature lines and corners from spectral clusters (Feng et al. 2010, section 4.2, eq. 4):
/// cluster boundaries are thickened to a band of the faces nearest to them, re-cut with a
/// minimum s-t cut whose edge weights (eq. 4) favour short paths through high curvature, broken
/// into non-branching segments at junctions, and kept where their mean |mean curvature| is at
/// least the average of the top 30% vertex values (scaled, see curvatureThresholdScale).
/// Corners are the vertices of maximal |mean curvature| within an N-ring, of which the top 10%
/// are kept, and the junctions of feature lines.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"

#include <cstdint>
#include <vector>

namespace tc
{
struct FeatureRefinementOptions
{
  /// The refinement band covers this fraction of all faces, those nearest to a boundary.
  double bandFraction = 0.10;
  /// Eq. 4's beta where a crest line separates two faces (1 elsewhere).
  double crestBeta = 0.1;
  /// A segment is a feature if its mean |H| is at least the mean of the top this-fraction of
  /// vertex |H| values (the paper: 30%).
  double curvatureTopFraction = 0.30;
  /// Scales that threshold (1 = the paper's rule). Below 1 by default: the paper's rule
  /// assumes that features are a small part of the mesh, so that the top 30% are feature
  /// vertices and a feature segment reaches their mean. Where features hold a large share of
  /// the vertices (coarse CAD meshes), or where the estimate varies along a crease, crease
  /// segments fall below the mean of the top 30%.
  double curvatureThresholdScale = 0.7;
  /// Corners: maxima of |H| within this many rings (the paper: 7 to 10).
  int cornerRings = 8;
  /// Corners: the top this-fraction of those maxima by |H| are kept (the paper: 10%), rounded
  /// up so that a mesh with any maximum can keep one. A kept maximum must also reach the
  /// segment threshold (curvatureThreshold), so that flat or evenly curved meshes get none.
  double cornerFraction = 0.10;

  // Additions to the paper's parameters.

  /// The band also holds every face within this many face-adjacency steps of a face that
  /// touches a boundary, whatever bandFraction says. With many clusters or on a coarse mesh
  /// the faces along the boundaries alone exceed 10%, and a band one face thick on each side
  /// lets the cut move a boundary by one face at most.
  int bandRings = 2;
  /// The cuts are computed again from the refined boundaries until no face changes, at most
  /// this many times (1 = the paper's single refinement). Each band face is cut between the two
  /// clusters of its nearest boundary only; near a junction of 3 or more clusters that pair can
  /// be the wrong one, and a face of the third cluster is then left with one of the two until
  /// a later pass sees the moved boundary. Later passes stay inside the first band, so
  /// boundaries move no farther than the paper's band allows.
  int cutPasses = 8;

  /// Eq. 4 is multiplied by exp(-dihedralWeight theta_ij / sigma_theta), theta_ij the angle
  /// between the normals of faces i and j and sigma_theta its standard deviation over all
  /// interior edges; 0 gives the paper's eq. 4. The estimated |H| is smooth: around a sharp
  /// crease it stays high over 2 to 3 rings and is often highest on the curved side, so eq. 4
  /// alone moves boundaries that lay exactly on creases off them. The dihedral angle is the
  /// curvature concentrated on the edge itself and puts the cut on the crease; the default
  /// makes its factor on a sharp crease outweigh the curvature factor. On noisy scans theta is
  /// mostly noise and the refined boundaries get longer; few of their segments pass the
  /// threshold there.
  double dihedralWeight = 8.0;

  /// Noise floor of the segment (and corner) threshold: it is at least this value divided by
  /// the bounding-box diagonal. The paper's relative threshold alone keeps half the boundary
  /// of a flat plane, where every |H| is rounding noise; 1 is the |H| of a sphere whose
  /// diameter is twice the diagonal, far below any feature. 0 disables the floor.
  double minCurvatureTimesSize = 1.0;
  /// Vertices where three or more kept feature lines meet are corners as well. Where sharp
  /// creases meet, the |H| estimate straddles the creases (on a coarse CAD mesh the corners
  /// can have nearly the same |H|, and an N-ring maximum then keeps one of several), while the
  /// meeting of the detected lines locates the corner exactly.
  bool junctionCorners = true;
  /// After the cuts, one-face zig-zags of the boundaries are straightened: a face with two
  /// boundary sides to the same other cluster at a vertex on no other boundary edge joins that
  /// cluster, so the boundary takes the face's third side. A cut runs along mesh edges, so a
  /// boundary across the mesh's grain is a staircase; each step is a sharp turn that the base
  /// complex cannot collapse along the curve (Feng et al. 5.1 keeps feature vertices on their
  /// curve), so the steps pin many base vertices. Creases are kept: a step whose sides include
  /// an edge of at least creaseAngle is only straightened onto an edge that is one as well.
  bool straightenLines = true;
  /// Dihedral angle in degrees from which an edge counts as a crease for straightenLines.
  double creaseAngle = 30.0;
  /// Crease chains join the feature lines: chains of edges whose dihedral angle reaches this
  /// many degrees and that no kept cluster-boundary segment holds, broken where they meet a
  /// line (step 4b of refineFeatures); 0 (the default) keeps only the paper's cluster-boundary
  /// lines. A part has more creases than a fixed number of spectral clusters has boundaries,
  /// and a crease edge is where the normal turns, which a chart grid follows only on its sides
  /// (inside a chart its error halves per level instead of quartering).
  double creaseLineAngle = 0.0;
  /// A crease chain is kept when it has at least this many edges: a lone sharp edge is more
  /// often a badly shaped triangle than a crease.
  int creaseLineEdges = 2;
  /// Seam sides of the input (#F bit masks from tc::seamSides, empty: none): the texture seams,
  /// joined to the feature lines whatever their curvature (step 4c), so that no chart straddles
  /// a seam and its grid interpolates texture coordinates only where they are continuous. Input
  /// data rather than a setting; it lives here so that the entry point keeps its signature.
  std::vector<uint8_t> seamSides;
  /// Skin regions of the input (#F: the joint that dominates each face, tc::boneDominanceClusters'
  /// clusterId; empty: none): the edges between faces of different joints are joined to the
  /// feature lines whatever their curvature (step 4d), so that no chart straddles a bending joint
  /// (Feng et al. 2010, 4.3: "the resulting triangular patches do not cross bending joints"),
  /// where a flat region of the rest pose bends into a curved one. Input data, like seamSides.
  std::vector<int32_t> skinRegions;
};

struct FeatureRefinementResult
{
  std::vector<int32_t> clusterId;        ///< #F refined clusters
  std::vector<uint8_t> featureVertex;    ///< #V 1 on a kept feature line
  std::vector<uint8_t> cornerVertex;     ///< #V 1 at a corner
  std::vector<int64_t> lineOffsets{ 0 }; ///< #L + 1 offsets into lineVertices
  std::vector<int32_t> lineVertices;     ///< feature lines as paths over mesh edges (vertex ids);
                                         ///< a closed line repeats its first vertex
  std::vector<double> lineCurvature;     ///< #L mean |H| along each line (length-weighted)
  std::vector<int32_t> corners;          ///< corner vertex ids, ascending
  double curvatureThreshold = 0.0;       ///< the |H| threshold segments were tested against
  int64_t bandFaces = 0;                 ///< faces in the refinement band (section 4.2)
  int64_t relabeledFaces = 0;    ///< faces whose cluster the cuts or the straightening changed
  int64_t straightenedFaces = 0; ///< faces relabelled by straightenLines
  int64_t candidateSegments = 0; ///< non-branching boundary segments before the threshold

  int64_t numLines() const { return static_cast<int64_t>(lineOffsets.size()) - 1; }
};

/// Refines spectral clusters and extracts feature lines and corners (section 4.2).
///
/// 1. Boundary edges: mesh edges whose faces have different clusters (mesh-boundary edges
///    never are). The band: the ceil(bandFraction #F) faces nearest to a boundary by dual path
///    length (face centroid to centroid, multi-source Dijkstra), and always every face that
///    touches a boundary. Each band face remembers the pair of clusters (a, b) of its nearest
///    boundary.
/// 2. One minimum s-t cut (Boykov-Kolmogorov max-flow) per pair (a, b) (Katz and Tal 2003):
///    the free nodes are the band faces of a or b nearest to that pair's boundary; neighbours
///    of a outside them are contracted into the source, of b into the sink; other clusters are
///    left out. The capacities are eq. 4 (see dihedralWeight). The pairs' node sets are
///    disjoint, so one max-flow over their union solves all of them, independently of any
///    order. A free node in neither search tree keeps its cluster; a pair whose nodes touch no
///    face of a or none of b is not cut; if a cluster would lose all its faces, the cuts of its
///    pairs are undone, so every input cluster keeps at least one face. Repeated on the new
///    boundaries inside the same band (cutPasses). The max-flow is not interruptible: abort is
///    honoured between the steps.
/// 3. Segments: the refined boundary graph over mesh vertices is broken at vertices with other
///    than 2 boundary edges (junctions of 3 or more boundaries, ends on the mesh border or at
///    non-manifold spots); closed loops without such a vertex are one segment. A segment is kept
///    where its length-weighted mean |H| (each edge: length x mean |H| of its ends) reaches
///    curvatureThreshold = max(curvatureThresholdScale x mean of the top curvatureTopFraction
///    of |H| over the vertices that triangles use, minCurvatureTimesSize / bbox diagonal).
/// 4b. Crease chains (creaseLineAngle, creaseLineEdges) are appended to the lines.
/// 4c. Seam chains (options.seamSides: every seam edge no line holds, chained like the crease
///    chains, of any length) are appended to the lines.
/// 4d. Skin chains (options.skinRegions: every edge between faces that different joints
///    dominate, no line holds), likewise.
/// 4. Corners: vertices whose |H| is the largest within cornerRings rings (ties go to the
///    smaller id), the top ceil(cornerFraction x count) of them by |H| that reach
///    curvatureThreshold; with junctionCorners also every vertex where 3 or more feature-line
///    edges meet.
///
/// Deterministic: the output does not depend on the number of threads. Components of the mesh
/// need no special treatment (no dual edge joins them). Cluster ids need not be compact.
/// Cost: O(#F log #F) plus the max-flows over the band.
///
/// @param[in] mesh               #V x 3 points, #F x 3 triangles
/// @param[in] clusterId          #F clusters (spectralClustering())
/// @param[in] meanCurvature      #V mean curvature per vertex
/// @param[in] faceMeanCurvature  #F mean curvature per face
/// @param[in] crestVertex        #V 1 where a crest line passes, may be empty
/// @param[in] options            see FeatureRefinementOptions
/// @param[in] progress           reported about 20 times; may abort (tc::Aborted)
/// @throws InputError when arrays do not match the mesh, a cluster id is negative, a curvature
///   is not finite, or a triangle references a missing vertex or repeats one
FeatureRefinementResult refineFeatures(const TriMesh& mesh, const std::vector<int32_t>& clusterId,
  const std::vector<double>& meanCurvature, const std::vector<double>& faceMeanCurvature,
  const std::vector<uint8_t>& crestVertex, const FeatureRefinementOptions& options = {},
  const Progress& progress = {});
} // namespace tc
