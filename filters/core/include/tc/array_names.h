// SPDX-License-Identifier: BSD-3-Clause
/// @file array_names.h
/// Names of the arrays and field data that TriChart stages share. Every stage, the app and the
/// Python package read the names from here; strings are never retyped.
#pragma once

namespace tc
{
// tcMeshPreparation
constexpr const char* kNonManifoldEdge =
  "NonManifoldEdge"; ///< cell: 1 if a side is shared by > 2 faces
constexpr const char* kNonManifoldVertex =
  "NonManifoldVertex";                                    ///< point: 1 if its fan is not one disk
constexpr const char* kBoundaryVertex = "BoundaryVertex"; ///< point: 1 if on an open boundary
constexpr const char* kComponentId = "ComponentId";       ///< cell: connected component index
constexpr const char* kInputPointId = "InputPointId";     ///< point: id in the stage's input mesh
constexpr const char* kInputCellId = "InputCellId";       ///< cell: id of the polygon it came from
constexpr const char* kPreparationReport = "PreparationReport"; ///< field: human-readable report

// tcCurvature
constexpr const char* kPrincipalCurvatures = "PrincipalCurvatures"; ///< point: k1 >= k2
constexpr const char* kPrincipalDirections = "PrincipalDirections"; ///< point: d1 (xyz), d2 (xyz)
constexpr const char* kMeanCurvature = "MeanCurvature";             ///< point: (k1 + k2) / 2
constexpr const char* kGaussianCurvature = "GaussianCurvature";     ///< point: k1 * k2
constexpr const char* kFaceMeanCurvature = "FaceMeanCurvature";     ///< cell: mean of its vertices
constexpr const char* kVertexNormal = "Normals";                    ///< point: fitted unit normal
constexpr const char* kStrength = "Strength";                       ///< crest cell: integral of |k|
constexpr const char* kCrestType = "CrestType";     ///< crest cell: 0 ridge, 1 valley
constexpr const char* kCrestVertex = "CrestVertex"; ///< point: 1 next to a crest line

// tcSpectralClustering / tcFeatureRefinement
constexpr const char* kClusterId = "ClusterId";         ///< cell: cluster of the face
constexpr const char* kEigenvalues = "Eigenvalues";     ///< field: largest eigenvalues, descending
constexpr const char* kFeatureVertex = "FeatureVertex"; ///< point: 1 on a feature line
constexpr const char* kCornerVertex = "CornerVertex";   ///< point: 1 at a corner
constexpr const char* kMeanAbsCurvature = "MeanAbsCurvature"; ///< line cell: mean |H| along it
constexpr const char* kFeatureEdges = "FeatureEdges"; ///< field: #E x 2 point ids of feature edges

// tcBaseComplex
constexpr const char* kBaseFaceId = "BaseFaceId"; ///< base cell id; input point: its base face
constexpr const char* kBaseBarycentric = "BaseBarycentric"; ///< input point: 3 barycentrics in it
constexpr const char* kBaseEdgeIsFeature =
  "BaseEdgeIsFeature"; ///< base cell: 3 flags, side (i, i+1)

// tcMeshReader
constexpr const char* kReaderReport = "ReaderReport"; ///< field: what was read
} // namespace tc
