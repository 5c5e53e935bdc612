// SPDX-License-Identifier: BSD-3-Clause
#include "tcLODRepresentation.h"

#include "tcMeshConversion.h"

#include "tc/common/array_names.h"

#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataObject.h>
#include <vtkDataObjectTree.h>
#include <vtkDataObjectTreeIterator.h>
#include <vtkDataObjectTreeRange.h>
#include <vtkDataSet.h>
#include <vtkDataSetAttributes.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMath.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkPVRenderView.h>
#include <vtkPVView.h>
#include <vtkPointData.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <array>
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

/// A shallow copy of `input` that VTK's legacy format writes without reordering its arrays.
/// ParaView moves a piece between processes in that format (vtkMPIMoveData through
/// vtkGenericDataObjectWriter), which writes each data set's active attributes before its other
/// arrays, while the atlas's images are read by array order (Position, Normal, then the
/// resampled ones): the copy's data sets own their attribute lists, with no attribute active.
vtkSmartPointer<vtkDataObject> DeliverableCopy(vtkDataObject* input)
{
  vtkSmartPointer<vtkDataObject> copy = vtk::TakeSmartPointer(input->NewInstance());
  copy->ShallowCopy(input);
  auto* tree = vtkDataObjectTree::SafeDownCast(copy);
  if (!tree)
  {
    return copy;
  }
  // ShallowCopy clones the inner trees but shares the leaves, which belong to the pipeline.
  vtkSmartPointer<vtkDataObjectTreeIterator> leaf = vtk::TakeSmartPointer(tree->NewTreeIterator());
  leaf->VisitOnlyLeavesOn();
  leaf->TraverseSubTreeOn();
  leaf->SkipEmptyNodesOn();
  for (leaf->InitTraversal(); !leaf->IsDoneWithTraversal(); leaf->GoToNextItem())
  {
    auto* data = vtkDataSet::SafeDownCast(leaf->GetCurrentDataObject());
    if (!data)
    {
      continue;
    }
    vtkSmartPointer<vtkDataSet> own = vtk::TakeSmartPointer(data->NewInstance());
    own->ShallowCopy(data);
    const std::array<vtkDataSetAttributes*, 2> lists{ own->GetPointData(), own->GetCellData() };
    for (vtkDataSetAttributes* attributes : lists)
    {
      for (int type = 0; type < vtkDataSetAttributes::NUM_ATTRIBUTES; ++type)
      {
        attributes->SetActiveAttribute(-1, type);
      }
    }
    tree->SetDataSet(leaf, own);
  }
  return copy;
}

/// True when the trees `a` and `b` hold the very same leaves (a shallow copy of one another).
bool SharesLeaves(vtkDataObject* a, vtkDataObject* b)
{
  auto* treeA = vtkDataObjectTree::SafeDownCast(a);
  auto* treeB = vtkDataObjectTree::SafeDownCast(b);
  if (!treeA || !treeB)
  {
    return a == b;
  }
  const auto options =
    vtk::DataObjectTreeOptions::VisitOnlyLeaves | vtk::DataObjectTreeOptions::TraverseSubTree;
  const auto leavesA = vtk::Range(treeA, options);
  const auto leavesB = vtk::Range(treeB, options);
  return std::equal(leavesA.begin(), leavesA.end(), leavesB.begin(), leavesB.end(),
    [](vtkDataObject* x, vtkDataObject* y) { return x == y; });
}

/// The latest modification of `data` or of any of its leaves (their arrays included).
/// What decides whether an input is the atlas last converted: the latest modification of its
/// leaves (the chart table and the images) and its rig. The multiblock itself is left out: a
/// skinned atlas's reader gives a new one at every time (with the time and the animation's
/// name), sharing the same leaves, and a new time must not convert the atlas again.
std::pair<vtkMTimeType, std::string> AtlasStamp(vtkDataObject* data)
{
  vtkMTimeType time = 0;
  auto* tree = vtkDataObjectTree::SafeDownCast(data);
  if (!tree)
  {
    return { data->GetMTime(), "" };
  }
  for (vtkDataObject* leaf : vtk::Range(tree,
         vtk::DataObjectTreeOptions::VisitOnlyLeaves | vtk::DataObjectTreeOptions::TraverseSubTree))
  {
    time = std::max(time, leaf ? leaf->GetMTime() : 0);
  }
  return { time, tcvtk::GetTextField(data->GetFieldData(), tc::kRig) };
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
  // the pipeline with a bare type name. Optional: the client of a client-server session has no
  // input, only what the server delivers.
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int tcLODRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = inputVector[0]->GetNumberOfInformationObjects() > 0
    ? vtkDataObject::GetData(inputVector[0], 0)
    : nullptr;
  // An update of the same, unmodified input keeps the conversion rather than converting again.
  const auto stamp = input ? AtlasStamp(input) : std::pair<vtkMTimeType, std::string>();
  const bool unchanged = input && this->Atlas && input == this->Input && stamp == this->InputStamp;
  // A skinned atlas plays the animation its reader names (the first when none is named).
  const std::string animation =
    input ? tcvtk::GetTextLine(input->GetFieldData(), tc::kAnimationName) : "";
  this->Mapper->SetAnimation(animation.c_str());
  if (!unchanged)
  {
    this->Atlas = nullptr;
    vtkMath::UninitializeBounds(this->Bounds);
    this->Input = input;
    this->InputStamp = stamp;
    if (input)
    {
      this->Atlas = this->MeasureAtlas(DeliverableCopy(input));
    }
  }
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

vtkSmartPointer<vtkDataObject> tcLODRepresentation::MeasureAtlas(vtkDataObject* atlas)
{
  // The drawing mapper validates and converts the atlas, and its bounds are what the view
  // frames: the one converted copy of this process, which it goes on drawing when the view
  // delivers this atlas back to it (UseDeliveredAtlas).
  std::string messages;
  vtkNew<vtkCallbackCommand> collect;
  collect->SetCallback(CollectError);
  collect->SetClientData(&messages);
  const unsigned long observer = this->Mapper->AddObserver(vtkCommand::ErrorEvent, collect);
  this->Mapper->SetInputData(atlas);
  this->Mapper->GetBounds(this->Bounds);
  this->Mapper->RemoveObserver(observer);
  if (messages.empty())
  {
    return atlas;
  }
  this->Mapper->SetInputData(nullptr);
  vtkMath::UninitializeBounds(this->Bounds);
  vtkErrorMacro("The TriChart LOD representation draws atlases only (the output of TriChart "
                "Atlas Reader or TriChart Geometry Images), and this input is not one: "
    << messages
    << " Nothing is drawn; apply TriChart Geometry Image Mesh to show it as a mesh, or choose "
       "another representation.");
  return nullptr;
}

void tcLODRepresentation::UseDeliveredAtlas(vtkDataObject* delivered)
{
  // ParaView delivers a shallow copy of the piece: where it is this process's own atlas
  // (builtin session, or rendering on the server), the mapper keeps the atlas it converted in
  // RequestData; elsewhere (the client) it converts the delivered one. An empty piece: nothing.
  vtkDataObject* draw = nullptr;
  if (this->Atlas && delivered && SharesLeaves(delivered, this->Atlas))
  {
    draw = this->Atlas;
  }
  else if (auto* blocks = vtkMultiBlockDataSet::SafeDownCast(delivered))
  {
    draw = blocks->GetNumberOfBlocks() > 0 ? delivered : nullptr;
  }
  if (this->Mapper->GetInputDataObject(0, 0) != draw)
  {
    this->Mapper->SetInputData(draw);
  }
  this->Actor->SetVisibility(this->GetVisibility() && draw != nullptr);
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
    // Every process gives a piece, and of one type: the delivery manager moves data only
    // between processes that all have one (the client has no input), so an empty multiblock
    // stands for "nothing to draw".
    vtkPVView::SetPiece(inInfo, this, this->Atlas ? this->Atlas.Get() : this->NoAtlas.Get());
    if (this->Atlas && vtkMath::AreBoundsInitialized(this->Bounds))
    {
      vtkPVRenderView::SetGeometryBounds(inInfo, this, this->Bounds, this->Actor->GetMatrix());
    }
  }
  else if (request == vtkPVView::REQUEST_RENDER())
  {
    // The animation toolbar's time poses a skinned atlas (the mapper skins on the GPU).
    this->Mapper->SetAnimationTime(this->GetUpdateTimeValid() ? this->GetUpdateTime() : 0.0);
    this->UseDeliveredAtlas(vtkPVView::GetDeliveredPiece(inInfo, this));
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
