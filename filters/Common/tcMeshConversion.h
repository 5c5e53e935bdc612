// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file tcMeshConversion.h
 * @brief Conversions between vtkPolyData and the core's flat meshes, and the bridge from a
 * vtkAlgorithm's progress/abort to tc::Progress. Every TriChart filter uses these, so no
 * filter converts by hand.
 */
#ifndef tcMeshConversion_h
#define tcMeshConversion_h

#include "TriChartCommonModule.h"

#include "tc/common/mesh.h"
#include "tc/common/progress.h"
#include "tc/gim/base_complex.h"
#include "tc/gim/path_tracing.h"

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <cstdint>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkCellArray;
class vtkDataArray;
class vtkDataSetAttributes;
class vtkFieldData;
class vtkUnsignedCharArray;
class vtkPolyData;

namespace tcvtk
{
/// Polygons and triangle strips of `input` as a polygon soup (strips become triangles).
/// `polygonCell` receives, per soup polygon, the id of the vtkPolyData cell it came from.
/// Vertices and lines are not surface elements and are counted in `ignoredCells`.
TRICHARTCOMMON_EXPORT tc::PolygonSoup ToPolygonSoup(
  vtkPolyData* input, std::vector<int64_t>& polygonCell, int64_t& ignoredCells);

/// The triangles of `input`; returns false and says why in `error` when there is no input
/// ("no input") or it has cells that are not triangles (the message tells the user to run
/// tcMeshPreparation first).
TRICHARTCOMMON_EXPORT bool ToTriMesh(vtkPolyData* input, tc::TriMesh& mesh, std::string& error);

/// Sets points (double precision) and triangles of `output` from a core mesh.
TRICHARTCOMMON_EXPORT void FromTriMesh(const tc::TriMesh& mesh, vtkPolyData* output);

/// Sets points and polygons of `output` from a polygon soup (ids are not validated here).
TRICHARTCOMMON_EXPORT void FromPolygonSoup(const tc::PolygonSoup& soup, vtkPolyData* output);

/// Polylines over vertices of `mesh`: path k visits ids[offsets[k] .. offsets[k+1]). `output`
/// gets only the points used, with point array InputPointId (their ids in `mesh`). With
/// offsets {0, 1, 2, ...} the paths are single vertices and become vertex cells instead.
TRICHARTCOMMON_EXPORT void FromVertexPaths(const tc::TriMesh& mesh,
  const std::vector<int64_t>& offsets, const std::vector<int32_t>& ids, vtkPolyData* output,
  bool asVertices = false);

/// A new vtkCellArray with these offsets (#cells + 1) and connectivity (point ids, back to back).
TRICHARTCOMMON_EXPORT vtkSmartPointer<vtkCellArray> MakeCellArray(
  const std::vector<int64_t>& offsets, const std::vector<int64_t>& connectivity);

/// A new double array named `name` holding `values` (#tuples x components, interleaved).
TRICHARTCOMMON_EXPORT vtkSmartPointer<vtkDataArray> MakeArray(
  const char* name, int components, const std::vector<double>& values);

/// A new integer array from `values`: (un)signed char for 1-byte T, int for 4, vtkIdType for 8.
template <typename T>
vtkSmartPointer<vtkDataArray> MakeIntArray(const char* name, const std::vector<T>& values);

/// A new int array named `name` of #values / components tuples (interleaved), for the arrays of
/// index pairs and triples (SteinerEdge, FeatureEdges, SampleChart).
TRICHARTCOMMON_EXPORT vtkSmartPointer<vtkDataArray> MakeIntTuples(
  const char* name, int components, const std::vector<int32_t>& values);

/// Copies the array `name` of `attributes` (point or cell data) into `values` as doubles.
/// Returns false and says which array is missing or has the wrong size in `error`.
TRICHARTCOMMON_EXPORT bool ReadArray(vtkDataSetAttributes* attributes, const char* name,
  vtkIdType tuples, int components, std::vector<double>& values, std::string& error);

/// The same for integer arrays (ids, flags); values are rounded to the nearest integer.
template <typename T>
bool ReadIntArray(vtkDataSetAttributes* attributes, const char* name, vtkIdType tuples,
  std::vector<T>& values, std::string& error);

/// ReadIntArray for an array a stage uses when present: true with `values` empty when
/// `attributes` has no array `name`; false, saying why in `error`, when it has one of the wrong
/// size.
template <typename T>
bool ReadOptionalIntArray(vtkDataSetAttributes* attributes, const char* name, vtkIdType tuples,
  std::vector<T>& values, std::string& error);

/// Adds a string array `name` to `fd`, one line of `text` per value.
TRICHARTCOMMON_EXPORT void SetTextField(
  vtkFieldData* fd, const char* name, const std::string& text);

/// Reads back a text field written by SetTextField ("" when absent), each line ended by "\n".
TRICHARTCOMMON_EXPORT std::string GetTextField(vtkFieldData* fd, const char* name);

/// The first line of a text field, without its end ("" when absent): a one-line field such as
/// a name.
TRICHARTCOMMON_EXPORT std::string GetTextLine(vtkFieldData* fd, const char* name);

/// Adds a base-colour texture as tcMeshReader gives it: the field arrays BaseColorTexture
/// (`rgba`, 4 unsigned chars per texel, width x height tuples, row 0 the bottom),
/// BaseColorTextureSize (one tuple: width, height) and BaseColorTextureName (one value: `name`).
TRICHARTCOMMON_EXPORT void AddBaseColorTextureFields(
  vtkFieldData* fd, vtkUnsignedCharArray* rgba, int width, int height, const std::string& name);

/// Adds (or replaces) the int field array `name` of #values / components tuples to `fd`.
TRICHARTCOMMON_EXPORT void AddIntField(
  vtkFieldData* fd, const char* name, int components, const std::vector<int32_t>& values);

/// Adds the base complex of `base` (BaseVertexIds, BaseTriangles #Fb x 3, BaseEdgeIsFeature
/// #Fb x 3) to `fd` as field arrays.
TRICHARTCOMMON_EXPORT void AddBaseComplexFields(
  const tc::BaseComplexResult& base, vtkFieldData* fd);

/// The base complex and MAPS parameterization carried by tcBaseComplex's second output: field
/// arrays as AddBaseComplexFields writes them, point arrays BaseFaceId and BaseBarycentric.
/// Returns false and says what is missing in `error`.
TRICHARTCOMMON_EXPORT bool ReadBaseComplex(
  vtkPolyData* parameterized, tc::BaseComplexResult& base, std::string& error);

/// The split mesh, paths and base complex carried by tcPathTracing's first output (point
/// arrays InputPointId, SteinerEdge, SteinerParameter; cell arrays PatchId, InputCellId; field
/// arrays of the base complex and the paths). `base` gets baseVertices, baseTriangles and
/// baseEdgeIsFeature only. Returns false and says what is missing in `error`.
TRICHARTCOMMON_EXPORT bool ReadPatchMesh(
  vtkPolyData* patches, tc::PatchMesh& mesh, tc::BaseComplexResult& base, std::string& error);

/// Progress of the core reported through `algorithm`'s UpdateProgress (ParaView's progress
/// bar) and aborted when its AbortExecute flag is set.
TRICHARTCOMMON_EXPORT tc::Progress MakeProgress(vtkAlgorithm* algorithm);
} // namespace tcvtk

#endif
