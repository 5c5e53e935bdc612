// SPDX-License-Identifier: BSD-3-Clause
#include "tcAtlasReader.h"

#include "tcAtlasConversion.h"
#include "tcMeshConversion.h"

#include "tc/common/array_names.h"
#include "tc/common/errors.h"
#include "tc/io/atlas_io.h"
#include "tc/skinning/skin.h"

#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <filesystem>
#include <system_error>
#include <vector>

vtkStandardNewMacro(tcAtlasReader);

/// The last file read: its name and modification time, its atlas as pipeline data (outputs
/// share its arrays) and its rig.
struct tcAtlasReader::Cache
{
  std::string fileName;
  std::filesystem::file_time_type modified;
  vtkNew<vtkMultiBlockDataSet> output;
  tc::Rig rig;
};

tcAtlasReader::tcAtlasReader()
  : Cached(new Cache)
{
  this->SetNumberOfInputPorts(0);
}

tcAtlasReader::~tcAtlasReader() = default;

bool tcAtlasReader::CanReadFile(const char* fileName)
{
  return fileName && tc::isAtlasFile(fileName);
}

bool tcAtlasReader::ReadCached()
{
  if (this->FileName.empty())
  {
    vtkErrorMacro("No atlas file name was set.");
    return false;
  }
  Cache& cache = *this->Cached;
  std::error_code code;
  const auto modified = std::filesystem::last_write_time(this->FileName, code);
  if (!code && cache.fileName == this->FileName && cache.modified == modified)
  {
    return true;
  }
  cache.fileName.clear();
  try
  {
    const tc::Atlas atlas = tc::readAtlas(this->FileName, tcvtk::MakeProgress(this));
    cache.output->Initialize();
    tcvtk::FromAtlas(atlas, cache.output);
    cache.rig = atlas.rig;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot read the atlas: " << e.what());
    return false;
  }
  cache.fileName = this->FileName;
  cache.modified = modified;
  return true;
}

int tcAtlasReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  vtkInformation* info = out->GetInformationObject(0);
  info->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  info->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  if (this->FileName.empty())
  {
    vtkErrorMacro("No atlas file name was set.");
    return 0;
  }
  try
  {
    // The headers only: ParaView asks for information at every change of a property, and the
    // texels are read once, by RequestData.
    const tc::Rig rig = tc::readAtlasRig(this->FileName);
    const int a = tc::findAnimation(rig.animations, this->Animation);
    if (a >= 0)
    {
      const std::vector<double> times =
        tc::animationKeyTimes(rig.animations[static_cast<size_t>(a)]);
      const double range[2] = { times.front(), times.back() };
      info->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
        static_cast<int>(times.size()));
      info->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
    }
  }
  catch (const tc::InputError& e)
  {
    vtkErrorMacro("Cannot read the atlas: " << e.what());
    return 0;
  }
  return 1;
}

int tcAtlasReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  if (!this->ReadCached())
  {
    return 0;
  }
  vtkMultiBlockDataSet* output = vtkMultiBlockDataSet::GetData(out, 0);
  output->ShallowCopy(this->Cached->output);
  vtkInformation* info = out->GetInformationObject(0);
  if (info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()) &&
    info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    // The animation's name rides in field data of the output's own (the cache's stays as read).
    const std::vector<tc::Animation>& animations = this->Cached->rig.animations;
    vtkNew<vtkFieldData> fields;
    fields->ShallowCopy(this->Cached->output->GetFieldData());
    output->SetFieldData(fields);
    try
    {
      const int a = tc::findAnimation(animations, this->Animation);
      tcvtk::SetTextField(fields, tc::kAnimationName,
        a >= 0 ? animations[static_cast<size_t>(a)].name : std::string());
    }
    catch (const tc::InputError& e)
    {
      // The file changed between the information and the data requests.
      vtkErrorMacro("Cannot read the atlas: " << e.what());
      return 0;
    }
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(),
      info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()));
  }
  return 1;
}

void tcAtlasReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Animation: " << this->Animation << "\n";
}
