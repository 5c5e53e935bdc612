// SPDX-License-Identifier: BSD-3-Clause
// trichart-viewer: open a mesh or an atlas, browse the TriChart stages, tune them, take
// screenshots.
#include "tcViewerWindow.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QSurfaceFormat>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkLogger.h>
#include <vtkOutputWindow.h>

#include <iostream>
#include <vector>

int main(int argc, char* argv[])
{
  // The VTK widget needs its surface format set before the application exists.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  QApplication::setApplicationName("trichart-viewer");

  const QString stageList = tcViewerWindow::StageNames().join(", ");
  QCommandLineParser parser;
  parser.setApplicationDescription("TriChart viewer: inspect every stage of the pipeline.");
  parser.addHelpOption();
  parser.addPositionalArgument("files",
    "Mesh (.ply, .ply.gz, .obj, .stl, .off, .vtp, .vtk; scenes .glb, .gltf, .fbx, .x, .md2) or "
    "atlas (.exr) files, opened in turn; "
    "the last one that opens stays shown. An atlas shows its reconstruction (or --stage atlas or "
    "lod).",
    "[files...]");
  QCommandLineOption screenshot("screenshot",
    "Run up to the stage, save a PNG of the window and exit. With several stages the file name "
    "holds {stage}, replaced by each stage's name.",
    "file");
  QCommandLineOption stage("stage",
    "Stage to show: " + stageList +
      " (default curvature); with --screenshot, several separated by commas, each framed as if "
      "shown alone (one pipeline run for all).",
    "name", "curvature");
  QCommandLineOption array("array", "Colour the surface by this array.", "name");
  QCommandLineOption level(
    "level", "Level of the reconstruction (-1: each chart's finest, the default).", "n", "-1");
  QCommandLineOption saveAtlas("save-atlas",
    "Write the atlas of the last file (built, or the one opened) as .exr, as File > Save atlas "
    "does.",
    "file");
  QCommandLineOption instances("instances",
    "Instances of the lod stage's crowd, on a square grid of the ground (1 to 2500, default 1).",
    "n", "1");
  parser.addOption(screenshot);
  parser.addOption(stage);
  parser.addOption(array);
  parser.addOption(level);
  parser.addOption(saveAtlas);
  parser.addOption(instances);
  parser.process(app);

  std::vector<int> stages;
  for (const QString& name : parser.value(stage).split(','))
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
      return 2;
    }
    stages.push_back(index);
  }
  if (stages.empty())
  {
    std::cerr << "trichart-viewer: --stage needs a stage name; use " << stageList.toStdString()
              << "\n";
    return 2;
  }
  const QString shotPattern = parser.value(screenshot);
  if (stages.size() > 1 && !shotPattern.contains("{stage}"))
  {
    std::cerr << "trichart-viewer: several stages need --screenshot FILE with {stage} in FILE\n";
    return 2;
  }

  bool levelOk = false;
  const int levelValue = parser.value(level).toInt(&levelOk);
  if (!levelOk || levelValue < -1)
  {
    std::cerr << "trichart-viewer: --level needs an integer >= -1, not '"
              << parser.value(level).toStdString() << "'\n";
    return 2;
  }

  bool instancesOk = false;
  const int instancesValue = parser.value(instances).toInt(&instancesOk);
  if (!instancesOk || instancesValue < 1 || instancesValue > 2500)
  {
    std::cerr << "trichart-viewer: --instances needs an integer from 1 to 2500, not '"
              << parser.value(instances).toStdString() << "'\n";
    return 2;
  }

  tcViewerWindow window;
  window.SetReconstructionLevel(levelValue);
  window.SetInstances(instancesValue);
  const bool batch = parser.isSet(screenshot) || parser.isSet(saveAtlas);
  window.SetBatchMode(batch);
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
  window.show();
  QApplication::processEvents();

  const QStringList files = parser.positionalArguments();
  if (batch && files.isEmpty())
  {
    std::cerr << "trichart-viewer: --screenshot and --save-atlas need a mesh or atlas file\n";
    return 2;
  }
  // Each file is opened as if dropped on the window in turn: a file that fails leaves the
  // window usable for the next one.
  bool ok = true;
  bool opened = false;
  for (const QString& file : files)
  {
    opened = window.OpenFile(file, stages.front());
    ok = ok && opened;
  }
  if (opened && parser.isSet(array))
  {
    window.SetColorArray(parser.value(array));
  }
  if (batch)
  {
    for (size_t k = 0; parser.isSet(screenshot) && k < stages.size(); ++k)
    {
      // The first stage is shown by OpenFile; the others run on from it, each framed anew.
      if (k > 0 && opened)
      {
        ok = window.ShowStage(stages[k]) && ok;
        window.ResetCamera();
        if (parser.isSet(array))
        {
          window.SetColorArray(parser.value(array));
        }
      }
      const QString path =
        QString(shotPattern).replace("{stage}", tcViewerWindow::StageNames()[stages[k]]);
      const bool saved = window.SaveScreenshot(path);
      if (!saved)
      {
        std::cerr << "trichart-viewer: cannot write " << path.toStdString() << "\n";
      }
      ok = ok && saved;
    }
    // Saved last, so that the pictures do not show the status message of the save.
    if (opened && parser.isSet(saveAtlas))
    {
      ok = window.SaveAtlas(parser.value(saveAtlas)) && ok;
    }
    return ok ? 0 : 1;
  }
  return app.exec();
}
