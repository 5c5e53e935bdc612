// SPDX-License-Identifier: BSD-3-Clause
/// @file progress.h
/// Progress reporting and abort for long core computations.
#pragma once

#include "tc/common/errors.h"

#include <functional>
#include <utility>

namespace tc
{
/// Reports the fraction done of a computation, mapped into [begin, end] of the caller's range.
/// The callback returns false to ask for an abort; report() then throws tc::Aborted. Call it
/// from the thread that started the computation only (parallel_for does).
class Progress
{
public:
  using Callback = std::function<bool(double)>;

  Progress() = default;
  explicit Progress(Callback callback, double begin = 0.0, double end = 1.0)
    : Callback_(std::move(callback))
    , Begin_(begin)
    , End_(end)
  {
  }

  /// @param[in] fraction  in [0, 1] of this range
  void report(double fraction) const
  {
    if (Callback_ && !Callback_(Begin_ + (End_ - Begin_) * fraction))
    {
      throw Aborted();
    }
  }

  /// A progress object for the sub-range [from, to] of this one (both fractions in [0, 1]).
  Progress sub(double from, double to) const
  {
    return Progress(Callback_, Begin_ + (End_ - Begin_) * from, Begin_ + (End_ - Begin_) * to);
  }

private:
  Callback Callback_;
  double Begin_ = 0.0;
  double End_ = 1.0;
};
} // namespace tc
