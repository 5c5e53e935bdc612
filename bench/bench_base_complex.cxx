// SPDX-License-Identifier: BSD-3-Clause
// Times tcBaseComplex (feature-free quadric half-edge collapses with the MAPS
// parameterization, Feng et al. 5.1) on prepared meshes and, on the same triangles in the same
// run, meshoptimizer's meshopt_simplify to the same face count (simplification only, no
// parameterization). Prints triangles per second for both and their ratio, then the same
// filter with its default MaxError, which stops before the coarsest collapses.
//
//   tc_bench_base_complex [mesh ...]   default: bunny_glmark2 (70K) and bunny00_loop2 (1.2M)
#include "bench_common.h"

#include "tcBaseComplex.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTimerLog.h>

#include <meshoptimizer.h>

#include <fstream>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  const std::vector<std::string> files =
    tcbench::Meshes(argc, argv, "static_large/bunny00_loop2.ply.gz");
  std::cout << "mesh, triangles, base triangles, tcBaseComplex s, triangles/s, "
               "meshopt_simplify s, meshopt triangles/s, meshopt faces, ratio (meshopt/ours), "
               "default MaxError: base triangles, s, triangles/s\n";
  for (const std::string& file : files)
  {
    vtkSmartPointer<vtkPolyData> mesh = tcbench::Prepared(file);
    const double triangles = static_cast<double>(mesh->GetNumberOfPolys());

    vtkNew<tcBaseComplex> base;
    base->SetInputData(mesh);
    // All the way to TargetFaces (100), as meshopt_simplify is asked: no error bound.
    base->SetMaxError(0.0);
    const double ours = tcbench::Seconds(base);
    const vtkIdType baseFaces = base->GetOutput()->GetNumberOfPolys();

    // The same triangles for meshoptimizer, as float positions and 32-bit indices.
    std::vector<float> positions(3 * static_cast<size_t>(mesh->GetNumberOfPoints()));
    for (vtkIdType v = 0; v < mesh->GetNumberOfPoints(); ++v)
    {
      const double* p = mesh->GetPoint(v);
      positions[3 * v] = static_cast<float>(p[0]);
      positions[3 * v + 1] = static_cast<float>(p[1]);
      positions[3 * v + 2] = static_cast<float>(p[2]);
    }
    std::vector<unsigned int> indices;
    auto it = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n = 0;
      const vtkIdType* ids = nullptr;
      it->GetCurrentCell(n, ids);
      for (vtkIdType k = 0; k < n; ++k)
      {
        indices.push_back(static_cast<unsigned int>(ids[k]));
      }
    }
    std::vector<unsigned int> simplified(indices.size());
    const double start = vtkTimerLog::GetUniversalTime();
    const size_t kept =
      meshopt_simplify(simplified.data(), indices.data(), indices.size(), positions.data(),
        positions.size() / 3, 3 * sizeof(float), 3 * static_cast<size_t>(baseFaces), 1.0f);
    const double peer = vtkTimerLog::GetUniversalTime() - start;

    // The filter's defaults: the error bound stops before the coarsest, costliest collapses.
    vtkNew<tcBaseComplex> bounded;
    bounded->SetInputData(mesh);
    const double boundedSeconds = tcbench::Seconds(bounded);

    std::cout << tcbench::BaseName(file) << ", " << triangles << ", " << baseFaces << ", " << ours
              << ", " << triangles / ours << ", " << peer << ", " << triangles / peer << ", "
              << kept / 3 << ", " << ours / peer << ", " << bounded->GetOutput()->GetNumberOfPolys()
              << ", " << boundedSeconds << ", " << triangles / boundedSeconds << "\n";
  }
  return 0;
}
