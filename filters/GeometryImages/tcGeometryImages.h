// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcGeometryImages
 * @brief Resamples every triangle patch into a triangular geometry image with mip levels and
 * packs them in pairs into one atlas (Feng et al. 2010, section 5.2).
 *
 * Each patch is parameterized onto a right triangle (Floater's mean-value coordinates, its
 * three paths fixed on the sides by arc length, then reweighted to lower its stretch, see
 * SetStretchIterations) and resampled on grids of 2^d + 1 samples per
 * side for d = 0 .. d_max, d_max following the patch's curvature-weighted area under a total
 * sample budget (or by measured error under it, or down to an error target: see SetLevelRule
 * and SetErrorTarget). Shared sides are sampled once
 * along their path, so neighbouring charts hold bit-identical samples there and stitch without
 * cracks. Two charts of close resolution share each (2^dh + 2) x (2^dh + 1) rectangle. Every chart
 * also gets an oriented bounding box and an error estimate per level.
 *
 * Input: tcPathTracing's first output (point array MeanCurvature is used when present).
 * Output: the atlas as a multiblock (tcAtlasConversion.h): block 0 the chart table, block 1
 * one vtkImageData per mip step with float arrays Position, Normal (3 components, input units)
 * and the point arrays chosen with AddResampledArray; tcAtlasWriter saves it. Input without
 * the patch arrays, a missing resampled array, or MinLevel above MaxLevel is an error.
 */
#ifndef tcGeometryImages_h
#define tcGeometryImages_h

#include "TriChartGeometryImagesModule.h"

#include "tc/gim/geometry_images.h" // for the defaults of the properties

#include <vtkMultiBlockDataSetAlgorithm.h>

#include <string>
#include <vector>

class TRICHARTGEOMETRYIMAGES_EXPORT tcGeometryImages : public vtkMultiBlockDataSetAlgorithm
{
public:
  static tcGeometryImages* New();
  vtkTypeMacro(tcGeometryImages, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The Error level rule's goal, a fraction of the input's bounding-box diagonal: a chart
  /// rises to finer levels while its measured error is above it (up to MaxLevel and the
  /// budget), and no further. Default 7e-4 (tc::kDefaultErrorTarget). 0: no goal, the budget
  /// alone decides.
  vtkSetClampMacro(ErrorTarget, double, 0.0, 0.5);
  vtkGetMacro(ErrorTarget, double);
  ///@}

  ///@{
  /// Total samples over all charts at their finest level; 0: as many as the ErrorTarget needs
  /// (up to 16 times the input's points), or with no target the input's point count.
  vtkSetClampMacro(SampleBudget, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(SampleBudget, vtkIdType);
  ///@}

  ///@{
  /// Smallest and largest d_max of a chart (2^d + 1 samples per side).
  vtkSetClampMacro(MinLevel, int, 0, 12);
  vtkGetMacro(MinLevel, int);
  vtkSetClampMacro(MaxLevel, int, 0, 12);
  vtkGetMacro(MaxLevel, int);
  ///@}

  ///@{
  /// Weight of |mean curvature| x diagonal in the curvature-weighted area that sets d_max
  /// (0: area only). Uses the point array MeanCurvature when the input has it.
  vtkSetClampMacro(CurvatureWeight, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(CurvatureWeight, double);
  ///@}

  ///@{
  /// How each chart's d_max is chosen: Area (0) makes 4^d_max proportional to the
  /// curvature-weighted area under the budget (paper section 5.2); Error (1, the default)
  /// measures each chart's error level by level and raises the charts with the largest error
  /// until every one is below ErrorTarget (or the budget or MaxLevel stops it).
  enum LevelRules
  {
    LEVEL_RULE_AREA = 0,
    LEVEL_RULE_ERROR = 1
  };
  vtkSetClampMacro(LevelRule, int, LEVEL_RULE_AREA, LEVEL_RULE_ERROR);
  vtkGetMacro(LevelRule, int);
  void SetLevelRuleToArea() { this->SetLevelRule(LEVEL_RULE_AREA); }
  void SetLevelRuleToError() { this->SetLevelRule(LEVEL_RULE_ERROR); }
  ///@}

  ///@{
  /// Stretch-reducing passes over each patch's mean-value map (Yoshizawa et al. 2004), 0 .. 100;
  /// 0 keeps Floater's map alone. Passes stop once the L2 stretch no longer falls. They spread
  /// the samples over protrusions that the mean-value map squeezes (default 10).
  vtkSetClampMacro(StretchIterations, int, 0, 100);
  vtkGetMacro(StretchIterations, int);
  ///@}

  ///@{
  /// Fit the samples of every chart's finest level to the surface by least squares (sides to
  /// their paths, interiors to their patches) instead of interpolating the surface at them
  /// (default on): a grid triangle is a chord that lies to one side of a curved surface, and
  /// fitted samples put it on both sides, which lowers the RMS error of the finest level.
  /// Feature curves stay sampled on the curve.
  vtkSetMacro(FitSamples, bool);
  vtkGetMacro(FitSamples, bool);
  vtkBooleanMacro(FitSamples, bool);
  ///@}

  ///@{
  /// Point arrays of the input to resample into the atlas besides Position and Normal.
  void AddResampledArray(const char* name);
  void ClearResampledArrays();
  ///@}

  ///@{
  /// Keep the input's look (default on): resample its TextureCoordinates and Colors point
  /// arrays when it has them (as tcMeshReader names them, each chart from its own side of a
  /// texture seam) and carry its base-colour texture (the field BaseColorTexture) into the
  /// atlas, for tcLODMapper and the glTF export.
  vtkSetMacro(KeepAppearance, bool);
  vtkGetMacro(KeepAppearance, bool);
  vtkBooleanMacro(KeepAppearance, bool);
  ///@}

  ///@{
  /// Keep the input's skin (default on): when it has the point arrays SkinIndices and
  /// SkinWeights and the field Rig (as tcMeshReader gives a skinned scene), resample them as
  /// the atlas attribute Skin (each sample the union of its source triangle's influences,
  /// weights interpolated, the 4 largest kept; tc::blendInfluences) and carry the rig, so the
  /// atlas poses like the input.
  vtkSetMacro(KeepSkin, bool);
  vtkGetMacro(KeepSkin, bool);
  vtkBooleanMacro(KeepSkin, bool);
  ///@}

protected:
  tcGeometryImages();
  ~tcGeometryImages() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcGeometryImages(const tcGeometryImages&) = delete;
  void operator=(const tcGeometryImages&) = delete;

  double ErrorTarget = tc::GeometryImageOptions{}.errorTarget;
  vtkIdType SampleBudget = tc::GeometryImageOptions{}.sampleBudget;
  int MinLevel = tc::GeometryImageOptions{}.minLevel;
  int MaxLevel = tc::GeometryImageOptions{}.maxLevel;
  double CurvatureWeight = tc::GeometryImageOptions{}.curvatureWeight;
  // int(...), not static_cast: VTK's wrapper parser cannot read a static_cast here.
  int LevelRule = int(tc::GeometryImageOptions{}.levelRule);
  int StretchIterations = tc::GeometryImageOptions{}.stretchIterations;
  bool FitSamples = tc::GeometryImageOptions{}.fitSamples;
  std::vector<std::string> ResampledArrays;
  bool KeepAppearance = true;
  bool KeepSkin = true;
};

#endif
