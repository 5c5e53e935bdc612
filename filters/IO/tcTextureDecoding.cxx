// SPDX-License-Identifier: BSD-3-Clause
#include "tcTextureDecoding.h"

#include "tcFirstMessage.h"

#include "tc/common/array_names.h"
#include "tc/io/png_check.h"

#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkImageReader2.h>
#include <vtkIntArray.h>
#include <vtkJPEGReader.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cstdint>

namespace tcvtk
{
namespace
{
/// Texels a texture may have: 16384 x 16384. A damaged header's size is refused, not allocated.
constexpr int64_t kMaxTexels = int64_t(1) << 28;

/// The reader for `bytes` by their signature, or null.
vtkSmartPointer<vtkImageReader2> ReaderFor(const std::string& bytes)
{
  if (bytes.compare(0, 8, "\x89PNG\r\n\x1a\n", 8) == 0)
  {
    return vtkSmartPointer<vtkPNGReader>::New();
  }
  if (bytes.size() > 3 && bytes.compare(0, 3, "\xff\xd8\xff", 3) == 0)
  {
    return vtkSmartPointer<vtkJPEGReader>::New();
  }
  return nullptr;
}

/// The image's point scalars as RGBA bytes: grey to RGB, alpha 255 where it has none, 16-bit
/// channels to 8.
DecodedTexture ToRGBA(vtkImageData* image)
{
  DecodedTexture out;
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  int dims[3] = { 0, 0, 0 };
  if (image)
  {
    image->GetDimensions(dims);
  }
  const int nc = scalars ? scalars->GetNumberOfComponents() : 0;
  if (!scalars || nc < 1 || nc > 4 || dims[0] < 1 || dims[1] < 1 ||
    scalars->GetNumberOfTuples() != vtkIdType(dims[0]) * dims[1])
  {
    out.error = "the image reader gave no 2-D image of 1 to 4 channels";
    return out;
  }
  const double scale = scalars->GetDataTypeSize() == 2 ? 1.0 / 257.0 : 1.0;
  out.width = dims[0];
  out.height = dims[1];
  out.rgba = vtkSmartPointer<vtkUnsignedCharArray>::New();
  out.rgba->SetNumberOfComponents(4);
  out.rgba->SetNumberOfTuples(scalars->GetNumberOfTuples());
  for (vtkIdType t = 0; t < scalars->GetNumberOfTuples(); ++t)
  {
    const auto channel = [&](int c)
    { return static_cast<unsigned char>(scalars->GetComponent(t, c) * scale + 0.5); };
    const bool grey = nc < 3;
    unsigned char rgba[4] = { channel(0), channel(grey ? 0 : 1), channel(grey ? 0 : 2), 255 };
    rgba[3] = nc == 2 ? channel(1) : nc == 4 ? channel(3) : 255;
    out.rgba->SetTypedTuple(t, rgba);
  }
  return out;
}

/// A PNG or JPEG decoded from memory.
DecodedTexture DecodeEncoded(const std::string& bytes)
{
  DecodedTexture out;
  vtkSmartPointer<vtkImageReader2> reader = ReaderFor(bytes);
  if (!reader)
  {
    out.error = "it is neither PNG nor JPEG (TriChart decodes those two)";
    return out;
  }
  // vtkPNGReader crashes while it cleans up after an error of libpng: a damaged PNG must not
  // reach it.
  const std::string damage = reader->IsA("vtkPNGReader") ? tc::pngDamage(bytes) : "";
  if (!damage.empty())
  {
    out.error = "it is a damaged PNG: " + damage;
    return out;
  }
  vtkNew<FirstMessage> errors, warnings;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->AddObserver(vtkCommand::WarningEvent, warnings);
  reader->SetMemoryBuffer(bytes.data());
  reader->SetMemoryBufferLength(static_cast<vtkIdType>(bytes.size()));
  // The header first: its size decides whether the image is read at all.
  reader->UpdateInformation();
  const int* extent = reader->GetDataExtent();
  const int64_t texels = int64_t(extent[1] - extent[0] + 1) * (extent[3] - extent[2] + 1);
  if (!errors->Text.empty() || texels <= 0 || texels > kMaxTexels)
  {
    out.error = errors->Text.empty()
      ? "its header declares " + std::to_string(texels) + " texels (a damaged image?)"
      : errors->Text;
    return out;
  }
  reader->Update();
  if (!errors->Text.empty())
  {
    out.error = errors->Text;
    return out;
  }
  out = ToRGBA(reader->GetOutput());
  out.warning = warnings->Text;
  return out;
}
} // namespace

DecodedTexture DecodeTexture(const tc::BaseColorTexture& texture)
{
  if (!texture.encoded.empty())
  {
    return DecodeEncoded(texture.encoded);
  }
  DecodedTexture out;
  const int64_t texels = int64_t(texture.width) * texture.height;
  if (texels <= 0 || texels > kMaxTexels || texture.rgba.size() != size_t(4 * texels))
  {
    out.error = "it holds no image";
    return out;
  }
  out.width = texture.width;
  out.height = texture.height;
  out.rgba = vtkSmartPointer<vtkUnsignedCharArray>::New();
  out.rgba->SetNumberOfComponents(4);
  out.rgba->SetNumberOfTuples(texels);
  std::copy(texture.rgba.begin(), texture.rgba.end(), out.rgba->GetPointer(0));
  return out;
}

} // namespace tcvtk
