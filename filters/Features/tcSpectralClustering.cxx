// SPDX-License-Identifier: BSD-3-Clause
#include "tcSpectralClustering.h"

#include "tcMeshConversion.h"

#include "tc/common/array_names.h"
#include "tc/common/mesh_topology.h"
#include "tc/features/spectral_clustering.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStripper.h>

vtkStandardNewMacro(tcSpectralClustering);

tcSpectralClustering::tcSpectralClustering()
{
  this->SetNumberOfOutputPorts(2);
}

tcSpectralClustering::~tcSpectralClustering() = default;

namespace
{
/// The mesh edges between faces of different clusters, joined into polylines for display.
void BoundaryPolylines(
  const tc::TriMesh& mesh, const std::vector<int32_t>& clusterId, vtkPolyData* boundaries)
{
  const std::vector<int32_t> pairs =
    tc::labelBoundaryEdges(tc::buildEdgeTable(mesh.triangles), clusterId);
  std::vector<int64_t> offsets(pairs.size() / 2 + 1);
  for (size_t k = 0; k < offsets.size(); ++k)
  {
    offsets[k] = static_cast<int64_t>(2 * k);
  }
  vtkNew<vtkPolyData> edges;
  tcvtk::FromVertexPaths(mesh, offsets, pairs, edges);
  vtkNew<vtkStripper> stripper;
  stripper->SetInputData(edges);
  stripper->JoinContiguousSegmentsOn();
  stripper->Update();
  boundaries->ShallowCopy(stripper->GetOutput());
}
} // namespace

int tcSpectralClustering::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // 1. Input and outputs.
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* boundaries = vtkPolyData::GetData(outputVector, 1);

  // 2 and 3. Validate while converting: triangles with face mean curvature.
  tc::TriMesh mesh;
  std::string error;
  std::vector<double> faceCurvature;
  std::vector<uint8_t> crest;
  if (!tcvtk::ToTriMesh(input, mesh, error) ||
    !tcvtk::ReadArray(
      input->GetCellData(), tc::kFaceMeanCurvature, mesh.numTriangles(), 1, faceCurvature, error))
  {
    vtkErrorMacro(
      "Cannot cluster: " << error << "; apply tcCurvature before tcSpectralClustering.");
    return 0;
  }
  std::string ignored; // a crest array of the wrong size is not used
  if (!tcvtk::ReadOptionalIntArray(
        input->GetPointData(), tc::kCrestVertex, mesh.numPoints(), crest, ignored))
  {
    crest.clear();
  }

  // 4. Cluster.
  tc::SpectralClusteringOptions options;
  options.numClusters = this->NumberOfClusters;
  options.numEigenvectors = this->NumberOfEigenvectors;
  options.crestBeta = this->CrestBeta;
  options.extraEdgeFactor = this->ExtraEdgeFactor;
  options.exactNormalSigma = this->NormalSigma;
  options.nystromThreshold = this->NystromThreshold;
  options.nystromSamples = this->NystromSamples;
  options.kmeansRestarts = this->KMeansRestarts;
  options.seed = static_cast<uint64_t>(this->Seed);
  tc::SpectralClusteringResult result;
  try
  {
    result = tc::spectralClustering(mesh, faceCurvature, crest, options, tcvtk::MakeProgress(this));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot cluster: " << e.what());
    return 0;
  }

  // 5. ClusterId and eigenvalues on the mesh; boundaries as polylines.
  output->ShallowCopy(input);
  output->GetCellData()->AddArray(tcvtk::MakeIntArray(tc::kClusterId, result.clusterId));
  output->GetCellData()->SetActiveScalars(tc::kClusterId);
  output->GetFieldData()->AddArray(tcvtk::MakeArray(tc::kEigenvalues, 1, result.eigenvalues));
  BoundaryPolylines(mesh, result.clusterId, boundaries);
  return 1;
}

void tcSpectralClustering::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfClusters: " << this->NumberOfClusters << "\n";
  os << indent << "NumberOfEigenvectors: " << this->NumberOfEigenvectors << "\n";
  os << indent << "CrestBeta: " << this->CrestBeta << "\n";
  os << indent << "ExtraEdgeFactor: " << this->ExtraEdgeFactor << "\n";
  os << indent << "NormalSigma: " << this->NormalSigma << "\n";
  os << indent << "NystromThreshold: " << this->NystromThreshold << "\n";
  os << indent << "NystromSamples: " << this->NystromSamples << "\n";
  os << indent << "KMeansRestarts: " << this->KMeansRestarts << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
}
