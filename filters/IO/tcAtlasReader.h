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
 */
#ifndef tcAtlasReader_h
#define tcAtlasReader_h

#include "TriChartIOModule.h"

#include <vtkMultiBlockDataSetAlgorithm.h>

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

  /// True if `fileName` is an OpenEXR file that holds a TriChart atlas.
  static bool CanReadFile(const char* fileName);

protected:
  tcAtlasReader();
  ~tcAtlasReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcAtlasReader(const tcAtlasReader&) = delete;
  void operator=(const tcAtlasReader&) = delete;

  std::string FileName;
};

#endif
