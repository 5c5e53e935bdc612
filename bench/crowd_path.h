// SPDX-License-Identifier: BSD-3-Clause
/// @file crowd_path.h
/// The camera path of the crowd benchmarks (bench_lod_rendering, bench_skinned_crowd), so that
/// their figures are taken along the same flight: a slow pass over a grid of instances on the
/// ground plane y = 0 (x from 0, z from 0 towards -extent), lower and closer as it goes, looking
/// ahead.
#ifndef crowd_path_h
#define crowd_path_h

#include <vtkCamera.h>

namespace tcbench
{
/// Places `camera` at frame `frame` of `frames` over a crowd `extent` wide of objects `size`
/// high (both in world units).
inline void PlaceCamera(vtkCamera* camera, int frame, int frames, double extent, double size)
{
  const double t = frames > 1 ? static_cast<double>(frame) / (frames - 1) : 0.0;
  const double x = -0.2 * extent + 0.9 * extent * t;
  camera->SetPosition(x, 1.5 * size + 3.0 * size * (1.0 - t), 2.0 * size);
  camera->SetFocalPoint(x + 0.3 * extent, 0.0, -0.6 * extent);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(50);
  camera->SetClippingRange(0.05 * size, 4.0 * extent);
}
} // namespace tcbench

#endif
