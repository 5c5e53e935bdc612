// SPDX-License-Identifier: BSD-3-Clause
#include "tcGLTFWriter.h"

#include "tcAtlasConversion.h"
#include "tcMeshConversion.h"

#include <vtkErrorCode.h>
#include <vtkInformation.h>
#include <vtkObjectFactory.h>

vtkStandardNewMacro(tcGLTFWriter);

static_assert(tcGLTFWriter::CHAIN_ERROR == static_cast<int>(tc::GltfChain::Error) &&
    tcGLTFWriter::CHAIN_UNIFORM == static_cast<int>(tc::GltfChain::Uniform) &&
    tcGLTFWriter::LAYOUT_MSFT_LOD == static_cast<int>(tc::GltfLayout::MsftLod) &&
    tcGLTFWriter::LAYOUT_NAMED_NODES == static_cast<int>(tc::GltfLayout::NamedNodes) &&
    tc::GltfExportOptions{}.chain == tc::GltfChain::Error &&
    tc::GltfExportOptions{}.layout == tc::GltfLayout::MsftLod,
  "the writer's enums and defaults are the core's");

tcGLTFWriter::tcGLTFWriter() = default;
tcGLTFWriter::~tcGLTFWriter() = default;

int tcGLTFWriter::FillInputPortInformation(int, vtkInformation* info)
{
  // Any data object: ToAtlas explains what an atlas is when it gets something else.
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

void tcGLTFWriter::WriteData()
{
  this->Lods.clear();
  if (this->FileName.empty())
  {
    vtkErrorMacro("No glTF file name was set.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  tc::Atlas atlas;
  std::string error;
  if (!tcvtk::ToAtlas(this->GetInputDataObject(0, 0), atlas, error))
  {
    vtkErrorMacro("Cannot write glTF: " << error << ".");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  this->InputDiagonal = atlas.inputDiagonal;
  tc::GltfExportOptions options;
  options.chain = static_cast<tc::GltfChain>(this->Chain);
  options.layout = static_cast<tc::GltfLayout>(this->Layout);
  options.errorRatio = this->ErrorRatio;
  options.maxLods = this->MaxLods;
  options.errorPixels = this->ErrorPixels;
  options.viewportHeight = this->ViewportHeight;
  try
  {
    this->Lods = tc::writeGltf(this->FileName, atlas, options, tcvtk::MakeProgress(this));
    for (const std::string& note : tc::gltfExportNotes(atlas))
    {
      vtkWarningMacro("" << note);
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot write glTF: " << e.what());
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}

bool tcGLTFWriter::IsGLTFFileName(const char* path)
{
  return path && tc::isGltfFileName(path);
}

vtkIdType tcGLTFWriter::GetLodTriangles(int lod) const
{
  return lod >= 0 && lod < this->GetNumberOfLods() ? this->Lods[lod].triangles : -1;
}

double tcGLTFWriter::GetLodError(int lod) const
{
  return lod >= 0 && lod < this->GetNumberOfLods() ? this->Lods[lod].error : -1.0;
}

double tcGLTFWriter::GetLodScreenCoverage(int lod) const
{
  return lod >= 0 && lod < this->GetNumberOfLods() ? this->Lods[lod].screenCoverage : -1.0;
}

void tcGLTFWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Chain: " << this->Chain << "\n";
  os << indent << "Layout: " << this->Layout << "\n";
  os << indent << "ErrorRatio: " << this->ErrorRatio << "\n";
  os << indent << "MaxLods: " << this->MaxLods << "\n";
  os << indent << "ErrorPixels: " << this->ErrorPixels << "\n";
  os << indent << "ViewportHeight: " << this->ViewportHeight << "\n";
}
