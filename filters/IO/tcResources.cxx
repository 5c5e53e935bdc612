// SPDX-License-Identifier: BSD-3-Clause
#include "tcResources.h"

#include "tc/common/errors.h"
#include "tc/common/resources.h"
#include "tc/gim/build_memory.h"
#include "tc/io/mesh_header.h"

#include <vtkObjectFactory.h>

vtkStandardNewMacro(tcResources);

void tcResources::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaxThreads: " << tcResources::GetMaxThreads() << "\n";
  os << indent << "AvailableMemory: " << tcResources::GetAvailableMemory() << "\n";
}

bool tcResources::SetMaxThreads(int n)
{
  try
  {
    tc::setMaxThreads(n);
    return true;
  }
  catch (const tc::InputError&)
  {
    return false;
  }
}

int tcResources::GetMaxThreads()
{
  return tc::maxThreads();
}

vtkTypeInt64 tcResources::GetAvailableMemory()
{
  return tc::availableMemory();
}

void tcResources::GetMeshFileCounts(const char* fileName, vtkTypeInt64 counts[2])
{
  const tc::MeshFileCounts c = tc::readMeshFileCounts(fileName ? fileName : "");
  counts[0] = c.points;
  counts[1] = c.triangles;
}

vtkTypeInt64 tcResources::EstimateBuildMemory(vtkTypeInt64 points, vtkTypeInt64 triangles,
  vtkTypeInt64 sampleBudget, int maxLevel, vtkTypeInt64 targetFaces, vtkTypeInt64 nystromThreshold,
  double errorTarget)
{
  tc::BuildMemoryRequest request;
  request.errorTarget = errorTarget;
  request.points = points;
  request.triangles = triangles;
  request.sampleBudget = sampleBudget;
  request.maxLevel = maxLevel;
  request.targetFaces = targetFaces;
  request.nystromThreshold = nystromThreshold;
  try
  {
    return tc::estimateBuildMemory(request).peak();
  }
  catch (const tc::InputError&)
  {
    return -1;
  }
}
