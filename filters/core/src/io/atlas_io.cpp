// SPDX-License-Identifier: BSD-3-Clause
// The atlas file as OpenEXR parts: the one translation unit that includes OpenEXR. The chart
// table is atlas_metadata.cpp's, the texel layout atlas_layout.cpp's, the temporary file
// temporary_file.cpp's; docs/atlas-format.md describes the file.
#include "tc/io/atlas_io.h"

#include "io/atlas_codes.h"
#include "io/atlas_layout.h"
#include "io/atlas_metadata.h"
#include "tc/io/temporary_file.h"

#include "tc/common/errors.h"
#include "tc/common/file_names.h"

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputPart.h>
#include <ImfIntAttribute.h>
#include <ImfMultiPartInputFile.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfStringAttribute.h>
#include <ImfVersion.h>
#include <openexr.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <new>
#include <set>

// The checksums are taken over the float data as it lies in memory; the file stores it
// little-endian, so a big-endian host would need a byte swap first.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "atlas_io assumes a little-endian host");

namespace tc
{
namespace
{
using namespace detail;

/// Texel data is read and written in blocks of about this many floats, so progress and abort
/// come at least every few milliseconds even for one large image.
constexpr size_t kBlockFloats = size_t(1) << 20;

/// No lossless coder OpenEXR offers shrinks float data by more than this (deflate's limit is
/// about 1032:1): a file declaring more texel data than this times its size is damaged, and is
/// refused before the memory for it is allocated.
constexpr uint64_t kMaxCompressionRatio = 4096;

/// A frame buffer over 4-byte values of `type` (FLOAT or UINT), one per channel of `names`
/// interleaved, rows of `width` texels. OpenEXR takes a non-const base pointer for writing too;
/// it only reads through it then.
Imf::FrameBuffer frameBuffer(
  char* data, int32_t width, const std::vector<std::string>& names, Imf::PixelType type)
{
  Imf::FrameBuffer buffer;
  const size_t xStride = 4 * names.size();
  const size_t yStride = xStride * static_cast<size_t>(width);
  for (size_t c = 0; c < names.size(); ++c)
  {
    buffer.insert(names[c], Imf::Slice(type, data + 4 * c, xStride, yStride));
  }
  return buffer;
}

/// A frame buffer over one attribute of one image: components interleaved, rows y = 0 .. h-1.
Imf::FrameBuffer frameBuffer(float* data, int32_t width, int32_t components)
{
  return frameBuffer(reinterpret_cast<char*>(data), width, channelNames(components), Imf::FLOAT);
}

/// The one channel of a texture's part: each texel's R, G, B, A bytes as one 32-bit UINT,
/// R in the lowest byte (OpenEXR has no 8-bit type; this stores the bytes losslessly).
const std::vector<std::string> kTextureChannels{ "RGBA" };

/// A frame buffer over the bytes of a texture: 4 a texel, rows from the bottom.
Imf::FrameBuffer textureBuffer(const AtlasTexture& texture, uint8_t* bytes)
{
  return frameBuffer(reinterpret_cast<char*>(bytes), texture.width, kTextureChannels, Imf::UINT);
}

/// A frame buffer over the codes of coded attribute a (version 4).
Imf::FrameBuffer codeBuffer(uint32_t* data, int32_t width, size_t a)
{
  return frameBuffer(reinterpret_cast<char*>(data), width, codeChannelNames(a), Imf::UINT);
}

/// Whether attribute a of an atlas stored on `lattice` is coded (version 4), not float.
bool coded(const std::optional<AtlasLattice>& lattice, size_t a)
{
  return lattice && a < kCodedAttributes;
}

/// Values per texel of attribute a in its parts: codes or floats.
int32_t storedComponents(const Atlas& atlas, const std::optional<AtlasLattice>& lattice, size_t a)
{
  return coded(lattice, a) ? codeComponents(a) : atlas.attributes[a].components;
}

/// Calls io(y, rows) over the `height` rows of a part of `rowFloats` floats a row, in blocks of
/// about kBlockFloats floats; counts the floats into `done` and reports done / total (in the
/// first 95 % of the range).
template <class IO>
void inBlocks(int32_t height, size_t rowFloats, uint64_t& done, uint64_t total,
  const Progress& progress, IO&& io)
{
  const int32_t block =
    static_cast<int32_t>(std::max<size_t>(1, kBlockFloats / std::max<size_t>(1, rowFloats)));
  for (int32_t y = 0; y < height; y += block)
  {
    const int32_t rows = std::min(block, height - y);
    io(y, rows);
    done += static_cast<uint64_t>(rows) * rowFloats;
    progress.report(0.95 * static_cast<double>(done) / static_cast<double>(total));
  }
}

// ------------------------------------------------------------------------------------------
// Writing

/// OpenEXR output into the temporary file, so that every failure (including those in the
/// destructor of MultiPartOutputFile, which writes the chunk offset tables and swallows
/// exceptions) is seen, and the data can be flushed to disk before the rename.
class FileOStream : public Imf::OStream
{
public:
  explicit FileOStream(TemporaryFile& file)
    : Imf::OStream(file.path().c_str())
    , File(file)
  {
  }

  void write(const char c[], int n) override
  {
    if (n > 0)
    {
      File.write(c, static_cast<size_t>(n));
    }
  }

  uint64_t tellp() override { return File.tell(); }

  void seekp(uint64_t pos) override { File.seek(pos); }

private:
  TemporaryFile& File;
};

/// What the writer stores for every image.
struct WritePlan
{
  std::vector<ImageLayout> layouts;    ///< per image: compact whenever its texels allow it
  std::vector<uint8_t> compact;        ///< per image: layouts[k].compact
  AtlasChecksums crcs;                 ///< per image, per attribute
  std::vector<uint32_t> textureCrcs;   ///< per texture
  std::optional<AtlasLattice> lattice; ///< version 4: Position and Normal as codes on it
  uint64_t totalFloats = 0;            ///< 4-byte values in all parts
  int32_t displayWidth = 1;            ///< of the largest image
  int32_t displayHeight = 1;
};

WritePlan planParts(const Atlas& atlas)
{
  const size_t numImages = atlas.images.size();
  WritePlan plan;
  plan.crcs.resize(numImages);
  for (size_t k = 0; k < numImages; ++k)
  {
    plan.layouts.push_back(chooseLayout(atlas, k));
    plan.compact.push_back(plan.layouts[k].compact ? 1 : 0);
  }
  plan.lattice = exactLattice(atlas, plan.layouts);
  for (size_t k = 0; k < numImages; ++k)
  {
    const AtlasImage& image = atlas.images[k];
    for (size_t a = 0; a < atlas.attributes.size(); ++a)
    {
      plan.crcs[k].push_back(crc32Of(image.data[a].data(), image.data[a].size() * sizeof(float)));
      plan.totalFloats += partFloats(
        image.width, plan.layouts[k].partHeight, { "", storedComponents(atlas, plan.lattice, a) });
    }
    plan.displayWidth = std::max(plan.displayWidth, image.width);
    plan.displayHeight = std::max(plan.displayHeight, image.height);
  }
  for (const AtlasTexture& texture : atlas.textures)
  {
    plan.textureCrcs.push_back(crc32Of(texture.rgba.data(), texture.rgba.size()));
    plan.totalFloats += texture.rgba.size() / 4;
    plan.displayWidth = std::max(plan.displayWidth, texture.width);
    plan.displayHeight = std::max(plan.displayHeight, texture.height);
  }
  return plan;
}

/// A scan-line part of `width` x `height` pixels in the file's display window, compressed.
Imf::Header partHeader(
  const WritePlan& plan, const std::string& name, int32_t width, int32_t height)
{
  const Imath::Box2i display(
    Imath::V2i(0, 0), Imath::V2i(plan.displayWidth - 1, plan.displayHeight - 1));
  Imf::Header header(display, Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(width - 1, height - 1)));
  header.setName(name);
  header.setType(Imf::SCANLINEIMAGE);
  header.compression() = Imf::ZIP_COMPRESSION;
  // Deflate's level 6: on the byte planes of version 4 within 1 % of level 9 (whose long
  // match chains over the planes' zeros take twice the time) and 3 % smaller than
  // OpenEXR's default 4.
  header.zipCompressionLevel() = 6;
  return header;
}

/// One header per part, coarsest image first, so that a file read front to back refines, then
/// one per texture; the first carries the metadata.
std::vector<Imf::Header> partHeaders(const Atlas& atlas, const WritePlan& plan,
  const std::string& metadata, const std::string& packedMetadata)
{
  std::vector<Imf::Header> headers;
  for (size_t k = atlas.images.size(); k-- > 0;)
  {
    const AtlasImage& image = atlas.images[k];
    const int32_t height = plan.layouts[k].partHeight;
    for (size_t a = 0; a < atlas.attributes.size(); ++a)
    {
      const AtlasAttribute& attribute = atlas.attributes[a];
      Imf::Header header = partHeader(plan, partName(attribute.name, k), image.width, height);
      const bool codes = coded(plan.lattice, a);
      for (const std::string& channel :
        codes ? codeChannelNames(a) : channelNames(attribute.components))
      {
        header.channels().insert(channel, Imf::Channel(codes ? Imf::UINT : Imf::FLOAT));
      }
      if (headers.empty())
      {
        header.insert(kCompressedMetadataAttribute, Imf::StringAttribute(packedMetadata));
        header.insert(
          kMetadataLengthAttribute, Imf::IntAttribute(static_cast<int>(metadata.size())));
        header.insert(
          kMetadataCrcAttribute, Imf::IntAttribute(static_cast<int>(crc32Of(metadata))));
      }
      headers.push_back(std::move(header));
    }
  }
  for (const AtlasTexture& texture : atlas.textures)
  {
    Imf::Header header =
      partHeader(plan, texturePartName(texture.name), texture.width, texture.height);
    header.channels().insert(kTextureChannels[0], Imf::Channel(Imf::UINT));
    headers.push_back(std::move(header));
  }
  return headers;
}

/// The texels of every part, in the order of the headers.
void writeParts(Imf::MultiPartOutputFile& file, const Atlas& atlas, const WritePlan& plan,
  const Progress& progress)
{
  uint64_t floatsWritten = 0;
  int index = 0;
  std::optional<CodeWriter> codes;
  if (plan.lattice)
  {
    codes.emplace(atlas, *plan.lattice);
  }
  for (size_t k = atlas.images.size(); k-- > 0;)
  {
    const AtlasImage& image = atlas.images[k];
    const ImageLayout& layout = plan.layouts[k];
    for (size_t a = 0; a < atlas.attributes.size(); ++a, ++index)
    {
      const int32_t components = storedComponents(atlas, plan.lattice, a);
      Imf::OutputPart part(file, index);
      std::vector<float> packed;
      std::vector<uint32_t> residuals;
      if (coded(plan.lattice, a))
      {
        residuals =
          planeValues(codes->residuals(k, a, layout), image.width, static_cast<size_t>(components));
        part.setFrameBuffer(codeBuffer(residuals.data(), image.width, a));
      }
      else
      {
        if (layout.compact)
        {
          packed =
            compactTexels(image.data[a], layout.roles, image.width, layout.partHeight, components);
        }
        part.setFrameBuffer(
          frameBuffer(const_cast<float*>(layout.compact ? packed.data() : image.data[a].data()),
            image.width, components));
      }
      const size_t rowFloats = static_cast<size_t>(image.width) * static_cast<size_t>(components);
      inBlocks(layout.partHeight, rowFloats, floatsWritten, plan.totalFloats, progress,
        [&part](int32_t, int32_t rows) { part.writePixels(rows); });
    }
  }
  for (const AtlasTexture& texture : atlas.textures)
  {
    Imf::OutputPart part(file, index++);
    part.setFrameBuffer(textureBuffer(texture, const_cast<uint8_t*>(texture.rgba.data())));
    inBlocks(texture.height, static_cast<size_t>(texture.width), floatsWritten, plan.totalFloats,
      progress, [&part](int32_t, int32_t rows) { part.writePixels(rows); });
  }
}

/// The OpenEXR file into `temporary`, flushed to disk; any failure as an InputError.
void writeFile(TemporaryFile& temporary, std::vector<Imf::Header>& headers, const Atlas& atlas,
  const WritePlan& plan, const std::string& path, const Progress& progress)
{
  try
  {
    FileOStream stream(temporary);
    {
      Imf::MultiPartOutputFile file(stream, headers.data(), static_cast<int>(headers.size()));
      writeParts(file, atlas, plan, progress);
    } // The destructor writes the chunk offset tables.
    temporary.finish();
  }
  catch (const InputError&)
  {
    throw;
  }
  catch (const Aborted&)
  {
    throw;
  }
  catch (const std::exception& error)
  {
    throw InputError("cannot write atlas " + path + ": " + error.what());
  }
}

// ------------------------------------------------------------------------------------------
// Reading

/// The size of `path`, after checking that it is a file that opens and starts like OpenEXR.
uint64_t exrFileSize(const std::string& path)
{
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
  {
    throw InputError("cannot read atlas " + path + ": it is a folder; give the atlas file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throw InputError("cannot read atlas " + path + ": " + std::strerror(errno) +
      " (check the path and the file's permissions)");
  }
  char magic[4] = { 0, 0, 0, 0 };
  in.read(magic, 4);
  if (in.gcount() != 4 || !Imf::isImfMagic(magic))
  {
    throw InputError("cannot read atlas " + path +
      ": it is not an OpenEXR file; open an atlas (*.exr) written by TriChart");
  }
  in.seekg(0, std::ios::end);
  return static_cast<uint64_t>(in.tellg());
}

/// The first message of OpenEXRCore's header parser, for the error the reader throws.
thread_local std::string exrCoreMessage;

/// Refuses damaged headers before the C++ reader of OpenEXR sees them. OpenEXRCore's parser
/// (hardened by fuzzing) checks every size against the file before it allocates; OpenEXR 3.1's
/// C++ reader does not: one damaged string size makes it allocate and clear 2 GiB.
void checkHeaders(const std::string& path)
{
  exrCoreMessage.clear();
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = [](exr_const_context_t, exr_result_t, const char* message)
  {
    if (exrCoreMessage.empty() && message)
    {
      exrCoreMessage = message;
    }
  };
  // Without the strict flag the parser skips over some damage after reporting it, so any
  // report at all refuses the file.
  init.flags = EXR_CONTEXT_FLAG_STRICT_HEADER;
  exr_context_t context = nullptr;
  const exr_result_t result = exr_start_read(&context, path.c_str(), &init);
  if (context)
  {
    exr_finish(&context);
  }
  if (result != EXR_ERR_SUCCESS || !exrCoreMessage.empty())
  {
    throw InputError("cannot read atlas " + path + ": OpenEXR cannot read its headers (" +
      (exrCoreMessage.empty() ? std::string(exr_get_default_error_message(result))
                              : exrCoreMessage) +
      "); the file is truncated or damaged (write the atlas again)");
  }
}

/// The metadata of the file's first part: the JSON text inflated from "trichartAtlasZ"
/// (versions 2 and 3) or as stored in "trichartAtlas" (version 1), and its checksum.
StoredMetadata storedMetadata(const std::string& path, const Imf::Header& first)
{
  StoredMetadata stored;
  const auto* packed = first.findTypedAttribute<Imf::StringAttribute>(kCompressedMetadataAttribute);
  stored.compressed = packed != nullptr;
  if (packed)
  {
    const auto* length = first.findTypedAttribute<Imf::IntAttribute>(kMetadataLengthAttribute);
    if (!length)
    {
      throw InputError("cannot read atlas " + path + ": its compressed metadata has no '" +
        kMetadataLengthAttribute + "' attribute; the file is damaged (write the atlas again)");
    }
    stored.text = inflateMetadata(path, packed->value(), length->value());
  }
  else
  {
    const auto* text = first.findTypedAttribute<Imf::StringAttribute>(kMetadataAttribute);
    if (!text)
    {
      throw InputError("cannot read atlas " + path +
        ": it is an OpenEXR image but not a TriChart atlas (its first part has no '" +
        kCompressedMetadataAttribute + "' or '" + kMetadataAttribute +
        "' metadata); open an atlas written by TriChart");
    }
    stored.text = text->value();
  }
  const auto* crc = first.findTypedAttribute<Imf::IntAttribute>(kMetadataCrcAttribute);
  if (crc)
  {
    stored.crc = static_cast<uint32_t>(crc->value());
  }
  return stored;
}

/// Refuses a part whose type, size (width x height pixels) or channels differ from what the
/// metadata says.
void checkPart(const std::string& path, const std::string& name, const Imf::Header& header,
  int32_t width, int32_t height, const std::vector<std::string>& channels, Imf::PixelType type)
{
  const std::string prefix = "cannot read atlas " + path + ": part '" + name + "' ";
  const std::string suffix = "; the file is damaged or was not written by TriChart";
  if (!header.hasType() || header.type() != Imf::SCANLINEIMAGE)
  {
    throw InputError(prefix + "is not a scan-line image" + suffix);
  }
  const Imath::Box2i& window = header.dataWindow();
  if (window.min.x != 0 || window.min.y != 0 || window.max.x != width - 1 ||
    window.max.y != height - 1)
  {
    throw InputError(prefix + "covers pixels (" + std::to_string(window.min.x) + ", " +
      std::to_string(window.min.y) + ") .. (" + std::to_string(window.max.x) + ", " +
      std::to_string(window.max.y) + ") but the metadata makes it " + std::to_string(width) +
      " x " + std::to_string(height) + suffix);
  }
  const std::set<std::string> expected(channels.begin(), channels.end());
  const std::string kind = type == Imf::FLOAT ? "32-bit float" : "32-bit unsigned integer";
  std::set<std::string> found;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
  {
    const Imf::Channel& channel = it.channel();
    if (channel.type != type || channel.xSampling != 1 || channel.ySampling != 1)
    {
      throw InputError(prefix + "channel '" + it.name() + "' is not full-resolution " + kind +
        " (as its attribute and format version store it)" + suffix);
    }
    found.insert(it.name());
  }
  if (found != expected)
  {
    std::string names;
    for (const std::string& channel : expected)
    {
      names += (names.empty() ? "" : ", ") + channel;
    }
    throw InputError(prefix + "does not have exactly the channels " + names + " that its " +
      std::to_string(channels.size()) + " " + kind + " values a texel need" + suffix);
  }
}

/// The parts of the file by name, when there are as many as the metadata describes.
std::map<std::string, int> partIndex(
  const std::string& path, Imf::MultiPartInputFile& file, const Atlas& atlas)
{
  std::map<std::string, int> parts;
  for (int p = 0; p < file.parts(); ++p)
  {
    if (file.header(p).hasName())
    {
      parts.emplace(file.header(p).name(), p);
    }
  }
  const size_t expectedParts =
    atlas.attributes.size() * atlas.images.size() + atlas.textures.size();
  if (static_cast<size_t>(file.parts()) != expectedParts)
  {
    throw InputError("cannot read atlas " + path + ": it has " + std::to_string(file.parts()) +
      " parts but its metadata describes " + std::to_string(expectedParts) + " (" +
      std::to_string(atlas.attributes.size()) + " attributes x " +
      std::to_string(atlas.images.size()) + " images + " + std::to_string(atlas.textures.size()) +
      " textures); the file is damaged");
  }
  return parts;
}

/// The index of part `name`, which must be there.
int partOf(
  const std::string& path, const std::map<std::string, int>& parts, const std::string& name)
{
  const auto it = parts.find(name);
  if (it == parts.end())
  {
    throw InputError("cannot read atlas " + path + ": part '" + name +
      "' is missing; the file is damaged or was not written by TriChart");
  }
  return it->second;
}

/// Per image: its layout, every part of it checked against it (present, type, size,
/// channels), and every texture's part; the 4-byte values the parts store in all. Refuses more
/// texel data than the file's size can hold.
std::vector<ImageLayout> checkParts(const std::string& path, Imf::MultiPartInputFile& file,
  const std::map<std::string, int>& parts, const AtlasMetadata& metadata, uint64_t fileSize,
  uint64_t& storedFloats)
{
  const Atlas& atlas = metadata.atlas;
  std::vector<ImageLayout> layouts;
  uint64_t totalFloats = 0;
  storedFloats = 0;
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    const AtlasImage& image = atlas.images[k];
    layouts.push_back(imageLayout(atlas, k, metadata.compact[k] != 0));
    for (size_t a = 0; a < atlas.attributes.size(); ++a)
    {
      const std::string name = partName(atlas.attributes[a].name, k);
      const bool codes = coded(metadata.lattice, a);
      checkPart(path, name, file.header(partOf(path, parts, name)), image.width,
        layouts[k].partHeight,
        codes ? codeChannelNames(a) : channelNames(atlas.attributes[a].components),
        codes ? Imf::UINT : Imf::FLOAT);
      totalFloats += floatCount(image, atlas.attributes[a]);
      storedFloats += partFloats(
        image.width, layouts[k].partHeight, { "", storedComponents(atlas, metadata.lattice, a) });
    }
  }
  for (const AtlasTexture& texture : atlas.textures)
  {
    const std::string name = texturePartName(texture.name);
    checkPart(path, name, file.header(partOf(path, parts, name)), texture.width, texture.height,
      kTextureChannels, Imf::UINT);
    const uint64_t texels = static_cast<uint64_t>(texture.width) * texture.height;
    totalFloats += texels;
    storedFloats += texels;
  }
  if (totalFloats * sizeof(float) > kMaxCompressionRatio * std::max<uint64_t>(fileSize, 1))
  {
    throw InputError("cannot read atlas " + path + ": it declares " +
      std::to_string(totalFloats * sizeof(float)) + " bytes of texels in a file of " +
      std::to_string(fileSize) + " bytes, more than any compression gives; the file is damaged");
  }
  return layouts;
}

/// The texels of every image, coarsest first: a compact image takes its inherited texels from
/// the next coarser one. Refuses texels that do not match their checksum. Counts the values
/// read into `floatsRead`.
void readImages(const std::string& path, Imf::MultiPartInputFile& file,
  const std::map<std::string, int>& parts, const std::vector<ImageLayout>& layouts,
  uint64_t& floatsRead, uint64_t storedFloats, AtlasMetadata& metadata, const Progress& progress)
{
  Atlas& atlas = metadata.atlas;
  std::optional<CodeReader> codes;
  if (metadata.lattice)
  {
    codes.emplace(atlas, *metadata.lattice);
  }
  for (size_t k = atlas.images.size(); k-- > 0;)
  {
    AtlasImage& image = atlas.images[k];
    const ImageLayout& layout = layouts[k];
    image.data.resize(atlas.attributes.size());
    for (size_t a = 0; a < atlas.attributes.size(); ++a)
    {
      const std::string name = partName(atlas.attributes[a].name, k);
      const int32_t components = storedComponents(atlas, metadata.lattice, a);
      const bool isCoded = coded(metadata.lattice, a);
      std::vector<float>& data = image.data[a];
      data.assign(floatCount(image, atlas.attributes[a]), 0.0f);
      const size_t storedValues = layout.compact ? static_cast<size_t>(image.width) *
          static_cast<size_t>(layout.partHeight) * static_cast<size_t>(components)
                                                 : 0;
      std::vector<float> stored(isCoded ? 0 : storedValues, 0.0f);
      std::vector<uint32_t> residuals(isCoded ? storedValues : 0, 0u);
      Imf::InputPart part(file, parts.at(name));
      part.setFrameBuffer(isCoded
          ? codeBuffer(residuals.data(), image.width, a)
          : frameBuffer(layout.compact ? stored.data() : data.data(), image.width, components));
      const size_t rowFloats = static_cast<size_t>(image.width) * static_cast<size_t>(components);
      inBlocks(layout.partHeight, rowFloats, floatsRead, storedFloats, progress,
        [&part](int32_t y, int32_t rows) { part.readPixels(y, y + rows - 1); });
      if (isCoded)
      {
        codes->decode(k, a, layout,
          planeResiduals(std::move(residuals), image.width, static_cast<size_t>(components)), path,
          name, data);
      }
      else if (layout.compact)
      {
        expandTexels(stored, layout.roles, components, data);
        copyInherited(atlas, k, a, data);
      }
      if (crc32Of(data.data(), data.size() * sizeof(float)) != metadata.crcs[k][a])
      {
        throw InputError("cannot read atlas " + path + ": the texels of part '" + name +
          "' do not match their checksum; the file is damaged (write the atlas again)");
      }
    }
  }
}

/// The bytes of every texture, after the images. Refuses bytes that do not match their checksum.
void readTextures(const std::string& path, Imf::MultiPartInputFile& file,
  const std::map<std::string, int>& parts, uint64_t& valuesRead, uint64_t storedFloats,
  AtlasMetadata& metadata, const Progress& progress)
{
  for (size_t t = 0; t < metadata.atlas.textures.size(); ++t)
  {
    AtlasTexture& texture = metadata.atlas.textures[t];
    const std::string name = texturePartName(texture.name);
    texture.rgba.assign(
      static_cast<size_t>(texture.width) * static_cast<size_t>(texture.height) * 4, 0);
    Imf::InputPart part(file, parts.at(name));
    part.setFrameBuffer(textureBuffer(texture, texture.rgba.data()));
    inBlocks(texture.height, static_cast<size_t>(texture.width), valuesRead, storedFloats, progress,
      [&part](int32_t y, int32_t rows) { part.readPixels(y, y + rows - 1); });
    if (crc32Of(texture.rgba.data(), texture.rgba.size()) != metadata.textureCrcs[t])
    {
      throw InputError("cannot read atlas " + path + ": the texels of part '" + name +
        "' do not match their checksum; the file is damaged (write the atlas again)");
    }
  }
}

/// The atlas in `path` (headers checked), unvalidated; OpenEXR's exceptions pass through.
Atlas readAtlasFile(const std::string& path, uint64_t fileSize, const Progress& progress)
{
  Imf::MultiPartInputFile file(path.c_str());
  AtlasMetadata metadata = parseMetadata(path, storedMetadata(path, file.header(0)));
  try
  {
    // Compact parts are placed by the chart layout: it must hold before any texel is.
    validateAtlasLayout(metadata.atlas);
  }
  catch (const InputError& invalid)
  {
    throw InputError("cannot read atlas " + path + ": " + invalid.what() +
      " (the file is damaged or was written by a faulty program)");
  }
  const std::map<std::string, int> parts = partIndex(path, file, metadata.atlas);
  uint64_t storedFloats = 0;
  const std::vector<ImageLayout> layouts =
    checkParts(path, file, parts, metadata, fileSize, storedFloats);
  uint64_t valuesRead = 0;
  readImages(path, file, parts, layouts, valuesRead, storedFloats, metadata, progress);
  readTextures(path, file, parts, valuesRead, storedFloats, metadata, progress);
  return std::move(metadata.atlas);
}

/// readAtlasFile with every failure as an InputError that names the file.
Atlas readAtlasOrExplain(const std::string& path, uint64_t fileSize, const Progress& progress)
{
  try
  {
    return readAtlasFile(path, fileSize, progress);
  }
  catch (const Iex::BaseExc& exrError)
  {
    throw InputError("cannot read atlas " + path + ": OpenEXR cannot read it (" + exrError.what() +
      "); the file is truncated or damaged (write the atlas again)");
  }
  catch (const std::bad_alloc&)
  {
    throw InputError("cannot read atlas " + path +
      ": not enough memory for the sizes it declares; the file may be damaged");
  }
  catch (const InputError&)
  {
    throw;
  }
  catch (const Aborted&)
  {
    throw;
  }
  catch (const std::exception& other)
  {
    throw InputError("cannot read atlas " + path + ": " + other.what() +
      "; the file is truncated or damaged (write the atlas again)");
  }
}
} // namespace

bool isAtlasFile(const std::string& path)
{
  try
  {
    checkHeaders(path);
    Imf::MultiPartInputFile file(path.c_str());
    checkMetadata(path, storedMetadata(path, file.header(0)));
    return true;
  }
  catch (const std::exception&)
  {
    return false;
  }
}

bool isAtlasFileName(const std::string& path)
{
  return hasExtension(path, ".exr");
}

void writeAtlas(const Atlas& atlas, const std::string& path, const Progress& progress)
{
  progress.report(0.0);
  if (!isAtlasFileName(path))
  {
    throw InputError("cannot write atlas " + path +
      ": an atlas file is OpenEXR, named .exr (a mesh or LOD chain for other tools: trichart "
      "mesh or trichart export)");
  }
  // 1. Refuse an atlas that is invalid or that the file cannot hold exactly.
  try
  {
    validateAtlas(atlas);
  }
  catch (const InputError& error)
  {
    throw InputError(
      "cannot write atlas " + path + ": " + error.what() + " (fix the stage that built it)");
  }
  checkWritable(atlas, path);

  // 2. Per image: compact (its parts hold only the texels no coarser image holds) when the
  // texels allow it, the part height, and the checksum of every attribute.
  const WritePlan plan = planParts(atlas);

  // 3. The metadata, deflated into the header of the first part.
  const std::string metadata = metadataJson(
    atlas, plan.crcs, plan.textureCrcs, plan.compact, plan.lattice ? &*plan.lattice : nullptr);
  std::vector<Imf::Header> headers =
    partHeaders(atlas, plan, metadata, compressMetadata(metadata, path));

  // 4. The parts into a temporary file beside the target, renamed over it once on disk.
  TemporaryFile temporary(path, "cannot write atlas " + path);
  writeFile(temporary, headers, atlas, plan, path, progress);
  temporary.commit();
  progress.report(1.0);
}

Atlas readAtlas(const std::string& path, const Progress& progress)
{
  progress.report(0.0);
  // 1. An OpenEXR file whose headers OpenEXRCore's strict parser accepts.
  const uint64_t fileSize = exrFileSize(path);
  checkHeaders(path);
  // 2. The metadata, the parts it describes and their texels.
  Atlas atlas = readAtlasOrExplain(path, fileSize, progress);
  // 3. Every invariant of atlas.h.
  try
  {
    validateAtlas(atlas);
  }
  catch (const InputError& invalid)
  {
    throw InputError("cannot read atlas " + path + ": " + invalid.what() +
      " (the file is damaged or was written by a faulty program)");
  }
  progress.report(1.0);
  return atlas;
}

Rig readAtlasRig(const std::string& path)
{
  exrFileSize(path);
  checkHeaders(path);
  try
  {
    Imf::MultiPartInputFile file(path.c_str());
    return parseMetadata(path, storedMetadata(path, file.header(0))).atlas.rig;
  }
  catch (const Iex::BaseExc& exrError)
  {
    throw InputError("cannot read atlas " + path + ": OpenEXR cannot read its headers (" +
      exrError.what() + "); the file is truncated or damaged (write the atlas again)");
  }
}
} // namespace tc
