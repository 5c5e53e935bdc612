// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcGLTFWriter
 * @brief Writes an atlas (tcGeometryImages' or tcAtlasReader's output) as a glTF 2.0 LOD
 * chain, .glb or .gltf by the file name's extension: one mesh per LOD, each what
 * tcGeometryImageMesh draws at that LOD's chart levels, linked by MSFT_lod with screen-coverage
 * hints from the measured errors (tc/io/gltf_export.h documents the chain and the layout).
 *
 * The file is written to a temporary name in the same folder and renamed at the end, so a
 * failed or aborted write never leaves a half-written file.
 */
#ifndef tcGLTFWriter_h
#define tcGLTFWriter_h

#include "TriChartIOModule.h"

#include "tc/io/gltf_export.h"

#include <vtkWriter.h>

#include <string>
#include <vector>

class TRICHARTIO_EXPORT tcGLTFWriter : public vtkWriter
{
public:
  static tcGLTFWriter* New();
  vtkTypeMacro(tcGLTFWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to write: .glb (binary) or .gltf (JSON, the buffer embedded).
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /// Whether the writer takes this file name (.glb or .gltf).
  static bool IsGLTFFileName(const char* path);

  enum
  {
    CHAIN_ERROR = 0,   ///< per-chart levels, the largest error growing by ErrorRatio per LOD
    CHAIN_UNIFORM = 1, ///< one level for every chart per LOD
  };
  ///@{
  /// How the LODs are chosen; default CHAIN_ERROR.
  vtkSetClampMacro(Chain, int, CHAIN_ERROR, CHAIN_UNIFORM);
  vtkGetMacro(Chain, int);
  ///@}

  enum
  {
    LAYOUT_MSFT_LOD = 0,    ///< LOD 0 in the scene, the others linked to it by MSFT_lod
    LAYOUT_NAMED_NODES = 1, ///< every LOD in the scene as TriChart_LOD<k>
  };
  ///@{
  /// How the LODs are laid out in the scene; default LAYOUT_MSFT_LOD.
  vtkSetClampMacro(Layout, int, LAYOUT_MSFT_LOD, LAYOUT_NAMED_NODES);
  vtkGetMacro(Layout, int);
  ///@}

  ///@{
  /// Growth of the largest error from one LOD to the next (CHAIN_ERROR), > 1; default 2.
  vtkSetClampMacro(ErrorRatio, double, 1.0001, 1000.0);
  vtkGetMacro(ErrorRatio, double);
  ///@}

  ///@{
  /// The most LODs written, 1 .. 64; default 16.
  vtkSetClampMacro(MaxLods, int, 1, 64);
  vtkGetMacro(MaxLods, int);
  ///@}

  ///@{
  /// The screen-coverage hints: the error in pixels an LOD may show, in a viewport this many
  /// pixels tall; defaults 1 and 1080.
  vtkSetClampMacro(ErrorPixels, double, 0.001, 1000.0);
  vtkGetMacro(ErrorPixels, double);
  vtkSetClampMacro(ViewportHeight, double, 1.0, 100000.0);
  vtkGetMacro(ViewportHeight, double);
  ///@}

  ///@{
  /// After a write: the LODs written, and each one's triangles and largest error (input units).
  int GetNumberOfLods() const { return static_cast<int>(this->Lods.size()); }
  vtkIdType GetLodTriangles(int lod) const;
  double GetLodError(int lod) const;
  double GetLodScreenCoverage(int lod) const;
  /// The diagonal of the mesh the atlas was built from (the errors' unit).
  vtkGetMacro(InputDiagonal, double);
  ///@}

protected:
  tcGLTFWriter();
  ~tcGLTFWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

private:
  tcGLTFWriter(const tcGLTFWriter&) = delete;
  void operator=(const tcGLTFWriter&) = delete;

  std::string FileName;
  int Chain = CHAIN_ERROR;      // tc::GltfExportOptions{}.chain (checked in the .cxx)
  int Layout = LAYOUT_MSFT_LOD; // tc::GltfExportOptions{}.layout
  double ErrorRatio = tc::GltfExportOptions{}.errorRatio;
  int MaxLods = tc::GltfExportOptions{}.maxLods;
  double ErrorPixels = tc::GltfExportOptions{}.errorPixels;
  double ViewportHeight = tc::GltfExportOptions{}.viewportHeight;
  double InputDiagonal = 0.0;
  std::vector<tc::GltfLod> Lods; ///< of the last write
};

#endif
