// SPDX-License-Identifier: BSD-3-Clause
#include "tcMeshReader.h"

#include "tcFirstMessage.h"
#include "tcMeshConversion.h"
#include "tcTextureDecoding.h"

#include "tc/common/array_names.h"
#include "tc/common/errors.h"
#include "tc/common/file_names.h"
#include "tc/io/off_io.h"
#include "tc/io/scene_io.h"
#include "tc/io/soup_io.h"

#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkGenericDataObjectReader.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataReader.h>
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

vtkStandardNewMacro(tcMeshReader);

namespace
{
std::string Lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

/// The mesh formats read without Assimp, by extension (no one ends another after a dot), in the
/// order messages list them.
constexpr const char* kMeshExtensions[] = { "ply", "ply.gz", "obj", "stl", "off", "vtp", "vtk" };

/// The format key of a file name: one of kMeshExtensions, one of tc::sceneExtensions() (read
/// through Assimp), or "".
std::string FormatOf(const std::string& fileName)
{
  const std::string name = Lower(fileName);
  for (const char* ext : kMeshExtensions)
  {
    if (tc::hasExtension(name, std::string(".") + ext))
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

/// The mesh extensions for a sentence: ".ply, .ply.gz, ... and .vtk".
std::string MeshExtensionList()
{
  const size_t n = std::size(kMeshExtensions);
  std::string list;
  for (size_t i = 0; i < n; ++i)
  {
    list += (i == 0 ? "." : i + 1 == n ? " and ." : ", .") + std::string(kMeshExtensions[i]);
  }
  return list;
}

/// "N thing" or "N things".
std::string Count(int64_t n, const char* one, const char* many)
{
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

/// What one reader gave: the mesh (null when nothing was read), its error text, for a scene
/// file the facts the report adds, and the lines on what else was read (texture coordinates,
/// colours, the texture) and on what was left out (warnings). `aborted`: the user stopped the
/// read.
struct ReadResult
{
  vtkSmartPointer<vtkPolyData> mesh;
  std::string error;
  std::string sceneReport;
  std::vector<std::string> notes;
  bool aborted = false;
};

/// Adds the point arrays TextureCoordinates (the active TCoords) and Colors of `attributes` to
/// `mesh`, each when the file gave it; returns the report's lines on them.
std::vector<std::string> AddPointAttributes(
  vtkPolyData* mesh, const tc::PointAttributes& attributes)
{
  std::vector<std::string> notes;
  const vtkIdType n = mesh->GetNumberOfPoints();
  if (!attributes.textureCoordinates.empty() &&
    attributes.textureCoordinates.size() == static_cast<size_t>(2 * n))
  {
    vtkNew<vtkFloatArray> uv;
    uv->SetName(tc::kTextureCoordinates);
    uv->SetNumberOfComponents(2);
    uv->SetNumberOfTuples(n);
    std::copy(attributes.textureCoordinates.begin(), attributes.textureCoordinates.end(),
      uv->GetPointer(0));
    mesh->GetPointData()->SetTCoords(uv);
    notes.push_back(std::string("texture coordinates (point array ") + tc::kTextureCoordinates +
      ", v = 0 at the image's bottom)");
  }
  if (!attributes.colors.empty() && attributes.colors.size() == static_cast<size_t>(4 * n))
  {
    vtkNew<vtkUnsignedCharArray> rgba;
    rgba->SetName(tc::kColors);
    rgba->SetNumberOfComponents(4);
    rgba->SetNumberOfTuples(n);
    std::copy(attributes.colors.begin(), attributes.colors.end(), rgba->GetPointer(0));
    mesh->GetPointData()->AddArray(rgba);
    notes.push_back(std::string("vertex colours (point array ") + tc::kColors + ", RGBA)");
  }
  return notes;
}

/// Decodes the file's base-colour texture into the field arrays BaseColorTexture,
/// BaseColorTextureSize and BaseColorTextureName of `mesh`; returns the report's lines on it. A
/// texture that cannot be decoded is a warning: the mesh is read without it.
std::vector<std::string> AddTexture(vtkPolyData* mesh, const tc::BaseColorTexture& texture)
{
  std::vector<std::string> notes;
  if (texture.hasImage())
  {
    const tcvtk::DecodedTexture decoded = tcvtk::DecodeTexture(texture);
    if (decoded.rgba)
    {
      tcvtk::AddBaseColorTextureFields(
        mesh->GetFieldData(), decoded.rgba, decoded.width, decoded.height, texture.name);
      notes.push_back("texture " + texture.name + " " + std::to_string(decoded.width) + "x" +
        std::to_string(decoded.height) + " (field array " + tc::kBaseColorTexture + ")");
      if (!decoded.warning.empty())
      {
        notes.push_back("warning: texture '" + texture.name + "' is damaged: " + decoded.warning +
          "; it was decoded as far as it goes");
      }
    }
    else
    {
      notes.push_back("warning: texture '" + texture.name +
        "' cannot be decoded: " + decoded.error + "; the mesh is read without a texture");
    }
  }
  if (texture.leftOut > 0)
  {
    notes.push_back(Count(texture.leftOut, "other texture", "other textures") +
      " left out (only the first material's texture is kept)");
  }
  return notes;
}

/// Adds the point arrays and the texture a core reader gave to `read.mesh`, and the report's
/// lines on them and on the reader's warnings to `read.notes`.
void AddMeshFileData(ReadResult& read, const tc::PointAttributes& attributes,
  const tc::BaseColorTexture& texture, const std::vector<std::string>& warnings)
{
  read.notes = AddPointAttributes(read.mesh, attributes);
  const std::vector<std::string> textureNotes = AddTexture(read.mesh, texture);
  read.notes.insert(read.notes.end(), textureNotes.begin(), textureNotes.end());
  for (const std::string& warning : warnings)
  {
    read.notes.push_back("warning: " + warning);
  }
}

/// The report lines of a scene file: its meshes, skins, animations and skipped primitives.
std::string SceneReport(const tc::Scene& scene)
{
  std::ostringstream facts;
  facts << Count(static_cast<int64_t>(scene.meshNames.size()), "mesh", "meshes") << " ("
        << scene.meshInstances << " placed by the scene's nodes; cell array " << tc::kSceneMeshId
        << "), in the rest pose\n";
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
  return (scene.importer.empty() ? "" : "importer: " + scene.importer + "\n") + facts.str();
}

/// The surfaces of a scene file through Assimp (tc::readScene), with cell array SceneMeshId.
ReadResult ReadScene(const std::string& fileName, const tc::Progress& progress)
{
  ReadResult read;
  try
  {
    const tc::Scene scene = tc::readScene(fileName, progress);
    read.mesh = vtkSmartPointer<vtkPolyData>::New();
    tcvtk::FromPolygonSoup(scene.soup, read.mesh);
    read.mesh->GetCellData()->AddArray(tcvtk::MakeIntArray(tc::kSceneMeshId, scene.meshId));
    read.sceneReport = SceneReport(scene);
    AddMeshFileData(read, scene.attributes, scene.texture, scene.warnings);
  }
  catch (const tc::Aborted&)
  {
    read.aborted = true;
  }
  catch (const std::exception& e)
  {
    read.error = e.what();
  }
  return read;
}

/// True for the formats the core reads: OFF, PLY (also gzip-compressed) and OBJ.
bool IsCoreFormat(const std::string& format)
{
  return format == "off" || format == "ply" || format == "ply.gz" || format == "obj";
}

/// An OFF, PLY or OBJ file through the core's readers: for PLY and OBJ tc::readPLYFile and
/// tc::readOBJFile (with texture coordinates, colours and the texture), not vtkPLYReader and
/// vtkOBJReader, which crash on truncated or damaged files.
ReadResult ReadWithCore(const std::string& fileName, const std::string& format)
{
  ReadResult read;
  try
  {
    const tc::MeshFile file = format == "off" ? tc::MeshFile{ tc::readOFF(fileName), {}, {}, {} }
      : format == "obj"                       ? tc::readOBJFile(fileName)
                                              : tc::readPLYFile(fileName);
    read.mesh = vtkSmartPointer<vtkPolyData>::New();
    tcvtk::FromPolygonSoup(file.soup, read.mesh);
    AddMeshFileData(read, file.attributes, file.texture, file.warnings);
  }
  catch (const std::exception& e)
  {
    read.error = e.what();
  }
  return read;
}

/// Why vtkSTLReader must not read `fileName`, or "": a binary STL whose triangle count needs
/// more bytes than the file holds. vtkSTLReader allocates what the count says, and a failed
/// allocation aborts the process (a damaged count of 5e9 did). Binary is decided as
/// vtkSTLReader decides it, by vtksys's DetectFileType.
std::string BinarySTLError(const std::string& fileName)
{
  if (vtksys::SystemTools::DetectFileType(fileName.c_str()) != vtksys::SystemTools::FileTypeBinary)
  {
    return "";
  }
  std::error_code ec;
  const uintmax_t bytes = std::filesystem::file_size(fileName, ec);
  std::ifstream in(fileName, std::ios::binary);
  unsigned char count[4] = { 0, 0, 0, 0 };
  if (ec || !in.seekg(80) || !in.read(reinterpret_cast<char*>(count), 4))
  {
    return "a binary STL file needs an 80-byte header and a triangle count";
  }
  const uint64_t triangles = count[0] | count[1] << 8 | count[2] << 16 | uint64_t(count[3]) << 24;
  if (84 + 50 * triangles > bytes)
  {
    return "the binary STL header declares " + std::to_string(triangles) +
      " triangles, which need " + std::to_string(84 + 50 * triangles) +
      " bytes, but the file has " + std::to_string(bytes) + " (truncated or damaged)";
  }
  return "";
}

/// An STL, VTP or legacy VTK file through VTK's readers, whose first error message is kept.
/// Legacy VTK files may hold any dataset; non-polydata is reduced to its outer surface.
ReadResult ReadWithVTK(const std::string& fileName, const std::string& format)
{
  vtkNew<tcvtk::FirstMessage> catcher;
  vtkSmartPointer<vtkAlgorithm> reader;
  if (format == "stl")
  {
    ReadResult refused;
    refused.error = BinarySTLError(fileName);
    if (!refused.error.empty())
    {
      return refused;
    }
    vtkNew<vtkSTLReader> stl;
    stl->SetFileName(fileName.c_str());
    stl->MergingOff();
    reader = stl;
  }
  else if (format == "vtp")
  {
    vtkNew<vtkXMLPolyDataReader> vtp;
    vtp->SetFileName(fileName.c_str());
    reader = vtp;
  }
  else
  {
    vtkNew<vtkGenericDataObjectReader> legacy;
    legacy->SetFileName(fileName.c_str());
    vtkNew<vtkDataSetSurfaceFilter> surface;
    surface->SetInputConnection(legacy->GetOutputPort());
    legacy->AddObserver(vtkCommand::ErrorEvent, catcher);
    reader = surface;
  }
  reader->AddObserver(vtkCommand::ErrorEvent, catcher);
  reader->Update();
  ReadResult read;
  read.mesh = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  read.error = catcher->Text;
  return read;
}

/// The reader's report: what was read from where, the cell counts, the scene facts, the notes
/// (texture coordinates, colours, texture, warnings), and the point and cell arrays, one item per
/// line.
std::string ReadReport(const std::string& fileName, const std::string& format, vtkPolyData* output,
  const std::string& sceneReport, const std::vector<std::string>& notes)
{
  std::ostringstream report;
  report << "read " << format << " file '" << fileName << "'\n"
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
  for (const std::string& note : notes)
  {
    report << note << "\n";
  }
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
  return report.str();
}
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
  static const std::string extensions = []
  {
    std::string list;
    for (const char* ext : kMeshExtensions)
    {
      list += std::string(ext) + " ";
    }
    return list + tc::sceneExtensions();
  }();
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
    vtkErrorMacro("Cannot read '" << this->FileName << "': unknown extension; TriChart reads "
                                  << MeshExtensionList() << " meshes, and the scene formats "
                                  << tc::sceneExtensions() << ".");
    return 0;
  }

  // 3. Read with the reader of that format.
  const ReadResult read = tc::isSceneFile(this->FileName)
    ? ReadScene(this->FileName, tcvtk::MakeProgress(this))
    : IsCoreFormat(format) ? ReadWithCore(this->FileName, format)
                           : ReadWithVTK(this->FileName, format);
  if (read.aborted)
  {
    return 0;
  }

  // 4. A file without polygons is an error, whatever the reader said.
  const vtkIdType polygons =
    read.mesh ? read.mesh->GetNumberOfPolys() + read.mesh->GetNumberOfStrips() : 0;
  if (!read.error.empty() || polygons == 0)
  {
    vtkErrorMacro("Cannot read '" << this->FileName << "' as " << format << ": "
                                  << (read.error.empty() ? "no polygons found" : read.error)
                                  << ". Check that the file is a complete " << format
                                  << " surface mesh.");
    return 0;
  }

  // 5. Output and report.
  output->ShallowCopy(read.mesh);
  this->Report = ReadReport(this->FileName, format, output, read.sceneReport, read.notes);
  tcvtk::SetTextField(output->GetFieldData(), tc::kReaderReport, this->Report);
  return 1;
}

void tcMeshReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Report: " << this->Report << "\n";
}
