// SPDX-License-Identifier: BSD-3-Clause
#include "tcMeshWriter.h"

#include "tcMeshConversion.h"

#include "tc/common/errors.h"
#include "tc/common/file_names.h"
#include "tc/io/off_io.h"
#include "tc/io/temporary_file.h"

#include <vtkCellArray.h>
#include <vtkErrorCode.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkOBJWriter.h>
#include <vtkObjectFactory.h>
#include <vtkPLYWriter.h>
#include <vtkPolyData.h>
#include <vtkPolyDataWriter.h>
#include <vtkSTLWriter.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLWriter.h>

#include <array>
#include <type_traits>

vtkStandardNewMacro(tcMeshWriter);

namespace
{
const std::array<const char*, 6> kExtensions{ ".vtp", ".vtk", ".ply", ".obj", ".stl", ".off" };

/// The extension of `path` that the writer takes, lower case; "" for none.
std::string MeshExtension(const std::string& path)
{
  for (const char* extension : kExtensions)
  {
    if (tc::hasExtension(path, extension))
    {
      return extension;
    }
  }
  return "";
}

/// `mesh` written by VTK's writer W to `path`, binary where the format has a binary form.
template <class W>
bool WriteWith(vtkPolyData* mesh, const std::string& path)
{
  vtkNew<W> writer;
  if constexpr (std::is_base_of_v<vtkXMLWriter, W>)
  {
    writer->SetDataModeToBinary();
  }
  else if constexpr (!std::is_same_v<W, vtkOBJWriter>)
  {
    writer->SetFileTypeToBinary();
  }
  writer->SetInputData(mesh);
  writer->SetFileName(path.c_str());
  return writer->Write() == 1 && writer->GetErrorCode() == vtkErrorCode::NoError;
}

/// `mesh` written by VTK's writer of `extension` (any but .off) to `path`.
bool WriteWithVTK(vtkPolyData* mesh, const std::string& extension, const std::string& path)
{
  if (extension == ".vtp")
  {
    return WriteWith<vtkXMLPolyDataWriter>(mesh, path);
  }
  if (extension == ".vtk")
  {
    return WriteWith<vtkPolyDataWriter>(mesh, path);
  }
  if (extension == ".ply")
  {
    return WriteWith<vtkPLYWriter>(mesh, path);
  }
  if (extension == ".stl")
  {
    return WriteWith<vtkSTLWriter>(mesh, path);
  }
  return WriteWith<vtkOBJWriter>(mesh, path);
}
} // namespace

tcMeshWriter::tcMeshWriter() = default;
tcMeshWriter::~tcMeshWriter() = default;

int tcMeshWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

bool tcMeshWriter::IsMeshFileName(const char* path)
{
  return path && !MeshExtension(path).empty();
}

const char* tcMeshWriter::GetSupportedExtensions()
{
  return ".vtp .vtk .ply .obj .stl .off";
}

void tcMeshWriter::WriteData()
{
  const std::string extension = MeshExtension(this->FileName);
  auto* mesh = vtkPolyData::SafeDownCast(this->GetInputDataObject(0, 0));
  if (this->FileName.empty() || extension.empty())
  {
    vtkErrorMacro("Cannot write the mesh '"
      << this->FileName << "': unknown extension; a mesh is written as " << GetSupportedExtensions()
      << " (an atlas as .exr: tcAtlasWriter; an LOD chain as .glb or .gltf: tcGLTFWriter).");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  if ((extension == ".stl" || extension == ".off") && mesh->GetPolys()->GetMaxCellSize() > 3)
  {
    vtkErrorMacro("Cannot write the mesh '" << this->FileName << "': " << extension
                                            << " takes triangles only; triangulate it first.");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  if (!this->WriteFile(mesh, extension))
  {
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}

bool tcMeshWriter::WriteFile(vtkPolyData* mesh, const std::string& extension)
{
  try
  {
    if (extension == ".off")
    {
      // writeOFF replaces the file only once it is complete.
      tc::TriMesh triangles;
      std::string error;
      if (!tcvtk::ToTriMesh(mesh, triangles, error))
      {
        throw tc::InputError(error);
      }
      tc::writeOFF(this->FileName, triangles);
      return true;
    }
    tc::detail::TemporaryFile temporary(
      this->FileName, "cannot write " + this->FileName, extension);
    temporary.finish();
    if (!WriteWithVTK(mesh, extension, temporary.path()))
    {
      throw tc::InputError("VTK's writer failed (is the disk full or the folder not writable?)");
    }
    temporary.commit();
    return true;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot write the mesh '" << this->FileName << "': " << e.what());
    return false;
  }
}

void tcMeshWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
