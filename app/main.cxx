// SPDX-License-Identifier: BSD-3-Clause
// trichart-viewer: open a mesh or an atlas, browse the TriChart stages, tune them, take
// screenshots.
#include "tcViewerWindow.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QSurfaceFormat>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkLogger.h>
#include <vtkOutputWindow.h>

#include <iostream>
#include <limits>
#include <vector>

namespace
{
/// What the command line asks for.
struct ViewerOptions
{
  QStringList Files;
  std::vector<int> Stages; ///< at least one
  bool Screenshot = false;
  QString ScreenshotPattern; ///< holds {stage} when there are several stages
  bool Array = false;
  QString ArrayName;
  bool SaveAtlas = false;
  QString AtlasPath;
  bool ExportGltf = false;
  QString GltfPath;
  int Level = -1;
  int Instances = 1;
  double VerticalScale = 1.0;
  bool Animation = false;
  QString AnimationChoice;
  bool Time = false;
  double Seconds = 0.0;
  tcCameraView Camera;
};

void AddOptions(QCommandLineParser& parser, const QString& stageList)
{
  parser.setApplicationDescription("TriChart viewer: inspect every stage of the pipeline.");
  parser.addHelpOption();
  parser.addPositionalArgument("files",
    "Mesh (.ply, .ply.gz, .obj, .stl, .off, .vtp, .vtk; scenes .glb, .gltf, .fbx, .x, .md2; "
    "terrain rasters .tif, .tiff, .asc, .hgt, .dem, .pgm, .png, .bmp) or atlas (.exr) files, "
    "opened in turn; "
    "the last one that opens stays shown. An atlas shows its reconstruction (or --stage atlas or "
    "lod).",
    "[files...]");
  parser.addOption(QCommandLineOption("screenshot",
    "Run up to the stage, save a PNG of the window and exit. With several stages the file name "
    "holds {stage}, replaced by each stage's name.",
    "file"));
  parser.addOption(QCommandLineOption("stage",
    "Stage to show: " + stageList +
      " (default curvature); with --screenshot, several separated by commas, each framed as if "
      "shown alone (one pipeline run for all).",
    "name", "curvature"));
  parser.addOption(QCommandLineOption("array", "Colour the surface by this array.", "name"));
  parser.addOption(QCommandLineOption(
    "level", "Level of the reconstruction (-1: each chart's finest, the default).", "n", "-1"));
  parser.addOption(QCommandLineOption("save-atlas",
    "Write the atlas of the last file (built, or the one opened) as .exr, as File > Save atlas "
    "does.",
    "file"));
  parser.addOption(QCommandLineOption("export-gltf",
    "Write the LOD chain of the last file's atlas as glTF (.glb or .gltf), as File > Export "
    "LOD chain as glTF does.",
    "file"));
  parser.addOption(QCommandLineOption("view",
    "Look from this side: " + tcCameraView::Directions().join(", ") +
      " (default: the stage's own camera, from the front).",
    "side"));
  parser.addOption(QCommandLineOption(
    "azimuth", "Then turn the camera this many degrees about the view-up axis.", "deg", "0"));
  parser.addOption(
    QCommandLineOption("elevation", "Then turn it this many degrees up (-90 to 90).", "deg", "0"));
  parser.addOption(QCommandLineOption(
    "zoom", "Then zoom by this factor (> 1: closer; 0.05 to 20).", "factor", "1"));
  parser.addOption(QCommandLineOption(
    "vertical-scale", "A terrain raster: multiply its heights by this (default 1).", "s", "1"));
  parser.addOption(QCommandLineOption("instances",
    "Instances of the lod stage's crowd, on a square grid of the ground (1 to 2500, default 1).",
    "n", "1"));
  parser.addOption(QCommandLineOption("animation",
    "A skinned atlas in the lod stage: the animation that poses it, by name or index (default "
    "the first).",
    "name"));
  parser.addOption(QCommandLineOption("time",
    "A skinned atlas in the lod stage: pose it at this time of the animation, in seconds (0 to "
    "its duration; default 0). In a crowd each instance adds its own phase.",
    "seconds"));
}

/// The stages of --stage, in order; false (said on stderr) for an unknown or missing name.
bool ReadStages(
  const QCommandLineParser& parser, const QString& stageList, std::vector<int>& stages)
{
  for (const QString& name : parser.value("stage").split(','))
  {
    if (name.trimmed().isEmpty())
    {
      continue;
    }
    const int index = tcViewerWindow::StageFromName(name.trimmed());
    if (index < 0)
    {
      std::cerr << "trichart-viewer: unknown stage '" << name.trimmed().toStdString() << "'; use "
                << stageList.toStdString() << "\n";
      return false;
    }
    stages.push_back(index);
  }
  if (stages.empty())
  {
    std::cerr << "trichart-viewer: --stage needs a stage name; use " << stageList.toStdString()
              << "\n";
    return false;
  }
  return true;
}

/// The integer of option `name`, from `lo` to `hi`; false (said on stderr, with `rule`) if not.
bool ReadInteger(
  const QCommandLineParser& parser, const char* name, int lo, int hi, const char* rule, int& value)
{
  bool ok = false;
  value = parser.value(name).toInt(&ok);
  if (!ok || value < lo || value > hi)
  {
    std::cerr << "trichart-viewer: --" << name << " needs " << rule << ", not '"
              << parser.value(name).toStdString() << "'\n";
    return false;
  }
  return true;
}

/// The real number of option `name`, from `lo` to `hi`; false (said on stderr) if not.
bool ReadReal(
  const QCommandLineParser& parser, const char* name, double lo, double hi, double& value)
{
  bool ok = false;
  value = parser.value(name).toDouble(&ok);
  if (!ok || !(value >= lo && value <= hi))
  {
    std::cerr << "trichart-viewer: --" << name << " needs a number from " << lo << " to " << hi
              << ", not '" << parser.value(name).toStdString() << "'\n";
    return false;
  }
  return true;
}

/// --view, --azimuth, --elevation and --zoom; false (said on stderr) if one is refused.
bool ReadCamera(const QCommandLineParser& parser, tcCameraView& camera)
{
  camera.Direction = parser.value("view");
  if (parser.isSet("view") && !tcCameraView::Directions().contains(camera.Direction))
  {
    std::cerr << "trichart-viewer: unknown --view '" << camera.Direction.toStdString() << "'; use "
              << tcCameraView::Directions().join(", ").toStdString() << "\n";
    return false;
  }
  return ReadReal(parser, "azimuth", -360.0, 360.0, camera.Azimuth) &&
    ReadReal(parser, "elevation", -90.0, 90.0, camera.Elevation) &&
    ReadReal(parser, "zoom", 0.05, 20.0, camera.Zoom);
}

/// --animation and --time; false (said on stderr) for a time that is no number >= 0. Whether the
/// atlas has that animation, and that time, is known once it is open.
bool ReadPose(const QCommandLineParser& parser, ViewerOptions& options)
{
  options.Animation = parser.isSet("animation");
  options.AnimationChoice = parser.value("animation");
  options.Time = parser.isSet("time");
  return !options.Time || ReadReal(parser, "time", 0.0, 1e6, options.Seconds);
}

/// Reads the command line (--help exits here); false if it is refused (said on stderr).
bool ReadOptions(const QApplication& app, ViewerOptions& options)
{
  const QString stageList = tcViewerWindow::StageNames().join(", ");
  QCommandLineParser parser;
  AddOptions(parser, stageList);
  parser.process(app);
  if (!ReadStages(parser, stageList, options.Stages))
  {
    return false;
  }
  options.Screenshot = parser.isSet("screenshot");
  options.ScreenshotPattern = parser.value("screenshot");
  if (options.Stages.size() > 1 && !options.ScreenshotPattern.contains("{stage}"))
  {
    std::cerr << "trichart-viewer: several stages need --screenshot FILE with {stage} in FILE\n";
    return false;
  }
  if (!ReadInteger(
        parser, "level", -1, std::numeric_limits<int>::max(), "an integer >= -1", options.Level) ||
    !ReadInteger(parser, "instances", 1, 2500, "an integer from 1 to 2500", options.Instances) ||
    !ReadCamera(parser, options.Camera) || !ReadPose(parser, options) ||
    !ReadReal(parser, "vertical-scale", 1e-4, 1e4, options.VerticalScale))
  {
    return false;
  }
  options.Array = parser.isSet("array");
  options.ArrayName = parser.value("array");
  options.SaveAtlas = parser.isSet("save-atlas");
  options.AtlasPath = parser.value("save-atlas");
  options.ExportGltf = parser.isSet("export-gltf");
  options.GltfPath = parser.value("export-gltf");
  options.Files = parser.positionalArguments();
  return true;
}

/// Sends VTK's messages where the mode wants them.
void RouteLogs(bool batch)
{
  if (batch)
  {
    // Errors are reported once, by the window, on stderr.
    vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  else
  {
    // Filters log what they do at INFO level; the window shows what matters.
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_WARNING);
  }
}

/// Saves a screenshot of each stage asked for (the first one is shown by OpenFile; the others
/// run on from it, each framed anew); false if one fails.
bool SaveScreenshots(tcViewerWindow& window, const ViewerOptions& options, bool opened)
{
  bool ok = true;
  for (size_t k = 0; k < options.Stages.size(); ++k)
  {
    if (k > 0 && opened)
    {
      ok = window.ShowStage(options.Stages[k]) && ok;
      window.ResetCamera();
      if (options.Array)
      {
        window.SetColorArray(options.ArrayName);
      }
    }
    const QString path = QString(options.ScreenshotPattern)
                           .replace("{stage}", tcViewerWindow::StageNames()[options.Stages[k]]);
    const bool saved = window.SaveScreenshot(path);
    if (!saved)
    {
      std::cerr << "trichart-viewer: cannot write " << path.toStdString() << "\n";
    }
    ok = ok && saved;
  }
  return ok;
}
}

int main(int argc, char* argv[])
{
  // The VTK widget needs its surface format set before the application exists.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  QApplication::setApplicationName("trichart-viewer");
  ViewerOptions options;
  if (!ReadOptions(app, options))
  {
    return 2;
  }

  tcViewerWindow window;
  window.SetReconstructionLevel(options.Level);
  window.SetInstances(options.Instances);
  window.SetVerticalScale(options.VerticalScale);
  window.SetCameraView(options.Camera);
  if (options.Animation)
  {
    window.SetPoseAnimation(options.AnimationChoice);
  }
  if (options.Time)
  {
    window.SetPoseTime(options.Seconds);
  }
  const bool batch = options.Screenshot || options.SaveAtlas || options.ExportGltf;
  window.SetBatchMode(batch);
  RouteLogs(batch);
  window.show();
  QApplication::processEvents();
  if (batch && options.Files.isEmpty())
  {
    std::cerr << "trichart-viewer: --screenshot, --save-atlas and --export-gltf need a mesh or "
                 "atlas file\n";
    return 2;
  }

  // Each file is opened as if dropped on the window in turn: a file that fails leaves the
  // window usable for the next one.
  bool ok = true;
  bool opened = false;
  for (const QString& file : options.Files)
  {
    opened = window.OpenFile(file, options.Stages.front());
    ok = ok && opened;
  }
  if (opened && options.Array)
  {
    window.SetColorArray(options.ArrayName);
  }
  if (!batch)
  {
    return app.exec();
  }
  if (options.Screenshot)
  {
    ok = SaveScreenshots(window, options, opened) && ok;
  }
  // Saved last, so that the pictures do not show the status message of the save.
  if (opened && options.SaveAtlas)
  {
    ok = window.SaveAtlas(options.AtlasPath) && ok;
  }
  if (opened && options.ExportGltf)
  {
    ok = window.ExportGltf(options.GltfPath) && ok;
  }
  return ok ? 0 : 1;
}
