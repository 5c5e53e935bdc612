// SPDX-License-Identifier: BSD-3-Clause
/// @file close_values.h
/// Whether two attribute values are the same value up to rounding: the rule of the seam checks
/// (the preparation's merge, the rebuilt mesh's split), each with its own tolerance.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace tc
{
/// True when every component of a and b differs by at most `relative` times the larger of 1,
/// |a| and |b| (so near 0 an absolute tolerance); NaN is never close.
template <typename T>
bool closeValues(const T* a, const T* b, size_t components, T relative)
{
  for (size_t x = 0; x < components; ++x)
  {
    const T scale = std::max({ T(1), std::abs(a[x]), std::abs(b[x]) });
    if (!(std::abs(a[x] - b[x]) <= relative * scale))
    {
      return false;
    }
  }
  return true;
}
} // namespace tc
