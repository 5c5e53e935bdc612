// SPDX-License-Identifier: BSD-3-Clause
#include "tcMeshReader.h"

#include "tcMeshConversion.h"

#include "tc/common/array_names.h"
#include "tc/common/errors.h"
#include "tc/io/off_io.h"
#include "tc/io/soup_io.h"
#include "tc/io/scene_io.h"

#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkFieldData.h>
#include <vtkGenericDataObjectReader.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

vtkStandardNewMacro(tcMeshReader);

namespace
{
std::string Lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool EndsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() &&
    s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// The format key of a file name: "ply.gz", "ply", "obj", "stl", "off", "vtp", "vtk", one of
/// tc::sceneExtensions() (read through Assimp), or "".
std::string FormatOf(const std::string& fileName)
{
  const std::string name = Lower(fileName);
  for (const char* ext : { "ply.gz", "ply", "obj", "stl", "off", "vtp", "vtk" })
  {
    if (EndsWith(name, std::string(".") + ext))
    {
      return ext;
    }
  }
  if (tc::isSceneFile(name))
  {
    return name.substr(name.rfind('.') + 1);
  }
  return std::string();
}

/// "N thing" or "N things".
std::string Count(int64_t n, const char* one, const char* many)
{
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

/// Observes a VTK reader's error events so that their text can be reported as ours.
class ErrorCatcher : public vtkCommand
{
public:
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    if (callData && this->Text.empty())
    {
      this->Text = static_cast<const char*>(callData);
    }
  }
  std::string Text;
};
}

tcMeshReader::tcMeshReader()
{
  this->SetNumberOfInputPorts(0);
}

tcMeshReader::~tcMeshReader() = default;

bool tcMeshReader::CanReadFile(const char* fileName)
{
  return fileName && !FormatOf(fileName).empty();
}

const char* tcMeshReader::GetSupportedExtensions()
{
  static const std::string extensions =
    std::string("ply ply.gz obj stl off vtp vtk ") + tc::sceneExtensions();
  return extensions.c_str();
}

int tcMeshReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // 1. Output.
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->Report.clear();

  // 2. Validate: the file must exist and have an extension we know.
  if (this->FileName.empty())
  {
    vtkErrorMacro("No file name set; call SetFileName with a mesh file.");
    return 0;
  }
  if (!std::ifstream(this->FileName).good())
  {
    vtkErrorMacro(
      "Cannot open '" << this->FileName << "': the file does not exist or is not readable.");
    return 0;
  }
  const std::string format = FormatOf(this->FileName);
  if (format.empty())
  {
    vtkErrorMacro("Cannot read '" << this->FileName << "': unknown extension; TriChart reads ."
                                  << "ply, .ply.gz, .obj, .stl, .off, .vtp and .vtk meshes, and "
                                  << "the scene formats " << tc::sceneExtensions() << ".");
    return 0;
  }

  // 3. Read with the reader of that format, catching its error messages.
  vtkNew<ErrorCatcher> catcher;
  vtkSmartPointer<vtkPolyData> mesh;
  vtkSmartPointer<vtkAlgorithm> reader;
  std::string error;
  std::string sceneReport;
  if (tc::isSceneFile(this->FileName))
  {
    try
    {
      const tc::Scene scene = tc::readScene(this->FileName, tcvtk::MakeProgress(this));
      mesh = vtkSmartPointer<vtkPolyData>::New();
      tcvtk::FromPolygonSoup(scene.soup, mesh);
      mesh->GetCellData()->AddArray(tcvtk::MakeIntArray(tc::kSceneMeshId, scene.meshId));
      std::ostringstream facts;
      facts << Count(static_cast<int64_t>(scene.meshNames.size()), "mesh", "meshes") << " ("
            << scene.meshInstances << " placed by the scene's nodes; cell array "
            << tc::kSceneMeshId << "), in the rest pose\n";
      if (scene.skinnedMeshes > 0)
      {
        facts << "skinned: " << Count(scene.skinnedMeshes, "mesh", "meshes") << ", "
              << Count(scene.bones, "bone", "bones") << " (skin weights not read)\n";
      }
      if (scene.animations + scene.morphTargets > 0)
      {
        facts << Count(scene.animations, "animation", "animations") << " and "
              << Count(scene.morphTargets, "morph target", "morph targets") << " not applied\n";
      }
      if (scene.skippedPrimitives > 0)
      {
        facts << "skipped " << Count(scene.skippedPrimitives, "point or line", "points and lines")
              << "\n";
      }
      sceneReport = (scene.importer.empty() ? "" : "importer: " + scene.importer + "\n") +
        facts.str();
    }
    catch (const tc::Aborted&)
    {
      return 0;
    }
    catch (const std::exception& e)
    {
      error = e.what();
    }
  }
  else if (format == "off" || format == "ply" || format == "ply.gz" || format == "obj")
  {
    // The core readers; for PLY and OBJ tc::readPLY and tc::readOBJ, not vtkPLYReader and
    // vtkOBJReader, which crash on truncated or damaged files.
    try
    {
      const tc::PolygonSoup soup = format == "off" ? tc::readOFF(this->FileName)
        : format == "obj"                          ? tc::readOBJ(this->FileName)
                                                   : tc::readPLY(this->FileName);
      mesh = vtkSmartPointer<vtkPolyData>::New();
      tcvtk::FromPolygonSoup(soup, mesh);
    }
    catch (const std::exception& e)
    {
      error = e.what();
    }
  }
  else if (format == "stl")
  {
    vtkNew<vtkSTLReader> stl;
    stl->SetFileName(this->FileName.c_str());
    stl->MergingOff();
    reader = stl;
  }
  else if (format == "vtp")
  {
    vtkNew<vtkXMLPolyDataReader> vtp;
    vtp->SetFileName(this->FileName.c_str());
    reader = vtp;
  }
  else
  {
    // Legacy VTK files may hold any dataset; non-polydata is reduced to its outer surface.
    vtkNew<vtkGenericDataObjectReader> legacy;
    legacy->SetFileName(this->FileName.c_str());
    vtkNew<vtkDataSetSurfaceFilter> surface;
    surface->SetInputConnection(legacy->GetOutputPort());
    legacy->AddObserver(vtkCommand::ErrorEvent, catcher);
    reader = surface;
  }
  if (reader)
  {
    reader->AddObserver(vtkCommand::ErrorEvent, catcher);
    reader->Update();
    mesh = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
    if (!catcher->Text.empty())
    {
      error = catcher->Text;
    }
  }

  // 4. A file without polygons is an error, whatever the reader said.
  const vtkIdType polygons = mesh ? mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() : 0;
  if (!error.empty() || polygons == 0)
  {
    if (error.empty())
    {
      error = "no polygons found";
    }
    vtkErrorMacro("Cannot read '" << this->FileName << "' as " << format << ": " << error
                                  << ". Check that the file is a complete " << format
                                  << " surface mesh.");
    return 0;
  }

  // 5. Output and report.
  output->ShallowCopy(mesh);
  std::ostringstream report;
  report << "read " << format << " file '" << this->FileName << "'\n"
         << output->GetNumberOfPoints() << " points, " << output->GetNumberOfPolys() << " polygons";
  if (output->GetNumberOfStrips() > 0)
  {
    report << ", " << output->GetNumberOfStrips() << " triangle strips";
  }
  if (output->GetNumberOfLines() + output->GetNumberOfVerts() > 0)
  {
    report << ", " << output->GetNumberOfLines() + output->GetNumberOfVerts()
           << " vertices/lines (not surface cells)";
  }
  report << "\n" << sceneReport;
  for (int i = 0; i < output->GetPointData()->GetNumberOfArrays(); ++i)
  {
    const char* name = output->GetPointData()->GetArrayName(i);
    report << "point array " << (name ? name : "(unnamed)") << "\n";
  }
  for (int i = 0; i < output->GetCellData()->GetNumberOfArrays(); ++i)
  {
    const char* name = output->GetCellData()->GetArrayName(i);
    report << "cell array " << (name ? name : "(unnamed)") << "\n";
  }
  this->Report = report.str();
  tcvtk::SetTextField(output->GetFieldData(), tc::kReaderReport, this->Report);
  return 1;
}

void tcMeshReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Report: " << this->Report << "\n";
}
