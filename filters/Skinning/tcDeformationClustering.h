// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcDeformationClustering
 * @brief Deformation clusters and proxy bones of a deforming sequence (Feng et al. 2010, 4.3),
 * or the bone-dominance regions of a skinned mesh, with their boundaries as feature lines.
 *
 * A temporal filter: it requests every time step its input announces (a sequence read by
 * tcMeshReader, a folder of frames or an MD2 file, frame k at time k), one after the other,
 * keeping each frame's positions; the connectivity is the first frame's. Then
 * tc::fitProxyBones: per-face deformation gradients against frame 0, the eq. 5 similarity,
 * spectral clusters, one proxy bone per cluster with a rigid transform per frame, linear blend
 * weights (at most MaxInfluences per point, non-negative, summing to 1) fitted to all frames and
 * the bone transforms refitted.
 *
 * A mesh skinned to a skeleton of its own (SkinIndices, SkinWeights and a Rig that is not a
 * proxy rig) is not clustered: the faces are grouped by the joint that dominates them
 * (tc::boneDominanceClusters), and no frame is requested.
 *
 * Output port 0: the first frame with the cell array ClusterId and the point array
 * FeatureVertex; for a sequence also SkinIndices, SkinWeights, the field Rig (the proxy
 * skeleton and the fitted frames as the animation "frames", replacing the input's) and the
 * field arrays FitRms, FitMax and RigidFitRms (per frame, as fractions of the first frame's
 * diagonal; RigidFitRms binds each point to its own cluster's bone alone). Output port 1: the
 * cluster boundaries as polylines (point array InputPointId), the feature lines that keep
 * charts from straddling two bones.
 *
 * Behind tcMeshReader, turn its ProxyBones off: the reader would fit the same bones for its
 * rest frame, and this filter's skin replaces them.
 */
#ifndef tcDeformationClustering_h
#define tcDeformationClustering_h

#include "TriChartSkinningModule.h"

#include "tc/skinning/proxy_bones.h" // for the defaults of the properties

#include <vtkPolyDataAlgorithm.h>
#include <vtkSmartPointer.h>

#include <vector>

class TRICHARTSKINNING_EXPORT tcDeformationClustering : public vtkPolyDataAlgorithm
{
public:
  static tcDeformationClustering* New();
  vtkTypeMacro(tcDeformationClustering, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Clusters (proxy bones) over the sequence; 0 (the default) picks
  /// tc::defaultDeformationClusters of the face count.
  vtkSetClampMacro(NumberOfClusters, int, 0, 100000);
  vtkGetMacro(NumberOfClusters, int);
  ///@}
  ///@{
  /// Multiplies sigma_Gamma of eq. 5 (1: the paper's rule); smaller follows the deformation
  /// more and the distance along the surface less.
  vtkSetClampMacro(GradientSigmaScale, double, 1e-6, 1e6);
  vtkGetMacro(GradientSigmaScale, double);
  ///@}
  ///@{
  /// Seed of every random choice (k-means++): equal seeds give identical results.
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}
  ///@{
  /// Bone influences per point, 1 .. 4.
  vtkSetClampMacro(MaxInfluences, int, 1, tc::kMaxInfluences);
  vtkGetMacro(MaxInfluences, int);
  ///@}
  ///@{
  /// Rounds of (weights given transforms, transforms given weights), at least 1.
  vtkSetClampMacro(Iterations, int, 1, 100);
  vtkGetMacro(Iterations, int);
  ///@}

protected:
  tcDeformationClustering();
  ~tcDeformationClustering() override = default;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcDeformationClustering(const tcDeformationClustering&) = delete;
  void operator=(const tcDeformationClustering&) = delete;
  tc::ProxyBonesOptions Options() const;
  /// Clusters the frames gathered (or the skin of `rest`) into the outputs; false on an error.
  bool Finish(bool skinned, vtkPolyData* output, vtkPolyData* lines);

  int NumberOfClusters = tc::DeformationClusteringOptions{}.numClusters;
  double GradientSigmaScale = tc::DeformationClusteringOptions{}.gradientSigmaScale;
  int Seed = int(tc::DeformationClusteringOptions{}.seed);
  int MaxInfluences = tc::ProxyBonesOptions{}.maxInfluences;
  int Iterations = tc::ProxyBonesOptions{}.iterations;

  std::vector<double> Times;              ///< the input's time steps (empty: none)
  size_t Frame = 0;                       ///< the frame the next RequestData receives
  std::vector<std::vector<float>> Frames; ///< the positions gathered so far
  vtkSmartPointer<vtkPolyData> Rest;      ///< the first frame, as the input gave it
};

#endif
