// SPDX-License-Identifier: BSD-3-Clause
// Wavefront OBJ input, parsed by hand rather than with CGAL::IO::read_OBJ: CGAL's reader skips
// texture coordinates, vertex colours and materials, and reports a bad file as a bare false.
#include "tc/io/soup_io.h"

#include "detail/number_parsing.h"
#include "io/obj_materials.h"
#include "tc/common/errors.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string_view>
#include <unordered_map>

namespace tc
{
namespace
{
bool isBlank(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/// The whitespace-separated tokens of `line`.
std::vector<std::string_view> tokens(std::string_view line)
{
  std::vector<std::string_view> out;
  size_t at = 0;
  while (at < line.size())
  {
    while (at < line.size() && isBlank(line[at]))
    {
      ++at;
    }
    const size_t start = at;
    while (at < line.size() && !isBlank(line[at]))
    {
      ++at;
    }
    if (at > start)
    {
      out.push_back(line.substr(start, at - start));
    }
  }
  return out;
}

/// The text after the keyword of `line`, without surrounding blanks (a file name may hold
/// spaces).
std::string rest(std::string_view line, std::string_view keyword)
{
  std::string_view text = line.substr(line.find(keyword) + keyword.size());
  while (!text.empty() && isBlank(text.front()))
  {
    text.remove_prefix(1);
  }
  while (!text.empty() && isBlank(text.back()))
  {
    text.remove_suffix(1);
  }
  return std::string(text);
}

/// What one pass over the OBJ text gives. Corner indices are 0-based; negative ones of the file
/// are resolved against the counts so far, positive ones are checked once all are read.
struct ObjText
{
  std::vector<double> positions; ///< #v x 3
  std::vector<float> colors;     ///< #v x 3 in [0, 1], for "v x y z r g b" lines
  int64_t uncoloredVertices = 0; ///< v lines without r g b
  std::vector<float> uvs;        ///< #vt x 2
  std::vector<int64_t> offsets{ 0 };
  std::vector<int64_t> v;             ///< per corner: vertex
  std::vector<int64_t> t;             ///< per corner: texture coordinate, -1 if the corner has none
  std::vector<int64_t> faceLine;      ///< per face: its line number
  std::vector<std::string> libraries; ///< mtllib names, in file order
  std::vector<std::string> used;      ///< usemtl names in the order faces first use them
};

/// Parses the OBJ text line by line; throws InputError "cannot read 'path' as OBJ: line N: ...".
class ObjParser
{
public:
  ObjParser(const std::string& path)
    : Path(path)
  {
  }

  ObjText parse(const std::string& bytes)
  {
    size_t start = 0;
    while (start < bytes.size())
    {
      size_t stop = bytes.find('\n', start);
      stop = stop == std::string::npos ? bytes.size() : stop;
      std::string_view line(bytes.data() + start, stop - start);
      start = stop + 1;
      ++Line;
      line = line.substr(0, line.find('#'));
      const std::vector<std::string_view> words = tokens(line);
      if (!words.empty())
      {
        parseLine(line, words);
      }
    }
    return std::move(Text);
  }

private:
  [[noreturn]] void fail(const std::string& what) const
  {
    throw InputError(
      "cannot read '" + Path + "' as OBJ: line " + std::to_string(Line) + ": " + what);
  }

  double number(std::string_view token, const char* what) const
  {
    double value = 0.0;
    if (!detail::parseDouble(token, value))
    {
      fail("'" + std::string(token.substr(0, 40)) + "' is no number (" + what + ")");
    }
    return value;
  }

  void parseLine(std::string_view line, const std::vector<std::string_view>& words)
  {
    const std::string_view keyword = words[0];
    if (keyword == "v")
    {
      parseVertex(words);
    }
    else if (keyword == "vt")
    {
      if (words.size() < 2)
      {
        fail("a texture coordinate needs u and v; the line has none (a truncated file?)");
      }
      Text.uvs.push_back(static_cast<float>(number(words[1], "u of a texture coordinate")));
      // The OBJ format makes v optional (0 by default), as it makes w.
      Text.uvs.push_back(words.size() > 2
          ? static_cast<float>(number(words[2], "v of a texture coordinate"))
          : 0.0f);
    }
    else if (keyword == "f")
    {
      parseFace(words);
    }
    else if (keyword == "mtllib")
    {
      Text.libraries.push_back(rest(line, keyword));
    }
    else if (keyword == "usemtl")
    {
      Material = rest(line, keyword);
      MaterialUsed = false;
    }
    // Other statements (vn, g, o, s, l, p, ...) carry nothing the reader keeps.
  }

  void parseVertex(const std::vector<std::string_view>& words)
  {
    if (words.size() < 4)
    {
      fail("a vertex needs x, y and z; the line has " + std::to_string(words.size() - 1) +
        " numbers (a truncated file?)");
    }
    for (size_t c = 1; c < 4; ++c)
    {
      Text.positions.push_back(number(words[c], "a vertex coordinate"));
    }
    // "v x y z r g b" is a common extension; "v x y z w" is the format's own.
    if (words.size() != 7)
    {
      ++Text.uncoloredVertices;
      return;
    }
    for (size_t c = 4; c < 7; ++c)
    {
      Text.colors.push_back(static_cast<float>(number(words[c], "a vertex colour")));
    }
  }

  /// A corner's index of `count` items so far: 1-based, or negative counting back from the last.
  int64_t index(std::string_view token, int64_t count, const char* what) const
  {
    int64_t value = 0;
    if (!detail::parseInteger(token, value))
    {
      fail("'" + std::string(token.substr(0, 40)) + "' is no " + what + " index");
    }
    if (value == 0 || (value < 0 && count + value < 0))
    {
      fail("face corner refers to " + std::string(what) + " " + std::to_string(value) +
        (value == 0 ? "; OBJ counts from 1" : ", before the first one"));
    }
    return value > 0 ? value - 1 : count + value;
  }

  void parseFace(const std::vector<std::string_view>& words)
  {
    if (words.size() < 4)
    {
      fail("face " + std::to_string(Text.faceLine.size()) + " has " +
        std::to_string(words.size() - 1) + " corners; a face needs 3 or more");
    }
    const int64_t vertices = static_cast<int64_t>(Text.positions.size() / 3);
    const int64_t uvs = static_cast<int64_t>(Text.uvs.size() / 2);
    for (size_t c = 1; c < words.size(); ++c)
    {
      // v, v/vt, v//vn or v/vt/vn.
      const std::string_view corner = words[c];
      const size_t slash = corner.find('/');
      Text.v.push_back(index(corner.substr(0, slash), vertices, "vertex"));
      const std::string_view after =
        slash == std::string_view::npos ? std::string_view() : corner.substr(slash + 1);
      const std::string_view vt = after.substr(0, after.find('/'));
      Text.t.push_back(vt.empty() ? -1 : index(vt, uvs, "texture coordinate"));
    }
    Text.offsets.push_back(static_cast<int64_t>(Text.v.size()));
    Text.faceLine.push_back(Line);
    if (!Material.empty() && !MaterialUsed)
    {
      MaterialUsed = true;
      if (std::find(Text.used.begin(), Text.used.end(), Material) == Text.used.end())
      {
        Text.used.push_back(Material);
      }
    }
  }

  std::string Path;
  int64_t Line = 0;
  std::string Material;
  bool MaterialUsed = false;
  ObjText Text;
};

/// Refuses a corner whose vertex or texture coordinate the file does not have, naming the line.
void checkCorners(const std::string& path, const ObjText& text)
{
  const int64_t vertices = static_cast<int64_t>(text.positions.size() / 3);
  const int64_t uvs = static_cast<int64_t>(text.uvs.size() / 2);
  for (size_t f = 0; f + 1 < text.offsets.size(); ++f)
  {
    for (int64_t c = text.offsets[f]; c < text.offsets[f + 1]; ++c)
    {
      const bool badVertex = text.v[c] >= vertices;
      if (badVertex || text.t[c] >= uvs)
      {
        throw InputError("cannot read '" + path + "' as OBJ: line " +
          std::to_string(text.faceLine[f]) + ": face corner " +
          std::to_string(c - text.offsets[f] + 1) + " refers to " +
          (badVertex ? "vertex " + std::to_string(text.v[c] + 1) + ", and the file has " +
                std::to_string(vertices) + " vertices"
                     : "texture coordinate " + std::to_string(text.t[c] + 1) +
                ", and the file has " + std::to_string(uvs)) +
          " (a truncated or damaged file?)");
      }
    }
  }
}

uint8_t colorByte(float value)
{
  return static_cast<uint8_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f));
}

/// Whether every corner has a texture coordinate. Some corners with and others without is
/// allowed by the format; then no corner's is kept (a guessed (0, 0) would paint wrong texels
/// without a trace), and a warning says where the first corner without one is.
bool everyCornerHasUV(const ObjText& text, std::vector<std::string>& warnings)
{
  const auto missing = static_cast<int64_t>(std::count(text.t.begin(), text.t.end(), -1));
  if (missing > 0 && missing < static_cast<int64_t>(text.t.size()))
  {
    const auto first = std::find(text.t.begin(), text.t.end(), -1) - text.t.begin();
    const auto face =
      std::upper_bound(text.offsets.begin(), text.offsets.end(), first) - text.offsets.begin() - 1;
    warnings.push_back(std::to_string(missing) + " of " + std::to_string(text.t.size()) +
      " face corners have no texture coordinate (the first on line " +
      std::to_string(text.faceLine[face]) + "): the mesh is read without texture coordinates");
  }
  return missing == 0 && !text.t.empty();
}

/// The soup: one point per vertex, and, with texture coordinates, one more per further distinct
/// (v, vt) pair of a vertex (a UV seam), as vtkOBJReader makes them; the first pair of a vertex
/// keeps its id. Vertices no face uses get (0, 0).
MeshFile buildMesh(const ObjText& text, bool withUV, bool withColors)
{
  MeshFile mesh;
  PolygonSoup& soup = mesh.soup;
  std::vector<float>& uv = mesh.attributes.textureCoordinates;
  std::vector<uint8_t>& rgba = mesh.attributes.colors;
  const int64_t vertices = static_cast<int64_t>(text.positions.size() / 3);
  soup.points = text.positions;
  uv.assign(withUV ? 2 * vertices : 0, 0.0f);
  for (int64_t p = 0; withColors && p < vertices; ++p)
  {
    rgba.insert(rgba.end(),
      { colorByte(text.colors[3 * p]), colorByte(text.colors[3 * p + 1]),
        colorByte(text.colors[3 * p + 2]), 255 });
  }
  std::vector<int64_t> firstUV(withUV ? vertices : 0, -1);
  std::unordered_map<uint64_t, int64_t> seamPoint; // (v << 32 | vt) -> point
  std::vector<int64_t> ids;
  for (size_t f = 0; f + 1 < text.offsets.size(); ++f)
  {
    ids.clear();
    for (int64_t c = text.offsets[f]; c < text.offsets[f + 1]; ++c)
    {
      const int64_t v = text.v[c], t = text.t[c];
      if (!withUV || firstUV[v] == t || firstUV[v] < 0)
      {
        if (withUV && firstUV[v] < 0)
        {
          firstUV[v] = t;
          std::copy_n(text.uvs.begin() + 2 * t, 2, uv.begin() + 2 * v);
        }
        ids.push_back(v);
        continue;
      }
      const auto [it, added] = seamPoint.emplace(
        static_cast<uint64_t>(v) << 32 | static_cast<uint64_t>(t), soup.numPoints());
      if (added)
      {
        soup.points.insert(
          soup.points.end(), text.positions.begin() + 3 * v, text.positions.begin() + 3 * v + 3);
        uv.insert(uv.end(), text.uvs.begin() + 2 * t, text.uvs.begin() + 2 * t + 2);
        if (withColors)
        {
          rgba.insert(rgba.end(), rgba.begin() + 4 * v, rgba.begin() + 4 * v + 4);
        }
      }
      ids.push_back(it->second);
    }
    soup.addPolygon(ids.data(), static_cast<int64_t>(ids.size()));
  }
  return mesh;
}
} // namespace

MeshFile readOBJFile(const std::string& path)
{
  std::ifstream file(path, std::ios::binary);
  if (!file.good())
  {
    throw InputError("cannot open '" + path + "': the file does not exist or is not readable");
  }
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const ObjText text = ObjParser(path).parse(bytes);
  const int64_t vertices = static_cast<int64_t>(text.positions.size() / 3);
  if (text.faceLine.empty())
  {
    throw InputError("'" + path + "' has no faces (" + std::to_string(vertices) +
      " vertices): a point cloud is no surface");
  }
  checkCorners(path, text);
  std::vector<std::string> warnings;
  const bool withUV = everyCornerHasUV(text, warnings);
  if (text.uncoloredVertices > 0 && text.uncoloredVertices < vertices)
  {
    warnings.push_back(std::to_string(text.uncoloredVertices) + " of " + std::to_string(vertices) +
      " vertices have no colour: the mesh is read without colours");
  }
  MeshFile mesh = buildMesh(text, withUV, vertices > 0 && text.uncoloredVertices == 0);
  mesh.texture = objBaseColorTexture(path, text.libraries, text.used, warnings);
  mesh.warnings = std::move(warnings);
  return mesh;
}

PolygonSoup readOBJ(const std::string& path)
{
  return readOBJFile(path).soup;
}
} // namespace tc
