// SPDX-License-Identifier: BSD-3-Clause
// trichart-viewer: open a mesh, browse the TriChart stages, tune them, take screenshots.
#include "tcViewerWindow.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QSurfaceFormat>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkOutputWindow.h>

#include <iostream>

int main(int argc, char* argv[])
{
  // The VTK widget needs its surface format set before the application exists.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  QApplication::setApplicationName("trichart-viewer");

  QCommandLineParser parser;
  parser.setApplicationDescription("TriChart viewer: inspect every stage of the pipeline.");
  parser.addHelpOption();
  parser.addPositionalArgument(
    "mesh", "Mesh file to open (.ply, .ply.gz, .obj, .stl, .off, .vtp, .vtk).");
  QCommandLineOption screenshot(
    "screenshot", "Run up to the stage, save a PNG of the window and exit.", "file");
  QCommandLineOption stage("stage",
    "Stage to show: input, preparation, curvature (default), clusters, features or base.", "name",
    "curvature");
  QCommandLineOption array("array", "Colour the surface by this array.", "name");
  parser.addOption(screenshot);
  parser.addOption(stage);
  parser.addOption(array);
  parser.process(app);

  const int stageIndex = tcViewerWindow::StageFromName(parser.value(stage));
  if (stageIndex < 0)
  {
    std::cerr << "trichart-viewer: unknown stage '" << parser.value(stage).toStdString()
              << "'; use input, preparation, curvature, clusters, features or base\n";
    return 2;
  }

  tcViewerWindow window;
  const bool batch = parser.isSet(screenshot);
  window.SetBatchMode(batch);
  if (batch)
  {
    // Errors are reported once, by the window, on stderr.
    vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  }
  window.show();
  QApplication::processEvents();

  const QStringList files = parser.positionalArguments();
  bool ok = true;
  if (!files.isEmpty())
  {
    ok = window.OpenFile(files.first(), stageIndex);
    if (ok && parser.isSet(array))
    {
      window.SetColorArray(parser.value(array));
    }
  }
  if (batch)
  {
    if (files.isEmpty())
    {
      std::cerr << "trichart-viewer: --screenshot needs a mesh file\n";
      return 2;
    }
    const bool saved = window.SaveScreenshot(parser.value(screenshot));
    if (!saved)
    {
      std::cerr << "trichart-viewer: cannot write " << parser.value(screenshot).toStdString()
                << "\n";
    }
    return ok && saved ? 0 : 1;
  }
  return app.exec();
}
