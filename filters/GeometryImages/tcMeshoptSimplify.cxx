// SPDX-License-Identifier: BSD-3-Clause
#include "tcMeshoptSimplify.h"

#include "tcMeshConversion.h"

#include "tc/metrics/qem_peer.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

vtkStandardNewMacro(tcMeshoptSimplify);

int tcMeshoptSimplify::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  tc::TriMesh mesh;
  std::string error;
  if (!input || !tcvtk::ToTriMesh(input, mesh, error))
  {
    vtkErrorMacro("Cannot simplify: " << (input ? error : "no input") << ".");
    return 0;
  }
  try
  {
    tcvtk::FromTriMesh(tc::simplifyQem(mesh, this->TargetTriangles), output);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot simplify: " << e.what());
    return 0;
  }
  return 1;
}

void tcMeshoptSimplify::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TargetTriangles: " << this->TargetTriangles << "\n";
}
