// SPDX-License-Identifier: BSD-3-Clause
#include "tcCameraView.h"

#include <vtkCamera.h>
#include <vtkRenderer.h>

#include <array>

namespace
{
struct Side
{
  const char* name;
  std::array<double, 3> from; ///< where the camera sits, seen from the focal point
  std::array<double, 3> up;
};

// Y is up, as in VTK's default camera (which looks from +Z: "front").
constexpr Side kSides[] = {
  { "front", { 0, 0, 1 }, { 0, 1, 0 } },
  { "back", { 0, 0, -1 }, { 0, 1, 0 } },
  { "left", { -1, 0, 0 }, { 0, 1, 0 } },
  { "right", { 1, 0, 0 }, { 0, 1, 0 } },
  { "top", { 0, 1, 0 }, { 0, 0, -1 } },
  { "bottom", { 0, -1, 0 }, { 0, 0, 1 } },
  { "iso", { 1, 1, 1 }, { 0, 1, 0 } },
};
} // namespace

QStringList tcCameraView::Directions()
{
  QStringList names;
  for (const Side& d : kSides)
  {
    names << d.name;
  }
  return names;
}

void tcCameraView::Apply(vtkRenderer* renderer) const
{
  vtkCamera* camera = renderer->GetActiveCamera();
  for (const Side& d : kSides)
  {
    if (this->Direction == d.name)
    {
      camera->SetFocalPoint(0.0, 0.0, 0.0);
      camera->SetPosition(d.from.data());
      camera->SetViewUp(d.up.data());
    }
  }
  renderer->ResetCamera();
  if (this->Azimuth != 0.0 || this->Elevation != 0.0)
  {
    camera->Azimuth(this->Azimuth);
    camera->Elevation(this->Elevation);
    camera->OrthogonalizeViewUp();
    renderer->ResetCamera();
  }
  if (this->Zoom != 1.0)
  {
    camera->Zoom(this->Zoom);
    renderer->ResetCameraClippingRange();
  }
}
