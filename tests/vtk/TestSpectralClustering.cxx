// SPDX-License-Identifier: BSD-3-Clause
// tcSpectralClustering on the bundled fandisk and bunny: every face gets a cluster in range,
// all clusters are used, eigenvalues are descending, two runs agree face for face, boundaries
// come out on port 1; then clusters and boundaries of both meshes against the baseline.
#include "tcSpectralClustering.h"
#include "tcTestUtilities.h"

#include "tc/common/array_names.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <set>

int TestSpectralClustering(int argc, char* argv[])
{
  tctest::Checker check;
  const std::string data = tctest::Arg(argc, argv, "-D");
  vtkSmartPointer<vtkRenderer> renderers[2];
  const char* meshes[2] = { "/meshes/fandisk.off", "/meshes/bunny_npm.off" };
  for (int m = 0; m < 2; ++m)
  {
    vtkSmartPointer<vtkPolyData> mesh = tctest::ReadPrepared(data + meshes[m]);
    if (!TC_CHECK(check, mesh != nullptr))
    {
      return 1;
    }
    vtkSmartPointer<vtkPolyData> surface = tctest::Curvature(mesh);
    vtkNew<tcSpectralClustering> clustering;
    clustering->SetInputData(surface);
    clustering->SetNumberOfClusters(12);
    clustering->Update();
    vtkPolyData* out = clustering->GetOutput();
    vtkDataArray* ids = out->GetCellData()->GetArray(tc::kClusterId);
    vtkDataArray* eigenvalues = out->GetFieldData()->GetArray(tc::kEigenvalues);
    if (!TC_CHECK(check, ids && eigenvalues))
    {
      return 1;
    }
    std::set<int> used;
    for (vtkIdType c = 0; c < ids->GetNumberOfTuples(); ++c)
    {
      used.insert(static_cast<int>(ids->GetTuple1(c)));
    }
    TC_CHECK(check, ids->GetNumberOfTuples() == mesh->GetNumberOfPolys());
    TC_CHECK(check, used.size() == 12 && *used.begin() == 0 && *used.rbegin() == 11);
    for (vtkIdType i = 1; i < eigenvalues->GetNumberOfTuples(); ++i)
    {
      TC_CHECK(check, eigenvalues->GetTuple1(i) <= eigenvalues->GetTuple1(i - 1));
    }
    TC_CHECK(check, clustering->GetOutput(1)->GetNumberOfLines() > 0);

    // Deterministic: a second filter with the same seed gives the same clusters.
    vtkNew<tcSpectralClustering> again;
    again->SetInputData(surface);
    again->SetNumberOfClusters(12);
    again->Update();
    vtkDataArray* ids2 = again->GetOutput()->GetCellData()->GetArray(tc::kClusterId);
    int differ = 0;
    for (vtkIdType c = 0; c < ids->GetNumberOfTuples(); ++c)
    {
      differ += ids->GetTuple1(c) != ids2->GetTuple1(c);
    }
    TC_CHECK(check, differ == 0);

    const double viewport[4] = { 0.5 * m, 0.0, 0.5 * (m + 1), 1.0 };
    auto clusters = vtkSmartPointer<vtkPolyData>::New();
    clusters->ShallowCopy(out);
    auto boundaries = vtkSmartPointer<vtkPolyData>::New();
    boundaries->ShallowCopy(clustering->GetOutput(1));
    renderers[m] = tctest::LabelRenderer(clusters, tc::kClusterId, boundaries, nullptr, viewport);
  }
  vtkSmartPointer<vtkRenderWindow> window = tctest::SideBySide(renderers[0], renderers[1]);
  TC_CHECK(check, tctest::MatchesBaseline(argc, argv, window));
  return check.failures == 0 ? 0 : 1;
}
