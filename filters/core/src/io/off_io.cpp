// SPDX-License-Identifier: BSD-3-Clause
#include "tc/io/off_io.h"

#include "detail/number_parsing.h"
#include "tc/common/errors.h"
#include "tc/io/temporary_file.h"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string_view>
#include <system_error>

namespace tc
{
namespace
{
bool isBlank(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

using detail::parseDouble;
using detail::parseInteger;

/// Line-by-line view of an OFF file held in memory. Comments ('#' to the end of the line) and
/// blank lines are skipped; the line number of the current line goes into every error.
class OffScanner
{
public:
  OffScanner(const std::string& path, const char* begin, const char* end)
    : Path(path)
    , Cursor(begin)
    , End(end)
  {
  }

  /// Moves to the next line with at least one token; false at the end of the file.
  bool nextLine()
  {
    while (Cursor < End)
    {
      const char* start = Cursor;
      const char* newline =
        static_cast<const char*>(std::memchr(Cursor, '\n', static_cast<size_t>(End - Cursor)));
      const char* stop = newline ? newline : End;
      Cursor = newline ? newline + 1 : End;
      ++LineNumber;
      const char* hash =
        static_cast<const char*>(std::memchr(start, '#', static_cast<size_t>(stop - start)));
      if (hash)
      {
        stop = hash;
      }
      while (start < stop && isBlank(*start))
      {
        ++start;
      }
      if (start < stop)
      {
        Token = start;
        LineEnd = stop;
        return true;
      }
    }
    return false;
  }

  /// Next whitespace-separated token of the current line; false when the line has no more.
  bool nextToken(std::string_view& token)
  {
    while (Token < LineEnd && isBlank(*Token))
    {
      ++Token;
    }
    if (Token == LineEnd)
    {
      return false;
    }
    const char* start = Token;
    while (Token < LineEnd && !isBlank(*Token))
    {
      ++Token;
    }
    token = std::string_view(start, static_cast<size_t>(Token - start));
    return true;
  }

  [[noreturn]] void fail(const std::string& message) const
  {
    throw InputError(Path + ":" + std::to_string(LineNumber) + ": " + message);
  }

private:
  const std::string& Path;
  const char* Cursor;
  const char* End;
  const char* Token = nullptr;
  const char* LineEnd = nullptr;
  int64_t LineNumber = 0;
};

std::string readWholeFile(const std::string& path)
{
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
  {
    throw InputError(path + ": cannot read the OFF file: it does not exist");
  }
  if (std::filesystem::is_directory(status))
  {
    throw InputError(path + ": cannot read the OFF file: it is a folder");
  }
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file)
  {
    throw InputError(path + ": cannot open the OFF file: " + std::strerror(errno));
  }
  std::string text;
  text.reserve(static_cast<size_t>(std::filesystem::file_size(path, ec)));
  char buffer[1 << 16];
  size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof(buffer), file)) > 0)
  {
    text.append(buffer, got);
  }
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed)
  {
    throw InputError(path + ": error while reading the OFF file");
  }
  return text;
}

std::string quoted(std::string_view token)
{
  constexpr size_t kMaxShown = 40;
  std::string shown(token.substr(0, kMaxShown));
  if (token.size() > kMaxShown)
  {
    shown += "...";
  }
  return "'" + shown + "'";
}
/// The next token, on this line or, when it has no more, on the next line with one.
bool nextTokenOrLine(OffScanner& scan, std::string_view& token)
{
  return scan.nextToken(token) || (scan.nextLine() && scan.nextToken(token));
}

/// What the keyword line says about the vertex lines.
struct VertexLayout
{
  bool homogeneous = false; ///< 4OFF: x y z w, the point being x/w y/w z/w
  int64_t dimension = 3;    ///< nOFF: coordinates per point (3 otherwise)
  int64_t columns() const { return dimension + (homogeneous ? 1 : 0); }
};

/// Reads the keyword [ST][C][N][4][n]OFF (only the 4 and n prefixes change the vertex layout)
/// and the dimension of nOFF; leaves `token` at the first count.
VertexLayout readKeyword(OffScanner& scan, std::string_view& token)
{
  if (!scan.nextLine() || !scan.nextToken(token))
  {
    scan.fail("not an OFF file: it is empty");
  }
  std::string_view keyword = token;
  auto eat = [&keyword](std::string_view prefix)
  {
    if (keyword.substr(0, prefix.size()) == prefix)
    {
      keyword.remove_prefix(prefix.size());
      return true;
    }
    return false;
  };
  eat("ST");
  eat("C");
  eat("N");
  VertexLayout layout;
  layout.homogeneous = eat("4");
  const bool anyDimension = eat("n");
  if (keyword != "OFF")
  {
    scan.fail("not an OFF file: the first word is " + quoted(token) +
      ", expected OFF (or COFF, NOFF, CNOFF, STOFF, 4OFF, nOFF)");
  }
  if (!nextTokenOrLine(scan, token))
  {
    scan.fail("the file ends before the counts line 'vertices faces edges'");
  }
  if (token == "BINARY")
  {
    scan.fail("binary OFF is not supported; convert the file to ASCII OFF");
  }
  if (anyDimension)
  {
    if (!parseInteger(token, layout.dimension) || layout.dimension < 1 || layout.dimension > 64)
    {
      scan.fail("bad nOFF dimension " + quoted(token) + ", expected an integer from 1 to 64");
    }
    if (!nextTokenOrLine(scan, token))
    {
      scan.fail("the file ends before the counts line 'vertices faces edges'");
    }
  }
  return layout;
}

/// Reads the vertex and face counts from `token` on, refusing counts that a file of `bytes`
/// bytes cannot hold.
void readCounts(
  OffScanner& scan, std::string_view& token, int64_t bytes, int64_t& numVertices, int64_t& numFaces)
{
  if (!parseInteger(token, numVertices) || numVertices < 0)
  {
    scan.fail("bad vertex count " + quoted(token) +
      ": expected the line 'vertices faces edges' "
      "with non-negative integers");
  }
  if (!scan.nextToken(token) || !parseInteger(token, numFaces) || numFaces < 0)
  {
    scan.fail("bad or missing face count: expected the line 'vertices faces edges' with "
              "non-negative integers");
  }
  // A vertex line takes at least 6 bytes and a face line 8: larger counts cannot be right, and
  // must not make us reserve gigabytes.
  if (numVertices > bytes / 6 + 1 || numFaces > bytes / 8 + 1)
  {
    scan.fail("the counts (" + std::to_string(numVertices) + " vertices, " +
      std::to_string(numFaces) + " faces) do not fit in a file of " + std::to_string(bytes) +
      " bytes; the file is truncated or the counts are wrong");
  }
}

/// Reads `numVertices` vertex lines into soup.points.
void readVertices(
  OffScanner& scan, const VertexLayout& layout, int64_t numVertices, PolygonSoup& soup)
{
  const int64_t columns = layout.columns();
  std::string_view token;
  soup.points.resize(3 * numVertices);
  double coordinates[65];
  for (int64_t v = 0; v < numVertices; ++v)
  {
    if (!scan.nextLine())
    {
      scan.fail("the file ends after " + std::to_string(v) + " of " + std::to_string(numVertices) +
        " vertices; it is truncated or the counts are wrong");
    }
    for (int64_t c = 0; c < columns; ++c)
    {
      if (!scan.nextToken(token))
      {
        scan.fail("vertex " + std::to_string(v) + " has " + std::to_string(c) +
          " coordinates, expected " + std::to_string(columns));
      }
      if (!parseDouble(token, coordinates[c]))
      {
        scan.fail("vertex " + std::to_string(v) + ": " + quoted(token) + " is not a number");
      }
    }
    const double w = layout.homogeneous ? coordinates[columns - 1] : 1.0;
    for (int64_t c = 0; c < 3; ++c)
    {
      soup.points[3 * v + c] = c < layout.dimension ? coordinates[c] / w : 0.0;
    }
  }
}

/// Reads `numFaces` face lines "n i0 .. i(n-1) [colour]" into the soup's polygons.
void readFaces(OffScanner& scan, int64_t numVertices, int64_t numFaces, PolygonSoup& soup)
{
  std::string_view token;
  for (int64_t f = 0; f < numFaces; ++f)
  {
    if (!scan.nextLine())
    {
      scan.fail("the file ends after " + std::to_string(f) + " of " + std::to_string(numFaces) +
        " faces; it is truncated or the counts are wrong");
    }
    int64_t corners = 0;
    scan.nextToken(token);
    if (!parseInteger(token, corners) || corners < 1)
    {
      scan.fail("face " + std::to_string(f) + ": bad corner count " + quoted(token) +
        ", expected a positive integer");
    }
    for (int64_t c = 0; c < corners; ++c)
    {
      int64_t id = 0;
      if (!scan.nextToken(token))
      {
        scan.fail("face " + std::to_string(f) + " has " + std::to_string(c) +
          " corner indices, expected " + std::to_string(corners));
      }
      if (!parseInteger(token, id))
      {
        scan.fail("face " + std::to_string(f) + ": " + quoted(token) + " is not a vertex index");
      }
      if (id < 0 || id >= numVertices)
      {
        scan.fail("face " + std::to_string(f) + ": vertex index " + std::to_string(id) +
          " is out of range; the file has " + std::to_string(numVertices) + " vertices (0 to " +
          std::to_string(numVertices - 1) + ")");
      }
      soup.connectivity.push_back(id);
    }
    soup.offsets.push_back(static_cast<int64_t>(soup.connectivity.size()));
  }
}
} // namespace

// Parsed by hand rather than with CGAL::IO::read_OFF: CGAL reports a bad file as a bare
// `false`, while users fixing a broken file need to be told which line is wrong and why.
PolygonSoup readOFF(const std::string& path)
{
  // 1. The whole file, without a UTF-8 byte order mark.
  const std::string text = readWholeFile(path);
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (text.size() >= 3 && std::memcmp(begin, "\xEF\xBB\xBF", 3) == 0)
  {
    begin += 3;
  }
  if (begin == end)
  {
    throw InputError(path + ": not an OFF file: it is empty");
  }
  OffScanner scan(path, begin, end);
  std::string_view token;

  // 2. The keyword and the counts "V F [E]", on its line or the next.
  const VertexLayout layout = readKeyword(scan, token);
  int64_t numVertices = 0;
  int64_t numFaces = 0;
  readCounts(scan, token, static_cast<int64_t>(end - begin), numVertices, numFaces);

  // 3. The vertices, then the faces; anything after them (an edge list) is ignored.
  PolygonSoup soup;
  soup.offsets.reserve(numFaces + 1);
  soup.connectivity.reserve(3 * numFaces);
  readVertices(scan, layout, numVertices, soup);
  readFaces(scan, numVertices, numFaces, soup);
  return soup;
}

namespace
{
/// Refuses arrays that are not whole triples and triangles that refer to missing points.
void checkMesh(const std::string& path, const TriMesh& mesh)
{
  const int64_t nv = mesh.numPoints();
  if (mesh.points.size() % 3 != 0 || mesh.triangles.size() % 3 != 0)
  {
    throw InputError("writeOFF " + path +
      ": the point and triangle arrays must hold whole "
      "triples");
  }
  for (int64_t i = 0; i < 3 * mesh.numTriangles(); ++i)
  {
    if (mesh.triangles[i] < 0 || mesh.triangles[i] >= nv)
    {
      throw InputError("writeOFF " + path + ": triangle " + std::to_string(i / 3) +
        " refers to point " + std::to_string(mesh.triangles[i]) + " but the mesh has " +
        std::to_string(nv) + " points");
    }
  }
}

/// The OFF text of `mesh`. std::to_chars without a format gives the shortest text that reads
/// back to the same double.
std::string offText(const TriMesh& mesh)
{
  const int64_t nv = mesh.numPoints();
  const int64_t nf = mesh.numTriangles();
  std::string text;
  text.reserve(static_cast<size_t>(nv * 3 * 24 + nf * 28 + 64));
  text += "OFF\n" + std::to_string(nv) + " " + std::to_string(nf) + " 0\n";
  char buffer[64];
  for (int64_t i = 0; i < 3 * nv; ++i)
  {
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), mesh.points[i]);
    text.append(buffer, result.ptr);
    text += (i % 3 == 2) ? '\n' : ' ';
  }
  for (int64_t f = 0; f < nf; ++f)
  {
    text += '3';
    for (int c = 0; c < 3; ++c)
    {
      text += ' ';
      const auto result = std::to_chars(buffer, buffer + sizeof(buffer), mesh.triangles[3 * f + c]);
      text.append(buffer, result.ptr);
    }
    text += '\n';
  }
  return text;
}

} // namespace

void writeOFF(const std::string& path, const TriMesh& mesh)
{
  checkMesh(path, mesh);
  const std::string text = offText(mesh);
  detail::TemporaryFile file(path, "cannot write " + path);
  file.write(text.data(), text.size());
  file.finish();
  file.commit();
}
} // namespace tc
