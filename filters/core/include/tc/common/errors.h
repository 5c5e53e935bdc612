// SPDX-License-Identifier: BSD-3-Clause
/// @file errors.h
/// Exceptions of the TriChart core. Algorithms throw these; the VTK layer turns them into
/// vtkErrorMacro messages, the CLI into an error line and a non-zero exit code.
#pragma once

#include <stdexcept>
#include <string>

namespace tc
{
/// The input cannot be processed; the message says what is wrong and what to do about it.
class InputError : public std::runtime_error
{
public:
  explicit InputError(const std::string& what)
    : std::runtime_error(what)
  {
  }
};

/// The base edges cannot be traced onto the mesh: the MAPS parameterization is not one-to-one
/// somewhere, which slivers (needles and caps of scans and CAD tessellations) cause. Every face
/// (CLI, Python, viewer) answers it by removing slivers in the preparation and building again,
/// and reads reason() instead of parsing the message.
class UntraceableError : public InputError
{
public:
  /// @param reason  what could not be traced, for a note ("input triangle 785 cannot be ...")
  /// @param advice  the rest of the message: why, and what to change
  UntraceableError(const std::string& reason, const std::string& advice)
    : InputError("tracePaths: " + reason + advice)
    , Reason(reason)
  {
  }
  const std::string& reason() const { return this->Reason; }

private:
  std::string Reason;
};

/// The user aborted a long computation through its progress callback.
class Aborted : public std::runtime_error
{
public:
  Aborted()
    : std::runtime_error("aborted by the user")
  {
  }
};
} // namespace tc
