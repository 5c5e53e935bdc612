// SPDX-License-Identifier: BSD-3-Clause
// tcLODMapper under the settings a VTK user can choose, on the atlas of the bundled bunny: each
// renders into its own 240 x 240 image, compared with testing-data/baselines/
// TestLODMapperSettings_<setting>.png, or is refused with a warning; the test fails on any error
// in VTK's log (a shader that does not compile, a link error), on any warning it did not ask
// for, and on an OpenGL error left after the render. Then the hardware selector: every picked
// cell lies on the triangle that LocateCell names, at the level the chart table and the frame's
// levels give it.
#include "tcGeometryImages.h"
#include "tcLODMapper.h"
#include "tcTestUtilities.h"

#include "tcAtlasConversion.h"

#include "tc/common/array_names.h"
#include "tc/gim/atlas.h"
#include "tc/gim/geometry_image_mesh.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDataObject.h>
#include <vtkHardwareSelector.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPlane.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRegressionTestImage.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkShaderProperty.h>
#include <vtkTexture.h>
#include <vtk_glew.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <functional>
#include <set>
#include <string>
#include <vector>

namespace
{
/// VTK's log, kept: errors (a shader compile or link failure is one) and warnings.
class tcLogWatch : public vtkOutputWindow
{
public:
  static tcLogWatch* New();
  vtkTypeMacro(tcLogWatch, vtkOutputWindow);
  void DisplayErrorText(const char* text) override { this->Keep(this->Errors, text); }
  void DisplayWarningText(const char* text) override { this->Keep(this->Warnings, text); }
  void DisplayGenericWarningText(const char* text) override { this->Keep(this->Warnings, text); }
  std::string Errors;
  std::string Warnings;

private:
  void Keep(std::string& log, const char* text)
  {
    log += text;
    std::fprintf(stderr, "%s\n", text);
  }
};
vtkStandardNewMacro(tcLogWatch);

/// The X display every window of the test shares: one connection, not one per window (Xvfb
/// refuses connections now and then when many open in a row).
void* gDisplay = nullptr;

/// One window, one renderer, one LOD actor of the atlas, seen from the same place every time.
struct Scene
{
  vtkNew<tcLODMapper> mapper;
  vtkNew<vtkActor> actor;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;

  explicit Scene(vtkAlgorithmOutput* atlas)
  {
    this->mapper->SetInputConnection(atlas);
    // The paper's area rule (eq. 7, not the default error target), two levels finer than it
    // gives in so small a window, for the pictures' sake.
    this->mapper->SetErrorTarget(0.0);
    this->mapper->SetLODBias(2.0);
    this->actor->SetMapper(this->mapper);
    this->actor->GetProperty()->SetColor(0.9, 0.75, 0.55);
    this->renderer->AddActor(this->actor);
    this->renderer->SetBackground(0.1, 0.12, 0.18);
    this->window->SetDisplayId(gDisplay);
    this->window->SetOffScreenRendering(1);
    this->window->SetMultiSamples(0);
    this->window->SetSize(240, 240);
    this->window->AddRenderer(this->renderer);
    vtkCamera* camera = this->renderer->GetActiveCamera();
    camera->SetPosition(0.3, 0.2, 1.0);
    camera->SetViewUp(0, 1, 0);
    this->renderer->ResetCamera();
  }
};

/// Compares the window with testing-data/baselines/TestLODMapperSettings_<name>.png.
bool MatchesSettingBaseline(
  int argc, char* argv[], vtkRenderWindow* window, const std::string& name)
{
  const std::string baseline =
    tctest::Arg(argc, argv, "-D") + "/baselines/TestLODMapperSettings_" + name + ".png";
  std::string temporary = tctest::Arg(argc, argv, "-T");
  std::vector<std::string> args{ argv[0], "-T", temporary, "-V", baseline };
  std::vector<char*> pointers;
  for (std::string& a : args)
  {
    pointers.push_back(&a[0]);
  }
  window->Render();
  return vtkRegressionTester::Test(static_cast<int>(pointers.size()), pointers.data(), window,
           0.05) == vtkRegressionTester::PASSED;
}

/// OpenGL errors left after the window's last render (0 when none): VTK reports only those it
/// checks for, in debug builds.
unsigned int GLErrors(vtkRenderWindow* window)
{
  window->MakeCurrent();
  unsigned int count = 0;
  while (glGetError() != GL_NO_ERROR && count < 100)
  {
    ++count;
  }
  return count;
}

/// A setting: what it changes in a fresh scene, and the warning it must raise ("" for none).
struct Setting
{
  std::string name;
  std::function<void(Scene&)> apply;
  std::string warning;
  std::string baseline; // "" : its own, TestLODMapperSettings_<name>.png
};

/// A plane through the middle of the bunny that keeps its left half: the inside shows.
void ClipHalf(Scene& s)
{
  double b[6];
  s.mapper->GetBounds(b);
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]));
  plane->SetNormal(-1, 0, 0);
  s.mapper->AddClippingPlane(plane);
}

std::vector<Setting> Settings()
{
  return {
    { "gouraud", [](Scene&) {}, "", "" },
    { "lighting_off",
      [](Scene& s)
      {
        s.actor->GetProperty()->LightingOff();
        s.mapper->SetColorMode(tcLODMapper::ColorByChart);
      },
      "", "" },
    { "flat", [](Scene& s) { s.actor->GetProperty()->SetInterpolationToFlat(); }, "", "" },
    { "phong", [](Scene& s) { s.actor->GetProperty()->SetInterpolationToPhong(); }, "", "" },
    { "wireframe", [](Scene& s) { s.actor->GetProperty()->SetRepresentationToWireframe(); }, "",
      "" },
    { "points",
      [](Scene& s)
      {
        s.actor->GetProperty()->SetRepresentationToPoints();
        s.actor->GetProperty()->SetPointSize(2);
      },
      "", "" },
    { "surface_with_edges",
      [](Scene& s)
      {
        s.actor->GetProperty()->EdgeVisibilityOn();
        s.actor->GetProperty()->SetEdgeColor(0.1, 0.1, 0.4);
      },
      "", "" },
    { "opacity_depth_peeling",
      [](Scene& s)
      {
        s.actor->GetProperty()->SetOpacity(0.4);
        s.renderer->UseDepthPeelingOn();
        s.renderer->SetMaximumNumberOfPeels(8);
        s.renderer->SetOcclusionRatio(0.0);
      },
      "", "" },
    { "opacity_no_peeling",
      [](Scene& s)
      {
        s.actor->GetProperty()->SetOpacity(0.4);
        s.renderer->UseDepthPeelingOff();
      },
      "", "" },
    // A closed surface: culling its back faces changes nothing; culling its front faces shows
    // the inside of its back.
    { "backface_culling", [](Scene& s) { s.actor->GetProperty()->BackfaceCullingOn(); }, "",
      "gouraud" },
    { "frontface_culling", [](Scene& s) { s.actor->GetProperty()->FrontfaceCullingOn(); }, "", "" },
    { "clipping_plane", ClipHalf, "", "" },
    { "user_shader_property",
      [](Scene& s)
      {
        // The user's own property: a fragment replacement that inverts the lit colour.
        vtkNew<vtkShaderProperty> property;
        property->AddFragmentShaderReplacement("//VTK::Light::Impl", false,
          "//VTK::Light::Impl\n  gl_FragData[0].rgb = vec3(1.0) - gl_FragData[0].rgb;\n", false);
        s.actor->SetShaderProperty(property);
      },
      "", "" },
    { "scalars_on",
      [](Scene& s)
      {
        s.mapper->SetColorMode(tcLODMapper::ColorByAttribute);
        s.mapper->SetColorAttribute(tc::kMeanCurvature);
      },
      "", "" },
    { "scalars_off",
      [](Scene& s)
      {
        s.mapper->SetColorMode(tcLODMapper::ColorByAttribute);
        s.mapper->SetColorAttribute(tc::kMeanCurvature);
        s.mapper->ScalarVisibilityOff();
      },
      "", "gouraud" },
    { "texture_refused",
      [](Scene& s)
      {
        vtkNew<vtkImageData> image;
        image->SetDimensions(2, 2, 1);
        image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
        vtkNew<vtkTexture> texture;
        texture->SetInputData(image);
        s.actor->SetTexture(texture);
      },
      "does not draw", "gouraud" },
  };
}

/// Renders every setting in a scene of its own; false when one fails.
bool CheckSettings(int argc, char* argv[], vtkAlgorithmOutput* atlas, tcLogWatch* log)
{
  bool ok = true;
  for (const Setting& setting : Settings())
  {
    log->Errors.clear();
    log->Warnings.clear();
    Scene scene(atlas);
    setting.apply(scene);
    scene.renderer->ResetCamera();
    const std::string baseline = setting.baseline.empty() ? setting.name : setting.baseline;
    const bool image = MatchesSettingBaseline(argc, argv, scene.window, baseline);
    const unsigned int glErrors = GLErrors(scene.window);
    const bool warned = setting.warning.empty()
      ? log->Warnings.empty()
      : log->Warnings.find(setting.warning) != std::string::npos;
    const bool peeled =
      setting.name != "opacity_depth_peeling" || scene.renderer->GetLastRenderingUsedDepthPeeling();
    std::printf("setting %-22s image %s, %s, %u OpenGL errors, %s%s\n", setting.name.c_str(),
      image ? "matches" : "DIFFERS", log->Errors.empty() ? "no error" : "ERRORS", glErrors,
      setting.warning.empty() ? (warned ? "no warning" : "UNEXPECTED WARNING")
                              : (warned ? "refused with a warning" : "NO WARNING"),
      peeled ? "" : ", DEPTH PEELING NOT USED");
    ok = ok && image && log->Errors.empty() && glErrors == 0 && warned && peeled;
    if (setting.name == "user_shader_property")
    {
      // The mapper's replacements do not go into the user's property.
      const int count = scene.actor->GetShaderProperty()->GetNumberOfShaderReplacements();
      std::printf("  the user's shader property holds %d replacement(s)\n", count);
      ok = ok && count == 1;
    }
  }
  return ok;
}

/// Two LOD actors with their own mappers and a third sharing the first's, in one renderer; two
/// windows with a mapper each; one mapper drawn into two windows in turn, and again after the
/// second window is gone. The windows' pictures are those of single scenes (the same baselines).
bool CheckTwoActorsAndWindows(int argc, char* argv[], vtkAlgorithmOutput* atlas, tcLogWatch* log)
{
  log->Errors.clear();
  log->Warnings.clear();
  bool ok = true;
  {
    Scene scene(atlas);
    double b[6];
    scene.mapper->GetBounds(b);
    vtkNew<tcLODMapper> second;
    second->SetInputConnection(atlas);
    second->SetColorMode(tcLODMapper::ColorByLevel);
    second->SetFixedLevel(2);
    vtkNew<vtkActor> secondActor;
    secondActor->SetMapper(second);
    secondActor->SetPosition(1.1 * (b[1] - b[0]), 0, 0);
    vtkNew<vtkActor> shared;
    shared->SetMapper(scene.mapper);
    shared->GetProperty()->SetColor(0.4, 0.6, 0.9);
    shared->SetPosition(-1.1 * (b[1] - b[0]), 0, 0);
    scene.renderer->AddActor(secondActor);
    scene.renderer->AddActor(shared);
    scene.renderer->ResetCamera();
    const bool image = MatchesSettingBaseline(argc, argv, scene.window, "two_actors");
    std::printf("two actors with a mapper each and a third sharing one: image %s\n",
      image ? "matches" : "DIFFERS");
    ok = ok && image;
  }
  {
    Scene a(atlas), b(atlas);
    b.actor->GetProperty()->SetInterpolationToFlat();
    b.renderer->ResetCamera();
    bool images = true;
    for (int round = 0; round < 2; ++round)
    {
      images = MatchesSettingBaseline(argc, argv, a.window, "gouraud") && images;
      images = MatchesSettingBaseline(argc, argv, b.window, "flat") && images;
    }
    std::printf(
      "two windows, a mapper each, drawn in turn twice: images %s\n", images ? "match" : "DIFFER");
    ok = ok && images;
  }
  {
    Scene a(atlas);
    bool images = true;
    {
      Scene b(atlas);
      b.actor->SetMapper(a.mapper);
      b.actor->GetProperty()->SetInterpolationToFlat();
      for (int round = 0; round < 2; ++round)
      {
        images = MatchesSettingBaseline(argc, argv, a.window, "gouraud") && images;
        images = MatchesSettingBaseline(argc, argv, b.window, "flat") && images;
      }
    }
    images = MatchesSettingBaseline(argc, argv, a.window, "gouraud") && images;
    std::printf("one mapper in two windows in turn, then after the second is deleted: images %s\n",
      images ? "match" : "DIFFER");
    ok = ok && images;
  }
  std::printf("  %s, %s\n", log->Errors.empty() ? "no error" : "ERRORS",
    log->Warnings.empty() ? "no warning" : "UNEXPECTED WARNING");
  return ok && log->Errors.empty() && log->Warnings.empty();
}

/// Corners (i, j) of triangle t of a level-n grid, in the grid order of tc::rebuildMesh: row by
/// row (j), and in a row (i, j) (i + 1, j) (i, j + 1) then (i + 1, j) (i + 1, j + 1) (i, j + 1).
std::array<std::array<int, 2>, 3> GridTriangle(int n, vtkIdType t)
{
  const int big = 1 << n;
  int j = 0;
  while (t >= 2 * (big - j) - 1)
  {
    t -= 2 * (big - j) - 1;
    ++j;
  }
  const int i = static_cast<int>(t / 2);
  if (t % 2 == 0)
  {
    return { { { i, j }, { i + 1, j }, { i, j + 1 } } };
  }
  return { { { i + 1, j }, { i + 1, j + 1 }, { i, j + 1 } } };
}

/// Whether display pixel (x, y) lies within `slack` pixels of the screen box of triangle
/// `location` (instance 0, untransformed), its corners stitched to the frame's `levels` (eq. 8).
bool OnTriangle(vtkRenderer* renderer, const tc::Atlas& atlas, vtkIntArray* levels,
  const vtkIdType location[4], unsigned int x, unsigned int y, double slack)
{
  const auto chart = static_cast<int32_t>(location[1]);
  const auto level = static_cast<int32_t>(location[2]);
  std::array<int32_t, 3> across{};
  for (size_t k = 0; k < 3; ++k)
  {
    const int32_t nb = atlas.charts[static_cast<size_t>(chart)].neighborChart[k];
    across[k] = nb >= 0 && levels->GetValue(nb) >= 0 ? levels->GetValue(nb) : level;
  }
  double box[4] = { 1e300, -1e300, 1e300, -1e300 };
  for (const auto& ij : GridTriangle(level, location[3]))
  {
    const std::array<int32_t, 2> moved = tc::stitchedGridPoint(level, across, ij[0], ij[1]);
    const float* p = tc::atlasSample(atlas, chart, 0, level, moved[0], moved[1]);
    renderer->SetWorldPoint(p[0], p[1], p[2], 1.0);
    renderer->WorldToDisplay();
    const double* d = renderer->GetDisplayPoint();
    box[0] = std::min(box[0], d[0]);
    box[1] = std::max(box[1], d[0]);
    box[2] = std::min(box[2], d[1]);
    box[3] = std::max(box[3], d[1]);
  }
  return x + 0.5 >= box[0] - slack && x + 0.5 <= box[1] + slack && y + 0.5 >= box[2] - slack &&
    y + 0.5 <= box[3] + slack;
}

/// Cell selection: every picked cell is located on a chart of the table, at the level the last
/// frame drew it, on a triangle under the pixel. Point selection is refused with a warning.
bool CheckSelection(tcGeometryImages* images, tcLogWatch* log)
{
  log->Errors.clear();
  log->Warnings.clear();
  tc::Atlas atlas;
  std::string error;
  if (!tcvtk::ToAtlas(images->GetOutput(), atlas, error))
  {
    std::printf("%s\n", error.c_str());
    return false;
  }
  Scene scene(images->GetOutputPort());
  scene.window->Render();
  vtkNew<vtkIntArray> levels;
  scene.mapper->GetLevels(levels);
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(scene.renderer);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  selector->SetArea(0, 0, 239, 239);
  if (!selector->CaptureBuffers())
  {
    std::printf("the selector captured nothing\n");
    return false;
  }
  int picked = 0, wrong = 0;
  std::set<vtkIdType> charts, levelsSeen;
  for (unsigned int y = 2; y < 240; y += 4)
  {
    for (unsigned int x = 2; x < 240; x += 4)
    {
      const unsigned int pos[2] = { x, y };
      const vtkHardwareSelector::PixelInformation info = selector->GetPixelInformation(pos);
      if (!info.Valid || info.Prop != scene.actor)
      {
        continue;
      }
      ++picked;
      vtkIdType where[4];
      const bool found = scene.mapper->LocateCell(info.AttributeID, where);
      const bool right = found && where[0] == 0 &&
        where[1] < static_cast<vtkIdType>(atlas.charts.size()) &&
        where[2] == levels->GetValue(where[1]) &&
        where[2] <= atlas.charts[static_cast<size_t>(where[1])].maxLevel &&
        OnTriangle(scene.renderer, atlas, levels, where, x, y, 1.0);
      wrong += !right;
      charts.insert(where[1]);
      levelsSeen.insert(where[2]);
    }
  }
  std::printf("selection: %d pixels picked on %zu charts at %zu levels, %d not on the located "
              "triangle, chart or level\n",
    picked, charts.size(), levelsSeen.size(), wrong);
  bool ok = picked > 500 && charts.size() > 20 && wrong == 0 && log->Errors.empty();

  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_POINTS);
  const bool captured = selector->CaptureBuffers();
  const unsigned int center[2] = { 120, 120 };
  const bool hit = captured && selector->GetPixelInformation(center).Prop == scene.actor;
  const bool refused = log->Warnings.find("point selection") != std::string::npos;
  std::printf("point selection: %s, the bunny %s\n",
    refused ? "refused with a warning" : "NOT REFUSED", hit ? "PICKED" : "not drawn");
  return ok && refused && !hit && log->Errors.empty();
}

/// The watch itself: a user's replacement that does not compile is reported in the log (so the
/// checks above can fail on a shader error), and the mapper draws nothing rather than crash.
bool CheckTheWatchSeesShaderErrors(vtkAlgorithmOutput* atlas, tcLogWatch* log)
{
  log->Errors.clear();
  Scene scene(atlas);
  vtkNew<vtkShaderProperty> property;
  property->AddFragmentShaderReplacement(
    "//VTK::Light::Impl", false, "//VTK::Light::Impl\n  not glsl;\n", false);
  scene.actor->SetShaderProperty(property);
  scene.window->Render();
  scene.window->Render(); // the second try, where VTK's own UpdateShaders crashes
  const bool seen = log->Errors.find("vtkShaderProgram") != std::string::npos;
  std::printf("a user's replacement that does not compile, drawn twice: %s, no crash\n",
    seen ? "reported in the log" : "NOT SEEN IN THE LOG");
  log->Errors.clear();
  return seen;
}
} // namespace

int TestLODMapperSettings(int argc, char* argv[])
{
  tctest::Checker check;
  vtkNew<tcLogWatch> log;
  vtkOutputWindow::SetInstance(log);
  const std::string data = tctest::Arg(argc, argv, "-D");
  vtkSmartPointer<vtkPolyData> mesh = tctest::ReadPrepared(data + "/meshes/bunny_npm.off");
  if (!TC_CHECK(check, mesh != nullptr))
  {
    return 1;
  }
  vtkNew<vtkRenderWindow> host;
  vtkNew<vtkRenderer> hostRenderer;
  host->AddRenderer(hostRenderer);
  host->SetOffScreenRendering(1);
  host->SetSize(8, 8);
  host->Render();
  gDisplay = host->GetGenericDisplayId();
  vtkSmartPointer<tcGeometryImages> images = tctest::AtlasStages(mesh);
  images->AddResampledArray(tc::kMeanCurvature);
  images->Update();
  TC_CHECK(check, CheckSettings(argc, argv, images->GetOutputPort(), log));
  TC_CHECK(check, CheckTwoActorsAndWindows(argc, argv, images->GetOutputPort(), log));
  TC_CHECK(check, CheckSelection(images, log));
  TC_CHECK(check, CheckTheWatchSeesShaderErrors(images->GetOutputPort(), log));
  vtkOutputWindow::SetInstance(nullptr);
  return check.failures == 0 ? 0 : 1;
}
