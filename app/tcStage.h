// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcStage
 * @brief The stages of trichart-viewer's browser, in pipeline order, with their command-line
 * names and their titles.
 *
 * No Qt: tcStagePipeline runs stages by these numbers, the window lists them.
 */
#ifndef tcStage_h
#define tcStage_h

struct tcStage
{
  enum Id
  {
    Input = 0,
    Preparation,
    Curvature,
    Clusters,
    Features,
    Base,
    Patches,
    Atlas,
    Reconstruction,
    LOD,
    Count
  };

  /// The command-line name of `stage` ("input", "preparation", "curvature", "clusters",
  /// "features", "base", "patches", "atlas", "reconstruction", "lod").
  static const char* Name(int stage);

  /// The title of `stage` in the stage list and its summary ("Input mesh", ...).
  static const char* Label(int stage);
};

#endif
