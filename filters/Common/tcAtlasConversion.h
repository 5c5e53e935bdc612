// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file tcAtlasConversion.h
 * @brief The atlas (tc::Atlas) as a VTK data object and back, losslessly.
 *
 * In the pipeline an atlas is a vtkMultiBlockDataSet:
 * - block 0 "Charts": a vtkTable with one row per chart (ChartId, MaxLevel, CornerVertices,
 *   NeighborChart, NeighborSide, FeatureSide, Partner, Rotated, Origin per image, OrientedBox,
 *   LevelError);
 * - block 1 "Images": a vtkMultiBlockDataSet with one vtkImageData per mip step (image 0 the
 *   finest), one float point array per attribute (Position, Normal, then any resampled array);
 * - block 2 "Textures", only when the atlas has textures: a vtkMultiBlockDataSet with one
 *   vtkImageData per texture, named as the texture (BaseColor), its bytes as the unsigned char
 *   point array RGBA (the active scalars, row 0 the bottom) and its file as the field
 *   TextureSource;
 * - field data of the top block: AtlasSource, InputPoints, InputTriangles, InputDiagonal.
 * The conversion copies floats and doubles bit for bit, so an atlas read from a file, shown in
 * ParaView and written again is unchanged.
 */
#ifndef tcAtlasConversion_h
#define tcAtlasConversion_h

#include "TriChartCommonModule.h"

#include "tc/gim/atlas.h"

#include <string>

class vtkMultiBlockDataSet;
class vtkDataObject;

namespace tcvtk
{
/// Fills `output` (cleared first) with the blocks and field data above.
TRICHARTCOMMON_EXPORT void FromAtlas(const tc::Atlas& atlas, vtkMultiBlockDataSet* output);

/// Reads an atlas back from a data object made by FromAtlas (or a reader). Returns false and
/// says what is missing or inconsistent in `error`; tc::validateAtlas is applied too.
TRICHARTCOMMON_EXPORT bool ToAtlas(vtkDataObject* input, tc::Atlas& atlas, std::string& error);
} // namespace tcvtk

#endif
