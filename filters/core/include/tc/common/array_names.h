// SPDX-License-Identifier: BSD-3-Clause
/// @file array_names.h
/// Names of the arrays, field data and blocks that TriChart stages share. Every stage, the app and
/// the Python package read the names from here; strings are never retyped. Python reads them
/// through the wrapped class tcArrayNames (filters/IO), generated from this file: tc::kX is
/// tcArrayNames.X().
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
/// Cell array name suffix: "<array>Corners" holds a point array's values at the three corners
/// of each triangle (3 x its components), for arrays the merge of seam copies made discontinuous
/// (tc/prep/corner_attributes.h).
constexpr const char* kCornerValuesSuffix = "Corners";
constexpr const char* kSeamSides = "SeamSides"; ///< cell: bit k set if side k is on a seam

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

// tcPathTracing
constexpr const char* kPatchId = "PatchId";       ///< cell: base face (= patch, = chart) of a piece
constexpr const char* kBaseEdgeId = "BaseEdgeId"; ///< path cell: the base edge it traces
constexpr const char* kSteinerEdge =
  "SteinerEdge"; ///< point: 2 input points of its input edge (-1 -1)
constexpr const char* kSteinerParameter = "SteinerParameter"; ///< point: t along that edge
constexpr const char* kBaseVertexIds = "BaseVertexIds"; ///< field: input point of each base vertex
constexpr const char* kBaseTriangles = "BaseTriangles"; ///< field: #Fb x 3 base vertex indices
constexpr const char* kBaseEdges = "BaseEdges";         ///< field: #Eb x 2 base vertex indices
constexpr const char* kFaceEdges = "FaceEdges";         ///< field: #Fb x 3 base edge of each side
constexpr const char* kPathOffsets = "PathOffsets";     ///< field: #Eb + 1 offsets into PathPoints
constexpr const char* kPathPoints = "PathPoints";       ///< field: point ids of every path

// tcGeometryImages / tcGeometryImageMesh (the atlas as a multiblock: block 0 the chart table,
// block 1 one vtkImageData per mip step)
constexpr const char* kChartId = "ChartId";             ///< cell / table: chart of a triangle
constexpr const char* kLevel = "Level";                 ///< cell: level it was rebuilt at
constexpr const char* kMaxLevel = "MaxLevel";           ///< table: d_max
constexpr const char* kChartCorners = "CornerVertices"; ///< table: 3 base vertices (input ids)
constexpr const char* kNeighborChart = "NeighborChart"; ///< table: chart across each side
constexpr const char* kNeighborSide = "NeighborSide";   ///< table: its side
constexpr const char* kFeatureSide = "FeatureSide";     ///< table: side follows a feature
constexpr const char* kPartner = "Partner";             ///< table: chart sharing the rectangle
constexpr const char* kRotated = "Rotated";             ///< table: upper-right, turned 180 deg
constexpr const char* kOrigin = "Origin";   ///< table: 2 x levels texel of sample (0,0) per image
constexpr const char* kBox = "OrientedBox"; ///< table: 4 corners (c0 and its 3 neighbours)
constexpr const char* kLevelError = "LevelError";         ///< table: error per level (NaN: none)
constexpr const char* kAtlasSource = "AtlasSource";       ///< field: what it was built from
constexpr const char* kInputPoints = "InputPoints";       ///< field: input point count
constexpr const char* kInputTriangles = "InputTriangles"; ///< field: input triangle count
constexpr const char* kInputDiagonal = "InputDiagonal";   ///< field: input bounding-box diagonal
constexpr const char* kSampleChart = "SampleChart"; ///< rebuilt point: chart, i, j it was read from
constexpr const char* kChartsBlock = "Charts";      ///< block 0 of the atlas: the chart table
constexpr const char* kImagesBlock = "Images"; ///< block 1 of the atlas: one image per mip step
constexpr const char* kImageBlockPrefix = "Image "; ///< image k of block 1 is "Image k"
/// block 2 of an atlas with textures: one vtkImageData per texture, named as the texture
constexpr const char* kTexturesBlock = "Textures";
constexpr const char* kTextureBytes = "RGBA";           ///< point: unsigned char, 4 a texel
constexpr const char* kTextureSource = "TextureSource"; ///< field of a texture: its file

// tcSurfaceDistance
constexpr const char* kDistance = "Distance";             ///< point: distance to the other surface
constexpr const char* kDistanceReport = "DistanceReport"; ///< field: the figures, as text
constexpr const char* kHausdorff = "Hausdorff";           ///< field: symmetric Hausdorff distance
constexpr const char* kMeanDistance = "MeanDistance";     ///< field: symmetric mean distance
constexpr const char* kRmsDistance = "RmsDistance";       ///< field: symmetric RMS distance
constexpr const char* kRelativeHausdorff = "RelativeHausdorff"; ///< field: Hausdorff / diagonal
constexpr const char* kRelativeMeanDistance = "RelativeMeanDistance"; ///< field: mean / diagonal
constexpr const char* kRelativeRmsDistance = "RelativeRmsDistance";   ///< field: RMS / diagonal
constexpr const char* kReferenceDiagonal =
  "ReferenceDiagonal"; ///< field: reference's bbox diagonal

// tcMultilevelMesh (a multiblock, one vtkPolyData per level, finest first)
constexpr const char* kParentId = "ParentId";       ///< point: its vertex in the next coarser level
constexpr const char* kClusterSize = "ClusterSize"; ///< point: M0 vertices in its cluster
constexpr const char* kQuadricError = "QuadricError"; ///< point: its quadric at its position
/// point of level 0: "ClusterId<k>" holds the vertex of level k each M0 vertex lies under
constexpr const char* kLevelClusterIdPrefix = "ClusterId";
constexpr const char* kLevelBlockPrefix = "Level "; ///< block k is "Level k"

// tcMeshReader
constexpr const char* kReaderReport = "ReaderReport"; ///< field: what was read
constexpr const char* kSceneMeshId = "SceneMeshId";   ///< cell: mesh of a scene file (glTF, FBX...)
/// point: int, 4 components: each point's joints (tc::SkinWeights), largest weight first
constexpr const char* kSkinIndices = "SkinIndices";
/// point: float, 4 components: the weights of SkinIndices (unused slots 0)
constexpr const char* kSkinWeights = "SkinWeights";
/// skeleton point: string, the joint's name
constexpr const char* kJointNames = "JointNames";
/// skeleton point: int, the parent joint's index, -1 for a root
constexpr const char* kJointParent = "JointParent";
/// skeleton point: double, 16 components, row-major: from the bind pose into the joint's frame
constexpr const char* kInverseBindMatrices = "InverseBindMatrices";
/// skeleton point: double, 16 components, row-major: the joint's frame in the scene at the
/// output's time
constexpr const char* kJointTransforms = "JointTransforms";
/// field: string, JSON (tc::encodeRig): the skeleton and animations of a skinned mesh, carried
/// from the reader through every stage into the atlas
constexpr const char* kRig = "Rig";
/// field: string, the animation the output is posed by ("" in the rest pose)
constexpr const char* kAnimationName = "AnimationName";
/// point: float (u, v), the active TCoords; v = 0 at the image's bottom row (OpenGL / VTK)
constexpr const char* kTextureCoordinates = "TextureCoordinates";
/// point: unsigned char RGBA (alpha 255 when the file gives RGB only)
constexpr const char* kColors = "Colors";
/// field: unsigned char RGBA, width x height tuples, row 0 = the image's bottom (VTK order)
constexpr const char* kBaseColorTexture = "BaseColorTexture";
/// field: int, one tuple (width, height) of BaseColorTexture
constexpr const char* kBaseColorTextureSize = "BaseColorTextureSize";
/// field: string, the texture's file name, or "embedded:<k>" for the file's k-th image
constexpr const char* kBaseColorTextureName = "BaseColorTextureName";
// tcDeformationClustering
/// field: double, per frame: RMS distance of the proxy-bone skin's frame to the input frame, as
/// a fraction of the first frame's diagonal
constexpr const char* kFitRms = "FitRms";
/// field: double, per frame: the largest such distance, a fraction of the diagonal
constexpr const char* kFitMax = "FitMax";
/// field: double, per frame: RMS distance with each point bound to its own cluster's bone alone
constexpr const char* kRigidFitRms = "RigidFitRms";
/// point: float, a height field's height as read (before VerticalScale)
constexpr const char* kElevation = "Elevation";
/// field: double, 2 components: a height field's first cell centre in the file's coordinates
/// (the mesh's origin; its CRS units, or degrees)
constexpr const char* kGeoOrigin = "GeoOrigin";
/// field: string, a height field's coordinate system as WKT (absent when the file has none)
constexpr const char* kGeoCRS = "GeoCRS";
} // namespace tc
