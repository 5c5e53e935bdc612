// SPDX-License-Identifier: BSD-3-Clause
// Times tcMeshPreparation on read meshes: the default cleaning, then with hole filling and
// with sliver removal, next to VTK's nearest filters in the same run (vtkCleanPolyData +
// vtkPolyDataNormals with consistent orientation for the cleaning, vtkFillHolesFilter for the
// holes; sliver removal has no VTK peer). Prints seconds, ratios and what each repair did.
//
//   tc_bench_preparation [mesh ...]   default: bunny_glmark2 (70K) and dragon_vrip (871K scan)
#include "bench_common.h"

#include <vtkCleanPolyData.h>
#include <vtkFillHolesFilter.h>
#include <vtkLogger.h>
#include <vtkPolyDataNormals.h>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace
{
/// The report's line that contains `what`, or "-".
std::string ReportLine(const std::string& report, const std::string& what)
{
  size_t start = 0;
  while (start < report.size())
  {
    const size_t end = report.find('\n', start);
    const std::string line = report.substr(start, end - start);
    if (line.find(what) != std::string::npos)
    {
      return line;
    }
    if (end == std::string::npos)
    {
      break;
    }
    start = end + 1;
  }
  return "-";
}
} // namespace

int main(int argc, char* argv[])
{
  // The filter logs what it changed at INFO level; the figures below are what counts here.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_WARNING);
  for (const std::string& file : tcbench::Meshes(argc, argv))
  {
    vtkNew<tcMeshReader> reader;
    reader->SetFileName(file.c_str());
    const double read = tcbench::Seconds(reader);
    vtkPolyData* mesh = reader->GetOutput();
    std::cout << "== " << tcbench::BaseName(file) << ": " << mesh->GetNumberOfPolys()
              << " polygons, read in " << read << " s\n";

    vtkNew<tcMeshPreparation> plain;
    plain->SetInputData(mesh);
    const double ours = tcbench::Seconds(plain);
    vtkNew<vtkCleanPolyData> clean;
    clean->SetInputData(mesh);
    vtkNew<vtkPolyDataNormals> orient;
    orient->SetInputConnection(clean->GetOutputPort());
    orient->ConsistencyOn();
    orient->SplittingOff();
    orient->ComputeCellNormalsOff();
    const double peer = tcbench::Seconds(orient);
    std::printf("cleaning: tcMeshPreparation %.3f s, vtkCleanPolyData + vtkPolyDataNormals "
                "%.3f s, ratio (peer/ours) %.2f\n",
      ours, peer, peer / ours);

    vtkNew<tcMeshPreparation> filled;
    filled->SetInputData(mesh);
    filled->SplitNonManifoldOn();
    filled->FillHolesOn();
    const double fill = tcbench::Seconds(filled);
    const std::string fillReport = filled->GetReport();
    vtkNew<vtkFillHolesFilter> vtkFill;
    vtkFill->SetInputConnection(clean->GetOutputPort());
    vtkFill->SetHoleSize(1e30);
    const double vtkFillSeconds = tcbench::Seconds(vtkFill);
    std::printf("holes: tcMeshPreparation (split + FillHoles, faired) %.3f s (%s), "
                "vtkFillHolesFilter (flat patches, on vtkCleanPolyData's output) %.3f s\n",
      fill, ReportLine(fillReport, "filled").c_str(), vtkFillSeconds);

    vtkNew<tcMeshPreparation> repaired;
    repaired->SetInputData(mesh);
    repaired->SplitNonManifoldOn();
    repaired->FillHolesOn();
    repaired->RemoveSliversOn();
    const double slivers = tcbench::Seconds(repaired);
    const std::string report = repaired->GetReport();
    std::printf("slivers: split + FillHoles + RemoveSlivers %.3f s, %.3f s more (%s; %s), "
                "no VTK peer\n",
      slivers, slivers - fill, ReportLine(report, "found").c_str(),
      ReportLine(report, "left").c_str());
    std::printf("peak memory so far: %.0f MB\n", tcbench::PeakMegabytes());
  }
  return 0;
}
