// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcResources
 * @brief The machine's resources for the faces (CLI, Python, viewer): the thread cap of the
 * core's parallel loops, the available memory, the counts a mesh file declares and the memory
 * estimate of a build (tc/common/resources.h, tc/io/mesh_header.h, tc/gim/build_memory.h).
 */
#ifndef tcResources_h
#define tcResources_h

#include "TriChartIOModule.h"

#include <vtkObject.h>

class TRICHARTIO_EXPORT tcResources : public vtkObject
{
public:
  static tcResources* New();
  vtkTypeMacro(tcResources, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Caps the threads of every TriChart stage of the process at n (0: one per core); false,
  /// with nothing changed, for n outside 0 .. 4096.
  static bool SetMaxThreads(int n);
  /// The threads a stage may use now.
  static int GetMaxThreads();
  /// Bytes the system can give a new computation (MemAvailable); 0 when it does not say.
  static vtkTypeInt64 GetAvailableMemory();

  /// counts = {points, triangles} that the mesh file declares, -1 where it does not say.
  static void GetMeshFileCounts(const char* fileName, vtkTypeInt64 counts[2]);

  /// The estimated peak memory in bytes of the static pipeline on a mesh of these counts
  /// (sampleBudget and errorTarget as tcGeometryImages's), above what the process holds
  /// before; -1 for negative counts or a maxLevel outside 0 .. 12.
  static vtkTypeInt64 EstimateBuildMemory(vtkTypeInt64 points, vtkTypeInt64 triangles,
    vtkTypeInt64 sampleBudget, int maxLevel, vtkTypeInt64 targetFaces,
    vtkTypeInt64 nystromThreshold, double errorTarget);

protected:
  tcResources() = default;
  ~tcResources() override = default;

private:
  tcResources(const tcResources&) = delete;
  void operator=(const tcResources&) = delete;
};

#endif
