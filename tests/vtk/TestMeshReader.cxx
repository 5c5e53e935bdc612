// SPDX-License-Identifier: BSD-3-Clause
// tcMeshReader: every format reads back what was written, with its counts; bad files are
// refused with an error naming the file, and never crash. The textured sphere's texture
// coordinates, from glTF and OBJ alike, pick the texel colour its checker has at each vertex.
#include "tc/common/array_names.h"
#include "tcMeshReader.h"
#include "tcTestUtilities.h"

#include <vtkCallbackCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkJPEGWriter.h>
#include <vtkNew.h>
#include <vtkOBJWriter.h>
#include <vtkPLYWriter.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataWriter.h>
#include <vtkSTLWriter.h>
#include <vtkSphereSource.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace
{
struct ReadResult
{
  vtkIdType points = -1;
  vtkIdType polys = -1;
  std::string error;
  std::string report;
};

void OnError(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* text = static_cast<std::string*>(clientData);
  if (callData && text->empty())
  {
    *text = static_cast<const char*>(callData);
  }
}

ReadResult ReadFile(const std::string& path)
{
  vtkNew<tcMeshReader> reader;
  ReadResult r;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetCallback(OnError);
  cb->SetClientData(&r.error);
  reader->AddObserver(vtkCommand::ErrorEvent, cb);
  reader->SetFileName(path.c_str());
  reader->Update();
  r.points = reader->GetOutput()->GetNumberOfPoints();
  r.polys = reader->GetOutput()->GetNumberOfPolys();
  r.report = reader->GetReport();
  return r;
}

void WriteText(const std::string& path, const std::string& text)
{
  std::ofstream(path, std::ios::binary) << text;
}

std::string ReadText(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

/// The colour of checker square (column, row from the image's top) of the textured sphere's
/// image, as scripts/make-textured-sphere.py makes it.
std::array<int, 3> CheckerColour(int column, int row)
{
  static const int hues[8][3] = { { 255, 0, 0 }, { 255, 128, 0 }, { 255, 255, 0 }, { 0, 255, 0 },
    { 0, 255, 255 }, { 0, 0, 255 }, { 128, 0, 255 }, { 255, 0, 255 } };
  std::array<int, 3> rgb;
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = hues[column][c] * (4 - row) / 4;
  }
  return rgb;
}

/// Reads the textured sphere (.glb or .obj) and checks its texture coordinates, its texture and,
/// at every vertex in the middle of a checker square (ring and segment 2 mod 4), that the texel
/// its texture coordinate picks has the colour of the square its position lies in: longitude
/// atan2(-z, x) gives the column, polar angle acos(y) the row from the top. A flipped v picks
/// the row of the other hemisphere, a wrong seam or u the wrong hue.
void CheckTexturedSphere(tctest::Checker& check, const std::string& path, const char* name)
{
  vtkNew<tcMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* sphere = reader->GetOutput();
  const std::string report = reader->GetReport();
  auto* uv = vtkFloatArray::SafeDownCast(sphere->GetPointData()->GetTCoords());
  vtkFieldData* fd = sphere->GetFieldData();
  auto* texels = vtkUnsignedCharArray::SafeDownCast(fd->GetArray(tc::kBaseColorTexture));
  auto* size = vtkIntArray::SafeDownCast(fd->GetArray(tc::kBaseColorTextureSize));
  auto* label = vtkStringArray::SafeDownCast(fd->GetAbstractArray(tc::kBaseColorTextureName));
  if (!TC_CHECK(check, uv && texels && size && label && sphere->GetNumberOfPoints() == 559))
  {
    std::cerr << "  for " << path << ": report\n" << report;
    return;
  }
  TC_CHECK(check, std::string(uv->GetName()) == tc::kTextureCoordinates);
  TC_CHECK(check, uv->GetNumberOfComponents() == 2);
  double range[2][2];
  uv->GetRange(range[0], 0);
  uv->GetRange(range[1], 1);
  TC_CHECK(check, range[0][0] == 0 && range[0][1] == 1 && range[1][0] == 0 && range[1][1] == 1);
  TC_CHECK(
    check, size->GetNumberOfTuples() == 1 && size->GetValue(0) == 64 && size->GetValue(1) == 32);
  TC_CHECK(check, texels->GetNumberOfComponents() == 4 && texels->GetNumberOfTuples() == 64 * 32);
  TC_CHECK(check, label->GetNumberOfValues() == 1 && label->GetValue(0) == name);
  TC_CHECK(check, report.find("texture coordinates") != std::string::npos);
  TC_CHECK(check, report.find(std::string("texture ") + name + " 64x32") != std::string::npos);
  int checked = 0, wrong = 0;
  for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
  {
    double x[3];
    sphere->GetPoint(p, x);
    const double pi = std::acos(-1.0);
    const double ring = std::acos(std::clamp(x[1], -1.0, 1.0)) / pi * 16;
    double segment = std::atan2(-x[2], x[0]) / (2 * pi) * 32;
    segment += segment < -1e-6 ? 32 : 0;
    if (std::abs(ring - std::round(ring)) > 1e-3 || std::lround(ring) % 4 != 2 ||
      std::abs(segment - std::round(segment)) > 1e-3 || std::lround(segment) % 4 != 2)
    {
      continue;
    }
    ++checked;
    const std::array<int, 3> expected = CheckerColour(
      static_cast<int>(std::lround(segment) / 4), static_cast<int>(std::lround(ring) / 4));
    // Texture coordinate (u, v) is texel (u width, v height), row 0 at the bottom.
    const int tx = std::clamp(static_cast<int>(uv->GetComponent(p, 0) * 64), 0, 63);
    const int ty = std::clamp(static_cast<int>(uv->GetComponent(p, 1) * 32), 0, 31);
    unsigned char texel[4];
    texels->GetTypedTuple(ty * 64 + tx, texel);
    const bool same = texel[0] == expected[0] && texel[1] == expected[1] &&
      texel[2] == expected[2] && texel[3] == 255;
    wrong += same ? 0 : 1;
    if (!same && wrong <= 3)
    {
      std::cerr << "  " << path << " point " << p << ": texel (" << tx << ", " << ty << ") is "
                << int(texel[0]) << " " << int(texel[1]) << " " << int(texel[2]) << ", expected "
                << expected[0] << " " << expected[1] << " " << expected[2] << "\n";
    }
  }
  TC_CHECK(check, checked == 32 && wrong == 0);
}

/// Reads `obj` with a material whose map_Kd is `image`, written with the bytes `png` (no file
/// when they are empty); returns the reader's report, and the output in `mesh`.
std::string ReadMaterialObj(const std::string& tmp, const std::string& obj,
  const std::string& image, const std::string& png, vtkSmartPointer<vtkPolyData>& mesh)
{
  // `tmp` ends in a prefix of the file names, which the names in the files repeat.
  const std::string prefix = tmp.substr(tmp.rfind('/') + 1);
  WriteText(tmp + "material.obj", "mtllib " + prefix + "material.mtl\nusemtl m\n" + obj);
  WriteText(tmp + "material.mtl", "newmtl m\nmap_Kd " + prefix + image + "\n");
  std::remove((tmp + image).c_str()); // not left from an earlier run
  if (!png.empty())
  {
    WriteText(tmp + image, png);
  }
  vtkNew<tcMeshReader> reader;
  reader->SetFileName((tmp + "material.obj").c_str());
  reader->Update();
  mesh = reader->GetOutput();
  return reader->GetReport();
}

/// `image` encoded by `writer` (vtkPNGWriter, vtkJPEGWriter) in memory.
template <typename Writer>
std::string Encode(vtkImageData* image, Writer* writer)
{
  writer->SetInputData(image);
  writer->SetWriteToMemory(true);
  writer->Write();
  vtkUnsignedCharArray* bytes = writer->GetResult();
  return std::string(reinterpret_cast<const char*>(bytes->GetPointer(0)),
    static_cast<size_t>(bytes->GetNumberOfTuples()));
}

/// Damaged copies of a PNG and a JPEG texture (cut, bytes replaced) are decoded or reported as
/// a warning, and the mesh is read: never a crash, though vtkPNGReader crashes on a damaged PNG.
void CheckDamagedTextures(tctest::Checker& check, const std::string& tmp, const std::string& png)
{
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                             "f 1/1 2/2 3/3\n";
  vtkNew<vtkImageData> image;
  image->SetDimensions(16, 8, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int t = 0; t < 16 * 8 * 3; ++t)
  {
    static_cast<unsigned char*>(image->GetScalarPointer())[t] = static_cast<unsigned char>(t * 7);
  }
  vtkNew<vtkJPEGWriter> jpegWriter;
  const std::string jpeg = Encode(image, jpegWriter.Get());
  int tried = 0, decoded = 0, warned = 0;
  for (const auto& [name, bytes] :
    { std::pair{ std::string("copy.png"), png }, std::pair{ std::string("copy.jpg"), jpeg } })
  {
    uint32_t random = 12345;
    for (int copy = 0; copy < 60; ++copy)
    {
      std::string damaged = bytes;
      if (copy < 10)
      {
        damaged.resize(bytes.size() * (copy + 1) / 11);
      }
      for (int k = 0; copy >= 10 && k < 1 + copy % 4; ++k)
      {
        random = random * 1664525u + 1013904223u;
        damaged[8 + random % (damaged.size() - 8)] = static_cast<char>(random >> 24);
      }
      vtkSmartPointer<vtkPolyData> mesh;
      const std::string report = ReadMaterialObj(tmp, square, name, damaged, mesh);
      ++tried;
      const bool texture = mesh->GetFieldData()->GetArray(tc::kBaseColorTexture) != nullptr;
      const bool refused = report.find("cannot be decoded") != std::string::npos;
      decoded += texture ? 1 : 0;
      warned += refused ? 1 : 0;
      TC_CHECK(check, mesh->GetNumberOfPolys() == 1 && texture != refused);
    }
  }
  std::cout << tried << " damaged textures: " << decoded << " decoded, " << warned
            << " refused with a warning\n";
  TC_CHECK(check, warned > 0);
}

/// A grey PNG becomes RGBA in VTK's row order; a texture that is missing or no image is a
/// warning in the report, and the mesh is read without it.
void CheckTextureConversionAndWarnings(tctest::Checker& check, const std::string& tmp)
{
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                             "f 1/1 2/2 3/3\n";
  vtkNew<vtkImageData> grey;
  grey->SetDimensions(4, 2, 1);
  grey->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  for (int t = 0; t < 8; ++t)
  {
    static_cast<unsigned char*>(grey->GetScalarPointer())[t] = static_cast<unsigned char>(30 * t);
  }
  vtkNew<vtkPNGWriter> writer;
  const std::string png = Encode(grey, writer.Get());
  vtkSmartPointer<vtkPolyData> mesh;
  std::string report = ReadMaterialObj(tmp, square, "grey.png", png, mesh);
  auto* texels =
    vtkUnsignedCharArray::SafeDownCast(mesh->GetFieldData()->GetArray(tc::kBaseColorTexture));
  unsigned char texel[4] = { 0, 0, 0, 0 };
  if (TC_CHECK(check, texels && texels->GetNumberOfTuples() == 8))
  {
    texels->GetTypedTuple(6, texel); // x = 2, y = 1: grey value 180
  }
  TC_CHECK(check, texel[0] == 180 && texel[1] == 180 && texel[2] == 180 && texel[3] == 255);
  TC_CHECK(check, report.find("grey.png 4x2") != std::string::npos);

  for (const auto& [image, bytes, warning] :
    { std::array<std::string, 3>{ "gone.png", "", "gone.png' not found" },
      std::array<std::string, 3>{
        "fake.png", "\x89PNG\r\n\x1a\n but no image", "cannot be decoded" },
      std::array<std::string, 3>{ "paint.bmp", "BM not decoded", "neither PNG nor JPEG" } })
  {
    report = ReadMaterialObj(tmp, square, image, bytes, mesh);
    const bool read = mesh->GetNumberOfPolys() == 1 && mesh->GetPointData()->GetTCoords() &&
      !mesh->GetFieldData()->GetArray(tc::kBaseColorTexture);
    if (!TC_CHECK(check, read && report.find(warning) != std::string::npos))
    {
      std::cerr << "  for " << image << ": report\n" << report;
    }
  }
}
}

int TestMeshReader(int argc, char* argv[])
{
  tctest::Checker check;
  const std::string tmp = tctest::Arg(argc, argv, "-T") + "/TestMeshReader_";
  const std::string data = tctest::Arg(argc, argv, "-D");

  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(9);
  sphere->Update();
  vtkPolyData* mesh = sphere->GetOutput();
  const vtkIdType nv = mesh->GetNumberOfPoints();
  const vtkIdType nf = mesh->GetNumberOfPolys();

  // Every writable format reads back with the same number of polygons.
  {
    vtkNew<vtkPLYWriter> w;
    w->SetInputData(mesh);
    w->SetFileName((tmp + "sphere.ply").c_str());
    w->Write();
    vtkNew<vtkSTLWriter> s;
    s->SetInputData(mesh);
    s->SetFileName((tmp + "sphere.stl").c_str());
    s->Write();
    vtkNew<vtkOBJWriter> o;
    o->SetInputData(mesh);
    o->SetFileName((tmp + "sphere.obj").c_str());
    o->Write();
    vtkNew<vtkXMLPolyDataWriter> x;
    x->SetInputData(mesh);
    x->SetFileName((tmp + "sphere.vtp").c_str());
    x->Write();
    vtkNew<vtkPolyDataWriter> l;
    l->SetInputData(mesh);
    l->SetFileName((tmp + "sphere.vtk").c_str());
    l->Write();
  }
  for (const char* ext : { "ply", "obj", "vtp", "vtk", "stl" })
  {
    const ReadResult r = ReadFile(tmp + "sphere." + ext);
    TC_CHECK(check, r.error.empty());
    TC_CHECK(check, r.polys == nf);
    // STL stores three corners per triangle; the others share points.
    TC_CHECK(check, std::string(ext) == "stl" ? r.points >= nv : r.points == nv);
    TC_CHECK(check, r.report.find(ext) != std::string::npos);
  }

  // Gzipped PLY.
  {
    std::ifstream in(tmp + "sphere.ply", std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    const std::string raw = bytes.str();
    gzFile gz = gzopen((tmp + "sphere.ply.gz").c_str(), "wb");
    gzwrite(gz, raw.data(), static_cast<unsigned>(raw.size()));
    gzclose(gz);
    const ReadResult r = ReadFile(tmp + "sphere.ply.gz");
    TC_CHECK(check, r.error.empty() && r.polys == nf && r.points == nv);
  }

  // OFF from the bundled data, with the counts of its README; the report says so.
  {
    const ReadResult r = ReadFile(data + "/meshes/bunny_npm.off");
    TC_CHECK(check, r.points == 1839 && r.polys == 3674);
    TC_CHECK(check, r.report.find("1839 points, 3674 polygons") != std::string::npos);
  }

  // A real gzipped PLY scan, when the shared data is there.
  const std::string dragon = tctest::SharedFile(argc, argv, "static_small/dragon_vrip_res4.ply.gz");
  if (!dragon.empty())
  {
    const ReadResult r = ReadFile(dragon);
    TC_CHECK(check, r.points == 5205 && r.polys == 11102);
  }

  // Bad input: each is an error that names the file; none crashes or yields polygons.
  WriteText(tmp + "empty.ply", "");
  WriteText(tmp + "garbage.off", "OFF\n3 1 0\n0 0 0\n1 zero 0\n");
  WriteText(tmp + "truncated.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n");
  WriteText(tmp + "mesh.xyz", "0 0 0\n");
  WriteText(tmp + "broken.ply.gz", "this is not gzip data");
  WriteText(tmp + "lines.vtk",
    "# vtk DataFile Version 3.0\nlines\nASCII\nDATASET POLYDATA\nPOINTS 2 float\n0 0 0 1 0 0\n"
    "LINES 1 3\n2 0 1\n");
  for (const std::string name : { "missing.ply", "empty.ply", "garbage.off", "truncated.off",
         "mesh.xyz", "broken.ply.gz", "lines.vtk" })
  {
    const ReadResult r = ReadFile(tmp + name);
    const bool refused = !r.error.empty() && r.polys <= 0;
    if (!TC_CHECK(check, refused) || !TC_CHECK(check, r.error.find(name) != std::string::npos))
    {
      std::cerr << "  for " << name << ": error '" << r.error << "'\n";
    }
  }
  // The textured sphere: the same texture coordinates and texture from both formats (the GLB
  // stores v from the image's top, the OBJ from its bottom).
  CheckTexturedSphere(check, data + "/meshes/textured_sphere.glb", "embedded:0");
  CheckTexturedSphere(check, data + "/meshes/textured_sphere.obj", "textured_sphere.png");
  CheckTextureConversionAndWarnings(check, tmp);
  CheckDamagedTextures(check, tmp, ReadText(data + "/meshes/textured_sphere.png"));

  TC_CHECK(check, tcMeshReader::CanReadFile("a/b/Mesh.PLY.GZ"));
  TC_CHECK(check, !tcMeshReader::CanReadFile("mesh.xyz"));
  return check.failures == 0 ? 0 : 1;
}
