// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcGeometryImageMesh
 * @brief Rebuilds a mesh from a geometry-image atlas at one level for all charts or a level per
 * chart, stitched without cracks by eq. 8 of Feng et al. 2010 (section 6.3).
 *
 * Chart c is drawn as its grid of 2^d + 1 samples per side at its level d; on a side whose
 * neighbour is coarser, each sample snaps to the neighbour's samples (t - t mod 2^(d - m)), so
 * the finer side follows the coarser one exactly and the triangles it collapses are dropped.
 * Shared samples become one point, so the result is a closed mesh when the atlas came from one;
 * only on a seam of a resampled array (a texture seam) a point comes once per side, each with
 * its chart's values. This is the CPU reference of the GPU renderer: it draws the same vertices.
 *
 * Input: an atlas (tcGeometryImages or tcAtlasReader). Output: the mesh with cell arrays
 * ChartId and Level, point array Normals and every further atlas attribute, and point array
 * SampleChart (chart, i, j of the sample each point was read from). With a base-colour texture
 * in the atlas, TextureCoordinates are the active texture coordinates and the texture is the
 * field arrays BaseColorTexture, BaseColorTextureSize and BaseColorTextureName, as tcMeshReader
 * gives them.
 */
#ifndef tcGeometryImageMesh_h
#define tcGeometryImageMesh_h

#include "TriChartGeometryImagesModule.h"

#include <vtkPolyDataAlgorithm.h>
#include <vtkSmartPointer.h>

class vtkIntArray;

class TRICHARTGEOMETRYIMAGES_EXPORT tcGeometryImageMesh : public vtkPolyDataAlgorithm
{
public:
  static tcGeometryImageMesh* New();
  vtkTypeMacro(tcGeometryImageMesh, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The level of every chart, capped by each chart's finest level; -1: every chart at its
  /// finest level.
  vtkSetClampMacro(Level, int, -1, 20);
  vtkGetMacro(Level, int);
  ///@}

  ///@{
  /// A level per chart (one value per chart, in chart order); when set it replaces Level.
  void SetChartLevels(vtkIntArray* levels);
  vtkIntArray* GetChartLevels();
  ///@}

protected:
  tcGeometryImageMesh();
  ~tcGeometryImageMesh() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  tcGeometryImageMesh(const tcGeometryImageMesh&) = delete;
  void operator=(const tcGeometryImageMesh&) = delete;

  int Level = -1;
  vtkSmartPointer<vtkIntArray> ChartLevels;
};

#endif
