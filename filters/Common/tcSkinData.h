// SPDX-License-Identifier: BSD-3-Clause
/// @file tcSkinData.h
/// A skeleton and skin weights (tc/skinning/skin.h) as VTK data: the readers' skeleton output and
/// the point arrays SkinIndices / SkinWeights.
#ifndef tcSkinData_h
#define tcSkinData_h

#include "TriChartCommonModule.h"

#include "tc/skinning/skin.h"

#include <vtkSmartPointer.h>

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
} // namespace tcvtk

#endif
