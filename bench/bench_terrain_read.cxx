// SPDX-License-Identifier: BSD-3-Clause
// Reads terrain rasters as triangle meshes: tcMeshReader's height fields (GDAL, a regular grid
// in metres, each square split along its diagonal of least height change) next to what a
// ParaView user builds from VTK's own filters in the same run (vtkGDALRasterReader,
// vtkImageDataGeometryFilter, vtkTriangleFilter, vtkWarpScalar), then tcMeshPreparation on
// ours. Prints seconds, triangles, the ratio and the peak memory.
//
//   tc_bench_terrain_read [raster ...]   default: the shared DEM, and the same DEM resampled
//                                         (bilinear) to 1,733 x 1,733 cells, 6M triangles
#include "bench_common.h"

#include "tcMeshPreparation.h"
#include "tcMeshReader.h"

#include "tc/io/height_field_io.h"

#include <vtkGDALRasterReader.h>
#include <vtkImageDataGeometryFilter.h>
#include <vtkLogger.h>
#include <vtkPolyData.h>
#include <vtkTriangleFilter.h>
#include <vtkWarpScalar.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
/// The shared 403 x 344 DEM resampled bilinearly to n x n cells, written as a 16-bit PGM with a
/// side file of the same ground extent into `folder`; "" when the DEM is absent.
std::string ResampledDem(const std::filesystem::path& folder, int n)
{
  const std::string dem =
    std::string(TC_SHARED_DATA_DIR) + "/terrain/jacksboro_fault_dem_403x344.pgm";
  if (!std::ifstream(dem).good())
  {
    return "";
  }
  const tc::HeightField field = tc::readHeightField(dem);
  const int w = int(field.columns), rows = int(field.rows);
  std::string pixels;
  for (int r = 0; r < n; ++r)
  {
    for (int c = 0; c < n; ++c)
    {
      const double x = c * (w - 1.0) / (n - 1), y = r * (rows - 1.0) / (n - 1);
      const int x0 = std::min(int(x), w - 2), y0 = std::min(int(y), rows - 2);
      const double fx = x - x0, fy = y - y0;
      const auto at = [&](int xx, int yy) { return field.heights[size_t(yy) * w + xx]; };
      const double v = (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
        fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
      const int q = std::clamp(int(std::lround(v)), 0, 65535);
      pixels += char(q >> 8);
      pixels += char(q & 255);
    }
  }
  const std::filesystem::path pgm = folder / ("dem_" + std::to_string(n) + ".pgm");
  std::ofstream(pgm, std::ios::binary) << "P5\n" << n << " " << n << "\n65535\n" << pixels;
  std::ofstream(folder / ("dem_" + std::to_string(n) + ".json"))
    << "{\"dx\": " << 0.33583333333 / n << ", \"dy\": " << 0.28666666667 / n
    << ", \"xmin\": -84.41375, \"ymin\": 36.73291666666667, \"xmax\": -84.07791666666667, "
       "\"ymax\": 36.44625, \"horizontal_units\": \"degrees\", \"height_units\": \"m\"}\n";
  return pgm.string();
}

/// What a ParaView user would build from VTK's filters: seconds and triangles.
double Peer(const std::string& raster, vtkIdType& triangles)
{
  const double start = vtkTimerLog::GetUniversalTime();
  vtkNew<vtkGDALRasterReader> reader;
  reader->SetFileName(raster.c_str());
  vtkNew<vtkImageDataGeometryFilter> surface;
  surface->SetInputConnection(reader->GetOutputPort());
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputConnection(surface->GetOutputPort());
  vtkNew<vtkWarpScalar> warp;
  warp->SetInputConnection(triangulate->GetOutputPort());
  warp->Update();
  triangles = vtkPolyData::SafeDownCast(warp->GetOutput())->GetNumberOfPolys();
  return vtkTimerLog::GetUniversalTime() - start;
}

void Row(const std::string& raster)
{
  vtkNew<tcMeshReader> reader;
  reader->SetFileName(raster.c_str());
  const double read = tcbench::Seconds(reader);
  vtkNew<tcMeshPreparation> prep;
  prep->SetInputConnection(reader->GetOutputPort());
  const double prepared = tcbench::Seconds(prep);
  vtkIdType peerTriangles = 0;
  const double peer = Peer(raster, peerTriangles);
  std::printf("%-34s %10lld %8.2f s %8.2f s %12lld %8.2f s  %5.2f  %8.0f MB\n",
    tcbench::BaseName(raster).c_str(),
    static_cast<long long>(reader->GetOutput()->GetNumberOfPolys()), read, prepared,
    static_cast<long long>(peerTriangles), peer, peer / read, tcbench::PeakMegabytes());
}
} // namespace

int main(int argc, char* argv[])
{
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_WARNING);
  std::vector<std::string> rasters(argv + 1, argv + argc);
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "tc_bench_terrain";
  if (rasters.empty())
  {
    std::filesystem::create_directories(folder);
    rasters = { std::string(TC_SHARED_DATA_DIR) + "/terrain/jacksboro_fault_dem_403x344.pgm",
      ResampledDem(folder, 1733) };
  }
  std::printf("%-34s %10s %10s %10s %12s %10s  %5s  %11s\n", "raster", "triangles", "read",
    "prepare", "VTK tris", "VTK read", "ratio", "peak");
  for (const std::string& raster : tcbench::Present(rasters))
  {
    Row(raster);
  }
  std::filesystem::remove_all(folder);
  return 0;
}
