// SPDX-License-Identifier: BSD-3-Clause
// Times tcSpectralClustering + tcFeatureRefinement (the feature-detection stages of Feng et al.
// 4.1-4.2) on real meshes, after preparation and curvature, and prints the process's peak
// memory. No peer implementation exists in VTK or the Debian packages to compare with.
//
//   tc_bench_features [mesh ...]     default: bunny_glmark2 (70K) and dragon_vrip (871K)
#include "bench_common.h"

#include "tcCurvature.h"
#include "tcFeatureRefinement.h"
#include "tcSpectralClustering.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <fstream>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  const std::vector<std::string> files = tcbench::Meshes(argc, argv);
  std::cout << "mesh, triangles, clusters, clustering s, refinement s, together s, "
               "feature lines, corners, peak MB so far\n";
  for (const std::string& file : files)
  {
    vtkSmartPointer<vtkPolyData> mesh = tcbench::Prepared(file);
    vtkNew<tcCurvature> curvature;
    curvature->SetInputData(mesh);
    curvature->Update();
    vtkNew<tcSpectralClustering> clustering;
    clustering->SetInputConnection(curvature->GetOutputPort());
    const double cluster = tcbench::Seconds(clustering);
    vtkNew<tcFeatureRefinement> refinement;
    refinement->SetInputConnection(clustering->GetOutputPort());
    const double refine = tcbench::Seconds(refinement);
    const std::string name = tcbench::BaseName(file);
    std::cout << name << ", " << mesh->GetNumberOfPolys() << ", "
              << clustering->GetNumberOfClusters() << ", " << cluster << ", " << refine << ", "
              << cluster + refine << ", " << refinement->GetOutput(1)->GetNumberOfLines() << ", "
              << refinement->GetOutput(2)->GetNumberOfPoints() << ", " << tcbench::PeakMegabytes()
              << "\n";
  }
  return 0;
}
