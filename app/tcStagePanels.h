// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcStagePanels
 * @brief The parameter panel of each stage of trichart-viewer: the rows of one filter, each
 * bound to that filter's setter (tcParameterPanel).
 *
 * Ranges and defaults come from the filters (their clamp macros and initializers) where the
 * filter states them; row names are the filters' property names, as in ParaView. The LOD panel
 * holds view settings, not pipeline parameters: each change redraws at once, with no Apply.
 */
#ifndef tcStagePanels_h
#define tcStagePanels_h

#include <functional>

class QWidget;
class tcBaseComplex;
class tcCurvature;
class tcFeatureRefinement;
class tcGeometryImageMesh;
class tcGeometryImages;
class tcLODView;
class tcMeshPreparation;
class tcMeshReader;
class tcParameterPanel;
class tcSpectralClustering;

class tcStagePanels
{
public:
  /// The preparation's rows, after the reader's (a terrain raster's VerticalScale).
  static tcParameterPanel* Preparation(
    tcMeshReader* reader, tcMeshPreparation* filter, QWidget* parent);
  static tcParameterPanel* Curvature(tcCurvature* filter, QWidget* parent);
  static tcParameterPanel* Clustering(tcSpectralClustering* filter, QWidget* parent);
  static tcParameterPanel* Refinement(tcFeatureRefinement* filter, QWidget* parent);
  static tcParameterPanel* BaseComplex(tcBaseComplex* filter, QWidget* parent);
  static tcParameterPanel* GeometryImages(tcGeometryImages* filter, QWidget* parent);
  static tcParameterPanel* Reconstruction(tcGeometryImageMesh* filter, QWidget* parent);

  /// The LOD view's settings, pushed to `view` once here and then at each change, with the
  /// animation box of a skinned atlas (tcAnimationControls); its "Reset camera" button calls
  /// `resetCamera`.
  static tcParameterPanel* LOD(tcLODView* view, std::function<void()> resetCamera, QWidget* parent);
};

#endif
