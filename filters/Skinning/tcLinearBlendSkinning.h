// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcLinearBlendSkinning
 * @brief Poses a skinned mesh at a time of one of its animations by linear blend skinning.
 *
 * The input is a mesh with the point arrays SkinIndices and SkinWeights (4 influences) and the
 * field Rig (the skeleton and animations), as tcMeshReader gives a skinned scene and
 * tcGeometryImageMesh a rebuilt skinned atlas. The output is the input with every point moved
 * to sum_k w_k M_k p, M_k the skinning matrix of joint k at Time seconds of Animation
 * (tc::skinPoints, Feng et al. 2010, 5.2: what the vertex shader does, on the CPU), and the
 * field AnimationName. Normals and other arrays are passed unchanged.
 */
#ifndef tcLinearBlendSkinning_h
#define tcLinearBlendSkinning_h

#include "TriChartSkinningModule.h"

#include <vtkPolyDataAlgorithm.h>

#include <string>

class TRICHARTSKINNING_EXPORT tcLinearBlendSkinning : public vtkPolyDataAlgorithm
{
public:
  static tcLinearBlendSkinning* New();
  vtkTypeMacro(tcLinearBlendSkinning, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The animation: its name or index in the rig; "" (the default) for the first. A name the
  /// rig does not have is an error that lists its animations.
  vtkSetStdStringFromCharMacro(Animation);
  vtkGetCharFromStdStringMacro(Animation);
  ///@}

  ///@{
  /// Seconds into the animation (held at its first and last keys outside it). Default 0.
  vtkSetMacro(Time, double);
  vtkGetMacro(Time, double);
  ///@}

protected:
  tcLinearBlendSkinning() = default;
  ~tcLinearBlendSkinning() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcLinearBlendSkinning(const tcLinearBlendSkinning&) = delete;
  void operator=(const tcLinearBlendSkinning&) = delete;

  std::string Animation;
  double Time = 0.0;
};

#endif
