// SPDX-License-Identifier: BSD-3-Clause
#include "tc/io/soup_io.h"

#include "io/ply_layout.h"
#include "tc/common/errors.h"

#include <CGAL/IO/PLY.h>
#include <CGAL/Simple_cartesian.h>

#include <zlib.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

namespace tc
{
namespace
{
using Point = CGAL::Simple_cartesian<double>::Point_3;

/// The points and faces a CGAL reader gave, as a soup whose every face has 3 or more corners
/// that exist.
PolygonSoup toSoup(const std::string& path, const std::vector<Point>& points,
  const std::vector<std::vector<std::size_t>>& faces)
{
  if (faces.empty())
  {
    throw InputError("'" + path + "' has no faces (" + std::to_string(points.size()) +
      " vertices): a point cloud is no surface");
  }
  PolygonSoup soup;
  soup.points.reserve(3 * points.size());
  for (const Point& p : points)
  {
    soup.points.insert(soup.points.end(), { p.x(), p.y(), p.z() });
  }
  soup.connectivity.reserve(3 * faces.size());
  soup.offsets.reserve(faces.size() + 1);
  std::vector<int64_t> ids;
  for (size_t f = 0; f < faces.size(); ++f)
  {
    if (faces[f].size() < 3)
    {
      throw InputError("'" + path + "': face " + std::to_string(f) + " has " +
        std::to_string(faces[f].size()) + " corners; a face needs 3 or more");
    }
    ids.assign(faces[f].begin(), faces[f].end());
    for (const int64_t id : ids)
    {
      if (id < 0 || id >= soup.numPoints())
      {
        throw InputError("'" + path + "': face " + std::to_string(f) + " refers to vertex " +
          std::to_string(id) + ", and the file has " + std::to_string(soup.numPoints()) +
          " (a damaged file?)");
      }
    }
    soup.addPolygon(ids.data(), static_cast<int64_t>(ids.size()));
  }
  return soup;
}

/// Refuses a list whose declared length the whole file cannot hold, and an element of items
/// without properties: CGAL's reader resizes a list to its declared length before it
/// reads it, and adds an item per declared item, so one damaged count (4e9 in a face of a
/// 411-byte file) allocates gigabytes and runs for minutes. A walk over the data, reading only
/// the list lengths; where the data ends early it stops, and CGAL's reader reports the file.
void checkListLengths(const std::string& path, const std::string& bytes, const PlyHeader& header)
{
  const bool ascii = header.format == "ascii";
  const bool big = header.format == "binary_big_endian";
  size_t at = header.body;
  // The next ASCII token, or the next binary value of `type` (as a count: lists' sizes are
  // integers); false at the end of the data.
  const auto next = [&](const std::string& type, unsigned long long& value)
  {
    if (ascii)
    {
      at = bytes.find_first_not_of(" \t\r\n", at);
      if (at == std::string::npos)
      {
        return false;
      }
      const size_t stop = std::min(bytes.find_first_of(" \t\r\n", at), bytes.size());
      value = std::strtoull(bytes.substr(at, std::min<size_t>(stop - at, 24)).c_str(), nullptr, 10);
      at = stop;
      return true;
    }
    const size_t n = plySize(type);
    if (at + n > bytes.size())
    {
      return false;
    }
    value = 0;
    for (size_t k = 0; k < n; ++k)
    {
      value |= static_cast<unsigned long long>(
                 static_cast<unsigned char>(bytes[at + (big ? n - 1 - k : k)]))
        << (8 * k);
    }
    at += n;
    return true;
  };
  for (const PlyElement& element : header.elements)
  {
    if (element.layout.empty() && element.count > 0)
    {
      throw InputError("'" + path + "' declares " + std::to_string(element.count) + " " +
        element.name + " items without properties (a damaged file?)");
    }
    for (long long item = 0; item < element.count; ++item)
    {
      for (const auto& [sizeType, valueType] : element.layout)
      {
        unsigned long long value = 0;
        if (!next(sizeType.empty() ? valueType : sizeType, value))
        {
          return;
        }
        const size_t itemBytes = ascii ? 2 : plySize(valueType);
        if (!sizeType.empty() && value > bytes.size() / itemBytes)
        {
          throw InputError("'" + path + "' declares a list of " + std::to_string(value) +
            " values in " + element.name + " " + std::to_string(item) + ", more than the whole " +
            "file holds (a damaged file?)");
        }
        if (!sizeType.empty() && value > (bytes.size() - at) / itemBytes)
        {
          return; // the data ends early: CGAL's reader says how far it read
        }
        if (sizeType.empty())
        {
          continue;
        }
        if (!ascii)
        {
          at += value * itemBytes; // within the data: checked above
          continue;
        }
        for (unsigned long long v = 0, skipped = 0; v < value; ++v)
        {
          if (!next(valueType, skipped))
          {
            return;
          }
        }
      }
    }
  }
}

/// Refuses the property types CGAL's reader would mistake: it reads a property it knows by
/// name (x, y, z of a vertex, the colour of a vertex or face, the ends of a halfedge) as the
/// type it expects without checking it, and dereferences a null pointer when the file says
/// otherwise (a vertex of float x, uchar y, float z did).
void checkCgalTypes(const std::string& path, const PlyElement& element)
{
  const auto typeOf = [&element](const char* name)
  {
    const auto it = element.types.find(name);
    return it == element.types.end() ? std::string() : it->second;
  };
  const auto refuse = [&](const char* name, const char* expected)
  {
    throw InputError("'" + path + "' declares " + element.name + " property '" + name + "' as " +
      typeOf(name) + "; TriChart reads it as " + expected + " (a damaged file?)");
  };
  const auto isByte = [&typeOf](const char* name)
  { return typeOf(name) == "uchar" || typeOf(name) == "uint8"; };
  const std::string& e = element.name;
  if (e == "vertex" || e == "vertices")
  {
    for (const char* name : { "x", "y", "z" })
    {
      const std::string type = typeOf(name);
      if (!type.empty() && type != "float" && type != "float32" && type != "double" &&
        type != "float64")
      {
        refuse(name, "float or double");
      }
    }
  }
  if (e == "vertex" || e == "vertices" || e == "face" || e == "faces")
  {
    // CGAL's choice of colour names: red, green, blue if red is a byte, else r, g, b; the
    // colour is read when each channel has a byte under one of its two names.
    const bool colours = (isByte("red") || isByte("r")) && (isByte("green") || isByte("g")) &&
      (isByte("blue") || isByte("b"));
    static const char* const longNames[] = { "red", "green", "blue" };
    static const char* const shortNames[] = { "r", "g", "b" };
    const char* const* names = isByte("red") ? longNames : shortNames;
    for (int c = 0; c < 3; ++c)
    {
      const char* name = names[c];
      if (colours && !typeOf(name).empty() && !isByte(name))
      {
        refuse(name, "uchar");
      }
    }
  }
  if (e == "halfedge")
  {
    for (const char* name : { "source", "target" })
    {
      if (!typeOf(name).empty() && typeOf(name) != "uint" && typeOf(name) != "uint32")
      {
        refuse(name, "uint");
      }
    }
  }
}

/// Checks the header line by line, so that CGAL's reader (which assumes a well-formed header and
/// crashes on, e.g., a property before any element) only sees headers it can parse; throws
/// InputError naming the first line that is not PLY. Returns the offset of the end_header line.
PlyHeader checkHeader(const std::string& path, const std::string& bytes)
{
  PlyHeader header;
  static const std::set<std::string> types = { "char", "uchar", "short", "ushort", "int", "uint",
    "float", "double", "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32",
    "float64" };
  int number = 0;
  bool element = false;
  std::vector<PlyElement>& elements = header.elements;
  // The header ends where CGAL's reader ends it: at the first line whose first word is
  // end_header (not at the first "end_header" in the bytes, which may sit inside another line).
  size_t start = 0;
  while (start < bytes.size())
  {
    size_t stop = bytes.find('\n', start);
    stop = stop == std::string::npos ? bytes.size() : stop;
    std::string line = bytes.substr(start, stop - start);
    const size_t lineStart = start;
    start = stop + 1;
    ++number;
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;)
    {
      w.push_back(word);
    }
    if (!w.empty() && w[0] == "end_header" && number > 2)
    {
      for (const PlyElement& e : elements)
      {
        checkCgalTypes(path, e);
      }
      header.end = lineStart;
      header.body = std::min(start, bytes.size());
      return header;
    }
    bool ok = false;
    if (number == 1)
    {
      ok = w.size() == 1 && w[0] == "ply";
    }
    else if (number == 2)
    {
      ok = w.size() == 3 && w[0] == "format" &&
        (w[1] == "ascii" || w[1] == "binary_little_endian" || w[1] == "binary_big_endian");
      header.format = ok ? w[1] : std::string();
    }
    else if (w.empty() || w[0] == "comment" || w[0] == "obj_info")
    {
      ok = true;
      if (w.size() > 2 && w[0] == "comment" && w[1] == "TextureFile")
      {
        header.textureFile = line.substr(line.find("TextureFile") + 12);
      }
    }
    else if (w[0] == "element")
    {
      ok = w.size() == 3 && !w[2].empty() &&
        w[2].find_first_not_of("0123456789") == std::string::npos && w[2].size() < 12;
      element = element || ok;
      elements.push_back({ ok ? w[1] : std::string(), ok ? std::stoll(w[2]) : 0, {}, {}, {} });
    }
    else if (w[0] == "property" && element)
    {
      ok = (w.size() == 3 && types.count(w[1])) ||
        (w.size() == 5 && w[1] == "list" && types.count(w[2]) && types.count(w[3]));
      if (ok)
      {
        elements.back().types.emplace(w.back(), w.size() == 3 ? w[1] : "list " + w[3]);
        elements.back().layout.emplace_back(
          w.size() == 3 ? std::string() : w[2], w.size() == 3 ? w[1] : w[3]);
        elements.back().names.push_back(w.back());
      }
    }
    if (!ok)
    {
      throw InputError("'" + path + "' is no PLY file: header line " + std::to_string(number) +
        " ('" + line.substr(0, 60) + "') is not PLY (a damaged file?)");
    }
  }
  throw InputError("'" + path + "' is no PLY file: its header has no end_header line");
}

/// The counts the header declares for an element ("vertex", "face"); -1 if it has none.
long long declared(const std::string& header, const std::string& element)
{
  std::istringstream lines(header);
  std::string line;
  while (std::getline(lines, line) && line.rfind("end_header", 0) != 0)
  {
    std::istringstream words(line);
    std::string keyword, name;
    long long count = -1;
    if (words >> keyword >> name >> count && keyword == "element" && name == element)
    {
      return count;
    }
  }
  return -1;
}
} // namespace

std::string readGzip(const std::string& path)
{
  // zlib reads a file without the gzip magic number as it is; a ".gz" must have it.
  char magic[2] = { 0, 0 };
  std::ifstream(path, std::ios::binary).read(magic, 2);
  if (static_cast<unsigned char>(magic[0]) != 0x1f || static_cast<unsigned char>(magic[1]) != 0x8b)
  {
    throw InputError("'" + path +
      "' is not a valid gzip file (no gzip header); decompress it "
      "or re-export it");
  }
  gzFile file = gzopen(path.c_str(), "rb");
  if (!file)
  {
    throw InputError("cannot open '" + path + "'");
  }
  std::string data;
  std::vector<char> buffer(1 << 16);
  int n = 0;
  while ((n = gzread(file, buffer.data(), static_cast<unsigned>(buffer.size()))) > 0)
  {
    data.append(buffer.data(), static_cast<size_t>(n));
  }
  int code = Z_OK;
  const std::string message = gzerror(file, &code);
  gzclose(file);
  if (n != 0 || code != Z_OK)
  {
    throw InputError(
      "'" + path + "' is not a valid gzip file (" + message + "); decompress it or re-export it");
  }
  return data;
}

MeshFile readPLYFile(const std::string& path)
{
  std::ifstream file(path, std::ios::binary);
  if (!file.good())
  {
    throw InputError("cannot open '" + path + "': the file does not exist or is not readable");
  }
  const bool gzipped = path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0;
  std::string bytes;
  if (gzipped)
  {
    file.close();
    bytes = readGzip(path);
  }
  else
  {
    std::ostringstream all;
    all << file.rdbuf();
    bytes = all.str();
  }
  if (bytes.compare(0, 3, "ply") != 0)
  {
    throw InputError("'" + path + "' is no PLY file: it does not start with 'ply'");
  }
  const PlyHeader layout = checkHeader(path, bytes);
  checkListLengths(path, bytes, layout);
  const std::string header = bytes.substr(0, layout.end);

  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  std::istringstream in(bytes);
  bool ok = false;
  try
  {
    ok = CGAL::IO::read_PLY(in, points, faces, CGAL::parameters::verbose(false));
  }
  catch (const std::exception& e)
  {
    throw InputError("cannot read '" + path + "' as PLY: " + e.what());
  }
  if (!ok)
  {
    const auto count = [&header](const char* element, const char* plural)
    {
      const long long n = declared(header, element);
      return n < 0 ? std::string("no ") + element + " element" : std::to_string(n) + " " + plural;
    };
    throw InputError("cannot read '" + path + "' as PLY: the header declares " +
      count("vertex", "vertices") + " and " + count("face", "faces") + ", and " +
      std::to_string(points.size()) + " vertices and " + std::to_string(faces.size()) +
      " faces were read before the data stopped matching it (a truncated or damaged file, or "
      "an unsupported layout)");
  }
  MeshFile mesh;
  mesh.soup = toSoup(path, points, faces);
  mesh.attributes = readPlyVertexAttributes(bytes, layout);
  if (!layout.textureFile.empty())
  {
    mesh.texture = readTextureFile(path, layout.textureFile, mesh.warnings);
  }
  return mesh;
}

PolygonSoup readPLY(const std::string& path)
{
  return readPLYFile(path).soup;
}
} // namespace tc
