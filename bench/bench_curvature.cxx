// SPDX-License-Identifier: BSD-3-Clause
// Times tcMeshPreparation + tcCurvature (with crest lines) on real meshes and prints the
// figures, with VTK's own discrete curvature filter (vtkCurvatures, mean and Gaussian only)
// timed in the same run as the peer.
//
//   tc_bench_curvature [mesh ...]     default: bunny_glmark2 (70K) and dragon_vrip (871K)
#include "bench_common.h"

#include "tcCurvature.h"
#include "tcMeshPreparation.h"
#include "tcMeshReader.h"

#include <vtkCurvatures.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <fstream>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  const std::vector<std::string> files = tcbench::Meshes(argc, argv);
  std::cout << "mesh, triangles, read s, preparation s, curvature+crest s, total s "
               "(prep+curv+crest), crest lines, vtkCurvatures s (mean+Gauss), ratio\n";
  for (const std::string& file : files)
  {
    vtkNew<tcMeshReader> reader;
    reader->SetFileName(file.c_str());
    const double read = tcbench::Seconds(reader);
    vtkNew<tcMeshPreparation> prep;
    prep->SetInputConnection(reader->GetOutputPort());
    const double prepare = tcbench::Seconds(prep);
    vtkNew<tcCurvature> curvature;
    curvature->SetInputConnection(prep->GetOutputPort());
    const double curv = tcbench::Seconds(curvature);

    vtkNew<vtkCurvatures> peerMean;
    peerMean->SetInputConnection(prep->GetOutputPort());
    peerMean->SetCurvatureTypeToMean();
    vtkNew<vtkCurvatures> peerGauss;
    peerGauss->SetInputConnection(prep->GetOutputPort());
    peerGauss->SetCurvatureTypeToGaussian();
    const double peer = tcbench::Seconds(peerMean) + tcbench::Seconds(peerGauss);

    const double total = prepare + curv;
    const std::string name = tcbench::BaseName(file);
    std::cout << name << ", " << prep->GetOutput()->GetNumberOfPolys() << ", " << read << ", "
              << prepare << ", " << curv << ", " << total << ", "
              << curvature->GetOutput(1)->GetNumberOfLines() << ", " << peer << ", " << total / peer
              << "\n";
  }
  return 0;
}
