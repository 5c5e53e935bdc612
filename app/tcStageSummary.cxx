// SPDX-License-Identifier: BSD-3-Clause
#include "tcStageSummary.h"

#include "tcGeometryImageMesh.h"
#include "tcLODView.h"
#include "tcMeshPreparation.h"
#include "tcMeshReader.h"
#include "tcStage.h"
#include "tcStagePipeline.h"
#include "tcSurfaceDistance.h"

#include "tc/common/array_names.h"

#include <QFileInfo>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPolyData.h>
#include <vtkTable.h>

namespace
{
/// The input's or the preparation's report, the folder of `fileName` left out: it is noise in a
/// narrow panel, and the file name says which file it is.
QString Report(const tcStagePipeline& pipeline, int stage, const QString& fileName)
{
  const char* report = stage == tcStage::Input ? pipeline.GetReader()->GetReport()
    : stage == tcStage::Preparation            ? pipeline.GetPreparation()->GetReport()
                                               : "";
  if (!report || !*report)
  {
    return QString();
  }
  QString text = QString(report).replace(fileName, QFileInfo(fileName).fileName());
  return "<br><pre>" + text.toHtmlEscaped() + "</pre>";
}

/// What to check in the preparation panel so that the base complex takes the prepared mesh,
/// when it is no closed, oriented manifold.
QString ClosedManifoldHint(const tcMeshPreparation* preparation)
{
  if (preparation->GetClosedManifold())
  {
    return QString();
  }
  return "<br><b>Not a closed, oriented manifold</b>: the base complex will refuse it: " +
    QString::fromUtf8(preparation->GetClosedManifoldRepairs()) +
    ". Check the box in the Preparation panel, then Apply.";
}

/// How many lines and corners the stage draws.
QString LinesAndCorners(int stage, const tcStageOutput& output)
{
  const char* const lineNames[] = { "", "", "crest lines", "boundary polylines", "feature lines",
    "base edges", "paths", "", "", "" };
  static_assert(sizeof(lineNames) / sizeof(*lineNames) == tcStage::Count, "one per stage");
  QString info;
  if (output.Lines && *lineNames[stage])
  {
    info += QString("<br>%1 %2").arg(output.Lines->GetNumberOfLines()).arg(lineNames[stage]);
  }
  if (output.Corners)
  {
    info += QString("<br>%1 corners").arg(output.Corners->GetNumberOfPoints());
  }
  return info;
}

/// How many patches the paths cut the mesh into.
QString Patches(vtkPolyData* surface)
{
  double range[2] = { 0.0, -1.0 };
  if (vtkDataArray* patches = surface->GetCellData()->GetArray(tc::kPatchId))
  {
    patches->GetRange(range);
  }
  return QString("<br>%1 patches").arg(static_cast<long long>(range[1]) + 1);
}

/// The atlas's charts, their finest levels and its mip steps.
QString Atlas(vtkMultiBlockDataSet* atlas)
{
  auto* charts = vtkTable::SafeDownCast(atlas->GetBlock(0));
  auto* images = vtkMultiBlockDataSet::SafeDownCast(atlas->GetBlock(1));
  auto* finest = images ? vtkImageData::SafeDownCast(images->GetBlock(0)) : nullptr;
  vtkDataArray* maxLevel =
    charts ? vtkArrayDownCast<vtkDataArray>(charts->GetColumnByName(tc::kMaxLevel)) : nullptr;
  if (!charts || !finest || !maxLevel)
  {
    return QString();
  }
  int dims[3];
  finest->GetDimensions(dims);
  double levels[2];
  maxLevel->GetRange(levels);
  return QString("<br>%1 charts, finest levels %2 to %3<br>%4 mip steps, the finest %5 x %6 "
                 "texels<br>(the mesh is every chart at its finest level)")
    .arg(charts->GetNumberOfRows())
    .arg(levels[0])
    .arg(levels[1])
    .arg(images->GetNumberOfBlocks())
    .arg(dims[0])
    .arg(dims[1]);
}

/// The levels of the reconstruction `rebuilt` and, for a mesh, its distance to the prepared mesh.
QString Reconstruction(const tcStagePipeline& pipeline, vtkPolyData* rebuilt)
{
  double levels[2] = { 0.0, 0.0 };
  if (vtkDataArray* level = rebuilt->GetCellData()->GetArray(tc::kLevel))
  {
    level->GetRange(levels);
  }
  const int asked = pipeline.GetReconstruction()->GetLevel();
  const QString requested = asked < 0 ? "finest" : QString::number(asked);
  QString info = levels[0] == levels[1]
    ? QString("<br>Level %1 (asked: %2)").arg(levels[0]).arg(requested)
    : QString("<br>Levels %1 to %2 (asked: %3)").arg(levels[0]).arg(levels[1]).arg(requested);
  if (pipeline.HasAtlasFile())
  {
    return info + "<br>No distance colouring: an atlas file has no input mesh to measure against.";
  }
  tcSurfaceDistance* distance = pipeline.GetDistance();
  const double diagonal = distance->GetDiagonal() > 0 ? distance->GetDiagonal() : 1;
  return info +
    QString("<br>Distance to the prepared mesh:<br>Hausdorff %1 (%2% of the diagonal)<br>RMS %3 "
            "(%4%)")
      .arg(distance->GetHausdorff(), 0, 'g', 4)
      .arg(100.0 * distance->GetHausdorff() / diagonal, 0, 'f', 3)
      .arg(distance->GetRmsDistance(), 0, 'g', 4)
      .arg(100.0 * distance->GetRmsDistance() / diagonal, 0, 'f', 3);
}
}

QString tcStageSummary::Stage(
  const tcStagePipeline& pipeline, int stage, const tcStageOutput& output, const QString& fileName)
{
  QString info = QString("<b>%1</b><br>%2 points, %3 cells")
                   .arg(tcStage::Label(stage))
                   .arg(output.Counted->GetNumberOfPoints())
                   .arg(output.Counted->GetNumberOfCells());
  info += Report(pipeline, stage, fileName);
  if (stage == tcStage::Preparation)
  {
    info += ClosedManifoldHint(pipeline.GetPreparation());
  }
  info += LinesAndCorners(stage, output);
  if (stage == tcStage::Patches)
  {
    info += Patches(output.Surface);
  }
  if (stage == tcStage::Atlas && output.Atlas)
  {
    info += Atlas(output.Atlas);
  }
  if (stage == tcStage::Reconstruction)
  {
    info += Reconstruction(pipeline, output.Counted);
  }
  const QString note = QString::fromStdString(pipeline.GetNote());
  if (!note.isEmpty())
  {
    info += "<br><font color='#a60'>Note: " + note.toHtmlEscaped() + "</font>";
  }
  return info;
}

QString tcStageSummary::LOD(const tcLODFrame& frame)
{
  QString text =
    QString("<b>%1</b><br>%2 charts x %3 instance%4<br>fps %5<br>%6 triangles drawn<br>%7 "
            "charts drawn<br>charts per level: %8<br>LOD selection %9 ms")
      .arg(tcStage::Label(tcStage::LOD))
      .arg(frame.Charts)
      .arg(frame.Instances)
      .arg(frame.Instances == 1 ? "" : "s")
      .arg(frame.Fps)
      .arg(frame.TrianglesDrawn)
      .arg(frame.ChartsDrawn)
      .arg(frame.PerLevel)
      .arg(frame.Selection);
  if (!frame.Animation.isEmpty())
  {
    text += "<br>" + frame.Animation.toHtmlEscaped();
  }
  return text;
}

QString tcStageSummary::Title(int stage)
{
  return QString("<b>%1</b>").arg(tcStage::Label(stage));
}

QString tcStageSummary::Failure(const QString& error)
{
  return "<font color='#b00'>" + error.toHtmlEscaped() + "</font>";
}
