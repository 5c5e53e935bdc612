// SPDX-License-Identifier: BSD-3-Clause
// tcMeshReader: every format reads back what was written, with its counts; bad files are
// refused with an error naming the file, and never crash.
#include "tcMeshReader.h"
#include "tcTestUtilities.h"

#include <vtkCallbackCommand.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkOBJWriter.h>
#include <vtkPLYWriter.h>
#include <vtkPolyData.h>
#include <vtkPolyDataWriter.h>
#include <vtkSTLWriter.h>
#include <vtkSphereSource.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <zlib.h>

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
  TC_CHECK(check, tcMeshReader::CanReadFile("a/b/Mesh.PLY.GZ"));
  TC_CHECK(check, !tcMeshReader::CanReadFile("mesh.xyz"));
  return check.failures == 0 ? 0 : 1;
}
