// SPDX-License-Identifier: BSD-3-Clause
/// @file tcTextureDecoding.h
/// The base-colour texture a core reader found (tc::BaseColorTexture: encoded bytes or raw
/// texels), decoded with VTK's image readers into the field arrays of tcMeshReader's output.
#ifndef tcTextureDecoding_h
#define tcTextureDecoding_h

#include "tc/io/mesh_file.h"

#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

#include <string>

class vtkFieldData;

namespace tcvtk
{
/// A texture as RGBA bytes: width x height tuples, row 0 = the image's bottom (VTK image
/// order), or, when it could not be decoded, why.
struct DecodedTexture
{
  int width = 0;
  int height = 0;
  vtkSmartPointer<vtkUnsignedCharArray> rgba; ///< null when `error` says why
  std::string error;
  std::string warning; ///< of a decoder that read a damaged image as well as it could
};

/// Decodes `texture`: raw texels as they are, a PNG or JPEG (chosen by its first bytes) with
/// vtkPNGReader / vtkJPEGReader from memory. Grey, grey-alpha and RGB images become RGBA (alpha
/// 255), 16-bit channels 8-bit. Other formats, damaged images and images of more than 2^28
/// texels give an error, never a crash.
DecodedTexture DecodeTexture(const tc::BaseColorTexture& texture);

} // namespace tcvtk

#endif
