// SPDX-License-Identifier: BSD-3-Clause
#include "tcFeatureRefinement.h"
#include "tcSkinData.h"

#include "tcMeshConversion.h"

#include "tc/common/array_names.h"
#include "tc/features/feature_refinement.h"
#include "tc/skinning/deformation_clustering.h"

#include <vtkCellData.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <utility>

vtkStandardNewMacro(tcFeatureRefinement);

tcFeatureRefinement::tcFeatureRefinement()
{
  this->SetNumberOfOutputPorts(3);
}

tcFeatureRefinement::~tcFeatureRefinement() = default;

namespace
{
/// The feature edges, for the base complex: consecutive vertices of every feature line, as
/// point-id pairs.
std::vector<int32_t> FeatureEdges(const tc::FeatureRefinementResult& result)
{
  std::vector<int32_t> edges;
  for (int64_t k = 0; k < result.numLines(); ++k)
  {
    for (int64_t i = result.lineOffsets[k]; i + 1 < result.lineOffsets[k + 1]; ++i)
    {
      edges.push_back(result.lineVertices[i]);
      edges.push_back(result.lineVertices[i + 1]);
    }
  }
  return edges;
}
} // namespace

int tcFeatureRefinement::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // 1. Input and outputs.
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* lines = vtkPolyData::GetData(outputVector, 1);
  vtkPolyData* corners = vtkPolyData::GetData(outputVector, 2);

  // 2 and 3. Validate while converting: triangles, clusters and curvature.
  tc::TriMesh mesh;
  std::string error;
  std::vector<int32_t> clusters;
  std::vector<double> vertexCurvature;
  std::vector<double> faceCurvature;
  std::vector<uint8_t> crest;
  if (!tcvtk::ToTriMesh(input, mesh, error) ||
    !tcvtk::ReadIntArray(
      input->GetCellData(), tc::kClusterId, mesh.numTriangles(), clusters, error) ||
    !tcvtk::ReadArray(
      input->GetPointData(), tc::kMeanCurvature, mesh.numPoints(), 1, vertexCurvature, error) ||
    !tcvtk::ReadArray(
      input->GetCellData(), tc::kFaceMeanCurvature, mesh.numTriangles(), 1, faceCurvature, error))
  {
    vtkErrorMacro("Cannot refine features: "
      << error << "; apply tcCurvature and tcSpectralClustering before tcFeatureRefinement.");
    return 0;
  }
  std::string ignored; // a crest array of the wrong size is not used
  if (!tcvtk::ReadOptionalIntArray(
        input->GetPointData(), tc::kCrestVertex, mesh.numPoints(), crest, ignored))
  {
    crest.clear();
  }
  std::vector<uint8_t> seams;
  if (this->SeamLines &&
    !tcvtk::ReadOptionalIntArray(
      input->GetCellData(), tc::kSeamSides, mesh.numTriangles(), seams, error))
  {
    vtkErrorMacro("Cannot refine features: " << error << ".");
    return 0;
  }

  std::vector<int32_t> skinRegions;
  if (this->SkinLines && !this->SkinRegions(input, mesh, skinRegions))
  {
    return 0;
  }

  // 4. Refine.
  tc::FeatureRefinementOptions options;
  options.bandFraction = this->BandFraction;
  options.crestBeta = this->CrestBeta;
  options.curvatureTopFraction = this->CurvatureTopFraction;
  options.curvatureThresholdScale = this->CurvatureThresholdScale;
  options.bandRings = this->BandRings;
  options.cutPasses = this->CutPasses;
  options.dihedralWeight = this->DihedralWeight;
  options.junctionCorners = this->JunctionCorners;
  options.straightenLines = this->StraightenLines;
  options.creaseAngle = this->CreaseAngle;
  options.creaseLineAngle = this->CreaseLineAngle;
  options.seamSides = std::move(seams);
  options.skinRegions = std::move(skinRegions);
  options.cornerRings = this->CornerRings;
  options.cornerFraction = this->CornerFraction;
  tc::FeatureRefinementResult result;
  try
  {
    result = tc::refineFeatures(
      mesh, clusters, vertexCurvature, faceCurvature, crest, options, tcvtk::MakeProgress(this));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot refine features: " << e.what());
    return 0;
  }

  // 5. Arrays on the mesh; feature lines and corners.
  output->ShallowCopy(input);
  output->GetCellData()->RemoveArray(tc::kClusterId);
  output->GetCellData()->AddArray(tcvtk::MakeIntArray(tc::kClusterId, result.clusterId));
  output->GetCellData()->SetActiveScalars(tc::kClusterId);
  output->GetPointData()->AddArray(tcvtk::MakeIntArray(tc::kFeatureVertex, result.featureVertex));
  output->GetPointData()->AddArray(tcvtk::MakeIntArray(tc::kCornerVertex, result.cornerVertex));

  output->GetFieldData()->AddArray(
    tcvtk::MakeIntTuples(tc::kFeatureEdges, 2, FeatureEdges(result)));
  tcvtk::FromVertexPaths(mesh, result.lineOffsets, result.lineVertices, lines);
  lines->GetCellData()->AddArray(tcvtk::MakeArray(tc::kMeanAbsCurvature, 1, result.lineCurvature));
  std::vector<int64_t> single(result.corners.size() + 1);
  for (size_t k = 0; k < single.size(); ++k)
  {
    single[k] = static_cast<int64_t>(k);
  }
  tcvtk::FromVertexPaths(mesh, single, result.corners, corners, true);
  return 1;
}

bool tcFeatureRefinement::SkinRegions(
  vtkPolyData* input, const tc::TriMesh& mesh, std::vector<int32_t>& regions)
{
  tc::SkinWeights skin;
  std::string error;
  if (!tcvtk::ReadSkinArrays(input->GetPointData(), mesh.numPoints(), skin, error))
  {
    if (!error.empty())
    {
      vtkErrorMacro("Cannot refine features: " << error << " (or turn SkinLines off).");
    }
    return error.empty();
  }
  regions = tc::boneDominanceClusters(mesh.triangles, skin).clusterId;
  return true;
}

void tcFeatureRefinement::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "BandFraction: " << this->BandFraction << "\n";
  os << indent << "CrestBeta: " << this->CrestBeta << "\n";
  os << indent << "CurvatureTopFraction: " << this->CurvatureTopFraction << "\n";
  os << indent << "CurvatureThresholdScale: " << this->CurvatureThresholdScale << "\n";
  os << indent << "BandRings: " << this->BandRings << "\n";
  os << indent << "CutPasses: " << this->CutPasses << "\n";
  os << indent << "DihedralWeight: " << this->DihedralWeight << "\n";
  os << indent << "JunctionCorners: " << this->JunctionCorners << "\n";
  os << indent << "StraightenLines: " << this->StraightenLines << "\n";
  os << indent << "CreaseAngle: " << this->CreaseAngle << "\n";
  os << indent << "CreaseLineAngle: " << this->CreaseLineAngle << "\n";
  os << indent << "SeamLines: " << this->SeamLines << "\n";
  os << indent << "SkinLines: " << this->SkinLines << "\n";
  os << indent << "CornerRings: " << this->CornerRings << "\n";
  os << indent << "CornerFraction: " << this->CornerFraction << "\n";
}
