// SPDX-License-Identifier: BSD-3-Clause
/// @file tcSkinData.h
/// A skeleton and skin weights (tc/skinning/skin.h) as VTK data: the readers' skeleton output and
/// the point arrays SkinIndices / SkinWeights.
#ifndef tcSkinData_h
#define tcSkinData_h

#include "TriChartCommonModule.h"

#include "tc/skinning/skin.h"

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <string>
#include <vector>

class vtkPointData;
class vtkPolyData;

namespace tcvtk
{
/// The skeleton posed by `globals` (tc::jointGlobals): a point per joint at its frame's origin,
/// a line from each joint to its parent, and the point arrays JointNames, JointParent,
/// InverseBindMatrices and JointTransforms (row-major 4 x 4).
TRICHARTCOMMON_EXPORT vtkSmartPointer<vtkPolyData> SkeletonPolyData(
  const tc::Skeleton& skeleton, const std::vector<tc::Matrix4>& globals);

/// Adds the point arrays SkinIndices (int, 4 components) and SkinWeights (float, 4) of `skin`.
TRICHARTCOMMON_EXPORT void AddSkinArrays(vtkPointData* pointData, const tc::SkinWeights& skin);

/// The skin of `points` points from the point arrays SkinIndices and SkinWeights into `skin`;
/// false with `error` saying what is missing or wrong (an absent pair is "": not skinned).
TRICHARTCOMMON_EXPORT bool ReadSkinArrays(
  vtkPointData* pointData, vtkIdType points, tc::SkinWeights& skin, std::string& error);
} // namespace tcvtk

#endif
