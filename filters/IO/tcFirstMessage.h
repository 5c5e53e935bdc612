// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file tcFirstMessage.h
 * @brief An observer that keeps the first message of a VTK object's error (or warning)
 * events, so that the IO module reports VTK readers' failures as its own messages.
 */
#ifndef tcFirstMessage_h
#define tcFirstMessage_h

#include <vtkCommand.h>

#include <string>

namespace tcvtk
{
class FirstMessage : public vtkCommand
{
public:
  static FirstMessage* New() { return new FirstMessage; }
  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    if (callData && this->Text.empty())
    {
      this->Text = static_cast<const char*>(callData);
    }
  }
  std::string Text; ///< the first message, "" if none came
};
} // namespace tcvtk

#endif
