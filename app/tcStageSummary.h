// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcStageSummary
 * @brief The summary trichart-viewer shows below its panels (HTML): what the shown stage made.
 *
 * Every stage's summary opens with its title and its point and cell counts; then come what the
 * stage reports (the reader's and the preparation's reports, and what to check when the prepared
 * mesh is no closed, oriented manifold), its lines and corners, its patches, the atlas's charts
 * and mip steps, the reconstruction's levels and distance to the prepared mesh, and the
 * pipeline's note (the sliver retry). The LOD stage's summary is the figures of its last frame,
 * and the animation and time that pose a skinned atlas.
 */
#ifndef tcStageSummary_h
#define tcStageSummary_h

#include <QString>

class tcStagePipeline;
struct tcLODFrame;
struct tcStageOutput;

class tcStageSummary
{
public:
  /// The summary of `stage` (not the LOD stage), which `pipeline` has just run and whose outputs
  /// are `output`; `fileName` is left out of the reports' paths but for its last part.
  static QString Stage(const tcStagePipeline& pipeline, int stage, const tcStageOutput& output,
    const QString& fileName);

  /// The LOD stage's summary of `frame`.
  static QString LOD(const tcLODFrame& frame);

  /// Just the title of `stage` (the LOD stage's summary until its first frame is drawn).
  static QString Title(int stage);

  /// The summary of a run that failed with `error`.
  static QString Failure(const QString& error);
};

#endif
