// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcCameraView
 * @brief The direction a screenshot looks from (the viewer's --view, --azimuth, --elevation and
 * --zoom): a named axis or the isometric corner, then turns about the focal point and a zoom,
 * the surface framed after each.
 */
#ifndef tcCameraView_h
#define tcCameraView_h

#include <QString>
#include <QStringList>

class vtkRenderer;

struct tcCameraView
{
  /// One of Directions(), or "" to keep the camera's own direction.
  QString Direction;
  double Azimuth = 0.0;   ///< degrees about the view-up axis
  double Elevation = 0.0; ///< degrees about the right axis
  double Zoom = 1.0;      ///< > 1 closer, < 1 farther

  /// front (from +Z), back, left (from -X), right, top (from +Y), bottom, iso (from +X+Y+Z).
  static QStringList Directions();

  /// Orients the renderer's camera, frames its visible props, turns and zooms.
  void Apply(vtkRenderer* renderer) const;
};

#endif
