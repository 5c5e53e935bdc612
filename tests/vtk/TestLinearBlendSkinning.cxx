// SPDX-License-Identifier: BSD-3-Clause
// tcLinearBlendSkinning on a known answer: a strip of three points, one on each of two joints
// of an arm and one blended half-way, the second joint turning a quarter about z over a
// second; then the errors a user meets (no skin arrays, an animation the rig lacks).
#include "tcLinearBlendSkinning.h"
#include "tcMeshConversion.h"
#include "tcTestUtilities.h"

#include "tc/common/array_names.h"
#include "tc/skinning/skin.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cmath>
#include <string>

namespace
{
/// Two joints: a root, and a child one unit along x turning about z by a quarter over 1 s.
tc::Rig ArmRig()
{
  tc::Rig rig;
  rig.skeleton.joints.resize(2);
  rig.skeleton.joints[0].name = "root";
  rig.skeleton.joints[0].restLocal = tc::identityMatrix();
  rig.skeleton.joints[0].inverseBind = tc::identityMatrix();
  tc::Joint& child = rig.skeleton.joints[1];
  child.name = "child";
  child.parent = 0;
  child.restLocal = tc::identityMatrix();
  child.restLocal[3] = 1.0;
  child.inverseBind = tc::identityMatrix();
  child.inverseBind[3] = -1.0;
  tc::Animation turn;
  turn.name = "turn";
  turn.duration = 1.0;
  tc::JointTrack track;
  track.joint = 1;
  track.rotationTimes = { 0.0, 1.0 };
  track.rotations = { { 1, 0, 0, 0 }, { std::sqrt(0.5), 0, 0, std::sqrt(0.5) } };
  turn.tracks.push_back(track);
  rig.animations.push_back(turn);
  return rig;
}

/// Three points at (2, 0, 0) as one triangle: on the child, on the root, blended half-way.
vtkSmartPointer<vtkPolyData> SkinnedStrip()
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  for (int p = 0; p < 3; ++p)
  {
    points->InsertNextPoint(2.0, 0.0, 0.0);
  }
  mesh->SetPoints(points);
  vtkNew<vtkCellArray> triangles;
  const vtkIdType ids[3] = { 0, 1, 2 };
  triangles->InsertNextCell(3, ids);
  mesh->SetPolys(triangles);
  vtkNew<vtkIntArray> joints;
  joints->SetName(tc::kSkinIndices);
  joints->SetNumberOfComponents(4);
  vtkNew<vtkFloatArray> weights;
  weights->SetName(tc::kSkinWeights);
  weights->SetNumberOfComponents(4);
  const int j[3][4] = { { 1, 0, 0, 0 }, { 0, 0, 0, 0 }, { 0, 1, 0, 0 } };
  const float w[3][4] = { { 1, 0, 0, 0 }, { 1, 0, 0, 0 }, { 0.5f, 0.5f, 0, 0 } };
  for (int p = 0; p < 3; ++p)
  {
    joints->InsertNextTypedTuple(j[p]);
    weights->InsertNextTypedTuple(w[p]);
  }
  mesh->GetPointData()->AddArray(joints);
  mesh->GetPointData()->AddArray(weights);
  tcvtk::SetTextField(mesh->GetFieldData(), tc::kRig, tc::encodeRig(ArmRig()));
  return mesh;
}

void KeepFirst(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* text = static_cast<std::string*>(clientData);
  if (callData && text->empty())
  {
    *text = static_cast<const char*>(callData);
  }
}

/// The error `filter` raises on `input` ("" for none).
std::string ErrorOn(tcLinearBlendSkinning* filter, vtkPolyData* input)
{
  std::string error;
  vtkNew<vtkCallbackCommand> catcher;
  catcher->SetCallback(KeepFirst);
  catcher->SetClientData(&error);
  filter->SetInputData(input);
  const unsigned long tag = filter->AddObserver(vtkCommand::ErrorEvent, catcher);
  filter->Update();
  filter->RemoveObserver(tag);
  return error;
}
} // namespace

int TestLinearBlendSkinning(int, char*[])
{
  tctest::Checker check;
  vtkNew<tcLinearBlendSkinning> pose;
  pose->SetInputData(SkinnedStrip());
  pose->SetTime(1.0);
  pose->Update();
  vtkPolyData* posed = pose->GetOutput();
  double p[3][3];
  for (int k = 0; k < 3; ++k)
  {
    posed->GetPoint(k, p[k]);
  }
  // The child's point turns a quarter about (1, 0, 0); the root's stays; the blend half-way.
  TC_CHECK(check, std::abs(p[0][0] - 1.0) < 1e-12 && std::abs(p[0][1] - 1.0) < 1e-12);
  TC_CHECK(check, p[1][0] == 2.0 && p[1][1] == 0.0);
  TC_CHECK(check, std::abs(p[2][0] - 1.5) < 1e-12 && std::abs(p[2][1] - 0.5) < 1e-12);
  TC_CHECK(check, tcvtk::GetTextField(posed->GetFieldData(), tc::kAnimationName) == "turn\n");
  TC_CHECK(check, tcvtk::GetTextLine(posed->GetFieldData(), tc::kAnimationName) == "turn");
  // Half-way in time, an eighth of a turn; by name as by index.
  pose->SetTime(0.5);
  pose->SetAnimation("turn");
  pose->Update();
  pose->GetOutput()->GetPoint(0, p[0]);
  TC_CHECK(check, std::abs(p[0][0] - (1.0 + std::sqrt(0.5))) < 1e-12);

  // The errors: an animation the rig lacks, a mesh without the skin arrays.
  pose->SetAnimation("wave");
  TC_CHECK(check, ErrorOn(pose, SkinnedStrip()).find("'turn' (0)") != std::string::npos);
  pose->SetAnimation("");
  vtkNew<vtkPolyData> bare;
  bare->ShallowCopy(SkinnedStrip());
  bare->GetPointData()->RemoveArray(tc::kSkinWeights);
  TC_CHECK(check, ErrorOn(pose, bare).find(tc::kSkinWeights) != std::string::npos);
  return check.failures == 0 ? 0 : 1;
}
