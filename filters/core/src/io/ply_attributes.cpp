// SPDX-License-Identifier: BSD-3-Clause
// The vertex properties of a PLY file that CGAL's soup reader skips (texture coordinates) or
// reads without alpha (colours), by a second walk over the data that tc::readPLY checked.
#include "io/ply_layout.h"

#include "detail/number_parsing.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace tc
{
namespace
{
bool isReal(const std::string& type)
{
  return type == "float" || type == "float32" || type == "double" || type == "float64";
}

/// Reads PLY scalars one after the other from the data after the header.
class PlyCursor
{
public:
  PlyCursor(const std::string& bytes, const PlyHeader& header)
    : Bytes(bytes)
    , At(header.body)
    , Ascii(header.format == "ascii")
    , Big(header.format == "binary_big_endian")
  {
  }

  /// The next value, of PLY type `type`, as a double; false at the end of the data or at a
  /// token that is no number.
  bool next(const std::string& type, double& value)
  {
    if (Ascii)
    {
      At = Bytes.find_first_not_of(" \t\r\n", At);
      if (At == std::string::npos)
      {
        return false;
      }
      const size_t stop = std::min(Bytes.find_first_of(" \t\r\n", At), Bytes.size());
      const std::string_view token(Bytes.data() + At, stop - At);
      At = stop;
      return detail::parseDouble(token, value);
    }
    const size_t n = plySize(type);
    if (At + n > Bytes.size())
    {
      return false;
    }
    unsigned char raw[8];
    for (size_t k = 0; k < n; ++k)
    {
      raw[k] = static_cast<unsigned char>(Bytes[At + (Big ? n - 1 - k : k)]);
    }
    At += n;
    value = decode(type, raw);
    return true;
  }

  /// Skips `count` values of `type`; false when the data ends first.
  bool skip(const std::string& type, double count)
  {
    if (!Ascii)
    {
      const double bytes = count * static_cast<double>(plySize(type));
      if (bytes > static_cast<double>(Bytes.size() - At))
      {
        return false;
      }
      At += static_cast<size_t>(bytes);
      return true;
    }
    double unused = 0.0;
    for (double k = 0; k < count; ++k)
    {
      if (!next(type, unused))
      {
        return false;
      }
    }
    return true;
  }

private:
  /// A little-endian binary scalar of `type`.
  static double decode(const std::string& type, const unsigned char* raw)
  {
    const auto as = [raw](auto value)
    {
      std::memcpy(&value, raw, sizeof(value));
      return static_cast<double>(value);
    };
    const bool signedType = type == "char" || type == "int8" || type == "short" ||
      type == "int16" || type == "int" || type == "int32";
    switch (plySize(type))
    {
      case 1:
        return signedType ? as(int8_t()) : as(uint8_t());
      case 2:
        return signedType ? as(int16_t()) : as(uint16_t());
      case 4:
        return isReal(type) ? as(float()) : signedType ? as(int32_t()) : as(uint32_t());
      default:
        return as(double());
    }
  }

  const std::string& Bytes;
  size_t At;
  bool Ascii;
  bool Big;
};

/// The index of the first name of `names` that the element has, or -1.
int propertyIndex(const PlyElement& element, std::initializer_list<const char*> names)
{
  for (const char* name : names)
  {
    const auto it = std::find(element.names.begin(), element.names.end(), name);
    if (it != element.names.end())
    {
      return static_cast<int>(it - element.names.begin());
    }
  }
  return -1;
}

/// A colour channel as a byte: integer types as they are (clamped), floats scaled from [0, 1].
uint8_t colorByte(double value, const std::string& type)
{
  return static_cast<uint8_t>(
    std::lround(std::clamp(isReal(type) ? value * 255.0 : value, 0.0, 255.0)));
}

/// Which property of the vertex element holds each attribute (-1: none): u, v, r, g, b, a.
struct VertexSlots
{
  int slot[6] = { -1, -1, -1, -1, -1, -1 };
  bool uv() const { return slot[0] >= 0 && slot[1] >= 0; }
  bool rgb() const { return slot[2] >= 0 && slot[3] >= 0 && slot[4] >= 0; }
};

VertexSlots vertexSlots(const PlyElement& vertex)
{
  // A pair counts only when both of its names are there: "u" of one pair and "t" of another
  // are no texture coordinate.
  const auto pair = [&vertex](int& a, int& b)
  {
    for (const auto& [u, v] : { std::pair{ "u", "v" }, std::pair{ "s", "t" },
           std::pair{ "texture_u", "texture_v" }, std::pair{ "texture_s", "texture_t" } })
    {
      a = propertyIndex(vertex, { u }), b = propertyIndex(vertex, { v });
      if (a >= 0 && b >= 0)
      {
        return;
      }
    }
  };
  VertexSlots s;
  pair(s.slot[0], s.slot[1]);
  const bool longNames = propertyIndex(vertex, { "red" }) >= 0;
  s.slot[2] = propertyIndex(vertex, { longNames ? "red" : "r" });
  s.slot[3] = propertyIndex(vertex, { longNames ? "green" : "g" });
  s.slot[4] = propertyIndex(vertex, { longNames ? "blue" : "b" });
  s.slot[5] = propertyIndex(vertex, { longNames ? "alpha" : "a" });
  return s;
}
} // namespace

PointAttributes readPlyVertexAttributes(const std::string& bytes, const PlyHeader& header)
{
  PlyCursor cursor(bytes, header);
  for (const PlyElement& element : header.elements)
  {
    const bool vertex = element.name == "vertex" || element.name == "vertices";
    const VertexSlots slots = vertex ? vertexSlots(element) : VertexSlots{};
    if (vertex && !slots.uv() && !slots.rgb())
    {
      return {};
    }
    PointAttributes read;
    double values[6] = { 0, 0, 0, 0, 0, 255 };
    for (long long item = 0; item < element.count; ++item)
    {
      for (size_t k = 0; k < element.layout.size(); ++k)
      {
        const auto& [sizeType, valueType] = element.layout[k];
        double value = 0.0;
        if (!cursor.next(sizeType.empty() ? valueType : sizeType, value) ||
          (!sizeType.empty() && (value < 0 || !cursor.skip(valueType, value))))
        {
          return {};
        }
        for (int a = 0; vertex && a < 6; ++a)
        {
          values[a] = slots.slot[a] == static_cast<int>(k) ? value : values[a];
        }
      }
      if (vertex && slots.uv())
      {
        read.textureCoordinates.push_back(static_cast<float>(values[0]));
        read.textureCoordinates.push_back(static_cast<float>(values[1]));
      }
      for (int a = 2; vertex && slots.rgb() && a < 6; ++a)
      {
        const int slot = slots.slot[a];
        read.colors.push_back(slot < 0 ? 255 : colorByte(values[a], element.layout[slot].second));
      }
    }
    if (vertex)
    {
      return read; // the vertices are all this walk is for
    }
  }
  return {};
}
} // namespace tc
