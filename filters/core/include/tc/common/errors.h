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
