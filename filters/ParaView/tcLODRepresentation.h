// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcLODRepresentation
 * @brief ParaView representation that draws an atlas with per-chart view-dependent level of
 * detail through tcLODMapper (Feng et al. 2010, section 6).
 *
 * Input: an atlas (tcAtlasReader, tcGeometryImages). In ParaView it is the "TriChart LOD"
 * representation type of the geometry representation (tcLODRepresentation.xml). The data goes
 * to the render view as ParaView 5.11 representations deliver it: the atlas is the piece given
 * to vtkPVView::SetPiece in REQUEST_UPDATE, with the mapper's bounds given to
 * vtkPVRenderView::SetGeometryBounds; in REQUEST_RENDER the mapper draws the delivered piece
 * (vtkPVView::GetDeliveredPiece). The level of detail is chosen per frame by the mapper, so the
 * view's own decimated LOD is not used.
 *
 * One converted atlas per process: the drawing mapper converts the input in RequestData (to
 * validate it and measure its bounds) and keeps drawing that conversion when the delivered
 * piece is this process's own atlas (builtin session, rendering on a server). In client-server
 * mode the client has no input; the server delivers the atlas (ParaView moves it in VTK's
 * legacy format), and the client's mapper converts what arrives. Every process delivers a
 * multiblock, an empty one when there is nothing to draw, so that the delivery manager moves
 * the data on all of them alike.
 *
 * Input that is not an atlas is reported through vtkErrorMacro, with what is missing, and
 * nothing is drawn; tcGeometryImageMesh (TriChart Geometry Image Mesh) shows such data as a mesh
 * instead.
 *
 * Properties forwarded to the mapper: LODBias, ErrorTarget, FreezeLOD, ColorMode,
 * ColorAttribute; to the actor's property: Wireframe, Opacity, Ambient, Diffuse, DiffuseColor.
 * Statistics of the last frame: GetTrianglesDrawn, GetChartsDrawn.
 */
#ifndef tcLODRepresentation_h
#define tcLODRepresentation_h

#include "TriChartParaViewModule.h"
#include "tcLODMapper.h" // for the mapper held by vtkNew

#include <vtkActor.h>             // for the actor held by vtkNew
#include <vtkMultiBlockDataSet.h> // for the empty piece held by vtkNew
#include <vtkNew.h>
#include <vtkPVDataRepresentation.h>
#include <vtkSmartPointer.h>

#include <string>
#include <utility>

class vtkDataObject;

class TRICHARTPARAVIEW_EXPORT tcLODRepresentation : public vtkPVDataRepresentation
{
public:
  static tcLODRepresentation* New();
  vtkTypeMacro(tcLODRepresentation, vtkPVDataRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The view passes: deliver the atlas and its bounds (REQUEST_UPDATE), connect the mapper to
  /// the delivered piece (REQUEST_RENDER).
  int ProcessViewRequest(
    vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo) override;

  /// Shows or hides the actor with the representation.
  void SetVisibility(bool visible) override;

  ///@{
  /// Levels added to every chosen level (tcLODMapper::SetLODBias). Default 0.
  void SetLODBias(double bias);
  double GetLODBias();
  ///@}

  ///@{
  /// Screen-space error target in pixels, 0 chooses by projected area
  /// (tcLODMapper::SetErrorTarget). Default 0.
  void SetErrorTarget(double pixels);
  double GetErrorTarget();
  ///@}

  ///@{
  /// Keep the last frame's levels while the camera moves (tcLODMapper::SetFreezeLOD). Default
  /// off.
  void SetFreezeLOD(bool freeze);
  bool GetFreezeLOD();
  ///@}

  ///@{
  /// tcLODMapper::ColorByActor (0, default), ColorByChart (1), ColorByLevel (2) or
  /// ColorByAttribute (3, the attribute named by ColorAttribute).
  void SetColorMode(int mode);
  int GetColorMode();
  ///@}

  ///@{
  /// The atlas attribute ColorByAttribute shows (e.g. "MeanCurvature"); empty (default): none.
  void SetColorAttribute(const char* name);
  const char* GetColorAttribute();
  ///@}

  ///@{
  /// Draw the grid edges instead of the surface. Default off.
  void SetWireframe(bool wireframe);
  bool GetWireframe();
  ///@}

  ///@{
  /// The actor's material: opacity (default 1), ambient (0) and diffuse (1) coefficients, and
  /// colour (white) for ColorByActor.
  void SetOpacity(double opacity);
  void SetAmbient(double ambient);
  void SetDiffuse(double diffuse);
  void SetDiffuseColor(double r, double g, double b);
  void SetDiffuseColor(const double rgb[3]) { this->SetDiffuseColor(rgb[0], rgb[1], rgb[2]); }
  ///@}

  ///@{
  /// Statistics of the last frame (tcLODMapper): grid triangles issued and charts drawn.
  vtkIdType GetTrianglesDrawn();
  vtkIdType GetChartsDrawn();
  ///@}

  /// True when this process's input is an atlas the mapper can draw (after the representation
  /// updated); false on the client of a client-server session, which has no input.
  bool GetInputIsAtlas() const { return this->Atlas != nullptr; }

  /// The mapper and actor that draw the atlas.
  tcLODMapper* GetMapper();
  vtkActor* GetActor();

protected:
  tcLODRepresentation();
  ~tcLODRepresentation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  bool AddToView(vtkView* view) override;
  bool RemoveFromView(vtkView* view) override;

private:
  tcLODRepresentation(const tcLODRepresentation&) = delete;
  void operator=(const tcLODRepresentation&) = delete;

  /// Validates `atlas` with the mapper and measures its bounds; returns it, or null (reported)
  /// when it is not an atlas.
  vtkSmartPointer<vtkDataObject> MeasureAtlas(vtkDataObject* atlas);
  /// Gives the mapper what the view delivered, or nothing when the piece is empty.
  void UseDeliveredAtlas(vtkDataObject* delivered);

  vtkNew<tcLODMapper> Mapper;
  vtkNew<vtkActor> Actor;
  /// The atlas to deliver (a shallow copy of the input); null when the input is not an atlas.
  vtkSmartPointer<vtkDataObject> Atlas;
  /// The input Atlas was made from, and its AtlasStamp (leaves and rig): an unchanged
  /// input keeps Atlas and the mapper's conversion of it.
  vtkSmartPointer<vtkDataObject> Input;
  std::pair<vtkMTimeType, std::string> InputStamp; // AtlasStamp of Input when converted
  /// The piece delivered when there is nothing to draw.
  vtkNew<vtkMultiBlockDataSet> NoAtlas;
  double Bounds[6] = { 1, -1, 1, -1, 1, -1 };
  std::string ColorAttribute;
};

#endif
