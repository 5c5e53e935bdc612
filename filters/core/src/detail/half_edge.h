// SPDX-License-Identifier: BSD-3-Clause
/// @file half_edge.h
/// Navigation of a corner table (Rossignac): half-edge h = 3f + i runs from corner i to corner
/// i + 1 of face f. The base complex and the path tracer both store meshes this way.
#pragma once

#include <cstdint>

namespace tc
{
namespace detail
{
/// The half-edge after h in its face.
inline int32_t nextHe(int32_t h)
{
  return h % 3 == 2 ? h - 2 : h + 1;
}
/// The half-edge before h in its face.
inline int32_t prevHe(int32_t h)
{
  return h % 3 == 0 ? h + 2 : h - 1;
}
} // namespace detail
} // namespace tc
