// SPDX-License-Identifier: BSD-3-Clause
// Times tcMeshPreparation + tcCurvature (with crest lines) on real meshes and prints the
// figures, with VTK's own discrete curvature filter (vtkCurvatures, mean and Gaussian only)
// timed in the same run as the peer.
//
//   tc_bench_curvature [mesh ...]     default: bunny_glmark2 (70K) and dragon_vrip (871K)
#include "tcCurvature.h"
#include "tcMeshPreparation.h"
#include "tcMeshReader.h"

#include <vtkCurvatures.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkTimerLog.h>

#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
double Seconds(vtkAlgorithm* algorithm)
{
  const double start = vtkTimerLog::GetUniversalTime();
  algorithm->Update();
  return vtkTimerLog::GetUniversalTime() - start;
}
}

int main(int argc, char* argv[])
{
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i)
  {
    files.emplace_back(argv[i]);
  }
  if (files.empty())
  {
    files = { std::string(TC_SHARED_DATA_DIR) + "/static_medium/bunny_glmark2.obj",
      std::string(TC_SHARED_DATA_DIR) + "/static_large/dragon_vrip.ply.gz" };
  }
  std::cout << "mesh, triangles, read s, preparation s, curvature+crest s, total s "
               "(prep+curv+crest), crest lines, vtkCurvatures s (mean+Gauss), ratio\n";
  for (const std::string& file : files)
  {
    if (!std::ifstream(file).good())
    {
      std::cout << file << ": absent, skipped\n";
      continue;
    }
    vtkNew<tcMeshReader> reader;
    reader->SetFileName(file.c_str());
    const double read = Seconds(reader);
    vtkNew<tcMeshPreparation> prep;
    prep->SetInputConnection(reader->GetOutputPort());
    const double prepare = Seconds(prep);
    vtkNew<tcCurvature> curvature;
    curvature->SetInputConnection(prep->GetOutputPort());
    const double curv = Seconds(curvature);

    vtkNew<vtkCurvatures> peerMean;
    peerMean->SetInputConnection(prep->GetOutputPort());
    peerMean->SetCurvatureTypeToMean();
    vtkNew<vtkCurvatures> peerGauss;
    peerGauss->SetInputConnection(prep->GetOutputPort());
    peerGauss->SetCurvatureTypeToGaussian();
    const double peer = Seconds(peerMean) + Seconds(peerGauss);

    const double total = prepare + curv;
    const std::string name = file.substr(file.find_last_of('/') + 1);
    std::cout << name << ", " << prep->GetOutput()->GetNumberOfPolys() << ", " << read << ", "
              << prepare << ", " << curv << ", " << total << ", "
              << curvature->GetOutput(1)->GetNumberOfLines() << ", " << peer << ", "
              << total / peer << "\n";
  }
  return 0;
}
