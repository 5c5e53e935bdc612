// SPDX-License-Identifier: BSD-3-Clause
// Times tcMeshReader on PLY and OBJ files next to VTK's readers of the same formats in the same
// run (vtkPLYReader, given the inflated bytes of a .ply.gz as TriChart inflates them itself;
// vtkOBJReader). TriChart reads PLY and OBJ with CGAL's readers, since VTK's crash on damaged
// files. Prints seconds, the counts read and the ratio.
//
//   tc_bench_readers [mesh ...]   default: the 871K dragon and 1.2M bunny scans, bunny_glmark2
#include "bench_common.h"

#include "tc/io/soup_io.h"

#include <vtkLogger.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace
{
bool EndsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() &&
    s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// The peer: VTK's reader of the format; nullptr for other formats. Inflating a .ply.gz is part
/// of its time, as it is of ours.
vtkSmartPointer<vtkAlgorithm> Peer(const std::string& file, double& seconds)
{
  const double start = vtkTimerLog::GetUniversalTime();
  if (EndsWith(file, ".ply.gz") || EndsWith(file, ".ply"))
  {
    auto ply = vtkSmartPointer<vtkPLYReader>::New();
    if (EndsWith(file, ".gz"))
    {
      ply->ReadFromInputStringOn();
      ply->SetInputString(tc::readGzip(file));
    }
    else
    {
      ply->SetFileName(file.c_str());
    }
    ply->Update();
    seconds = vtkTimerLog::GetUniversalTime() - start;
    return ply;
  }
  if (EndsWith(file, ".obj"))
  {
    auto obj = vtkSmartPointer<vtkOBJReader>::New();
    obj->SetFileName(file.c_str());
    obj->Update();
    seconds = vtkTimerLog::GetUniversalTime() - start;
    return obj;
  }
  return nullptr;
}
} // namespace

int main(int argc, char* argv[])
{
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_WARNING);
  std::vector<std::string> files(argv + 1, argv + argc);
  if (files.empty())
  {
    for (const char* name : { "static_large/dragon_vrip.ply.gz",
           "static_large/bunny00_loop2.ply.gz", "static_medium/bunny_glmark2.obj" })
    {
      files.push_back(std::string(TC_SHARED_DATA_DIR) + "/" + name);
    }
  }
  std::printf("%-24s %10s %10s %9s %9s %7s\n", "mesh", "points", "polygons", "ours s",
    "VTK s", "VTK/us");
  for (const std::string& file : tcbench::Present(files))
  {
    vtkNew<tcMeshReader> reader;
    reader->SetFileName(file.c_str());
    const double ours = tcbench::Seconds(reader);
    double peer = 0.0;
    const vtkSmartPointer<vtkAlgorithm> vtk = Peer(file, peer);
    auto* mesh = reader->GetOutput();
    std::printf("%-24s %10lld %10lld %9.3f", tcbench::BaseName(file).c_str(),
      static_cast<long long>(mesh->GetNumberOfPoints()),
      static_cast<long long>(mesh->GetNumberOfPolys()), ours);
    if (vtk)
    {
      auto* theirs = vtkPolyData::SafeDownCast(vtk->GetOutputDataObject(0));
      std::printf(" %9.3f %7.2f%s\n", peer, peer / ours,
        theirs && theirs->GetNumberOfPolys() == mesh->GetNumberOfPolys() ? ""
                                                                        : "  (other counts)");
    }
    else
    {
      std::printf(" %9s %7s\n", "-", "-");
    }
  }
  return 0;
}
