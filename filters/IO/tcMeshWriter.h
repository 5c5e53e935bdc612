// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcMeshWriter
 * @brief Writes a mesh (vtkPolyData) in the format its file name's extension names: .vtp (VTK
 * XML, binary), .vtk (legacy VTK, binary), .ply (binary), .obj, .stl (binary, triangles only)
 * or .off (ASCII, triangles only, every coordinate read back bit for bit). Any other extension
 * is refused with the list of these, and nothing is written.
 *
 * The file is written to a temporary name in the same folder and renamed at the end, so a
 * failed write never leaves a half-written mesh (and keeps an older file intact). The one place
 * the project chooses a mesh format by name: the command line and the viewer write through it.
 */
#ifndef tcMeshWriter_h
#define tcMeshWriter_h

#include "TriChartIOModule.h"

#include <vtkWriter.h>

#include <string>

class vtkPolyData;

class TRICHARTIO_EXPORT tcMeshWriter : public vtkWriter
{
public:
  static tcMeshWriter* New();
  vtkTypeMacro(tcMeshWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The mesh file to write; its extension (any case) chooses the format.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /// Whether the writer takes this file name, so that a caller can refuse a wrong one before
  /// the work.
  static bool IsMeshFileName(const char* path);

  /// The extensions it writes, lower case with their dots, space-separated: ".vtp .vtk .ply
  /// .obj .stl .off".
  static const char* GetSupportedExtensions();

protected:
  tcMeshWriter();
  ~tcMeshWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

private:
  tcMeshWriter(const tcMeshWriter&) = delete;
  void operator=(const tcMeshWriter&) = delete;

  bool WriteFile(vtkPolyData* mesh, const std::string& extension);

  std::string FileName;
};

#endif
