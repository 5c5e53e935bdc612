// SPDX-License-Identifier: BSD-3-Clause
#include "tcSkinData.h"

#include "tcMeshConversion.h"

#include "tc/common/array_names.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

#include <algorithm>

namespace tcvtk
{
namespace
{
vtkSmartPointer<vtkDoubleArray> MatrixArray(const char* name, vtkIdType n)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(16);
  array->SetNumberOfTuples(n);
  return array;
}
} // namespace

vtkSmartPointer<vtkPolyData> SkeletonPolyData(
  const tc::Skeleton& skeleton, const std::vector<tc::Matrix4>& globals)
{
  const vtkIdType n = static_cast<vtkIdType>(skeleton.joints.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkStringArray> names;
  names->SetName(tc::kJointNames);
  names->SetNumberOfValues(n);
  vtkNew<vtkIntArray> parents;
  parents->SetName(tc::kJointParent);
  parents->SetNumberOfValues(n);
  auto inverseBind = MatrixArray(tc::kInverseBindMatrices, n);
  auto transforms = MatrixArray(tc::kJointTransforms, n);
  for (vtkIdType j = 0; j < n; ++j)
  {
    const tc::Joint& joint = skeleton.joints[j];
    const tc::Matrix4& global = globals[j];
    points->SetPoint(j, global[3], global[7], global[11]);
    names->SetValue(j, joint.name);
    parents->SetValue(j, joint.parent);
    std::copy(joint.inverseBind.begin(), joint.inverseBind.end(), inverseBind->GetPointer(16 * j));
    std::copy(global.begin(), global.end(), transforms->GetPointer(16 * j));
    if (joint.parent >= 0)
    {
      const vtkIdType ends[2] = { joint.parent, j };
      lines->InsertNextCell(2, ends);
    }
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(points);
  out->SetLines(lines);
  out->GetPointData()->AddArray(names);
  out->GetPointData()->AddArray(parents);
  out->GetPointData()->AddArray(inverseBind);
  out->GetPointData()->AddArray(transforms);
  return out;
}

void AddSkinArrays(vtkPointData* pointData, const tc::SkinWeights& skin)
{
  const vtkIdType n = static_cast<vtkIdType>(skin.joints.size() / tc::kMaxInfluences);
  vtkNew<vtkIntArray> joints;
  joints->SetName(tc::kSkinIndices);
  joints->SetNumberOfComponents(tc::kMaxInfluences);
  joints->SetNumberOfTuples(n);
  std::copy(skin.joints.begin(), skin.joints.end(), joints->GetPointer(0));
  vtkNew<vtkFloatArray> weights;
  weights->SetName(tc::kSkinWeights);
  weights->SetNumberOfComponents(tc::kMaxInfluences);
  weights->SetNumberOfTuples(n);
  std::copy(skin.weights.begin(), skin.weights.end(), weights->GetPointer(0));
  pointData->AddArray(joints);
  pointData->AddArray(weights);
}

bool ReadSkinArrays(
  vtkPointData* pointData, vtkIdType points, tc::SkinWeights& skin, std::string& error)
{
  error.clear();
  if (!pointData->GetArray(tc::kSkinIndices) && !pointData->GetArray(tc::kSkinWeights))
  {
    return false;
  }
  std::vector<double> joints, weights;
  if (!ReadArray(pointData, tc::kSkinIndices, points, tc::kMaxInfluences, joints, error) ||
    !ReadArray(pointData, tc::kSkinWeights, points, tc::kMaxInfluences, weights, error))
  {
    return false;
  }
  skin = tc::SkinWeights();
  skin.joints.assign(joints.begin(), joints.end());
  skin.weights.assign(weights.begin(), weights.end());
  return true;
}
} // namespace tcvtk
