// SPDX-License-Identifier: BSD-3-Clause
#include "tcStage.h"

namespace
{
const char* const kStageNames[] = { "input", "preparation", "curvature", "clusters", "features",
  "base", "patches", "atlas", "reconstruction", "lod" };
const char* const kStageLabels[] = { "Input mesh", "Preparation", "Curvature", "Spectral clusters",
  "Feature lines and corners", "Base complex (MAPS)", "Triangle patches and paths",
  "Geometry-image atlas", "Reconstruction and its error", "Level of detail (GPU)" };
static_assert(sizeof(kStageNames) / sizeof(*kStageNames) == tcStage::Count, "one name per stage");
static_assert(
  sizeof(kStageLabels) / sizeof(*kStageLabels) == tcStage::Count, "one label per stage");
}

const char* tcStage::Name(int stage)
{
  return kStageNames[stage];
}

const char* tcStage::Label(int stage)
{
  return kStageLabels[stage];
}
