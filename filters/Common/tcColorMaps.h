// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file tcColorMaps.h
 * @brief The colour maps every TriChart picture uses (viewer, image tests), so that a stage
 * looks the same wherever it is shown.
 */
#ifndef tcColorMaps_h
#define tcColorMaps_h

#include "TriChartCommonModule.h"

#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

class vtkDataArray;
class vtkLookupTable;

namespace tcvtk
{
/// Blue (concave) - white - red (convex), symmetric about 0, spanning the magnitude below which
/// 95% of `component` of `values` lie (a few extreme vertices do not wash out the rest).
TRICHARTCOMMON_EXPORT void DivergingColors(
  vtkLookupTable* lut, vtkDataArray* values, int component = 0);

/// Well-separated colours (golden-ratio hues) for integer labels 0 .. max of `values`.
TRICHARTCOMMON_EXPORT void LabelColors(vtkLookupTable* lut, vtkDataArray* values);
/// Unit normals as RGB colours (each component from [-1, 1] to [0, 255]); zero normals (atlas
/// texels no chart covers) stay dark rather than mid-grey, which a lookup table cannot do.
TRICHARTCOMMON_EXPORT vtkSmartPointer<vtkUnsignedCharArray> NormalColors(vtkDataArray* normals);
} // namespace tcvtk

#endif
