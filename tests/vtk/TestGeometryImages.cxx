// SPDX-License-Identifier: BSD-3-Clause
// tcGeometryImages on the bundled bunny, saved by tcAtlasWriter and read back by tcAtlasReader:
// the chart table and every texel come back bit for bit, a truncated file is refused, a failed
// write leaves no file; then the finest atlas image (normals as colours) against the baseline.
#include "tcAtlasReader.h"
#include "tcAtlasWriter.h"
#include "tcBaseComplex.h"
#include "tcColorMaps.h"
#include "tcFeatureRefinement.h"
#include "tcGeometryImages.h"
#include "tcPathTracing.h"
#include "tcTestUtilities.h"

#include "tc/common/array_names.h"
#include "tc/gim/atlas.h"

#include <vtkCamera.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageActor.h>
#include <vtkImageData.h>
#include <vtkImageMapper3D.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkUnsignedCharArray.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace
{
/// Whether two atlas multiblocks hold the same images bit for bit and the same chart table.
bool SameAtlas(vtkMultiBlockDataSet* a, vtkMultiBlockDataSet* b)
{
  auto* ia = vtkMultiBlockDataSet::SafeDownCast(a->GetBlock(1));
  auto* ib = vtkMultiBlockDataSet::SafeDownCast(b->GetBlock(1));
  auto* ta = vtkTable::SafeDownCast(a->GetBlock(0));
  auto* tb = vtkTable::SafeDownCast(b->GetBlock(0));
  if (!ia || !ib || !ta || !tb || ia->GetNumberOfBlocks() != ib->GetNumberOfBlocks() ||
    ta->GetNumberOfRows() != tb->GetNumberOfRows() ||
    ta->GetNumberOfColumns() != tb->GetNumberOfColumns())
  {
    return false;
  }
  for (vtkIdType c = 0; c < ta->GetNumberOfColumns(); ++c)
  {
    vtkAbstractArray* ca = ta->GetColumn(c);
    vtkAbstractArray* cb = tb->GetColumnByName(ca->GetName());
    if (!cb || ca->GetNumberOfValues() != cb->GetNumberOfValues())
    {
      return false;
    }
    for (vtkIdType v = 0; v < ca->GetNumberOfValues(); ++v)
    {
      const double x = ca->GetVariantValue(v).ToDouble();
      const double y = cb->GetVariantValue(v).ToDouble();
      if (std::memcmp(&x, &y, sizeof x) != 0 && !(x != x && y != y))
      {
        return false;
      }
    }
  }
  for (unsigned int k = 0; k < ia->GetNumberOfBlocks(); ++k)
  {
    auto* pa = vtkImageData::SafeDownCast(ia->GetBlock(k))->GetPointData();
    auto* pb = vtkImageData::SafeDownCast(ib->GetBlock(k))->GetPointData();
    if (pa->GetNumberOfArrays() != pb->GetNumberOfArrays())
    {
      return false;
    }
    for (int i = 0; i < pa->GetNumberOfArrays(); ++i)
    {
      auto* fa = vtkFloatArray::SafeDownCast(pa->GetAbstractArray(i));
      auto* fb = vtkFloatArray::SafeDownCast(pb->GetAbstractArray(pa->GetArrayName(i)));
      if (!fa || !fb || fa->GetNumberOfValues() != fb->GetNumberOfValues() ||
        std::memcmp(fa->GetPointer(0), fb->GetPointer(0),
          sizeof(float) * static_cast<size_t>(fa->GetNumberOfValues())) != 0)
      {
        return false;
      }
    }
  }
  return true;
}
}

int TestGeometryImages(int argc, char* argv[])
{
  tctest::Checker check;
  const std::string data = tctest::Arg(argc, argv, "-D");
  const std::string temp = tctest::Arg(argc, argv, "-T");
  vtkSmartPointer<vtkPolyData> mesh = tctest::ReadPrepared(data + "/meshes/bunny_npm.off");
  if (!TC_CHECK(check, mesh != nullptr))
  {
    return 1;
  }
  vtkSmartPointer<tcGeometryImages> images = tctest::AtlasStages(mesh);
  images->AddResampledArray(tc::kMeanCurvature);
  images->Update();
  vtkMultiBlockDataSet* atlas = images->GetOutput();
  auto* charts = vtkTable::SafeDownCast(atlas->GetBlock(0));
  auto* levels = vtkMultiBlockDataSet::SafeDownCast(atlas->GetBlock(1));
  if (!TC_CHECK(check, charts && levels && levels->GetNumberOfBlocks() > 0))
  {
    return 1;
  }
  auto* patches = vtkPolyData::SafeDownCast(images->GetInputDataObject(0, 0));
  TC_CHECK(check,
    charts->GetNumberOfRows() ==
      patches->GetFieldData()->GetArray(tc::kBaseTriangles)->GetNumberOfTuples());
  auto* finest = vtkImageData::SafeDownCast(levels->GetBlock(0));
  TC_CHECK(check, finest->GetPointData()->GetArray(tc::kMeanCurvature) != nullptr);

  // Round trip through the file, bit for bit.
  const std::string path = temp + "/TestGeometryImages.exr";
  std::remove(path.c_str());
  vtkNew<tcAtlasWriter> writer;
  writer->SetInputData(atlas);
  writer->SetFileName(path.c_str());
  TC_CHECK(check, writer->Write() == 1);
  vtkNew<tcAtlasReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  TC_CHECK(check, SameAtlas(atlas, reader->GetOutput()));
  TC_CHECK(check, tcAtlasReader::CanReadFile(path.c_str()));
  TC_CHECK(check, !tcAtlasReader::CanReadFile((data + "/meshes/cube.off").c_str()));

  // A truncated copy is refused (an error, no output), never read as a smaller atlas.
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  const std::string truncated = temp + "/TestGeometryImages-truncated.exr";
  std::ofstream(truncated, std::ios::binary).write(bytes.data(), bytes.size() / 2);
  vtkNew<tcAtlasReader> bad;
  bad->SetFileName(truncated.c_str());
  std::printf("reading a truncated atlas (an error is expected):\n");
  TC_CHECK(check, bad->GetExecutive()->Update() == 0);
  std::remove(truncated.c_str());

  // A write into a missing folder fails and leaves nothing.
  const std::string nowhere = temp + "/no-such-folder/atlas.exr";
  writer->SetFileName(nowhere.c_str());
  std::printf("writing into a missing folder (an error is expected):\n");
  writer->Write();
  TC_CHECK(check, !std::ifstream(nowhere).good());
  std::remove(path.c_str());

  // Picture: the finest image, normals mapped to colours.
  int dims[3];
  finest->GetDimensions(dims);
  vtkDataArray* normals = finest->GetPointData()->GetArray(tc::kAtlasNormal);
  vtkNew<vtkImageData> picture;
  picture->SetDimensions(dims);
  vtkNew<vtkUnsignedCharArray> colours;
  tcColorMaps::NormalColors(normals, colours);
  picture->GetPointData()->SetScalars(colours);
  vtkNew<vtkImageActor> actor;
  actor->GetMapper()->SetInputData(picture);
  actor->InterpolateOff();
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.1);
  renderer->GetActiveCamera()->ParallelProjectionOn();
  renderer->ResetCamera();
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(600, 600);
  window->AddRenderer(renderer);
  window->Render();
  TC_CHECK(check, tctest::MatchesBaseline(argc, argv, window));
  return check.failures == 0 ? 0 : 1;
}
