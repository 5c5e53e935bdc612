// SPDX-License-Identifier: BSD-3-Clause
#include "tcAtlasWriter.h"

#include "tcAtlasConversion.h"
#include "tcMeshConversion.h"

#include "tc/io/atlas_io.h"

#include <vtkErrorCode.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>

vtkStandardNewMacro(tcAtlasWriter);

tcAtlasWriter::tcAtlasWriter() = default;
tcAtlasWriter::~tcAtlasWriter() = default;

int tcAtlasWriter::FillInputPortInformation(int, vtkInformation* info)
{
  // Any data object: ToAtlas explains what an atlas is when it gets something else.
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

void tcAtlasWriter::WriteData()
{
  if (this->FileName.empty())
  {
    vtkErrorMacro("No atlas file name was set.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  tc::Atlas atlas;
  std::string error;
  if (!tcvtk::ToAtlas(this->GetInputDataObject(0, 0), atlas, error))
  {
    vtkErrorMacro("Cannot write the atlas: " << error << ".");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  try
  {
    tc::writeAtlas(atlas, this->FileName, tcvtk::MakeProgress(this));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot write the atlas: " << e.what());
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}

bool tcAtlasWriter::IsAtlasFileName(const char* path)
{
  return path && tc::isAtlasFileName(path);
}

void tcAtlasWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
