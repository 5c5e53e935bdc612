// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcFeatureRefinement
 * @brief Feature lines and corner points from spectral clusters (Feng et al. 2010, section 4.2,
 * eq. 4).
 *
 * Cluster boundaries are thickened to the band of the BandFraction faces nearest to them and
 * re-cut with a minimum s-t cut whose weights (eq. 4) favour short paths through high |mean
 * curvature| and along crest lines. The refined boundaries are broken into non-branching
 * segments at junctions; a segment is a feature line when its mean |mean curvature| reaches the
 * average of the top CurvatureTopFraction vertex values (times CurvatureThresholdScale).
 * Corners are vertices of maximal |mean curvature| within CornerRings rings, of which the top
 * CornerFraction are kept.
 *
 * Input: tcSpectralClustering's output (ClusterId, MeanCurvature, FaceMeanCurvature, and
 * CrestVertex when present). Output port 0: the mesh with refined ClusterId, point arrays
 * FeatureVertex and CornerVertex, and field array FeatureEdges (point-id pairs of every mesh
 * edge on a feature line, which tcBaseComplex keeps on base edges). Port 1: feature lines, one
 * polyline per segment over mesh edges, with point array InputPointId and cell array
 * MeanAbsCurvature. Port 2: corner points as vertices with InputPointId.
 */
#ifndef tcFeatureRefinement_h
#define tcFeatureRefinement_h

#include "TriChartFeaturesModule.h"

#include "tc/features/feature_refinement.h" // for the defaults of the properties

#include <vtkPolyDataAlgorithm.h>

class TRICHARTFEATURES_EXPORT tcFeatureRefinement : public vtkPolyDataAlgorithm
{
public:
  static tcFeatureRefinement* New();
  vtkTypeMacro(tcFeatureRefinement, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Fraction of all faces, those nearest to a cluster boundary, that the graph cut may relabel.
  vtkSetClampMacro(BandFraction, double, 0.0, 1.0);
  vtkGetMacro(BandFraction, double);
  ///@}

  ///@{
  /// Cut-weight factor (eq. 4's beta) on edges that run along a crest line.
  vtkSetClampMacro(CrestBeta, double, 0.0, 1.0);
  vtkGetMacro(CrestBeta, double);
  ///@}

  ///@{
  /// Segments are features when their mean |H| reaches the mean of this top fraction of the
  /// vertices' |H|.
  vtkSetClampMacro(CurvatureTopFraction, double, 0.0, 1.0);
  vtkGetMacro(CurvatureTopFraction, double);
  ///@}

  ///@{
  /// Multiplies that curvature threshold (1 is the paper's rule; the default, below 1, keeps
  /// creases whose curvature varies along them).
  vtkSetClampMacro(CurvatureThresholdScale, double, 0.0, 100.0);
  vtkGetMacro(CurvatureThresholdScale, double);
  ///@}

  ///@{
  /// The band always holds the faces within this many steps of a boundary, even when the
  /// boundaries alone exceed BandFraction.
  vtkSetClampMacro(BandRings, int, 0, 100);
  vtkGetMacro(BandRings, int);
  ///@}

  ///@{
  /// The cut is repeated on the new boundaries, inside the first band, at most this many times.
  vtkSetClampMacro(CutPasses, int, 1, 100);
  vtkGetMacro(CutPasses, int);
  ///@}

  ///@{
  /// Eq. 4 is multiplied by exp(-w theta / sigma_theta) (theta: angle between the face
  /// normals), so that cuts also follow creases; 0 gives the paper's weights.
  vtkSetClampMacro(DihedralWeight, double, 0.0, 100.0);
  vtkGetMacro(DihedralWeight, double);
  ///@}

  ///@{
  /// One-face zig-zags of the cut boundaries are straightened (the boundary takes the face's
  /// third side), so that the base complex can simplify feature lines along themselves.
  vtkSetMacro(StraightenLines, bool);
  vtkGetMacro(StraightenLines, bool);
  vtkBooleanMacro(StraightenLines, bool);
  ///@}

  ///@{
  /// Dihedral angle (degrees) from which an edge is a crease: StraightenLines never trades a
  /// crease edge for a smoother one.
  vtkSetClampMacro(CreaseAngle, double, 0.0, 180.0);
  vtkGetMacro(CreaseAngle, double);
  ///@}

  ///@{
  /// Crease chains join the feature lines: chains of two or more edges whose faces meet at this
  /// dihedral angle (degrees) or more, where no cluster boundary runs. 0 (the default): only
  /// the cluster boundaries, as in the paper. A CAD part has more creases than the clusters
  /// have boundaries, and a chart follows a crease exactly only along its sides.
  vtkSetClampMacro(CreaseLineAngle, double, 0.0, 180.0);
  vtkGetMacro(CreaseLineAngle, double);
  ///@}

  ///@{
  /// Texture seams join the feature lines: the sides the preparation marked in SeamSides (where
  /// texture coordinates or colours jump), so that no chart straddles a seam.
  vtkSetMacro(SeamLines, bool);
  vtkGetMacro(SeamLines, bool);
  vtkBooleanMacro(SeamLines, bool);
  ///@}

  ///@{
  /// Skin boundaries join the feature lines: on a skinned mesh (point arrays SkinIndices and
  /// SkinWeights, from a skinned file or a sequence's proxy bones), the edges between faces that
  /// different joints dominate, so that no chart straddles a bending joint (Feng et al. 2010,
  /// 4.3). Default off: with the many overlapping bones of a real rig or of a sequence's proxy
  /// bones the dominance regions are many and small, and their boundaries multiply the charts
  /// (1.6 to 4.9 times on the shared skinned meshes) for a posed error that improves on one of
  /// them only (docs/parameters.md).
  vtkSetMacro(SkinLines, bool);
  vtkGetMacro(SkinLines, bool);
  vtkBooleanMacro(SkinLines, bool);
  ///@}

  ///@{
  /// Vertices where three or more feature lines meet are corners too.
  vtkSetMacro(JunctionCorners, bool);
  vtkGetMacro(JunctionCorners, bool);
  vtkBooleanMacro(JunctionCorners, bool);
  ///@}

  ///@{
  /// Corners are maxima of |H| within this many rings.
  vtkSetClampMacro(CornerRings, int, 1, 50);
  vtkGetMacro(CornerRings, int);
  ///@}

  ///@{
  /// Fraction of those maxima, the strongest, kept as corners.
  vtkSetClampMacro(CornerFraction, double, 0.0, 1.0);
  vtkGetMacro(CornerFraction, double);
  ///@}

protected:
  tcFeatureRefinement();
  ~tcFeatureRefinement() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// The joint that dominates each face of `input` (SkinLines), none when it has no skin.
  bool SkinRegions(vtkPolyData* input, const tc::TriMesh& mesh, std::vector<int32_t>& regions);

private:
  tcFeatureRefinement(const tcFeatureRefinement&) = delete;
  void operator=(const tcFeatureRefinement&) = delete;

  double BandFraction = tc::FeatureRefinementOptions{}.bandFraction;
  double CrestBeta = tc::FeatureRefinementOptions{}.crestBeta;
  double CurvatureTopFraction = tc::FeatureRefinementOptions{}.curvatureTopFraction;
  double CurvatureThresholdScale = tc::FeatureRefinementOptions{}.curvatureThresholdScale;
  int BandRings = tc::FeatureRefinementOptions{}.bandRings;
  int CutPasses = tc::FeatureRefinementOptions{}.cutPasses;
  double DihedralWeight = tc::FeatureRefinementOptions{}.dihedralWeight;
  bool JunctionCorners = tc::FeatureRefinementOptions{}.junctionCorners;
  bool StraightenLines = tc::FeatureRefinementOptions{}.straightenLines;
  double CreaseAngle = tc::FeatureRefinementOptions{}.creaseAngle;
  double CreaseLineAngle = tc::FeatureRefinementOptions{}.creaseLineAngle;
  bool SeamLines = true;
  bool SkinLines = false;
  int CornerRings = tc::FeatureRefinementOptions{}.cornerRings;
  double CornerFraction = tc::FeatureRefinementOptions{}.cornerFraction;
};

#endif
