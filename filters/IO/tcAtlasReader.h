// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcAtlasReader
 * @brief Reads a TriChart atlas (an OpenEXR multi-part file of triangular geometry images with
 * its chart table as JSON) into the pipeline's atlas multiblock.
 *
 * The output is block 0 "Charts" (vtkTable) and block 1 "Images" (one vtkImageData per mip
 * step), as tcGeometryImages makes it (see tcAtlasConversion.h). Every float is read back bit
 * for bit. A missing, truncated, corrupt or foreign file is an error that names the file and
 * what is wrong.
 *
 * A skinned atlas (one with a rig) announces the key times of its Animation as TIME_STEPS and
 * TIME_RANGE in seconds, as tcMeshReader does for the file it was built from, and gives each
 * requested time as DATA_TIME_STEP with the animation's name (field AnimationName): the atlas
 * itself does not change with time, a renderer (tcLODMapper) poses it. The file is read once per
 * file name and modification time; a new time costs no read.
 */
#ifndef tcAtlasReader_h
#define tcAtlasReader_h

#include "TriChartIOModule.h"

#include <vtkMultiBlockDataSetAlgorithm.h>

#include <memory>
#include <string>

class TRICHARTIO_EXPORT tcAtlasReader : public vtkMultiBlockDataSetAlgorithm
{
public:
  static tcAtlasReader* New();
  vtkTypeMacro(tcAtlasReader, vtkMultiBlockDataSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The atlas file to read (.exr).
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// The animation of a skinned atlas's rig whose key times are announced: its name, or its
  /// index as digits; "" (default) the first. An unknown name is an error that lists them.
  vtkSetStdStringFromCharMacro(Animation);
  vtkGetCharFromStdStringMacro(Animation);
  ///@}

  /// True if `fileName` is an OpenEXR file that holds a TriChart atlas.
  static bool CanReadFile(const char* fileName);

protected:
  tcAtlasReader();
  ~tcAtlasReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcAtlasReader(const tcAtlasReader&) = delete;
  void operator=(const tcAtlasReader&) = delete;

  bool ReadCached();

  std::string FileName;
  std::string Animation;
  struct Cache;
  std::unique_ptr<Cache> Cached;
};

#endif
