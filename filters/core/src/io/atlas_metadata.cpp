// SPDX-License-Identifier: BSD-3-Clause
// The JSON chart table of the atlas file (the rig in it is src/skinning/rig_json.cpp's).
#include "io/atlas_metadata.h"

#include "tc/common/errors.h"
#include "tc/io/atlas_io.h"

#include <nlohmann/json.hpp>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <new>

namespace tc
{
namespace detail
{
namespace
{
using Json = nlohmann::ordered_json;

/// Deflate turns at most 1032 output bytes into one input byte (a 1-bit length code for 258
/// bytes plus a 1-bit distance code): compressed metadata declaring a longer text than this
/// times its size is damaged, and is refused before anything is inflated.
constexpr uint64_t kMaxDeflateRatio = 1032;

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

/// Every AtlasChart field under its C++ name.
Json chartJson(const AtlasChart& chart)
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
  return c;
}

// ------------------------------------------------------------------------------------------
// Reading

/// Reads the fields of the metadata of `path`; every failure names the file and the field.
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

  const std::string& string(const Json& value, const std::string& where) const
  {
    if (!value.is_string())
    {
      fail("has " + where + " that is not a string");
    }
    return value.get_ref<const std::string&>();
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

/// The JSON of `stored`, checked for format, version, storage and checksum.
Json checkedJson(const std::string& path, const StoredMetadata& stored)
{
  Json root;
  try
  {
    root = Json::parse(stored.text);
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
  // Version 1 stored the text plainly, versions 2 to 6 compressed: anything else is not our
  // writer's.
  if (stored.compressed != (version->get<int64_t>() >= 2))
  {
    throw InputError("cannot read atlas " + path + ": its metadata says format version " +
      std::to_string(version->get<int64_t>()) + " but is stored " +
      (stored.compressed ? "compressed ('" + std::string(kCompressedMetadataAttribute) + "')"
                         : "as plain text ('" + std::string(kMetadataAttribute) + "')") +
      ", which that version does not do; the file is damaged or was not written by TriChart");
  }
  if (!stored.crc || *stored.crc != crc32Of(stored.text))
  {
    throw InputError("cannot read atlas " + path +
      ": its metadata does not match its checksum; the file is damaged (write the atlas again)");
  }
  return root;
}

/// "attributes": at most 1024, each with 1 to 64 components.
void parseAttributes(const MetadataReader& in, const Json& root, Atlas& atlas)
{
  const Json& attributes =
    in.array(in.member(root, "attributes", "the root"), 1, 1024, "attributes");
  for (size_t a = 0; a < attributes.size(); ++a)
  {
    const std::string where = "attributes[" + std::to_string(a) + "]";
    AtlasAttribute attribute;
    attribute.name = in.string(in.member(attributes[a], "name", where), where + ".name");
    attribute.components =
      in.int32(in.member(attributes[a], "components", where), where + ".components");
    if (attribute.components < 1 || attribute.components > 64)
    {
      in.fail("has " + where + ".components = " + std::to_string(attribute.components) +
        ", expected 1 to 64");
    }
    atlas.attributes.push_back(std::move(attribute));
  }
}

/// "images": at most 21, each at most 2^16 texels wide and high, with a checksum per attribute
/// and (from version 3) its storage.
void parseImages(const MetadataReader& in, const Json& root, AtlasMetadata& out)
{
  const size_t numAttributes = out.atlas.attributes.size();
  const Json& images = in.array(in.member(root, "images", "the root"), 1, 21, "images");
  out.crcs.assign(images.size(), {});
  out.compact.assign(images.size(), 0);
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
      out.compact[k] = texels == "new";
    }
    const Json& crc = in.array(
      in.member(images[k], "crc32", where), numAttributes, numAttributes, where + ".crc32");
    for (size_t a = 0; a < crc.size(); ++a)
    {
      out.crcs[k].push_back(static_cast<uint32_t>(
        in.integer(crc[a], 0, UINT32_MAX, where + ".crc32[" + std::to_string(a) + "]")));
    }
    out.atlas.images.push_back(std::move(image));
  }
}

/// "lattice" (version 4): the frame of the position codes and the bits of the normal codes.
AtlasLattice parseLattice(const MetadataReader& in, const Json& root)
{
  const Json& lattice = in.member(root, "lattice", "the root");
  AtlasLattice out;
  out.frame.stepExponent = static_cast<int32_t>(
    in.integer(in.member(lattice, "stepExponent", "lattice"), -1100, 1100, "lattice.stepExponent"));
  // Codes and origins within 2^52 steps: every origin + code is an exact double.
  out.frame.origin = in.integers<int64_t, 3>(in.member(lattice, "origin", "lattice"),
    -(int64_t(1) << 52), int64_t(1) << 52, "lattice.origin");
  out.frame.extent = in.integers<int64_t, 3>(
    in.member(lattice, "extent", "lattice"), 0, kMaxPositionExtent, "lattice.extent");
  out.normalBits = static_cast<int32_t>(
    in.integer(in.member(lattice, "normalBits", "lattice"), 2, 24, "lattice.normalBits"));
  return out;
}

/// "textures" (version 5): at most 64, each named once with its size and checksum; the texels
/// are the parts'.
void parseTextures(const MetadataReader& in, const Json& root, AtlasMetadata& out)
{
  const Json& textures = in.array(in.member(root, "textures", "the root"), 1, 64, "textures");
  for (size_t t = 0; t < textures.size(); ++t)
  {
    const std::string where = "textures[" + std::to_string(t) + "]";
    AtlasTexture texture;
    texture.name = in.string(in.member(textures[t], "name", where), where + ".name");
    texture.source = in.string(in.member(textures[t], "source", where), where + ".source");
    texture.width = static_cast<int32_t>(
      in.integer(in.member(textures[t], "width", where), 1, 1 << 16, where + ".width"));
    texture.height = static_cast<int32_t>(
      in.integer(in.member(textures[t], "height", where), 1, 1 << 16, where + ".height"));
    out.textureCrcs.push_back(static_cast<uint32_t>(
      in.integer(in.member(textures[t], "crc32", where), 0, UINT32_MAX, where + ".crc32")));
    out.atlas.textures.push_back(std::move(texture));
  }
}

/// Chart c of "charts".
AtlasChart parseChart(const MetadataReader& in, const Json& j, size_t c)
{
  const std::string where = "charts[" + std::to_string(c) + "]";
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
  return chart;
}
} // namespace

uint32_t crc32Of(const void* data, size_t bytes)
{
  return static_cast<uint32_t>(
    crc32_z(crc32_z(0L, Z_NULL, 0), static_cast<const Bytef*>(data), static_cast<z_size_t>(bytes)));
}

std::string texturePartName(const std::string& name)
{
  return name + ".texture";
}

uint32_t crc32Of(const std::string& text)
{
  return crc32Of(text.data(), text.size());
}

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
  for (const AtlasTexture& texture : atlas.textures)
  {
    if (!isUtf8(texture.name))
    {
      throw InputError("cannot write atlas " + path + ": texture name '" + texture.name +
        "' is not UTF-8 text; rename the texture");
    }
  }
}

std::string metadataJson(const Atlas& atlas, const AtlasChecksums& crcs,
  const std::vector<uint32_t>& textureCrcs, const std::vector<uint8_t>& compact,
  const AtlasLattice* lattice)
{
  Json root;
  root["format"] = kFormatName;
  root["version"] = !atlas.rig.empty() ? kAtlasFileVersion
    : !atlas.textures.empty()          ? kAtlasTextureVersion
    : lattice                          ? kAtlasLatticeVersion
                                       : kAtlasFloatVersion;
  root["source"] = atlas.source;
  root["inputPoints"] = atlas.inputPoints;
  root["inputTriangles"] = atlas.inputTriangles;
  root["inputDiagonal"] = encodeDouble(atlas.inputDiagonal);
  if (lattice)
  {
    root["lattice"] = { { "stepExponent", lattice->frame.stepExponent },
      { "origin", lattice->frame.origin }, { "extent", lattice->frame.extent },
      { "normalBits", lattice->normalBits } };
  }
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
  if (!atlas.textures.empty())
  {
    root["textures"] = Json::array();
    for (size_t t = 0; t < atlas.textures.size(); ++t)
    {
      const AtlasTexture& texture = atlas.textures[t];
      root["textures"].push_back({ { "name", texture.name }, { "source", texture.source },
        { "width", texture.width }, { "height", texture.height }, { "crc32", textureCrcs[t] } });
    }
  }
  if (!atlas.rig.empty())
  {
    root["rig"] = Json::parse(encodeRig(atlas.rig));
  }
  root["charts"] = Json::array();
  for (const AtlasChart& chart : atlas.charts)
  {
    root["charts"].push_back(chartJson(chart));
  }
  // Bytes that are not UTF-8 can only come from the sources here (names were checked).
  return root.dump(-1, ' ', false, Json::error_handler_t::replace);
}

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

void checkMetadata(const std::string& path, const StoredMetadata& stored)
{
  checkedJson(path, stored);
}

/// "rig" (version 6): the skeleton and animations of a skinned atlas, as tc::encodeRig writes
/// them.
void parseRig(const MetadataReader& in, const Json& root, Atlas& atlas)
{
  try
  {
    atlas.rig = decodeRig(in.member(root, "rig", "the root").dump());
  }
  catch (const InputError& e)
  {
    in.fail(std::string("has a rig that does not read: ") + e.what());
  }
}

AtlasMetadata parseMetadata(const std::string& path, const StoredMetadata& stored)
{
  const Json root = checkedJson(path, stored);
  const MetadataReader in(path);
  AtlasMetadata out;
  Atlas& atlas = out.atlas;
  atlas.source = in.string(in.member(root, "source", "the root"), "a source");
  atlas.inputPoints =
    in.integer(in.member(root, "inputPoints", "the root"), INT64_MIN, INT64_MAX, "inputPoints");
  atlas.inputTriangles = in.integer(
    in.member(root, "inputTriangles", "the root"), INT64_MIN, INT64_MAX, "inputTriangles");
  atlas.inputDiagonal = in.number(in.member(root, "inputDiagonal", "the root"), "inputDiagonal");
  // Attribute and image counts and sizes within validateAtlas's limits before anything is
  // allocated from them.
  parseAttributes(in, root, atlas);
  parseImages(in, root, out);
  const int64_t version = root["version"].get<int64_t>();
  // Version 5 always lists its textures; version 6 when it has any.
  if (version == 5 || (version >= 6 && root.contains("textures")))
  {
    parseTextures(in, root, out);
  }
  if (version >= 6)
  {
    parseRig(in, root, atlas);
  }
  // Version 4 codes Position and Normal always, version 5 when it has a lattice.
  if (version == 4 || (version >= 5 && root.contains("lattice")))
  {
    out.lattice = parseLattice(in, root);
    for (size_t k = 0; k < out.compact.size(); ++k)
    {
      if (!out.compact[k])
      {
        in.fail("has images[" + std::to_string(k) +
          "].texels = \"all\", which a file with a lattice does not have (its codes need every "
          "image compact)");
      }
    }
  }
  const Json& charts = in.member(root, "charts", "the root");
  if (!charts.is_array())
  {
    in.fail("has charts that is not an array");
  }
  atlas.charts.reserve(charts.size());
  for (size_t c = 0; c < charts.size(); ++c)
  {
    atlas.charts.push_back(parseChart(in, charts[c], c));
  }
  return out;
}
} // namespace detail
} // namespace tc
