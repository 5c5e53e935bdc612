// SPDX-License-Identifier: BSD-3-Clause
#include "tcLinearBlendSkinning.h"

#include "tcMeshConversion.h"
#include "tcSkinData.h"

#include "tc/common/array_names.h"
#include "tc/common/errors.h"
#include "tc/skinning/skin.h"

#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cmath>
#include <vector>

vtkStandardNewMacro(tcLinearBlendSkinning);

int tcLinearBlendSkinning::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // 1. Input and output.
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);

  // 2. Validate: the skin arrays, the rig, a finite time.
  const std::string text = tcvtk::GetTextField(input->GetFieldData(), tc::kRig);
  const vtkIdType np = input->GetNumberOfPoints();
  tc::SkinWeights skin;
  std::string error;
  if (!tcvtk::ReadSkinArrays(input->GetPointData(), np, skin, error) || text.empty())
  {
    vtkErrorMacro("Cannot pose the mesh: it needs the point arrays "
      << tc::kSkinIndices << " and " << tc::kSkinWeights << " and the field " << tc::kRig
      << " (read a skinned scene with tcMeshReader or rebuild a skinned atlas)"
      << (error.empty() ? "" : ": ") << error << ".");
    return 0;
  }
  if (!std::isfinite(this->Time))
  {
    vtkErrorMacro("Cannot pose the mesh: Time is not a finite number of seconds.");
    return 0;
  }

  // 3 and 4. Pose with the core.
  std::vector<double> posed;
  std::string animationName;
  try
  {
    const tc::Rig rig = tc::decodeRig(text);
    const int a = tc::findAnimation(rig.animations, this->Animation);
    const tc::Animation* animation = a >= 0 ? &rig.animations[a] : nullptr;
    animationName = animation ? animation->name : "";
    std::vector<double> bind(3 * static_cast<size_t>(np));
    for (vtkIdType p = 0; p < np; ++p)
    {
      input->GetPoint(p, &bind[3 * p]);
    }
    posed = tc::skinPoints(bind, skin,
      tc::skinningMatrices(rig.skeleton, tc::jointGlobals(rig.skeleton, animation, this->Time)));
  }
  catch (const tc::InputError& e)
  {
    vtkErrorMacro("Cannot pose the mesh: " << e.what() << ".");
    return 0;
  }

  // 5. The input with the posed points and the animation's name.
  output->ShallowCopy(input);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(np);
  std::copy(posed.begin(), posed.end(), static_cast<double*>(points->GetVoidPointer(0)));
  output->SetPoints(points);
  vtkNew<vtkFieldData> fields;
  fields->ShallowCopy(input->GetFieldData());
  output->SetFieldData(fields);
  tcvtk::SetTextField(fields, tc::kAnimationName, animationName);
  return 1;
}

void tcLinearBlendSkinning::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Animation: " << this->Animation << "\n";
  os << indent << "Time: " << this->Time << "\n";
}
