// SPDX-License-Identifier: BSD-3-Clause
#include "tcAtlasReader.h"

#include "tcAtlasConversion.h"
#include "tcMeshConversion.h"

#include "tc/io/atlas_io.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>

vtkStandardNewMacro(tcAtlasReader);

tcAtlasReader::tcAtlasReader()
{
  this->SetNumberOfInputPorts(0);
}

tcAtlasReader::~tcAtlasReader() = default;

bool tcAtlasReader::CanReadFile(const char* fileName)
{
  return fileName && tc::isAtlasFile(fileName);
}

int tcAtlasReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  vtkMultiBlockDataSet* output = vtkMultiBlockDataSet::GetData(out, 0);
  if (this->FileName.empty())
  {
    vtkErrorMacro("No atlas file name was set.");
    return 0;
  }
  try
  {
    const tc::Atlas atlas = tc::readAtlas(this->FileName, tcvtk::MakeProgress(this));
    tcvtk::FromAtlas(atlas, output);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot read the atlas: " << e.what());
    return 0;
  }
  return 1;
}

void tcAtlasReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
