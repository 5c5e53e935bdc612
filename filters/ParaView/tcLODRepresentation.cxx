// SPDX-License-Identifier: BSD-3-Clause
#include "tcLODRepresentation.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataObject.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMath.h>
#include <vtkObjectFactory.h>
#include <vtkPVRenderView.h>
#include <vtkPVView.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

#include <string>

namespace
{
/// Collects the messages of an internal object's ErrorEvent (which then are not printed), so
/// that the representation reports them once, with what the user can do.
void CollectError(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* messages = static_cast<std::string*>(clientData);
  if (!callData)
  {
    return;
  }
  // vtkErrorMacro's text is "ERROR: In <file>, line <n>\n<class> (<address>): <message>\n\n".
  std::string text = static_cast<const char*>(callData);
  const size_t start = text.find("): ");
  text = start == std::string::npos ? text : text.substr(start + 3);
  text.erase(text.find_last_not_of(" \n") + 1);
  *messages += (messages->empty() ? "" : " ") + text;
}
} // namespace

vtkStandardNewMacro(tcLODRepresentation);

tcLODRepresentation::tcLODRepresentation()
{
  this->Actor->SetMapper(this->Mapper);
  this->Actor->GetProperty()->SetRepresentationToSurface();
}

tcLODRepresentation::~tcLODRepresentation() = default;

int tcLODRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  // Any data object: what is not an atlas is explained in RequestData rather than refused by
  // the pipeline with a bare type name.
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int tcLODRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // 1. Input: a shallow copy, so that the pipeline's data object is delivered unchanged.
  this->Atlas = nullptr;
  vtkMath::UninitializeBounds(this->Bounds);
  vtkDataObject* input = inputVector[0]->GetNumberOfInformationObjects() > 0
    ? vtkDataObject::GetData(inputVector[0], 0)
    : nullptr;
  if (input)
  {
    vtkSmartPointer<vtkDataObject> atlas = vtk::TakeSmartPointer(input->NewInstance());
    atlas->ShallowCopy(input);

    // 2. Validate and measure: the mapper's conversion says what is missing; its bounds are the
    // charts' oriented boxes.
    std::string messages;
    vtkNew<vtkCallbackCommand> collect;
    collect->SetCallback(CollectError);
    collect->SetClientData(&messages);
    const unsigned long observer = this->BoundsMapper->AddObserver(vtkCommand::ErrorEvent, collect);
    this->BoundsMapper->SetInputData(atlas);
    this->BoundsMapper->GetBounds(this->Bounds);
    this->BoundsMapper->RemoveObserver(observer);
    // Without input the mapper frees its conversion: only the rendering mapper keeps one.
    this->BoundsMapper->SetInputData(nullptr);
    if (messages.empty())
    {
      this->Atlas = atlas;
    }
    else
    {
      vtkErrorMacro("The TriChart LOD representation draws atlases only (the output of TriChart "
                    "Atlas Reader or TriChart Geometry Images), and this input is not one: "
        << messages
        << " Nothing is drawn; apply TriChart Geometry Image Mesh to show it as a mesh, or choose "
           "another representation.");
    }
  }
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

int tcLODRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request, inInfo, outInfo))
  {
    // Not visible: the view asks nothing of this representation.
    return 0;
  }
  if (request == vtkPVView::REQUEST_UPDATE())
  {
    vtkPVView::SetPiece(inInfo, this, this->Atlas);
    if (this->Atlas && vtkMath::AreBoundsInitialized(this->Bounds))
    {
      vtkPVRenderView::SetGeometryBounds(inInfo, this, this->Bounds, this->Actor->GetMatrix());
    }
  }
  else if (request == vtkPVView::REQUEST_RENDER())
  {
    // The delivered atlas (on every rendering process); nothing when the input is no atlas.
    this->Mapper->SetInputConnection(vtkPVRenderView::GetPieceProducer(inInfo, this));
    this->Actor->SetVisibility(
      this->GetVisibility() && vtkPVView::GetDeliveredPiece(inInfo, this) != nullptr);
  }
  return 1;
}

bool tcLODRepresentation::AddToView(vtkView* view)
{
  auto* renderView = vtkPVRenderView::SafeDownCast(view);
  if (!renderView)
  {
    return false;
  }
  renderView->GetRenderer()->AddActor(this->Actor);
  return this->Superclass::AddToView(view);
}

bool tcLODRepresentation::RemoveFromView(vtkView* view)
{
  auto* renderView = vtkPVRenderView::SafeDownCast(view);
  if (!renderView)
  {
    return false;
  }
  renderView->GetRenderer()->RemoveActor(this->Actor);
  return this->Superclass::RemoveFromView(view);
}

void tcLODRepresentation::SetVisibility(bool visible)
{
  this->Superclass::SetVisibility(visible);
  this->Actor->SetVisibility(visible);
}

void tcLODRepresentation::SetLODBias(double bias)
{
  this->Mapper->SetLODBias(bias);
}

double tcLODRepresentation::GetLODBias()
{
  return this->Mapper->GetLODBias();
}

void tcLODRepresentation::SetErrorTarget(double pixels)
{
  this->Mapper->SetErrorTarget(pixels);
}

double tcLODRepresentation::GetErrorTarget()
{
  return this->Mapper->GetErrorTarget();
}

void tcLODRepresentation::SetFreezeLOD(bool freeze)
{
  this->Mapper->SetFreezeLOD(freeze);
}

bool tcLODRepresentation::GetFreezeLOD()
{
  return this->Mapper->GetFreezeLOD();
}

void tcLODRepresentation::SetColorMode(int mode)
{
  this->Mapper->SetColorMode(mode);
}

int tcLODRepresentation::GetColorMode()
{
  return this->Mapper->GetColorMode();
}

void tcLODRepresentation::SetColorAttribute(const char* name)
{
  // ParaView sends "" for an empty text field; the mapper's "none" is nullptr.
  this->ColorAttribute = name ? name : "";
  this->Mapper->SetColorAttribute(this->ColorAttribute.empty() ? nullptr : name);
}

const char* tcLODRepresentation::GetColorAttribute()
{
  return this->ColorAttribute.c_str();
}

void tcLODRepresentation::SetWireframe(bool wireframe)
{
  if (wireframe)
  {
    this->Actor->GetProperty()->SetRepresentationToWireframe();
  }
  else
  {
    this->Actor->GetProperty()->SetRepresentationToSurface();
  }
}

bool tcLODRepresentation::GetWireframe()
{
  return this->Actor->GetProperty()->GetRepresentation() == VTK_WIREFRAME;
}

void tcLODRepresentation::SetOpacity(double opacity)
{
  this->Actor->GetProperty()->SetOpacity(opacity);
}

void tcLODRepresentation::SetAmbient(double ambient)
{
  this->Actor->GetProperty()->SetAmbient(ambient);
}

void tcLODRepresentation::SetDiffuse(double diffuse)
{
  this->Actor->GetProperty()->SetDiffuse(diffuse);
}

void tcLODRepresentation::SetDiffuseColor(double r, double g, double b)
{
  this->Actor->GetProperty()->SetDiffuseColor(r, g, b);
}

vtkIdType tcLODRepresentation::GetTrianglesDrawn()
{
  return this->Mapper->GetTrianglesDrawn();
}

vtkIdType tcLODRepresentation::GetChartsDrawn()
{
  return this->Mapper->GetChartsDrawn();
}

tcLODMapper* tcLODRepresentation::GetMapper()
{
  return this->Mapper;
}

vtkActor* tcLODRepresentation::GetActor()
{
  return this->Actor;
}

void tcLODRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LODBias: " << this->GetLODBias() << "\n";
  os << indent << "ErrorTarget: " << this->GetErrorTarget() << "\n";
  os << indent << "FreezeLOD: " << this->GetFreezeLOD() << "\n";
  os << indent << "ColorMode: " << this->GetColorMode() << "\n";
  os << indent << "ColorAttribute: " << this->ColorAttribute << "\n";
  os << indent << "Wireframe: " << this->GetWireframe() << "\n";
  vtkProperty* property = this->Actor->GetProperty();
  os << indent << "Opacity: " << property->GetOpacity() << "\n";
  os << indent << "Ambient: " << property->GetAmbient() << "\n";
  os << indent << "Diffuse: " << property->GetDiffuse() << "\n";
  const double* color = property->GetDiffuseColor();
  os << indent << "DiffuseColor: " << color[0] << " " << color[1] << " " << color[2] << "\n";
  os << indent << "InputIsAtlas: " << this->GetInputIsAtlas() << "\n";
}
