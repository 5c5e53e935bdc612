// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcMeshReader
 * @brief Reads a surface mesh from PLY (also gzip-compressed .ply.gz), OBJ, STL, OFF, VTP or
 * legacy VTK, or the surfaces of a scene file (glTF .glb/.gltf, FBX, DirectX .x, MD2) through
 * Assimp, choosing the format by the file name's extension.
 *
 * The output is the file's polygons with their point and cell arrays, unchanged; cleaning is
 * tcMeshPreparation's job. PLY and OBJ files are read by tc::readPLYFile and tc::readOBJFile
 * (normals and groups are skipped), since VTK's PLY and OBJ readers crash on truncated or
 * damaged files. A scene file gives every mesh its nodes place, with their transforms, in the
 * rest pose, and a cell array "SceneMeshId"; its bones and animations are counted in the
 * report, not applied (tc::readScene).
 *
 * What OBJ, PLY and scene files hold besides positions is kept (tc/io/mesh_file.h):
 * - point array "TextureCoordinates" (float, 2 components, the active TCoords), v = 0 at the
 *   image's bottom row, as OpenGL and VTK have it (a glTF file's top-origin v is turned into
 *   1 - v by Assimp). A vertex with several texture coordinates (a UV seam) is one point per
 *   (vertex, texture coordinate) pair; an OBJ file where some face corners have none is read
 *   without texture coordinates, with a warning;
 * - point array "Colors" (unsigned char RGBA, alpha 255 for RGB): glTF COLOR_0, PLY vertex
 *   red green blue [alpha], OBJ "v x y z r g b";
 * - the base-colour texture of the first material that has one (glTF baseColorTexture, a
 *   diffuse map, OBJ map_Kd, PLY "comment TextureFile"), embedded or a file beside the mesh,
 *   decoded (PNG, JPEG) into the field arrays "BaseColorTexture" (unsigned char RGBA, width x
 *   height tuples, row 0 = the image's bottom: texture coordinate (u, v) is texel (u width,
 *   v height)), "BaseColorTextureSize" (int, one tuple: width, height) and
 *   "BaseColorTextureName" (the file name, or "embedded:<k>"). A texture that is missing or
 *   cannot be decoded is a warning: the mesh is read without it.
 *
 * What was read (format, points, polygons, texture coordinates, vertex colours, "texture NAME
 * WxH", arrays, warnings) is in GetReport() and in the field array "ReaderReport". A missing
 * file, an unknown extension or a file that holds no polygons is an error that names the file
 * and what to do.
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
