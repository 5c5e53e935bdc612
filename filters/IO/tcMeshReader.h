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
 * Skinned and animated scenes, and deforming sequences, are read over time:
 * - a scene's skeleton (tc::readScene) is on output port 1, a point per joint at its frame's
 *   origin with a line to its parent (point arrays JointNames, JointParent,
 *   InverseBindMatrices, JointTransforms), and the mesh has the point arrays SkinIndices and
 *   SkinWeights (the 4 largest influences). The reader announces the key times of the chosen
 *   Animation (TIME_STEPS and TIME_RANGE, in seconds); a time request returns the mesh and the
 *   skeleton posed by linear blend skinning at that time (any time, between keys too), and no
 *   time request (or BindPose on) the rest pose;
 * - a deforming sequence (tc::readSequence): a folder of OBJ/PLY/OFF frames with one
 *   connectivity, a glob pattern naming them, or an MD2 file's vertex keyframes. Frame k is
 *   at time k; a time request returns the frame at the largest time not after it. With
 *   ProxyBones, frame 0 also carries a linear blend skin fitted to the frames.
 *
 * A raster of heights (tc::readHeightField through GDAL: GeoTIFF .tif/.tiff, ESRI ASCII grid
 * .asc, SRTM .hgt, USGS .dem, PGM/PNG/BMP height maps) is read as a terrain: a regular grid of
 * two triangles per square of cells with data (no-data cells are holes), in metres relative to
 * the first cell's centre, heights times VerticalScale, with the point array "Elevation" (the
 * height read) and the field arrays "GeoOrigin" (that centre in the file's coordinates, double)
 * and "GeoCRS" (the file's coordinate system as WKT, when it has one). Spacing comes from the
 * file's geotransform or a JSON side file; degrees are converted to metres.
 *
 * What was read (format, points, polygons, texture coordinates, vertex colours, "texture NAME
 * WxH", arrays, warnings) is in GetReport() and in the field array "ReaderReport". A missing
 * file, an unknown extension or a file that holds no polygons is an error that names the file
 * and what to do.
 */
#ifndef tcMeshReader_h
#define tcMeshReader_h

#include "TriChartIOModule.h"

#include "tc/io/height_field_io.h" // for the default of VerticalScale

#include <vtkPolyDataAlgorithm.h>

#include <memory>
#include <string>

class tcMeshReaderCache;

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

  ///@{
  /// The animation that poses a scene at the requested times: its name or its index in the
  /// file; "" (the default) for the first. A name the file does not have is an error that
  /// lists the file's animations.
  vtkSetStdStringFromCharMacro(Animation);
  vtkGetCharFromStdStringMacro(Animation);
  ///@}

  ///@{
  /// Read a skinned or animated scene, or a sequence, in its rest pose (frame 0) and announce
  /// no time steps, so a pipeline downstream runs once. Off by default.
  vtkSetMacro(BindPose, bool);
  vtkGetMacro(BindPose, bool);
  vtkBooleanMacro(BindPose, bool);
  ///@}

  ///@{
  /// Fit proxy bones to a sequence of several frames (tc::fitProxyBones, Feng et al. 4.3): its
  /// rest frame then carries SkinIndices, SkinWeights and the field Rig (the fitted frames as
  /// the animation "frames"), so it builds into a skinned atlas. On by default.
  vtkSetMacro(ProxyBones, bool);
  vtkGetMacro(ProxyBones, bool);
  vtkBooleanMacro(ProxyBones, bool);
  ///@}

  ///@{
  /// Heights of a height field (a terrain raster) are multiplied by this: vertical
  /// exaggeration, or a unit conversion. > 0; 1 by default.
  vtkSetMacro(VerticalScale, double);
  vtkGetMacro(VerticalScale, double);
  ///@}
  /// The animations of the file last read (after UpdateInformation), in the file's order.
  int GetNumberOfAnimations() const;
  const char* GetAnimationName(int index) const;

  /// One line per fact of the last read: format, counts, arrays.
  const char* GetReport() const { return this->Report.c_str(); }

  /// True if the extension of `fileName` is one this reader handles (case-insensitive).
  static bool CanReadFile(const char* fileName);

  /// The extensions this reader handles, space-separated, without dots ("ply ply.gz obj ...").
  static const char* GetSupportedExtensions();

protected:
  tcMeshReader();
  ~tcMeshReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcMeshReader(const tcMeshReader&) = delete;
  void operator=(const tcMeshReader&) = delete;

  /// Reads the file into Cache unless it holds this file as it is on disk; false with an error
  /// raised when the file cannot be read (or the read was aborted).
  bool Load();

  std::string FileName;
  std::string Animation;
  bool BindPose = false;
  bool ProxyBones = true;
  double VerticalScale = tc::HeightFieldOptions{}.verticalScale;
  std::string Report;
  std::unique_ptr<tcMeshReaderCache> Cache;
};

#endif
