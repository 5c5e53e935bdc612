// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcMeshReader
 * @brief Reads a surface mesh from PLY (also gzip-compressed .ply.gz), OBJ, STL, OFF, VTP or
 * legacy VTK, or the surfaces of a scene file (glTF .glb/.gltf, FBX, DirectX .x, MD2) through
 * Assimp, choosing the format by the file name's extension.
 *
 * The output is the file's polygons with their point and cell arrays, unchanged; cleaning is
 * tcMeshPreparation's job. PLY and OBJ files are read by tc::readPLY and tc::readOBJ
 * (positions and faces; other properties, texture coordinates, normals and groups are
 * skipped), since VTK's PLY and OBJ readers crash on truncated or damaged files. A scene file
 * gives every mesh its nodes place, with their transforms, in the rest pose, and a cell array
 * "SceneMeshId"; its bones and animations are counted in the report, not applied
 * (tc::readScene). What was read (format, points, polygons, arrays) is in GetReport() and in
 * the field array "ReaderReport". A missing file, an unknown extension or a file that
 * holds no polygons is an error that names the file and what to do.
 */
#ifndef tcMeshReader_h
#define tcMeshReader_h

#include "TriChartIOModule.h"

#include <vtkPolyDataAlgorithm.h>

#include <string>

class TRICHARTIO_EXPORT tcMeshReader : public vtkPolyDataAlgorithm
{
public:
  static tcMeshReader* New();
  vtkTypeMacro(tcMeshReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /// One line per fact of the last read: format, counts, arrays.
  const char* GetReport() const { return this->Report.c_str(); }

  /// True if the extension of `fileName` is one this reader handles (case-insensitive).
  static bool CanReadFile(const char* fileName);

  /// The extensions this reader handles, space-separated, without dots ("ply ply.gz obj ...").
  static const char* GetSupportedExtensions();

protected:
  tcMeshReader();
  ~tcMeshReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcMeshReader(const tcMeshReader&) = delete;
  void operator=(const tcMeshReader&) = delete;

  std::string FileName;
  std::string Report;
};

#endif
