// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcSpectralClustering
 * @brief Spectral clustering of the mesh's faces by curvature similarity (Feng et al. 2010,
 * section 4.1, eq. 1-3), whose cluster boundaries are the candidates for feature lines.
 *
 * Faces are nodes of the dual graph, joined across shared edges and to nearby non-adjacent
 * faces; eq. 3 gives low similarity across high |mean curvature| and across crest lines. The
 * eigenvectors of D^-1/2 W D^-1/2 for the largest eigenvalues embed the faces and k-means
 * (k-means++ seeding, fixed seed: deterministic) groups them. Meshes above NystromThreshold faces
 * use the Nystrom approximation. Every connected component is clustered on its own.
 *
 * Input: tcCurvature's output (cell array FaceMeanCurvature; point array CrestVertex is used
 * when present). Output port 0: the mesh with cell array ClusterId (0 .. k - 1, every face in
 * one cluster) and field array Eigenvalues (the largest eigenvalues, descending). Output port 1:
 * the cluster boundaries as polylines over mesh edges (point array InputPointId). Input that is
 * not triangles or lacks FaceMeanCurvature is an error that names the stage to apply first.
 */
#ifndef tcSpectralClustering_h
#define tcSpectralClustering_h

#include "TriChartFeaturesModule.h"

#include "tc/features/spectral_clustering.h" // for the defaults of the properties

#include <vtkPolyDataAlgorithm.h>

class TRICHARTFEATURES_EXPORT tcSpectralClustering : public vtkPolyDataAlgorithm
{
public:
  static tcSpectralClustering* New();
  vtkTypeMacro(tcSpectralClustering, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Number of clusters k over the whole mesh.
  vtkSetClampMacro(NumberOfClusters, int, 1, 100000);
  vtkGetMacro(NumberOfClusters, int);
  ///@}

  ///@{
  /// Number of eigenvectors Ne of the embedding; 0 uses NumberOfClusters.
  vtkSetClampMacro(NumberOfEigenvectors, int, 0, 1000);
  vtkGetMacro(NumberOfEigenvectors, int);
  ///@}

  ///@{
  /// Similarity factor (eq. 3's beta) between faces that a crest line separates.
  vtkSetClampMacro(CrestBeta, double, 0.0, 1.0);
  vtkGetMacro(CrestBeta, double);
  ///@}

  ///@{
  /// Extra graph edges join faces closer than this times the mean adjacent-face distance.
  vtkSetClampMacro(ExtraEdgeFactor, double, 0.0, 10.0);
  vtkGetMacro(ExtraEdgeFactor, double);
  ///@}

  ///@{
  /// When above 0, similarities also fall with the angle between face normals,
  /// exp(-(1 - n_i . n_j) / NormalSigma), which puts boundaries on sharp creases of CAD parts
  /// (small values, a few hundredths, follow the creases); 0 (default) is the paper's eq. 3.
  vtkSetClampMacro(NormalSigma, double, 0.0, 100.0);
  vtkGetMacro(NormalSigma, double);
  ///@}

  ///@{
  /// Components with more faces than this use the Nystrom method.
  vtkSetClampMacro(NystromThreshold, vtkIdType, 100, VTK_ID_MAX);
  vtkGetMacro(NystromThreshold, vtkIdType);
  ///@}

  ///@{
  /// Number of faces sampled by the Nystrom method.
  vtkSetClampMacro(NystromSamples, int, 10, 100000);
  vtkGetMacro(NystromSamples, int);
  ///@}

  ///@{
  /// k-means restarts (the best is kept).
  vtkSetClampMacro(KMeansRestarts, int, 1, 1000);
  vtkGetMacro(KMeansRestarts, int);
  ///@}

  ///@{
  /// Seed of every random choice; equal seeds give identical clusters.
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

protected:
  tcSpectralClustering();
  ~tcSpectralClustering() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcSpectralClustering(const tcSpectralClustering&) = delete;
  void operator=(const tcSpectralClustering&) = delete;

  int NumberOfClusters = tc::SpectralClusteringOptions{}.numClusters;
  int NumberOfEigenvectors = tc::SpectralClusteringOptions{}.numEigenvectors;
  double CrestBeta = tc::SpectralClusteringOptions{}.crestBeta;
  double ExtraEdgeFactor = tc::SpectralClusteringOptions{}.extraEdgeFactor;
  double NormalSigma = tc::SpectralClusteringOptions{}.exactNormalSigma;
  vtkIdType NystromThreshold = tc::SpectralClusteringOptions{}.nystromThreshold;
  int NystromSamples = tc::SpectralClusteringOptions{}.nystromSamples;
  int KMeansRestarts = tc::SpectralClusteringOptions{}.kmeansRestarts;
  // int(...), not static_cast: VTK's wrapper parser cannot read a static_cast here.
  int Seed = int(tc::SpectralClusteringOptions{}.seed);
};

#endif
