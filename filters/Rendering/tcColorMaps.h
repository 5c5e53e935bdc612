// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcColorMaps
 * @brief The colour maps of every TriChart picture, so that a stage looks the same wherever it
 * is shown: the viewer, the image tests and the pictures of `trichart build` (trichart.render).
 *
 * Static methods that fill a lookup table (or a colour array) from the values it will colour;
 * wrapped for Python (`trichart.tcColorMaps.DivergingColors(lut, array, 0)`), so the Python
 * pictures use these maps rather than copies of them.
 */
#ifndef tcColorMaps_h
#define tcColorMaps_h

#include "TriChartRenderingModule.h"

#include <vtkObject.h>

class vtkDataArray;
class vtkLookupTable;
class vtkUnsignedCharArray;

class TRICHARTRENDERING_EXPORT tcColorMaps : public vtkObject
{
public:
  static tcColorMaps* New();
  vtkTypeMacro(tcColorMaps, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Blue (concave) - white - red (convex), symmetric about 0, spanning the magnitude below
  /// which 95% of `component` of `values` lie (a few extreme vertices do not wash out the rest);
  /// [-1, 1] without values. For signed curvatures.
  static void DivergingColors(vtkLookupTable* lut, vtkDataArray* values, int component = 0);

  /// Well-separated colours (golden-ratio hues) for integer labels 0 .. max of `values` (one
  /// colour without values). For cluster, chart, patch and base-face ids.
  static void LabelColors(vtkLookupTable* lut, vtkDataArray* values);

  /// A rainbow (blue to red) over the range of `component` of `values`, for arrays that are
  /// neither signed curvatures nor labels (a flat range is widened by 1).
  static void RangeColors(vtkLookupTable* lut, vtkDataArray* values, int component = 0);

  /// Unit normals (#T x 3) as RGB colours in `colors` (#T x 3, each component from [-1, 1] to
  /// [0, 255]); zero normals (atlas texels no chart covers) stay dark rather than mid-grey,
  /// which a lookup table cannot do.
  static void NormalColors(vtkDataArray* normals, vtkUnsignedCharArray* colors);

protected:
  tcColorMaps() = default;
  ~tcColorMaps() override = default;

private:
  tcColorMaps(const tcColorMaps&) = delete;
  void operator=(const tcColorMaps&) = delete;
};

#endif
