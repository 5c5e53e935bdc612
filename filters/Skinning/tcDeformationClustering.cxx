// SPDX-License-Identifier: BSD-3-Clause
#include "tcDeformationClustering.h"

#include "tcMeshConversion.h"
#include "tcSkinData.h"

#include "tc/common/array_names.h"
#include "tc/common/errors.h"
#include "tc/skinning/deformation_clustering.h"

#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <string>
#include <utility>

vtkStandardNewMacro(tcDeformationClustering);

namespace
{
/// `values` (distances in mesh units) as the field array `name`, fractions of `fit`'s diagonal.
void AddFitField(vtkFieldData* fields, const char* name, const std::vector<double>& values,
  const tc::FitError& fit)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  for (const double v : values)
  {
    array->InsertNextValue(fit.relative(v));
  }
  fields->AddArray(array);
}

/// True if `mesh` is skinned to a skeleton of its own: the skin arrays and a rig that
/// fitProxyBones did not make.
bool SkinnedToASkeleton(vtkPolyData* mesh)
{
  const std::string rig = tcvtk::GetTextField(mesh->GetFieldData(), tc::kRig);
  return mesh->GetPointData()->GetArray(tc::kSkinIndices) && !rig.empty() &&
    !tc::isProxyRig(tc::decodeRig(rig));
}

/// A fit holding only `clusters` (a skinned mesh keeps its own skin).
tc::ProxyBonesResult FitNothing(tc::DeformationClusteringResult clusters)
{
  tc::ProxyBonesResult fit;
  fit.clusters = std::move(clusters);
  return fit;
}

std::vector<float> FramePositions(vtkPolyData* mesh)
{
  std::vector<float> frame(3 * static_cast<size_t>(mesh->GetNumberOfPoints()));
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    const double* x = mesh->GetPoint(p);
    frame[3 * p] = static_cast<float>(x[0]);
    frame[3 * p + 1] = static_cast<float>(x[1]);
    frame[3 * p + 2] = static_cast<float>(x[2]);
  }
  return frame;
}
} // namespace

tcDeformationClustering::tcDeformationClustering()
{
  this->SetNumberOfOutputPorts(2);
}

int tcDeformationClustering::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // The output covers the whole sequence: it has no time of its own.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  this->Times.clear();
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()))
  {
    const double* t = inInfo->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    this->Times.assign(t, t + inInfo->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  }
  for (int port = 0; port < 2; ++port)
  {
    outputVector->GetInformationObject(port)->Remove(
      vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    outputVector->GetInformationObject(port)->Remove(
      vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  }
  this->Frame = 0;
  return 1;
}

int tcDeformationClustering::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (this->Frame < this->Times.size())
  {
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(), this->Times[this->Frame]);
  }
  return 1;
}

int tcDeformationClustering::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // 1. This frame's positions (a mesh skinned to a skeleton needs no frames).
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  const bool skinned = this->Frame == 0 && SkinnedToASkeleton(input);
  if (this->Frame == 0)
  {
    this->Frames.clear();
    this->Rest = vtkSmartPointer<vtkPolyData>::New();
    this->Rest->DeepCopy(input);
  }
  if (!skinned)
  {
    this->Frames.push_back(FramePositions(input));
  }

  // 2. Ask for the next frame until every one is in.
  if (!skinned && this->Frame + 1 < this->Times.size())
  {
    ++this->Frame;
    this->UpdateProgress(0.5 * this->Frame / this->Times.size());
    request->Set(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING(), 1);
    return 1;
  }
  request->Remove(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING());
  this->Frame = 0;

  // 3. Cluster, fit, and write the outputs.
  const bool ok = this->Finish(
    skinned, vtkPolyData::GetData(outputVector, 0), vtkPolyData::GetData(outputVector, 1));
  this->Frames.clear();
  this->Rest = nullptr;
  return ok ? 1 : 0;
}

tc::ProxyBonesOptions tcDeformationClustering::Options() const
{
  tc::ProxyBonesOptions options;
  options.clustering.numClusters = this->NumberOfClusters;
  options.clustering.gradientSigmaScale = this->GradientSigmaScale;
  options.clustering.seed = static_cast<uint64_t>(this->Seed);
  options.maxInfluences = this->MaxInfluences;
  options.iterations = this->Iterations;
  return options;
}

bool tcDeformationClustering::Finish(bool skinned, vtkPolyData* output, vtkPolyData* lines)
{
  // 1. Validate: several frames, or a skin.
  if (!skinned && this->Frames.size() < 2)
  {
    vtkErrorMacro("Cannot cluster by deformation: the input announces "
      << this->Times.size()
      << " time steps and has no skin; it needs a sequence of several frames (tcMeshReader on a "
         "folder of frames, a pattern or an MD2 file) or a mesh skinned to a skeleton.");
    return false;
  }
  std::string error;
  tc::SkinWeights skin;
  if (skinned &&
    !tcvtk::ReadSkinArrays(
      this->Rest->GetPointData(), this->Rest->GetNumberOfPoints(), skin, error))
  {
    vtkErrorMacro("Cannot cluster the mesh by its skin: " << error << ".");
    return false;
  }

  // 2. Cluster with the core (over the polygons' fan triangles, as the reader fits its proxy
  //    bones): bone dominance, or proxy bones fitted to the frames.
  tc::TriMesh rest;
  tc::ProxyBonesResult fit;
  try
  {
    std::vector<int64_t> polygonCell;
    int64_t ignoredCells = 0;
    const tc::PolygonSoup soup = tcvtk::ToPolygonSoup(this->Rest, polygonCell, ignoredCells);
    rest.points = soup.points;
    rest.triangles = tc::fanTriangles(soup);
    fit = skinned ? FitNothing(tc::boneDominanceClusters(rest.triangles, skin))
                  : tc::fitProxyBones(rest.triangles, this->Frames, this->Options(),
                      tcvtk::MakeProgress(this).sub(0.5, 1.0));
  }
  catch (const tc::Aborted&)
  {
    return false;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot cluster by deformation: " << e.what() << ".");
    return false;
  }

  // 3. Outputs: the first frame with the clusters (and the skin), the boundaries as lines.
  output->ShallowCopy(this->Rest);
  if (rest.numTriangles() != output->GetNumberOfCells())
  {
    // Polygons became fan triangles: the cells and their arrays are the triangles'.
    output->Initialize();
    tcvtk::FromTriMesh(rest, output);
    output->GetPointData()->ShallowCopy(this->Rest->GetPointData());
    output->GetFieldData()->ShallowCopy(this->Rest->GetFieldData());
  }
  output->GetCellData()->AddArray(tcvtk::MakeIntArray(tc::kClusterId, fit.clusters.clusterId));
  output->GetPointData()->AddArray(
    tcvtk::MakeIntArray(tc::kFeatureVertex, fit.clusters.featureVertex));
  if (!skinned)
  {
    tcvtk::AddSkinArrays(output->GetPointData(), fit.skin);
    std::vector<double> times(this->Times.begin(), this->Times.begin() + this->Frames.size());
    tcvtk::SetTextField(
      output->GetFieldData(), tc::kRig, tc::encodeRig(tc::proxyRig(fit, times, "frames")));
    AddFitField(output->GetFieldData(), tc::kFitRms, fit.lbs.rms, fit.lbs);
    AddFitField(output->GetFieldData(), tc::kFitMax, fit.lbs.max, fit.lbs);
    AddFitField(output->GetFieldData(), tc::kRigidFitRms, fit.rigid.rms, fit.rigid);
  }
  tcvtk::FromVertexPaths(rest, fit.clusters.lineOffsets, fit.clusters.lineVertices, lines);
  return true;
}

void tcDeformationClustering::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfClusters: " << this->NumberOfClusters << "\n";
  os << indent << "GradientSigmaScale: " << this->GradientSigmaScale << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "MaxInfluences: " << this->MaxInfluences << "\n";
  os << indent << "Iterations: " << this->Iterations << "\n";
}
