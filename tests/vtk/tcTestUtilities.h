// SPDX-License-Identifier: BSD-3-Clause
/// @file tcTestUtilities.h
/// Helpers of the VTK tests: where the data is, checks that print what failed, and the
/// standard curvature scene used by the image tests.
#ifndef tcTestUtilities_h
#define tcTestUtilities_h

#include <vtkSmartPointer.h>

#include <iostream>
#include <string>

class tcFeatureRefinement;
class tcGeometryImages;
class vtkPolyData;
class vtkRenderWindow;
class vtkRenderer;
class vtkScalarsToColors;

namespace tctest
{
/// The value after `flag` in argv ("" if absent): -D testing data, -S shared data, -T temp.
std::string Arg(int argc, char* argv[], const char* flag);

/// Path of a file under the shared data folder, or "" when it is absent (then skip: return 77).
std::string SharedFile(int argc, char* argv[], const std::string& relative);

/// Reads a mesh with tcMeshReader; nullptr (with the error printed) on failure.
vtkSmartPointer<vtkPolyData> Read(const std::string& path);

/// Reads and prepares (tcMeshPreparation with defaults).
vtkSmartPointer<vtkPolyData> ReadPrepared(const std::string& path);

/// tcCurvature's output for a prepared mesh.
vtkSmartPointer<vtkPolyData> Curvature(vtkPolyData* prepared);

/// tcCurvature -> tcSpectralClustering -> tcFeatureRefinement (defaults) on a prepared mesh,
/// updated; the refinement filter is returned, its three outputs ready.
vtkSmartPointer<tcFeatureRefinement> FeatureStages(vtkPolyData* prepared);

/// A 400x400 offscreen window showing `surface` coloured by point array `array` with a
/// diverging colour map symmetric about 0, and `lines` (if any) drawn in black on top.
vtkSmartPointer<vtkRenderWindow> CurvatureScene(
  vtkPolyData* surface, const char* array, vtkPolyData* lines);

/// A renderer over `viewport` (xmin, ymin, xmax, ymax) of `surface` coloured through `lut` by its
/// point array (or, with `cells`, cell array) `array`; the camera is left as it is.
vtkSmartPointer<vtkRenderer> ArrayRenderer(vtkPolyData* surface, const char* array, bool cells,
  vtkScalarsToColors* lut, const double viewport[4]);

/// A viewport-filling renderer for `surface` coloured by the integer cell (or else point) array
/// `labels`
/// (golden-ratio hues), with `lines` in black and `points` as red spheres on top (each optional).
/// `viewport` is (xmin, ymin, xmax, ymax) in the window.
vtkSmartPointer<vtkRenderer> LabelRenderer(vtkPolyData* surface, const char* labels,
  vtkPolyData* lines, vtkPolyData* points, const double viewport[4]);

/// A 800x400 offscreen window with `left` and `right` renderers side by side.
vtkSmartPointer<vtkRenderWindow> SideBySide(vtkRenderer* left, vtkRenderer* right);

/// Compares the window with the baseline given by -V; true when it matches.
bool MatchesBaseline(int argc, char* argv[], vtkRenderWindow* window, double threshold = 0.05);

/// V - E + F of a triangle mesh.
long long Euler(vtkPolyData* mesh);

/// Boundary plus non-manifold edges (0 for a closed manifold).
vtkIdType OpenOrNonManifoldEdges(vtkPolyData* mesh);

/// tcBaseComplex -> tcPathTracing -> tcGeometryImages after FeatureStages on a prepared mesh,
/// with `sampleBudget` (0: the filter's default); the geometry-image filter is returned updated,
/// its input chain reachable through it.
vtkSmartPointer<tcGeometryImages> AtlasStages(vtkPolyData* prepared, vtkIdType sampleBudget = 0);

/// Counts failed checks and prints each with its location.
struct Checker
{
  int failures = 0;
  bool operator()(bool ok, const char* what, const char* file, int line)
  {
    if (!ok)
    {
      std::cerr << file << ":" << line << ": check failed: " << what << "\n";
      ++this->failures;
    }
    return ok;
  }
};
} // namespace tctest

#define TC_CHECK(checker, condition) checker((condition), #condition, __FILE__, __LINE__)

#endif
