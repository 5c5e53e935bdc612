// SPDX-License-Identifier: BSD-3-Clause
/// @file skin_fixtures.h
/// What the skinning tests build their rigs from.
#pragma once

#include "tc/skinning/skin.h"

namespace tctest
{
/// The matrix that moves points by (x, y, z).
inline tc::Matrix4 translation(double x, double y, double z)
{
  tc::Matrix4 m = tc::identityMatrix();
  m[3] = x;
  m[7] = y;
  m[11] = z;
  return m;
}
} // namespace tctest
