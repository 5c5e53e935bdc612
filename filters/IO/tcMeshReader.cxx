// SPDX-License-Identifier: BSD-3-Clause
#include "tcMeshReader.h"

#include "tcFirstMessage.h"
#include "tcMeshConversion.h"
#include "tcSkinData.h"
#include "tcTextureDecoding.h"

#include "tc/common/array_names.h"
#include "tc/common/errors.h"
#include "tc/common/file_names.h"
#include "tc/io/height_field_io.h"
#include "tc/io/off_io.h"
#include "tc/io/scene_io.h"
#include "tc/io/sequence_io.h"
#include "tc/io/soup_io.h"
#include "tc/skinning/proxy_bones.h"

#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkGenericDataObjectReader.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataReader.h>
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
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
  if (tc::isSceneFile(name) || tc::isHeightFieldFile(name))
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

/// "1.25" seconds, shortest form.
std::string Seconds(double t)
{
  std::ostringstream text;
  text << t;
  return text.str();
}

/// The report lines of a scene file: its meshes, skeleton, skin, animations and skipped
/// primitives.
std::string SceneReport(const tc::Scene& scene)
{
  std::ostringstream facts;
  facts << Count(static_cast<int64_t>(scene.meshNames.size()), "mesh", "meshes") << " ("
        << scene.meshInstances << " placed by the scene's nodes; cell array " << tc::kSceneMeshId
        << ")\n";
  if (scene.skinnedMeshes > 0)
  {
    facts << "skinned: " << Count(scene.skinnedMeshes, "mesh", "meshes") << ", "
          << Count(scene.bones, "bone", "bones") << "\n";
  }
  if (!scene.skeleton.empty())
  {
    facts << "skeleton: "
          << Count(static_cast<int64_t>(scene.skeleton.joints.size()), "joint", "joints")
          << " (output port 1); skin weights per point (point arrays " << tc::kSkinIndices << ", "
          << tc::kSkinWeights << ", 4 influences)\n";
  }
  for (size_t a = 0; a < scene.animations.size(); ++a)
  {
    const tc::Animation& animation = scene.animations[a];
    facts << "animation " << a << " '" << animation.name << "': " << Seconds(animation.duration)
          << " s, " << tc::animationKeyTimes(animation).size() << " key times\n";
  }
  if (scene.morphTargets > 0)
  {
    facts << Count(scene.morphTargets, "morph target", "morph targets") << " not applied\n";
  }
  if (scene.skippedPrimitives > 0)
  {
    facts << "skipped " << Count(scene.skippedPrimitives, "point or line", "points and lines")
          << "\n";
  }
  return (scene.importer.empty() ? "" : "importer: " + scene.importer + "\n") + facts.str();
}

/// The surfaces of a scene file through Assimp (tc::readScene), with cell array SceneMeshId
/// and the skin's point arrays; the scene itself in `scene` (for posing).
ReadResult ReadScene(
  const std::string& fileName, const tc::Progress& progress, std::optional<tc::Scene>& scene)
{
  ReadResult read;
  try
  {
    scene = tc::readScene(fileName, progress);
    read.mesh = vtkSmartPointer<vtkPolyData>::New();
    tcvtk::FromPolygonSoup(scene->soup, read.mesh);
    read.mesh->GetCellData()->AddArray(tcvtk::MakeIntArray(tc::kSceneMeshId, scene->meshId));
    if (!scene->skin.empty())
    {
      tcvtk::AddSkinArrays(read.mesh->GetPointData(), scene->skin);
      tcvtk::SetTextField(read.mesh->GetFieldData(), tc::kRig,
        tc::encodeRig(tc::Rig{ scene->skeleton, scene->animations }));
    }
    read.sceneReport = SceneReport(*scene);
    AddMeshFileData(read, scene->attributes, scene->texture, scene->warnings);
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

/// The proxy bones of a sequence of several frames (tc::fitProxyBones) as the skin arrays and
/// the Rig field of `mesh`; returns the report's line.
std::string AddProxyBones(
  const tc::DeformingSequence& sequence, const tc::Progress& progress, vtkPolyData* mesh)
{
  const tc::ProxyBonesResult fit = tc::fitProxyBones(sequence, {}, progress);
  tcvtk::AddSkinArrays(mesh->GetPointData(), fit.skin);
  tcvtk::SetTextField(
    mesh->GetFieldData(), tc::kRig, tc::encodeRig(tc::proxyRig(fit, sequence.times, "frames")));
  std::ostringstream line;
  line << "proxy bones: " << fit.skeleton.joints.size() << " fitted to the frames (point arrays "
       << tc::kSkinIndices << ", " << tc::kSkinWeights << ", field " << tc::kRig << "), RMS "
       << 100 * fit.lbs.relative(fit.lbs.totalRms)
       << "% of the diagonal (one rigid bone per point: "
       << 100 * fit.rigid.relative(fit.rigid.totalRms) << "%)\n";
  return line.str();
}

/// A deforming sequence (tc::readSequence): frame 0 as the mesh, the frames in `sequence`,
/// and with `proxyBones` the skin fitted to them.
ReadResult ReadSequence(const std::string& path, const tc::Progress& progress, bool proxyBones,
  std::optional<tc::DeformingSequence>& sequence)
{
  ReadResult read;
  try
  {
    sequence = tc::readSequence(path, progress.sub(0.0, proxyBones ? 0.7 : 1.0));
    read.mesh = vtkSmartPointer<vtkPolyData>::New();
    tcvtk::FromPolygonSoup(sequence->soup, read.mesh);
    AddMeshFileData(read, sequence->attributes, sequence->texture, sequence->warnings);
    const std::vector<double>& times = sequence->times;
    read.sceneReport = "sequence (" + sequence->source + ") of " +
      Count(static_cast<int64_t>(times.size()), "frame", "frames") +
      " with one connectivity, times " + Seconds(times.front()) + " to " + Seconds(times.back()) +
      "\n";
    if (proxyBones && times.size() > 1)
    {
      read.sceneReport += AddProxyBones(*sequence, progress.sub(0.7, 1.0), read.mesh);
    }
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

/// The field arrays GeoOrigin (the first cell's centre in the file's coordinates) and GeoCRS
/// (its coordinate system, when the file has one) of a height field's mesh.
void AddGeoreference(const tc::HeightField& field, vtkPolyData* mesh)
{
  vtkNew<vtkDoubleArray> origin;
  origin->SetName(tc::kGeoOrigin);
  origin->SetNumberOfComponents(2);
  origin->InsertNextTuple(field.origin.data());
  mesh->GetFieldData()->AddArray(origin);
  if (!field.crs.empty())
  {
    tcvtk::SetTextField(mesh->GetFieldData(), tc::kGeoCRS, field.crs);
  }
}

/// A raster of heights (tc::readHeightField) as a terrain grid with the point array Elevation.
ReadResult ReadHeightField(
  const std::string& path, double verticalScale, const tc::Progress& progress)
{
  ReadResult read;
  try
  {
    const tc::HeightField field = tc::readHeightField(path, progress.sub(0.0, 0.6));
    tc::HeightFieldOptions options;
    options.verticalScale = verticalScale;
    const tc::HeightFieldMesh grid =
      tc::triangulateHeightField(field, options, progress.sub(0.6, 1.0));
    read.mesh = vtkSmartPointer<vtkPolyData>::New();
    tcvtk::FromTriMesh(grid.mesh, read.mesh);
    vtkNew<vtkFloatArray> elevation;
    elevation->SetName(tc::kElevation);
    elevation->SetNumberOfTuples(grid.mesh.numPoints());
    std::copy(grid.heights.begin(), grid.heights.end(), elevation->GetPointer(0));
    read.mesh->GetPointData()->AddArray(elevation);
    AddGeoreference(field, read.mesh);
    std::ostringstream facts;
    facts << "height field of " << field.columns << " x " << field.rows << " cells";
    facts << (grid.noDataCells > 0
        ? ", " + Count(grid.noDataCells, "cell", "cells") + " without data left out as holes"
        : std::string());
    read.sceneReport = facts.str() + "\n";
    read.notes = field.notes;
    if (verticalScale != 1.0)
    {
      read.notes.push_back("heights times " + Seconds(verticalScale) + " (VerticalScale); " +
        tc::kElevation + " holds them as read");
    }
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

/// The file last read, as read: the rest mesh with its arrays and report lines, and what poses
/// it over time (a scene's skeleton and animations, or a sequence's frames).
class tcMeshReaderCache
{
public:
  std::string fileName;
  std::filesystem::file_time_type stamp;
  std::string format;
  ReadResult rest;
  std::optional<tc::Scene> scene;
  std::optional<tc::DeformingSequence> sequence;
  bool proxyBones = false;
  double verticalScale = 1.0;
};

namespace
{
/// The file's last change (a folder's for a sequence folder; none for a pattern, read once).
std::filesystem::file_time_type Stamp(const std::string& path)
{
  std::error_code ec;
  const auto stamp = std::filesystem::last_write_time(path, ec);
  return ec ? std::filesystem::file_time_type() : stamp;
}

/// Sets the time steps and range of every output port; none when `times` is empty.
void AnnounceTimes(vtkInformationVector* outputs, const std::vector<double>& times)
{
  for (int port = 0; port < outputs->GetNumberOfInformationObjects(); ++port)
  {
    vtkInformation* info = outputs->GetInformationObject(port);
    info->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    info->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
    if (!times.empty())
    {
      const double range[2] = { times.front(), times.back() };
      info->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
        static_cast<int>(times.size()));
      info->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
    }
  }
}

/// `rest` with its points replaced by `points` (#V x 3), its arrays shared.
vtkSmartPointer<vtkPolyData> WithPoints(vtkPolyData* rest, const std::vector<double>& points)
{
  vtkNew<vtkPoints> moved;
  moved->SetDataTypeToDouble();
  moved->SetNumberOfPoints(rest->GetNumberOfPoints());
  std::copy(
    points.begin(), points.end(), static_cast<double*>(moved->GetData()->GetVoidPointer(0)));
  auto posed = vtkSmartPointer<vtkPolyData>::New();
  posed->ShallowCopy(rest);
  posed->SetPoints(moved);
  return posed;
}

/// The frame of `sequence` shown at `t`: the last one whose time is not after t (the first
/// before them all).
size_t FrameAt(const tc::DeformingSequence& sequence, double t)
{
  const auto& times = sequence.times;
  const size_t after =
    static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  return after == 0 ? 0 : after - 1;
}
} // namespace

tcMeshReader::tcMeshReader()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(2);
}

tcMeshReader::~tcMeshReader() = default;

bool tcMeshReader::CanReadFile(const char* fileName)
{
  return fileName && (!FormatOf(fileName).empty() || tc::isSequencePath(fileName));
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
    return list + tc::sceneExtensions() + " " + tc::heightFieldExtensions();
  }();
  return extensions.c_str();
}

int tcMeshReader::GetNumberOfAnimations() const
{
  return this->Cache && this->Cache->scene ? static_cast<int>(this->Cache->scene->animations.size())
                                           : 0;
}

const char* tcMeshReader::GetAnimationName(int index) const
{
  return index >= 0 && index < this->GetNumberOfAnimations()
    ? this->Cache->scene->animations[index].name.c_str()
    : nullptr;
}

bool tcMeshReader::Load()
{
  // 1. Validate: the file must exist and have an extension we know (or be a sequence).
  if (this->FileName.empty())
  {
    vtkErrorMacro("No file name set; call SetFileName with a mesh file.");
    return false;
  }
  const bool sequence = tc::isSequencePath(this->FileName);
  if (this->Cache && this->Cache->fileName == this->FileName &&
    this->Cache->stamp == Stamp(this->FileName) && this->Cache->proxyBones == this->ProxyBones &&
    this->Cache->verticalScale == this->VerticalScale)
  {
    return true;
  }
  this->Cache.reset();
  if (!sequence && !std::ifstream(this->FileName).good())
  {
    vtkErrorMacro(
      "Cannot open '" << this->FileName << "': the file does not exist or is not readable.");
    return false;
  }
  const std::string format = sequence ? "sequence" : FormatOf(this->FileName);
  if (format.empty())
  {
    vtkErrorMacro("Cannot read '" << this->FileName << "': unknown extension; TriChart reads "
                                  << MeshExtensionList() << " meshes, the scene formats "
                                  << tc::sceneExtensions() << ", the height fields "
                                  << tc::heightFieldExtensions()
                                  << ", and sequences (a folder of frames, a pattern with * or ?, "
                                     "or .md2).");
    return false;
  }

  // 2. Read with the reader of that format.
  auto cache = std::make_unique<tcMeshReaderCache>();
  const tc::Progress progress = tcvtk::MakeProgress(this);
  cache->rest = sequence ? ReadSequence(this->FileName, progress, this->ProxyBones, cache->sequence)
    : tc::isSceneFile(this->FileName) ? ReadScene(this->FileName, progress, cache->scene)
    : tc::isHeightFieldFile(this->FileName)
    ? ReadHeightField(this->FileName, this->VerticalScale, progress)
    : IsCoreFormat(format) ? ReadWithCore(this->FileName, format)
                           : ReadWithVTK(this->FileName, format);
  const ReadResult& read = cache->rest;
  if (read.aborted)
  {
    return false;
  }

  // 3. A file without polygons is an error, whatever the reader said.
  const vtkIdType polygons =
    read.mesh ? read.mesh->GetNumberOfPolys() + read.mesh->GetNumberOfStrips() : 0;
  if (!read.error.empty() || polygons == 0)
  {
    vtkErrorMacro(
      "Cannot read '" << this->FileName << "' as " << format << ": "
                      << (read.error.empty() ? "no polygons found" : read.error)
                      << ". Check that the file is a complete " << format
                      << (sequence                                   ? " of frames."
                             : tc::isHeightFieldFile(this->FileName) ? " raster of heights."
                                                                     : " surface mesh."));
    return false;
  }
  cache->fileName = this->FileName;
  cache->stamp = Stamp(this->FileName);
  cache->format = format;
  cache->proxyBones = this->ProxyBones;
  cache->verticalScale = this->VerticalScale;
  this->Cache = std::move(cache);
  return true;
}

int tcMeshReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (!this->Load())
  {
    return 0;
  }
  std::vector<double> times;
  if (this->Cache->scene && !this->BindPose)
  {
    std::string error;
    const int a = tc::findAnimation(this->Cache->scene->animations, this->Animation, error);
    if (!error.empty())
    {
      vtkErrorMacro("Cannot pose '" << this->FileName << "': " << error << ".");
      return 0;
    }
    times = a >= 0 ? tc::animationKeyTimes(this->Cache->scene->animations[a]) : times;
  }
  if (this->Cache->sequence && !this->BindPose)
  {
    times = this->Cache->sequence->times;
  }
  AnnounceTimes(outputVector, times);
  return 1;
}

int tcMeshReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // 1. Outputs.
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* skeletonOutput = vtkPolyData::GetData(outputVector, 1);
  this->Report.clear();

  // 2. Validate and read (once per file: RequestInformation has usually read it).
  if (!this->Load())
  {
    return 0;
  }
  const tcMeshReaderCache& cache = *this->Cache;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const bool timed = !this->BindPose &&
    outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()) &&
    outInfo->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const double t = timed ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()) : 0.0;

  // 3. Pose: a scene by its animation at t, a sequence by its frame at t.
  std::string pose = "in the rest pose", animationName;
  vtkSmartPointer<vtkPolyData> mesh = cache.rest.mesh;
  if (cache.scene && !cache.scene->skeleton.empty())
  {
    std::string error;
    const int a = timed ? tc::findAnimation(cache.scene->animations, this->Animation, error) : -1;
    const tc::Animation* animation = a >= 0 ? &cache.scene->animations[a] : nullptr;
    const std::vector<tc::Matrix4> globals = tc::jointGlobals(cache.scene->skeleton, animation, t);
    if (animation)
    {
      mesh = WithPoints(mesh,
        tc::skinPoints(cache.scene->soup.points, cache.scene->skin,
          tc::skinningMatrices(cache.scene->skeleton, globals)));
      pose = "posed by animation '" + animation->name + "' at " + Seconds(t) + " s";
      animationName = animation->name;
    }
    skeletonOutput->ShallowCopy(tcvtk::SkeletonPolyData(cache.scene->skeleton, globals));
  }
  if (cache.sequence && timed)
  {
    const size_t k = FrameAt(*cache.sequence, t);
    const std::vector<float>& frame = cache.sequence->frames[k];
    mesh = WithPoints(mesh, std::vector<double>(frame.begin(), frame.end()));
    pose = "frame " + std::to_string(k) + " (" + cache.sequence->frameNames[k] + ")";
  }

  // 4. Output, time and report, in field data of the output's own (the cached mesh's stays).
  output->ShallowCopy(mesh);
  vtkNew<vtkFieldData> fields;
  fields->ShallowCopy(mesh->GetFieldData());
  output->SetFieldData(fields);
  if (!animationName.empty())
  {
    tcvtk::SetTextField(fields, tc::kAnimationName, animationName);
  }
  if (timed)
  {
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
    skeletonOutput->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  }
  const bool moves = cache.sequence || (cache.scene && !cache.scene->animations.empty());
  this->Report = ReadReport(this->FileName, cache.format, output,
    cache.rest.sceneReport + (moves ? pose + "\n" : ""), cache.rest.notes);
  tcvtk::SetTextField(output->GetFieldData(), tc::kReaderReport, this->Report);
  return 1;
}

void tcMeshReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Animation: " << this->Animation << "\n";
  os << indent << "BindPose: " << this->BindPose << "\n";
  os << indent << "ProxyBones: " << this->ProxyBones << "\n";
  os << indent << "VerticalScale: " << this->VerticalScale << "\n";
  os << indent << "Report: " << this->Report << "\n";
}
