// SPDX-License-Identifier: BSD-3-Clause
#include "tc/io/atlas_io.h"

#include "tc/common/errors.h"

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
#include <nlohmann/json.hpp>
#include <openexr.h>
#include <zlib.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <new>
#include <random>
#include <set>

// The checksums are taken over the float data as it lies in memory; the file stores it
// little-endian, so a big-endian host would need a byte swap first.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "atlas_io assumes a little-endian host");

namespace tc
{
namespace
{
using Json = nlohmann::ordered_json;

constexpr const char* kFormatName = "TriChart atlas";
constexpr const char* kMetadataAttribute = "trichartAtlas";            ///< version 1: the JSON text
constexpr const char* kCompressedMetadataAttribute = "trichartAtlasZ"; ///< version 2: deflated
constexpr const char* kMetadataLengthAttribute = "trichartAtlasLength";
constexpr const char* kMetadataCrcAttribute = "trichartAtlasCrc32";

/// Deflate turns at most 1032 output bytes into one input byte (a 1-bit length code for 258
/// bytes plus a 1-bit distance code): compressed metadata declaring a longer text than this
/// times its size is damaged, and is refused before anything is inflated.
constexpr uint64_t kMaxDeflateRatio = 1032;

/// Texel data is read and written in blocks of about this many floats, so progress and abort
/// come at least every few milliseconds even for one large image.
constexpr size_t kBlockFloats = size_t(1) << 20;

/// No lossless coder OpenEXR offers shrinks float data by more than this (deflate's limit is
/// about 1032:1): a file declaring more texel data than this times its size is damaged, and is
/// refused before the memory for it is allocated.
constexpr uint64_t kMaxCompressionRatio = 4096;

std::string partName(const std::string& attribute, size_t image)
{
  return attribute + "." + std::to_string(image);
}

/// Channel names of an attribute with `components` components (see atlas_io.h).
std::vector<std::string> channelNames(int32_t components)
{
  switch (components)
  {
    case 1:
      return { "R" };
    case 2:
      return { "R", "G" };
    case 3:
      return { "X", "Y", "Z" };
    case 4:
      return { "R", "G", "B", "A" };
    default:
    {
      std::vector<std::string> names;
      for (int32_t c = 0; c < components; ++c)
      {
        names.push_back("C" + std::to_string(c));
      }
      return names;
    }
  }
}

uint32_t crc32Of(const void* data, size_t bytes)
{
  return static_cast<uint32_t>(
    crc32_z(crc32_z(0L, Z_NULL, 0), static_cast<const Bytef*>(data), static_cast<z_size_t>(bytes)));
}

uint32_t crc32Of(const std::string& text)
{
  return crc32Of(text.data(), text.size());
}

size_t floatCount(const AtlasImage& image, const AtlasAttribute& attribute)
{
  return static_cast<size_t>(image.width) * static_cast<size_t>(image.height) *
    static_cast<size_t>(attribute.components);
}

/// Rows per readPixels / writePixels call for an image of `rowFloats` floats per row.
int32_t rowsPerBlock(size_t rowFloats)
{
  return static_cast<int32_t>(std::max<size_t>(1, kBlockFloats / std::max<size_t>(1, rowFloats)));
}

/// A frame buffer over one attribute of one image: components interleaved, rows y = 0 .. h-1.
/// OpenEXR takes a non-const base pointer for writing too; it only reads through it then.
Imf::FrameBuffer frameBuffer(float* data, int32_t width, int32_t components)
{
  Imf::FrameBuffer buffer;
  const std::vector<std::string> names = channelNames(components);
  const size_t xStride = sizeof(float) * static_cast<size_t>(components);
  const size_t yStride = xStride * static_cast<size_t>(width);
  for (int32_t c = 0; c < components; ++c)
  {
    buffer.insert(names[static_cast<size_t>(c)],
      Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data + c), xStride, yStride));
  }
  return buffer;
}

// ------------------------------------------------------------------------------------------
// Version 3's compact parts: only the texels that no coarser image holds

/// What a texel of an image holds, for the compact layout.
enum TexelRole : uint8_t
{
  kEmptyTexel = 0, ///< no chart: 0 in every attribute
  kNewTexel = 1,   ///< a sample that no coarser image holds: stored in the part
  kInheritedTexel =
    2, ///< sample (i, j), both even, of level d >= 1: sample (i/2, j/2) of image k + 1
};

/// Calls f(texel of image k, texel of image k + 1) for every inherited texel of image k.
template <class F>
void forEachInherited(const Atlas& atlas, size_t k, F&& f)
{
  const size_t coarseWidth =
    k + 1 < atlas.images.size() ? static_cast<size_t>(atlas.images[k + 1].width) : 0;
  forEachImageSample(atlas, k,
    [&](int32_t c, int32_t d, int32_t i, int32_t j, size_t texel)
    {
      if (d >= 1 && i % 2 == 0 && j % 2 == 0)
      {
        const std::array<int32_t, 2> xy =
          atlasTexel(atlas.charts[static_cast<size_t>(c)], d - 1, i / 2, j / 2);
        f(texel, static_cast<size_t>(xy[1]) * coarseWidth + static_cast<size_t>(xy[0]));
      }
    });
}

/// The role of every texel of image k, rows of the image's width.
std::vector<uint8_t> texelRoles(const Atlas& atlas, size_t k)
{
  const AtlasImage& image = atlas.images[k];
  std::vector<uint8_t> roles(
    static_cast<size_t>(image.width) * static_cast<size_t>(image.height), kEmptyTexel);
  forEachImageSample(atlas, k,
    [&roles](int32_t, int32_t, int32_t, int32_t, size_t texel) { roles[texel] = kNewTexel; });
  forEachInherited(atlas, k, [&roles](size_t texel, size_t) { roles[texel] = kInheritedTexel; });
  return roles;
}

/// Floats in a part of `rows` rows of an image `width` texels wide.
uint64_t partFloats(int32_t width, int32_t rows, const AtlasAttribute& attribute)
{
  return static_cast<uint64_t>(width) * static_cast<uint64_t>(rows) *
    static_cast<uint64_t>(attribute.components);
}

/// Height of a compact part of an image `width` texels wide: rows enough for its new texels
/// (at least 1).
int32_t compactHeight(const std::vector<uint8_t>& roles, int32_t width)
{
  const size_t fresh = static_cast<size_t>(std::count(roles.begin(), roles.end(), kNewTexel));
  const size_t w = static_cast<size_t>(width);
  return static_cast<int32_t>(std::max<size_t>(1, (fresh + w - 1) / w));
}

/// Whether image k can be stored compactly: every inherited texel bit-identical to its coarser
/// copy and every empty texel all zero bits, in every attribute. The pipeline's point-sampled
/// pyramid always is; an atlas made otherwise is stored whole, so every atlas reads back exactly.
bool compactable(const Atlas& atlas, size_t k, const std::vector<uint8_t>& roles)
{
  for (size_t a = 0; a < atlas.attributes.size(); ++a)
  {
    const size_t comps = static_cast<size_t>(atlas.attributes[a].components);
    const float* fine = atlas.images[k].data[a].data();
    for (size_t t = 0; t < roles.size(); ++t)
    {
      if (roles[t] != kEmptyTexel)
      {
        continue;
      }
      for (size_t c = 0; c < comps; ++c)
      {
        uint32_t bits = 0;
        std::memcpy(&bits, fine + t * comps + c, sizeof(bits));
        if (bits != 0)
        {
          return false;
        }
      }
    }
    if (k + 1 == atlas.images.size())
    {
      continue;
    }
    const float* coarse = atlas.images[k + 1].data[a].data();
    bool same = true;
    forEachInherited(atlas, k,
      [&](size_t texel, size_t from)
      {
        same = same &&
          std::memcmp(fine + texel * comps, coarse + from * comps, comps * sizeof(float)) == 0;
      });
    if (!same)
    {
      return false;
    }
  }
  return true;
}

/// The new texels of `data` (`comps` floats each) in texel order, as `rows` rows of the image's
/// width: the last row ends in zeros.
std::vector<float> compactTexels(const std::vector<float>& data, const std::vector<uint8_t>& roles,
  int32_t width, int32_t rows, int32_t comps)
{
  const size_t nc = static_cast<size_t>(comps);
  std::vector<float> out(static_cast<size_t>(width) * static_cast<size_t>(rows) * nc, 0.0f);
  auto to = out.begin();
  for (size_t t = 0; t < roles.size(); ++t)
  {
    if (roles[t] == kNewTexel)
    {
      to = std::copy(data.begin() + static_cast<std::ptrdiff_t>(t * nc),
        data.begin() + static_cast<std::ptrdiff_t>((t + 1) * nc), to);
    }
  }
  return out;
}

/// The inverse of compactTexels for the new texels: puts them back into `data`.
void expandTexels(const std::vector<float>& compact, const std::vector<uint8_t>& roles,
  int32_t comps, std::vector<float>& data)
{
  const size_t nc = static_cast<size_t>(comps);
  auto from = compact.begin();
  for (size_t t = 0; t < roles.size(); ++t)
  {
    if (roles[t] == kNewTexel)
    {
      std::copy(from, from + static_cast<std::ptrdiff_t>(nc),
        data.begin() + static_cast<std::ptrdiff_t>(t * nc));
      from += static_cast<std::ptrdiff_t>(nc);
    }
  }
}

// ------------------------------------------------------------------------------------------
// Writing

/// A double as JSON: numbers print to the shortest text that reads back to the same bits (the
/// Grisu2 output of nlohmann-json, read with strtod); JSON has no infinity, so it is a string.
Json encodeDouble(double value)
{
  if (std::isfinite(value))
  {
    return value;
  }
  return value > 0 ? "inf" : "-inf";
}

bool isUtf8(const std::string& text)
{
  try
  {
    (void)Json(text).dump();
    return true;
  }
  catch (const Json::type_error&)
  {
    return false;
  }
}

/// The atlas metadata (everything but the texels) as JSON; `crcs` per image, per attribute;
/// `compact` per image: whether its parts hold only its new texels.
Json atlasMetadata(const Atlas& atlas, const std::vector<std::vector<uint32_t>>& crcs,
  const std::vector<uint8_t>& compact)
{
  Json root;
  root["format"] = kFormatName;
  root["version"] = kAtlasFileVersion;
  root["source"] = atlas.source;
  root["inputPoints"] = atlas.inputPoints;
  root["inputTriangles"] = atlas.inputTriangles;
  root["inputDiagonal"] = encodeDouble(atlas.inputDiagonal);
  root["attributes"] = Json::array();
  for (const AtlasAttribute& attribute : atlas.attributes)
  {
    root["attributes"].push_back(
      { { "name", attribute.name }, { "components", attribute.components } });
  }
  root["images"] = Json::array();
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    root["images"].push_back(
      { { "width", atlas.images[k].width }, { "height", atlas.images[k].height },
        { "texels", compact[k] ? "new" : "all" }, { "crc32", crcs[k] } });
  }
  root["charts"] = Json::array();
  for (const AtlasChart& chart : atlas.charts)
  {
    Json c;
    c["maxLevel"] = chart.maxLevel;
    c["cornerVertex"] = chart.cornerVertex;
    c["neighborChart"] = chart.neighborChart;
    c["neighborSide"] = chart.neighborSide;
    c["featureSide"] = chart.featureSide;
    c["partner"] = chart.partner;
    c["rotated"] = chart.rotated;
    c["origin"] = chart.origin;
    c["box"] = Json::array();
    for (double v : chart.box)
    {
      c["box"].push_back(encodeDouble(v));
    }
    c["levelError"] = Json::array();
    for (double v : chart.levelError)
    {
      c["levelError"].push_back(encodeDouble(v));
    }
    root["charts"].push_back(std::move(c));
  }
  return root;
}

/// The metadata JSON text deflated for "trichartAtlasZ" (zlib stream, best compression).
///
/// Text rather than a binary table because binary does not pay for a second encoding: on the
/// 70K bunny (520 charts) the 276 KB of JSON deflate to 98 KB; with the 8188 doubles of box and
/// levelError (3/5 of the text) as byte-shuffled binary the table would deflate to about 74 KB,
/// only 1.8 % of the 1.34 MB file less, whereas the JSON keeps version 1's exact-round-trip rules
/// and stays readable by any JSON tool once inflated.
std::string compressMetadata(const std::string& text, const std::string& path)
{
  // An OpenEXR attribute holds at most 2^31 - 1 bytes, and the length is an int attribute.
  const auto tooLarge = [&path](size_t bytes)
  {
    return InputError("cannot write atlas " + path + ": its metadata takes " +
      std::to_string(bytes) +
      " bytes, more than the 2^31 - 1 an OpenEXR attribute holds; split "
      "the mesh into fewer charts or several atlases");
  };
  if (text.size() > static_cast<size_t>(INT32_MAX))
  {
    throw tooLarge(text.size());
  }
  uLongf size = compressBound(static_cast<uLong>(text.size()));
  std::string packed(size, '\0');
  const int status = compress2(reinterpret_cast<Bytef*>(&packed[0]), &size,
    reinterpret_cast<const Bytef*>(text.data()), static_cast<uLong>(text.size()),
    Z_BEST_COMPRESSION);
  if (status != Z_OK)
  {
    throw InputError("cannot write atlas " + path + ": zlib cannot compress its metadata (" +
      zError(status) + ")");
  }
  if (size > static_cast<uLongf>(INT32_MAX))
  {
    throw tooLarge(size);
  }
  packed.resize(size);
  return packed;
}

/// Refuses what the file cannot hold exactly (validateAtlas has checked the layout).
void checkWritable(const Atlas& atlas, const std::string& path)
{
  const auto refuseNaN = [&path](double v, const std::string& what)
  {
    if (std::isnan(v))
    {
      throw InputError("cannot write atlas " + path + ": " + what +
        " is NaN, which the atlas file cannot hold; compute it, or leave levelError empty when "
        "it was not measured");
    }
  };
  refuseNaN(atlas.inputDiagonal, "inputDiagonal");
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    const AtlasChart& chart = atlas.charts[c];
    for (size_t i = 0; i < chart.box.size(); ++i)
    {
      refuseNaN(chart.box[i], "chart " + std::to_string(c) + " box[" + std::to_string(i) + "]");
    }
    for (size_t i = 0; i < chart.levelError.size(); ++i)
    {
      refuseNaN(chart.levelError[i],
        "chart " + std::to_string(c) + " levelError[" + std::to_string(i) + "]");
    }
  }
  for (const AtlasAttribute& attribute : atlas.attributes)
  {
    if (!isUtf8(attribute.name))
    {
      throw InputError("cannot write atlas " + path + ": attribute name '" + attribute.name +
        "' is not UTF-8 text; rename the attribute");
    }
  }
}

/// OpenEXR output into a stdio stream, so that every failure (including those in the
/// destructor of MultiPartOutputFile, which writes the chunk offset tables and swallows
/// exceptions) is seen, and the data can be flushed to disk before the rename.
class FileOStream : public Imf::OStream
{
public:
  FileOStream(std::FILE* file, const std::string& temporary, const std::string& target)
    : Imf::OStream(temporary.c_str())
    , File(file)
    , Target(target)
  {
  }

  ~FileOStream() override
  {
    if (File)
    {
      std::fclose(File);
    }
  }

  void write(const char c[], int n) override
  {
    if (n > 0 && std::fwrite(c, 1, static_cast<size_t>(n), File) != static_cast<size_t>(n))
    {
      fail();
    }
  }

  uint64_t tellp() override
  {
    const off_t at = ftello(File);
    if (at < 0)
    {
      fail();
    }
    return static_cast<uint64_t>(at);
  }

  void seekp(uint64_t pos) override
  {
    if (fseeko(File, static_cast<off_t>(pos), SEEK_SET) != 0)
    {
      fail();
    }
  }

  /// Flushes to disk and closes; throws if anything failed on the way.
  void finish()
  {
    if (Failed.empty() &&
      (std::fflush(File) != 0 || std::ferror(File) || ::fsync(fileno(File)) != 0))
    {
      Failed = std::strerror(errno);
    }
    const bool closed = std::fclose(File) == 0;
    File = nullptr;
    if (Failed.empty() && !closed)
    {
      Failed = std::strerror(errno);
    }
    if (!Failed.empty())
    {
      throw InputError("cannot write atlas " + Target + ": " + Failed +
        " (is the disk full or the folder no longer writable?)");
    }
  }

private:
  [[noreturn]] void fail()
  {
    if (Failed.empty())
    {
      Failed = std::strerror(errno);
    }
    throw InputError("cannot write atlas " + Target + ": " + Failed +
      " (is the disk full or the folder no longer writable?)");
  }

  std::FILE* File;
  std::string Target;
  std::string Failed;
};

/// Creates a new empty file `path`.tmp-XXXXXX beside `path` and opens it. Not mkstemp: that
/// creates the file with mode 0600, and the atlas would keep it after the rename; open with
/// O_EXCL and mode 0666 gives the mode the user's umask asks for, like any new file.
std::FILE* createTemporary(const std::string& path, std::string& temporary)
{
  static const char kLetters[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::random_device entropy;
  std::mt19937_64 random((static_cast<uint64_t>(entropy()) << 32) ^ entropy());
  for (int attempt = 0; attempt < 100; ++attempt)
  {
    temporary = path + ".tmp-";
    for (int i = 0; i < 6; ++i)
    {
      temporary += kLetters[random() % (sizeof(kLetters) - 1)];
    }
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0)
    {
      std::FILE* file = ::fdopen(fd, "wb");
      if (!file)
      {
        const int error = errno;
        ::close(fd);
        ::unlink(temporary.c_str());
        errno = error;
        break;
      }
      return file;
    }
    if (errno != EEXIST)
    {
      break;
    }
  }
  throw InputError("cannot write atlas " + path + ": " + std::strerror(errno) +
    " (does the folder exist and is it writable?)");
}

/// Removes the temporary file unless the write completed.
struct TemporaryGuard
{
  std::string Path;
  bool Keep = false;
  ~TemporaryGuard()
  {
    if (!Keep && !Path.empty())
    {
      ::unlink(Path.c_str());
    }
  }
};

// ------------------------------------------------------------------------------------------
// Reading

/// Parses the metadata of `path`; every failure names the file and the field.
class MetadataReader
{
public:
  explicit MetadataReader(const std::string& path)
    : Path(path)
  {
  }

  [[noreturn]] void fail(const std::string& what) const
  {
    throw InputError("cannot read atlas " + Path + ": its metadata " + what +
      "; the file is damaged or was not written by TriChart (write the atlas again)");
  }

  const Json& member(const Json& object, const char* key, const std::string& where) const
  {
    if (!object.is_object())
    {
      fail("has " + where + " that is not a JSON object");
    }
    const auto it = object.find(key);
    if (it == object.end())
    {
      fail("lacks " + where + "." + key);
    }
    return *it;
  }

  int64_t integer(const Json& value, int64_t low, int64_t high, const std::string& where) const
  {
    int64_t v = 0;
    if (value.is_number_unsigned())
    {
      const uint64_t u = value.get<uint64_t>();
      if (u > static_cast<uint64_t>(high))
      {
        fail("has " + where + " = " + value.dump() + ", out of range");
      }
      v = static_cast<int64_t>(u);
    }
    else if (value.is_number_integer())
    {
      v = value.get<int64_t>();
    }
    else
    {
      fail("has " + where + " that is not an integer");
    }
    if (v < low || v > high)
    {
      fail("has " + where + " = " + std::to_string(v) + ", out of range [" + std::to_string(low) +
        ", " + std::to_string(high) + "]");
    }
    return v;
  }

  int32_t int32(const Json& value, const std::string& where) const
  {
    return static_cast<int32_t>(integer(value, INT32_MIN, INT32_MAX, where));
  }

  double number(const Json& value, const std::string& where) const
  {
    if (value.is_number())
    {
      return value.get<double>();
    }
    if (value.is_string() && value.get_ref<const std::string&>() == "inf")
    {
      return HUGE_VAL;
    }
    if (value.is_string() && value.get_ref<const std::string&>() == "-inf")
    {
      return -HUGE_VAL;
    }
    fail("has " + where + " that is not a number");
  }

  const Json& array(
    const Json& value, size_t minSize, size_t maxSize, const std::string& where) const
  {
    if (!value.is_array() || value.size() < minSize || value.size() > maxSize)
    {
      fail("has " + where + " that is not an array of " +
        (minSize == maxSize ? std::to_string(minSize)
                            : std::to_string(minSize) + " to " + std::to_string(maxSize)) +
        " elements");
    }
    return value;
  }

  template <typename T, size_t N>
  std::array<T, N> integers(
    const Json& value, int64_t low, int64_t high, const std::string& where) const
  {
    array(value, N, N, where);
    std::array<T, N> out{};
    for (size_t i = 0; i < N; ++i)
    {
      out[i] = static_cast<T>(integer(value[i], low, high, where + "[" + std::to_string(i) + "]"));
    }
    return out;
  }

  std::string Path;
};

/// The atlas without texels, from the metadata JSON, plus the checksums per image and attribute.
Atlas parseMetadata(const std::string& path, const Json& root,
  std::vector<std::vector<uint32_t>>& crcs, std::vector<uint8_t>& compact)
{
  const MetadataReader in(path);
  Atlas atlas;
  const Json& source = in.member(root, "source", "the root");
  if (!source.is_string())
  {
    in.fail("has a source that is not a string");
  }
  atlas.source = source.get<std::string>();
  atlas.inputPoints =
    in.integer(in.member(root, "inputPoints", "the root"), INT64_MIN, INT64_MAX, "inputPoints");
  atlas.inputTriangles = in.integer(
    in.member(root, "inputTriangles", "the root"), INT64_MIN, INT64_MAX, "inputTriangles");
  atlas.inputDiagonal = in.number(in.member(root, "inputDiagonal", "the root"), "inputDiagonal");

  // Attribute and image counts and sizes within validateAtlas's limits before anything is
  // allocated from them.
  const Json& attributes =
    in.array(in.member(root, "attributes", "the root"), 1, 1024, "attributes");
  for (size_t a = 0; a < attributes.size(); ++a)
  {
    const std::string where = "attributes[" + std::to_string(a) + "]";
    AtlasAttribute attribute;
    const Json& name = in.member(attributes[a], "name", where);
    if (!name.is_string())
    {
      in.fail("has " + where + ".name that is not a string");
    }
    attribute.name = name.get<std::string>();
    attribute.components =
      in.int32(in.member(attributes[a], "components", where), where + ".components");
    if (attribute.components < 1 || attribute.components > 64)
    {
      in.fail("has " + where + ".components = " + std::to_string(attribute.components) +
        ", expected 1 to 64");
    }
    atlas.attributes.push_back(std::move(attribute));
  }
  const Json& images = in.array(in.member(root, "images", "the root"), 1, 21, "images");
  crcs.assign(images.size(), {});
  compact.assign(images.size(), 0);
  const bool hasLayout = root["version"].get<int64_t>() >= 3;
  for (size_t k = 0; k < images.size(); ++k)
  {
    const std::string where = "images[" + std::to_string(k) + "]";
    AtlasImage image;
    image.width = static_cast<int32_t>(
      in.integer(in.member(images[k], "width", where), 1, 1 << 16, where + ".width"));
    image.height = static_cast<int32_t>(
      in.integer(in.member(images[k], "height", where), 1, 1 << 16, where + ".height"));
    if (hasLayout)
    {
      const Json& texels = in.member(images[k], "texels", where);
      if (!texels.is_string() || (texels != "new" && texels != "all"))
      {
        in.fail("has " + where + ".texels that is neither \"new\" nor \"all\"");
      }
      compact[k] = texels == "new";
    }
    const Json& crc = in.array(
      in.member(images[k], "crc32", where), attributes.size(), attributes.size(), where + ".crc32");
    for (size_t a = 0; a < crc.size(); ++a)
    {
      crcs[k].push_back(static_cast<uint32_t>(
        in.integer(crc[a], 0, UINT32_MAX, where + ".crc32[" + std::to_string(a) + "]")));
    }
    atlas.images.push_back(std::move(image));
  }

  const Json& charts = in.member(root, "charts", "the root");
  if (!charts.is_array())
  {
    in.fail("has charts that is not an array");
  }
  atlas.charts.reserve(charts.size());
  for (size_t c = 0; c < charts.size(); ++c)
  {
    const std::string where = "charts[" + std::to_string(c) + "]";
    const Json& j = charts[c];
    AtlasChart chart;
    chart.maxLevel = in.int32(in.member(j, "maxLevel", where), where + ".maxLevel");
    chart.cornerVertex = in.integers<int32_t, 3>(
      in.member(j, "cornerVertex", where), INT32_MIN, INT32_MAX, where + ".cornerVertex");
    chart.neighborChart = in.integers<int32_t, 3>(
      in.member(j, "neighborChart", where), INT32_MIN, INT32_MAX, where + ".neighborChart");
    chart.neighborSide = in.integers<int32_t, 3>(
      in.member(j, "neighborSide", where), INT32_MIN, INT32_MAX, where + ".neighborSide");
    chart.featureSide =
      in.integers<uint8_t, 3>(in.member(j, "featureSide", where), 0, 255, where + ".featureSide");
    chart.partner = in.int32(in.member(j, "partner", where), where + ".partner");
    chart.rotated =
      static_cast<uint8_t>(in.integer(in.member(j, "rotated", where), 0, 255, where + ".rotated"));
    const Json& origin = in.array(in.member(j, "origin", where), 0, 64, where + ".origin");
    for (size_t k = 0; k < origin.size(); ++k)
    {
      chart.origin.push_back(in.integers<int32_t, 2>(
        origin[k], INT32_MIN, INT32_MAX, where + ".origin[" + std::to_string(k) + "]"));
    }
    const Json& box = in.array(in.member(j, "box", where), 12, 12, where + ".box");
    for (size_t i = 0; i < 12; ++i)
    {
      chart.box[i] = in.number(box[i], where + ".box[" + std::to_string(i) + "]");
    }
    const Json& levelError =
      in.array(in.member(j, "levelError", where), 0, 64, where + ".levelError");
    for (size_t i = 0; i < levelError.size(); ++i)
    {
      chart.levelError.push_back(
        in.number(levelError[i], where + ".levelError[" + std::to_string(i) + "]"));
    }
    atlas.charts.push_back(std::move(chart));
  }
  return atlas;
}

/// The JSON text deflated in `packed`, which the file says inflates to `declared` bytes. Memory
/// grows with the bytes actually inflated (never more than declared + 1), so a damaged length
/// or stream cannot make the reader allocate more than the metadata's real size.
std::string inflateMetadata(const std::string& path, const std::string& packed, int64_t declared)
{
  const std::string damaged = "; the file is damaged (write the atlas again)";
  if (declared < 0 ||
    static_cast<uint64_t>(declared) > kMaxDeflateRatio * static_cast<uint64_t>(packed.size()))
  {
    throw InputError("cannot read atlas " + path + ": its compressed metadata of " +
      std::to_string(packed.size()) + " bytes declares a length of " + std::to_string(declared) +
      " bytes, which deflate cannot give" + damaged);
  }
  z_stream stream{};
  if (inflateInit(&stream) != Z_OK)
  {
    throw std::bad_alloc();
  }
  // Ends the stream on every way out.
  struct End
  {
    z_stream& Stream;
    ~End() { inflateEnd(&Stream); }
  } end{ stream };
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(packed.data()));
  stream.avail_in = static_cast<uInt>(packed.size());
  const size_t limit = static_cast<size_t>(declared) + 1;
  std::string text;
  int status = Z_OK;
  while (status != Z_STREAM_END)
  {
    if (stream.avail_out == 0)
    {
      if (text.size() == limit)
      {
        throw InputError("cannot read atlas " + path +
          ": its compressed metadata inflates to more than the " + std::to_string(declared) +
          " bytes it declares" + damaged);
      }
      const size_t have = text.size();
      text.resize(std::min(limit, std::max<size_t>(2 * have, size_t(1) << 16)));
      stream.next_out = reinterpret_cast<Bytef*>(&text[0]) + have;
      stream.avail_out = static_cast<uInt>(text.size() - have);
    }
    status = inflate(&stream, Z_NO_FLUSH);
    if (status == Z_MEM_ERROR)
    {
      throw std::bad_alloc();
    }
    if (status != Z_OK && status != Z_STREAM_END)
    {
      // Z_BUF_ERROR here: all input used, no end of stream (output room was left).
      throw InputError("cannot read atlas " + path + ": its compressed metadata is " +
        (status == Z_BUF_ERROR
            ? std::string("cut short")
            : "corrupt (zlib: " + std::string(stream.msg ? stream.msg : zError(status)) + ")") +
        damaged);
    }
  }
  if (stream.avail_in != 0)
  {
    throw InputError("cannot read atlas " + path + ": its compressed metadata has " +
      std::to_string(stream.avail_in) + " stray bytes after its end" + damaged);
  }
  if (stream.total_out != static_cast<uLong>(declared))
  {
    throw InputError("cannot read atlas " + path + ": its compressed metadata inflates to " +
      std::to_string(stream.total_out) + " bytes, not the " + std::to_string(declared) +
      " it declares" + damaged);
  }
  text.resize(stream.total_out);
  return text;
}

/// The metadata JSON text of the file's first part: inflated from "trichartAtlasZ" (version 2,
/// `compressed` set) or as stored in "trichartAtlas" (version 1).
std::string metadataText(const std::string& path, const Imf::Header& first, bool& compressed)
{
  const auto* packed = first.findTypedAttribute<Imf::StringAttribute>(kCompressedMetadataAttribute);
  compressed = packed != nullptr;
  if (packed)
  {
    const auto* length = first.findTypedAttribute<Imf::IntAttribute>(kMetadataLengthAttribute);
    if (!length)
    {
      throw InputError("cannot read atlas " + path + ": its compressed metadata has no '" +
        kMetadataLengthAttribute + "' attribute; the file is damaged (write the atlas again)");
    }
    return inflateMetadata(path, packed->value(), length->value());
  }
  const auto* text = first.findTypedAttribute<Imf::StringAttribute>(kMetadataAttribute);
  if (!text)
  {
    throw InputError("cannot read atlas " + path +
      ": it is an OpenEXR image but not a TriChart atlas (its first part has no '" +
      kCompressedMetadataAttribute + "' or '" + kMetadataAttribute +
      "' metadata); open an atlas written by TriChart");
  }
  return text->value();
}

/// The metadata JSON of the file's first part, checked for format, version, storage and
/// checksum.
Json readMetadata(const std::string& path, const Imf::Header& first)
{
  bool compressed = false;
  const std::string text = metadataText(path, first, compressed);
  Json root;
  try
  {
    root = Json::parse(text);
  }
  catch (const Json::exception& error)
  {
    throw InputError("cannot read atlas " + path + ": its metadata is not valid JSON (" +
      error.what() + "); the file is damaged or was not written by TriChart");
  }
  const auto format = root.is_object() ? root.find("format") : root.end();
  if (format == root.end() || !format->is_string() || format->get<std::string>() != kFormatName)
  {
    throw InputError("cannot read atlas " + path + ": its metadata does not name the format '" +
      kFormatName + "'; open an atlas written by TriChart");
  }
  const auto version = root.find("version");
  if (version == root.end() || !version->is_number_integer() || version->get<int64_t>() < 1)
  {
    throw InputError("cannot read atlas " + path + ": its metadata has no valid format version");
  }
  if (version->get<int64_t>() > kAtlasFileVersion)
  {
    throw InputError("cannot read atlas " + path + ": it has format version " +
      std::to_string(version->get<int64_t>()) + " but this TriChart reads versions up to " +
      std::to_string(kAtlasFileVersion) + "; update TriChart to read it");
  }
  // Version 1 stored the text plainly, versions 2 and 3 compressed: anything else is not our
  // writer's.
  if (compressed != (version->get<int64_t>() >= 2))
  {
    throw InputError("cannot read atlas " + path + ": its metadata says format version " +
      std::to_string(version->get<int64_t>()) + " but is stored " +
      (compressed ? "compressed ('" + std::string(kCompressedMetadataAttribute) + "')"
                  : "as plain text ('" + std::string(kMetadataAttribute) + "')") +
      ", which that version does not do; the file is damaged or was not written by TriChart");
  }
  const auto* crc = first.findTypedAttribute<Imf::IntAttribute>(kMetadataCrcAttribute);
  if (!crc || static_cast<uint32_t>(crc->value()) != crc32Of(text))
  {
    throw InputError("cannot read atlas " + path +
      ": its metadata does not match its checksum; the file is damaged (write the atlas again)");
  }
  return root;
}

/// Refuses a part whose type, size (width x height pixels) or channels differ from what the
/// metadata says.
void checkPart(const std::string& path, const std::string& name, const Imf::Header& header,
  int32_t width, int32_t height, const AtlasAttribute& attribute)
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
  std::set<std::string> expected;
  for (const std::string& channel : channelNames(attribute.components))
  {
    expected.insert(channel);
  }
  std::set<std::string> found;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
  {
    const Imf::Channel& channel = it.channel();
    if (channel.type != Imf::FLOAT || channel.xSampling != 1 || channel.ySampling != 1)
    {
      throw InputError(
        prefix + "channel '" + it.name() + "' is not full-resolution 32-bit float" + suffix);
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
    throw InputError(prefix + "does not have exactly the channels " + names + " of a " +
      std::to_string(attribute.components) + "-component attribute" + suffix);
  }
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

Atlas readAtlasFile(const std::string& path, uint64_t fileSize, const Progress& progress)
{
  Imf::MultiPartInputFile file(path.c_str());
  const Json root = readMetadata(path, file.header(0));
  std::vector<std::vector<uint32_t>> crcs;
  std::vector<uint8_t> compact;
  Atlas atlas = parseMetadata(path, root, crcs, compact);
  try
  {
    // Compact parts are placed by the chart layout: it must hold before any texel is.
    validateAtlasLayout(atlas);
  }
  catch (const InputError& invalid)
  {
    throw InputError("cannot read atlas " + path + ": " + invalid.what() +
      " (the file is damaged or was written by a faulty program)");
  }

  // Parts by name; exactly one per attribute and image.
  std::map<std::string, int> parts;
  for (int p = 0; p < file.parts(); ++p)
  {
    if (file.header(p).hasName())
    {
      parts.emplace(file.header(p).name(), p);
    }
  }
  const size_t expectedParts = atlas.attributes.size() * atlas.images.size();
  if (static_cast<size_t>(file.parts()) != expectedParts)
  {
    throw InputError("cannot read atlas " + path + ": it has " + std::to_string(file.parts()) +
      " parts but its metadata describes " + std::to_string(expectedParts) + " (" +
      std::to_string(atlas.attributes.size()) + " attributes x " +
      std::to_string(atlas.images.size()) + " images); the file is damaged");
  }
  // Per image: texel roles and the part height (compact images), checked against every part.
  std::vector<std::vector<uint8_t>> roles(atlas.images.size());
  std::vector<int32_t> partHeight(atlas.images.size());
  uint64_t totalFloats = 0;
  uint64_t storedFloats = 0;
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    const AtlasImage& image = atlas.images[k];
    partHeight[k] = image.height;
    if (compact[k])
    {
      roles[k] = texelRoles(atlas, k);
      partHeight[k] = compactHeight(roles[k], image.width);
    }
    for (size_t a = 0; a < atlas.attributes.size(); ++a)
    {
      const std::string name = partName(atlas.attributes[a].name, k);
      const auto it = parts.find(name);
      if (it == parts.end())
      {
        throw InputError("cannot read atlas " + path + ": part '" + name +
          "' is missing; the file is damaged or was not written by TriChart");
      }
      checkPart(
        path, name, file.header(it->second), image.width, partHeight[k], atlas.attributes[a]);
      totalFloats += floatCount(image, atlas.attributes[a]);
      storedFloats += partFloats(image.width, partHeight[k], atlas.attributes[a]);
    }
  }
  if (totalFloats * sizeof(float) > kMaxCompressionRatio * std::max<uint64_t>(fileSize, 1))
  {
    throw InputError("cannot read atlas " + path + ": it declares " +
      std::to_string(totalFloats * sizeof(float)) + " bytes of texels in a file of " +
      std::to_string(fileSize) + " bytes, more than any compression gives; the file is damaged");
  }

  // Coarsest image first: a compact image takes its inherited texels from the next coarser one.
  uint64_t floatsRead = 0;
  for (size_t k = atlas.images.size(); k-- > 0;)
  {
    AtlasImage& image = atlas.images[k];
    image.data.resize(atlas.attributes.size());
    for (size_t a = 0; a < atlas.attributes.size(); ++a)
    {
      const std::string name = partName(atlas.attributes[a].name, k);
      const int32_t components = atlas.attributes[a].components;
      std::vector<float>& data = image.data[a];
      data.assign(floatCount(image, atlas.attributes[a]), 0.0f);
      std::vector<float> stored;
      if (compact[k])
      {
        stored.assign(static_cast<size_t>(image.width) * static_cast<size_t>(partHeight[k]) *
            static_cast<size_t>(components),
          0.0f);
      }
      Imf::InputPart part(file, parts.at(name));
      part.setFrameBuffer(
        frameBuffer(compact[k] ? stored.data() : data.data(), image.width, components));
      const size_t rowFloats = static_cast<size_t>(image.width) * static_cast<size_t>(components);
      const int32_t block = rowsPerBlock(rowFloats);
      for (int32_t y = 0; y < partHeight[k]; y += block)
      {
        const int32_t last = std::min(partHeight[k], y + block) - 1;
        part.readPixels(y, last);
        floatsRead += static_cast<uint64_t>(last - y + 1) * rowFloats;
        progress.report(0.95 * static_cast<double>(floatsRead) / static_cast<double>(storedFloats));
      }
      if (compact[k])
      {
        expandTexels(stored, roles[k], components, data);
        const size_t comps = static_cast<size_t>(components);
        const float* coarse =
          k + 1 < atlas.images.size() ? atlas.images[k + 1].data[a].data() : nullptr;
        forEachInherited(atlas, k,
          [&](size_t texel, size_t from) {
            std::copy(
              coarse + from * comps, coarse + (from + 1) * comps, data.begin() + texel * comps);
          });
      }
      if (crc32Of(data.data(), data.size() * sizeof(float)) != crcs[k][a])
      {
        throw InputError("cannot read atlas " + path + ": the texels of part '" + name +
          "' do not match their checksum; the file is damaged (write the atlas again)");
      }
    }
  }
  return atlas;
}
} // namespace

bool isAtlasFile(const std::string& path)
{
  try
  {
    checkHeaders(path);
    Imf::MultiPartInputFile file(path.c_str());
    readMetadata(path, file.header(0));
    return true;
  }
  catch (const std::exception&)
  {
    return false;
  }
}

void writeAtlas(const Atlas& atlas, const std::string& path, const Progress& progress)
{
  progress.report(0.0);
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

  // Per image: compact (its parts hold only the texels no coarser image holds) when the
  // texels allow it, the part height, and the checksum of every attribute.
  const size_t numImages = atlas.images.size();
  std::vector<std::vector<uint8_t>> roles(numImages);
  std::vector<uint8_t> compact(numImages, 0);
  std::vector<int32_t> partHeight(numImages);
  std::vector<std::vector<uint32_t>> crcs(numImages);
  uint64_t totalFloats = 0;
  int32_t displayWidth = 1;
  int32_t displayHeight = 1;
  for (size_t k = 0; k < numImages; ++k)
  {
    const AtlasImage& image = atlas.images[k];
    roles[k] = texelRoles(atlas, k);
    compact[k] = compactable(atlas, k, roles[k]);
    partHeight[k] = compact[k] ? compactHeight(roles[k], image.width) : image.height;
    if (!compact[k])
    {
      roles[k].clear();
    }
    for (size_t a = 0; a < atlas.attributes.size(); ++a)
    {
      crcs[k].push_back(crc32Of(image.data[a].data(), image.data[a].size() * sizeof(float)));
      totalFloats += partFloats(image.width, partHeight[k], atlas.attributes[a]);
    }
    displayWidth = std::max(displayWidth, image.width);
    displayHeight = std::max(displayHeight, image.height);
  }
  // Bytes that are not UTF-8 can only come from `source` here (names were checked).
  const std::string metadata =
    atlasMetadata(atlas, crcs, compact).dump(-1, ' ', false, Json::error_handler_t::replace);
  const std::string packedMetadata = compressMetadata(metadata, path);

  // One header per part, coarsest image first, so that a file read front to back refines.
  const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(displayWidth - 1, displayHeight - 1));
  std::vector<Imf::Header> headers;
  for (size_t k = numImages; k-- > 0;)
  {
    const AtlasImage& image = atlas.images[k];
    for (const AtlasAttribute& attribute : atlas.attributes)
    {
      Imf::Header header(
        display, Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(image.width - 1, partHeight[k] - 1)));
      header.setName(partName(attribute.name, k));
      header.setType(Imf::SCANLINEIMAGE);
      header.compression() = Imf::ZIP_COMPRESSION;
      for (const std::string& channel : channelNames(attribute.components))
      {
        header.channels().insert(channel, Imf::Channel(Imf::FLOAT));
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

  TemporaryGuard guard;
  std::FILE* handle = createTemporary(path, guard.Path);
  try
  {
    FileOStream stream(handle, guard.Path, path);
    {
      Imf::MultiPartOutputFile file(stream, headers.data(), static_cast<int>(headers.size()));
      uint64_t floatsWritten = 0;
      int index = 0;
      for (size_t k = numImages; k-- > 0;)
      {
        const AtlasImage& image = atlas.images[k];
        for (size_t a = 0; a < atlas.attributes.size(); ++a, ++index)
        {
          const int32_t components = atlas.attributes[a].components;
          const std::vector<float> packed = compact[k]
            ? compactTexels(image.data[a], roles[k], image.width, partHeight[k], components)
            : std::vector<float>();
          Imf::OutputPart part(file, index);
          part.setFrameBuffer(
            frameBuffer(const_cast<float*>(compact[k] ? packed.data() : image.data[a].data()),
              image.width, components));
          const size_t rowFloats =
            static_cast<size_t>(image.width) * static_cast<size_t>(components);
          const int32_t block = rowsPerBlock(rowFloats);
          for (int32_t y = 0; y < partHeight[k]; y += block)
          {
            const int32_t rows = std::min(block, partHeight[k] - y);
            part.writePixels(rows);
            floatsWritten += static_cast<uint64_t>(rows) * rowFloats;
            progress.report(
              0.95 * static_cast<double>(floatsWritten) / static_cast<double>(totalFloats));
          }
        }
      }
    } // The destructor writes the chunk offset tables.
    stream.finish();
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
  if (std::rename(guard.Path.c_str(), path.c_str()) != 0)
  {
    throw InputError("cannot write atlas " + path + ": " + std::strerror(errno) +
      " when replacing it (is it a folder, or is the folder no longer writable?)");
  }
  guard.Keep = true;
  progress.report(1.0);
}

Atlas readAtlas(const std::string& path, const Progress& progress)
{
  progress.report(0.0);
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
  {
    throw InputError("cannot read atlas " + path + ": it is a folder; give the atlas file");
  }
  uint64_t fileSize = 0;
  {
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
    fileSize = static_cast<uint64_t>(in.tellg());
  }

  checkHeaders(path);
  Atlas atlas;
  try
  {
    atlas = readAtlasFile(path, fileSize, progress);
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
} // namespace tc
