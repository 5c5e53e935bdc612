// SPDX-License-Identifier: BSD-3-Clause
#include "tcStagePipeline.h"

#include "tcAtlasReader.h"
#include "tcAtlasWriter.h"
#include "tcBaseComplex.h"
#include "tcCurvature.h"
#include "tcFeatureRefinement.h"
#include "tcGLTFWriter.h"
#include "tcGeometryImageMesh.h"
#include "tcGeometryImages.h"
#include "tcMeshPreparation.h"
#include "tcMeshReader.h"
#include "tcMeshWriter.h"
#include "tcPathTracing.h"
#include "tcSpectralClustering.h"
#include "tcStage.h"
#include "tcSurfaceDistance.h"

#include <vtkCommand.h>
#include <vtkErrorCode.h>
#include <vtkExtractEdges.h>
#include <vtkLinearSubdivisionFilter.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPolyData.h>

#include <cctype>
#include <utility>

namespace
{
/// `text` without the white space at its ends.
std::string Trimmed(const std::string& text)
{
  const char* const space = " \t\n\v\f\r";
  const size_t first = text.find_first_not_of(space);
  return first == std::string::npos ? std::string()
                                    : text.substr(first, text.find_last_not_of(space) - first + 1);
}
}

tcStagePipeline::tcStagePipeline()
{
  this->Preparation->SetInputConnection(this->Reader->GetOutputPort());
  this->Curvature->SetInputConnection(this->Preparation->GetOutputPort());
  this->Clustering->SetInputConnection(this->Curvature->GetOutputPort());
  this->Refinement->SetInputConnection(this->Clustering->GetOutputPort());
  this->BaseComplex->SetInputConnection(this->Refinement->GetOutputPort());
  this->BaseEdges->SetInputConnection(this->BaseComplex->GetOutputPort(0));
  this->PathTracing->SetInputConnection(this->BaseComplex->GetOutputPort(1));
  this->GeometryImages->SetInputConnection(this->PathTracing->GetOutputPort(0));
  this->AtlasMesh->SetInputConnection(this->GeometryImages->GetOutputPort());
  this->AtlasMesh->SetLevel(-1);
  this->Reconstruction->SetInputConnection(this->GeometryImages->GetOutputPort());
  // The error is measured against the prepared mesh: the surface the charts were cut from, on
  // the reconstruction with its triangles split (see the class comment).
  this->Subdivision->SetInputConnection(this->Reconstruction->GetOutputPort());
  this->Subdivision->SetNumberOfSubdivisions(2);
  this->Distance->SetInputConnection(0, this->Subdivision->GetOutputPort());
  this->Distance->SetReferenceConnection(this->Preparation->GetOutputPort());
  this->RebuiltEdges->SetInputConnection(this->Reconstruction->GetOutputPort());
  for (vtkAlgorithm* a : this->Filters())
  {
    a->AddObserver(vtkCommand::ProgressEvent, this, &tcStagePipeline::OnProgress);
    a->AddObserver(vtkCommand::ErrorEvent, this, &tcStagePipeline::OnError);
  }
}

tcStagePipeline::~tcStagePipeline() = default;

std::vector<vtkAlgorithm*> tcStagePipeline::Filters() const
{
  return { this->Reader, this->Preparation, this->Curvature, this->Clustering, this->Refinement,
    this->BaseComplex, this->PathTracing, this->GeometryImages, this->AtlasReader, this->AtlasMesh,
    this->Reconstruction, this->Subdivision, this->Distance, this->Writer, this->GltfWriter,
    this->MeshWriter };
}

bool tcStagePipeline::IsAtlasFile(const std::string& path)
{
  // By extension first, so that a damaged .exr is reported by the atlas reader (which says what
  // is wrong with it) rather than refused by the mesh reader as an unknown format.
  return tcAtlasWriter::IsAtlasFileName(path.c_str()) || tcAtlasReader::CanReadFile(path.c_str());
}

void tcStagePipeline::Open(const std::string& path)
{
  this->Note.clear();
  this->AtlasFile = IsAtlasFile(path);
  if (this->AtlasFile)
  {
    this->AtlasReader->SetFileName(path.c_str());
  }
  else
  {
    this->Reader->SetFileName(path.c_str());
  }
  this->AtlasMesh->SetInputConnection(this->AtlasSource()->GetOutputPort());
  this->Reconstruction->SetInputConnection(this->AtlasSource()->GetOutputPort());
}

bool tcStagePipeline::StageAvailable(int stage) const
{
  return stage >= 0 && stage < tcStage::Count && (!this->AtlasFile || stage >= tcStage::Atlas);
}

vtkAlgorithm* tcStagePipeline::StageAlgorithm(int stage) const
{
  // The atlas stage shows the atlas and the mesh rebuilt from it, the reconstruction its
  // distance to the prepared mesh (none for an atlas file, which has no input mesh), the LOD
  // stage the atlas itself.
  vtkAlgorithm* reconstruction = this->AtlasFile ? static_cast<vtkAlgorithm*>(this->Reconstruction)
                                                 : static_cast<vtkAlgorithm*>(this->Distance);
  vtkAlgorithm* algorithms[] = { this->Reader, this->Preparation, this->Curvature, this->Clustering,
    this->Refinement, this->BaseComplex, this->PathTracing, this->AtlasMesh, reconstruction,
    this->AtlasSource() };
  static_assert(sizeof(algorithms) / sizeof(*algorithms) == tcStage::Count, "one per stage");
  return algorithms[stage];
}

vtkAlgorithm* tcStagePipeline::AtlasSource() const
{
  return this->AtlasFile ? static_cast<vtkAlgorithm*>(this->AtlasReader)
                         : static_cast<vtkAlgorithm*>(this->GeometryImages);
}

tcStageOutput tcStagePipeline::Output(int stage)
{
  tcStageOutput output;
  vtkAlgorithm* algorithm = this->StageAlgorithm(stage);
  output.Surface = vtkPolyData::SafeDownCast(algorithm->GetOutputDataObject(0));
  // Crest lines, cluster boundaries, feature lines and paths are each stage's port 1; the base
  // complex is drawn as its edges over the parameterized input mesh (its port 1), the
  // reconstruction with its own edges over the split surface that carries the distances.
  output.Lines = stage >= tcStage::Curvature && stage <= tcStage::Patches
    ? vtkPolyData::SafeDownCast(algorithm->GetOutputDataObject(1))
    : nullptr;
  if (stage == tcStage::Base)
  {
    this->BaseEdges->Update();
    output.Surface = output.Lines;
    output.Lines = this->BaseEdges->GetOutput();
  }
  if (stage == tcStage::Reconstruction)
  {
    this->RebuiltEdges->Update();
    output.Lines = this->RebuiltEdges->GetOutput();
  }
  output.Corners = stage == tcStage::Features ? this->Refinement->GetOutput(2) : nullptr;
  output.Counted =
    stage == tcStage::Reconstruction ? this->Reconstruction->GetOutput() : output.Surface;
  output.Atlas = vtkMultiBlockDataSet::SafeDownCast(this->AtlasSource()->GetOutputDataObject(0));
  return output;
}

bool tcStagePipeline::Execute(vtkAlgorithm* algorithm, int port)
{
  this->Error.clear();
  this->ErrorSource = nullptr;
  this->WasCancelled = false;
  if (algorithm->GetNumberOfOutputPorts() > port)
  {
    algorithm->Update(port);
  }
  else
  {
    algorithm->Update(); // a writer: no output port, Update() is what runs it
  }
  bool aborted = false;
  for (vtkAlgorithm* a : this->Filters())
  {
    aborted = aborted || a->GetAbortExecute();
  }
  if (aborted)
  {
    for (vtkAlgorithm* a : this->Filters())
    {
      a->AbortExecuteOff();
      a->Modified(); // the cancelled result must not be reused
    }
    this->Error = "Cancelled";
    this->WasCancelled = true;
    return false;
  }
  return this->Error.empty();
}

bool tcStagePipeline::Run(vtkAlgorithm* algorithm, int port)
{
  const bool ok = this->Execute(algorithm, port);
  if (!ok && this->ErrorSource == this->PathTracing.GetPointer() &&
    this->PathTracing->GetUntraceable() && !this->Preparation->GetRemoveSlivers())
  {
    return this->RunWithoutSlivers(algorithm, port);
  }
  return ok;
}

bool tcStagePipeline::RunWithoutSlivers(vtkAlgorithm* algorithm, int port)
{
  // As `trichart build` does: slivers are what makes the parameterization of a scan or a CAD
  // mesh too thin to trace, so they are removed and the pipeline runs again; RemoveSlivers stays
  // on and the note says so.
  const std::string first = this->Error;
  const std::string reason = this->PathTracing->GetUntraceableReason();
  this->Preparation->SetRemoveSlivers(true);
  const bool ok = this->Execute(algorithm, port);
  if (ok)
  {
    this->Note = "The paths could not be traced (" + reason +
      "); built again with RemoveSlivers on (Preparation).";
  }
  else if (!this->WasCancelled)
  {
    this->Preparation->SetRemoveSlivers(false);
    this->Error = first + " Built again with RemoveSlivers on, it failed too: " + this->Error;
  }
  return ok;
}

void tcStagePipeline::Abort()
{
  for (vtkAlgorithm* a : this->Filters())
  {
    a->AbortExecuteOn();
  }
}

void tcStagePipeline::SetProgressCallback(std::function<void(const char*, double)> callback)
{
  this->Progress = std::move(callback);
}

vtkAlgorithm* tcStagePipeline::AtlasWriterFor(const std::string& path)
{
  this->Writer->SetInputConnection(this->AtlasSource()->GetOutputPort());
  this->Writer->SetFileName(path.c_str());
  this->Writer->Modified();
  return this->Writer;
}

bool tcStagePipeline::AtlasWritten() const
{
  return this->Writer->GetErrorCode() == vtkErrorCode::NoError;
}

vtkAlgorithm* tcStagePipeline::GltfWriterFor(const std::string& path)
{
  this->GltfWriter->SetInputConnection(this->AtlasSource()->GetOutputPort());
  this->GltfWriter->SetFileName(path.c_str());
  this->GltfWriter->Modified();
  return this->GltfWriter;
}

vtkAlgorithm* tcStagePipeline::MeshWriterFor(vtkPolyData* mesh, const std::string& path)
{
  this->MeshWriter->SetInputData(mesh);
  this->MeshWriter->SetFileName(path.c_str());
  this->MeshWriter->Modified();
  return this->MeshWriter;
}

bool tcStagePipeline::MeshWritten() const
{
  return this->MeshWriter->GetErrorCode() == vtkErrorCode::NoError;
}

bool tcStagePipeline::GltfWritten() const
{
  return this->GltfWriter->GetErrorCode() == vtkErrorCode::NoError &&
    this->GltfWriter->GetNumberOfLods() > 0;
}

void tcStagePipeline::OnProgress(vtkObject* caller, unsigned long, void*)
{
  if (this->Progress)
  {
    auto* algorithm = static_cast<vtkAlgorithm*>(caller);
    this->Progress(algorithm->GetClassName(), algorithm->GetProgress());
  }
}

void tcStagePipeline::OnError(vtkObject* caller, unsigned long, void* callData)
{
  if (callData && this->Error.empty())
  {
    this->ErrorSource = caller;
    // VTK prefixes the message with "ERROR: In file, line N\nclass (address): ".
    const std::string text = Trimmed(static_cast<const char*>(callData));
    const size_t colon = text.find("): ");
    this->Error = colon != std::string::npos ? Trimmed(text.substr(colon + 3)) : text;
  }
}
