// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcAtlasWriter
 * @brief Writes the pipeline's atlas multiblock (tcGeometryImages' output) as one OpenEXR
 * multi-part file: float32 images, one part per attribute and mip step (coarsest first, each
 * holding only the samples that the coarser steps do not), and the chart table as
 * zlib-compressed JSON in the header; docs/atlas-format.md documents the layout.
 *
 * The file is written to a temporary name in the same folder and renamed at the end, so a
 * failed or aborted write never leaves a half-written atlas (and keeps an older file intact).
 */
#ifndef tcAtlasWriter_h
#define tcAtlasWriter_h

#include "TriChartIOModule.h"

#include <vtkWriter.h>

#include <string>

class TRICHARTIO_EXPORT tcAtlasWriter : public vtkWriter
{
public:
  static tcAtlasWriter* New();
  vtkTypeMacro(tcAtlasWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The atlas file to write (.exr).
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /// Whether the writer takes this file name (.exr), so that a caller can refuse a wrong one
  /// before building the atlas.
  static bool IsAtlasFileName(const char* path);

protected:
  tcAtlasWriter();
  ~tcAtlasWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

private:
  tcAtlasWriter(const tcAtlasWriter&) = delete;
  void operator=(const tcAtlasWriter&) = delete;

  std::string FileName;
};

#endif
