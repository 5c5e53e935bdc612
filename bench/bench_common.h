// SPDX-License-Identifier: BSD-3-Clause
/// @file bench_common.h
/// What every TriChart benchmark shares: timing a VTK algorithm, the default meshes, peak
/// memory.
#ifndef bench_common_h
#define bench_common_h

#include "tcMeshPreparation.h"
#include "tcMeshReader.h"

#include <vtkAlgorithm.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTimerLog.h>

#include <sys/resource.h>

#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace tcbench
{
/// Wall-clock seconds of algorithm->Update().
inline double Seconds(vtkAlgorithm* algorithm)
{
  const double start = vtkTimerLog::GetUniversalTime();
  algorithm->Update();
  return vtkTimerLog::GetUniversalTime() - start;
}

/// The files of `files` that exist; absent ones are reported and left out.
inline std::vector<std::string> Present(const std::vector<std::string>& files)
{
  std::vector<std::string> present;
  for (const std::string& file : files)
  {
    if (std::ifstream(file).good())
    {
      present.push_back(file);
    }
    else
    {
      std::cout << file << ": absent, skipped\n";
    }
  }
  return present;
}

/// The meshes named on the command line, or else the 70K bunny and `large` (a path under
/// ../shared/data; the 871K dragon scan by default). Absent files are reported and left out.
inline std::vector<std::string> Meshes(
  int argc, char* argv[], const char* large = "static_large/dragon_vrip.ply.gz")
{
  std::vector<std::string> files(argv + 1, argv + argc);
  if (files.empty())
  {
    files = { std::string(TC_SHARED_DATA_DIR) + "/static_medium/bunny_glmark2.obj",
      std::string(TC_SHARED_DATA_DIR) + "/" + large };
  }
  return Present(files);
}

/// The mesh in `file`, read and prepared with the default options.
inline vtkSmartPointer<vtkPolyData> Prepared(const std::string& file)
{
  vtkNew<tcMeshReader> reader;
  reader->SetFileName(file.c_str());
  vtkNew<tcMeshPreparation> prep;
  prep->SetInputConnection(reader->GetOutputPort());
  prep->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(prep->GetOutput());
  return mesh;
}

/// Peak resident memory of this process so far, in MB.
inline double PeakMegabytes()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0; // Linux reports kilobytes
}

/// The file name without its folder.
inline std::string BaseName(const std::string& path)
{
  return path.substr(path.find_last_of('/') + 1);
}
} // namespace tcbench

#endif
