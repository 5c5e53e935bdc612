// SPDX-License-Identifier: BSD-3-Clause
#include "tc/io/sequence_io.h"

#include "io/md2_frames.h"
#include "tc/common/errors.h"
#include "tc/common/file_names.h"
#include "tc/io/off_io.h"
#include "tc/io/soup_io.h"

#include <fnmatch.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace tc
{
namespace
{
namespace fs = std::filesystem;

constexpr const char* kFrameExtensions = "obj ply ply.gz off";

/// Whether the file name `name` ends in one of kFrameExtensions (and is more than the extension).
bool isFrameFile(const std::string& name)
{
  std::istringstream extensions(kFrameExtensions);
  std::string ext;
  while (extensions >> ext)
  {
    ext = "." + ext;
    if (name.size() > ext.size() && hasExtension(name, ext))
    {
      return true;
    }
  }
  return false;
}

/// Natural order: runs of digits compare by their value, so "f_2" < "f_10"; of two runs of the
/// same value, the one with fewer leading zeros first; everything else byte by byte.
bool naturalLess(const std::string& a, const std::string& b)
{
  const auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size())
  {
    if (!digit(a[i]) || !digit(b[j]))
    {
      if (a[i] != b[j])
      {
        return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      }
      ++i, ++j;
      continue;
    }
    const size_t runA = i, runB = j;
    while (i < a.size() && digit(a[i]))
    {
      ++i;
    }
    while (j < b.size() && digit(b[j]))
    {
      ++j;
    }
    // Compared as strings without their leading zeros: no overflow for long runs.
    const std::string_view numA = std::string_view(a).substr(runA, i - runA);
    const std::string_view numB = std::string_view(b).substr(runB, j - runB);
    const std::string_view valueA = numA.substr(std::min(numA.find_first_not_of('0'), numA.size()));
    const std::string_view valueB = numB.substr(std::min(numB.find_first_not_of('0'), numB.size()));
    if (valueA.size() != valueB.size())
    {
      return valueA.size() < valueB.size();
    }
    if (valueA != valueB)
    {
      return valueA < valueB;
    }
    if (numA.size() != numB.size())
    {
      return numA.size() < numB.size();
    }
  }
  return a.size() - i < b.size() - j;
}

/// The names of the regular, not hidden files of `folder` that `keep` accepts.
template <typename Keep>
std::vector<std::string> filesOf(const fs::path& folder, Keep keep)
{
  std::error_code ec;
  std::vector<std::string> names;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
  {
    const std::string name = it->path().filename().string();
    // Hidden files include the "._f_0000.obj" resource forks macOS leaves beside real frames.
    if (name[0] != '.' && it->is_regular_file(ec) && keep(name))
    {
      names.push_back(name);
    }
  }
  if (ec)
  {
    throw InputError("cannot list the folder '" + folder.string() + "': " + ec.message());
  }
  std::sort(names.begin(), names.end(), naturalLess);
  return names;
}

/// The frame files of `pattern` (wildcards in the file name only), in natural order; `folder`
/// is set to the pattern's folder.
std::vector<std::string> patternFiles(
  const std::string& pattern, fs::path& folder, std::vector<std::string>& warnings)
{
  const size_t slash = pattern.find_last_of('/');
  folder = slash == std::string::npos ? fs::path(".") : fs::path(pattern.substr(0, slash + 1));
  const std::string name = slash == std::string::npos ? pattern : pattern.substr(slash + 1);
  if (folder.string().find_first_of("*?") != std::string::npos)
  {
    throw InputError("the pattern '" + pattern +
      "' has a wildcard in its folder: put '*' and '?' " + "in the file name only (dir/f_*.obj)");
  }
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
  {
    throw InputError("the folder of the pattern '" + pattern + "' does not exist");
  }
  std::vector<std::string> skipped;
  std::vector<std::string> names = filesOf(folder,
    [&](const std::string& file)
    {
      const bool matches = fnmatch(name.c_str(), file.c_str(), 0) == 0;
      if (matches && !isFrameFile(file))
      {
        skipped.push_back(file);
      }
      return matches && isFrameFile(file);
    });
  if (!skipped.empty())
  {
    warnings.push_back(std::to_string(skipped.size()) + " files match '" + pattern +
      "' but are no frame file (" + kFrameExtensions + "), e.g. '" + skipped.front() +
      "': they are skipped");
  }
  return names;
}

/// One frame file read with the core reader of its extension.
MeshFile readFrameFile(const std::string& path)
{
  if (hasExtension(path, ".obj"))
  {
    return readOBJFile(path);
  }
  if (hasExtension(path, ".off"))
  {
    MeshFile mesh;
    mesh.soup = readOFF(path);
    return mesh;
  }
  return readPLYFile(path); // .ply and .ply.gz
}

/// The polygon `p` of `soup` as "(a, b, c)".
std::string corners(const PolygonSoup& soup, int64_t p)
{
  std::string text = "(";
  for (int64_t c = soup.offsets[p]; c < soup.offsets[p + 1]; ++c)
  {
    text += (c > soup.offsets[p] ? ", " : "") + std::to_string(soup.connectivity[c]);
  }
  return text + ")";
}

/// How the connectivity of `frame` first differs from that of `first`, which is named `firstName`
/// ("has 1060 points where frame 0 (f_0000.obj) has 1058"), or "" when it does not.
std::string connectivityDifference(
  const PolygonSoup& frame, const PolygonSoup& first, const std::string& firstName)
{
  const std::string where = " where " + firstName + " has ";
  if (frame.numPoints() != first.numPoints())
  {
    return "has " + std::to_string(frame.numPoints()) + " points" + where +
      std::to_string(first.numPoints());
  }
  if (frame.numPolygons() != first.numPolygons())
  {
    return "has " + std::to_string(frame.numPolygons()) + " polygons" + where +
      std::to_string(first.numPolygons());
  }
  for (int64_t p = 0; p < first.numPolygons(); ++p)
  {
    const bool same = frame.offsets[p + 1] == first.offsets[p + 1] &&
      std::equal(first.connectivity.begin() + first.offsets[p],
        first.connectivity.begin() + first.offsets[p + 1],
        frame.connectivity.begin() + frame.offsets[p]);
    if (!same)
    {
      return "has polygon " + std::to_string(p) + " with corners " + corners(frame, p) + where +
        corners(first, p);
    }
  }
  return "";
}

/// The frames `names` of `folder`, in that order, each checked against frame 0.
DeformingSequence readFrames(
  const fs::path& folder, const std::vector<std::string>& names, const Progress& progress)
{
  DeformingSequence out;
  const std::string firstName = names.empty() ? "" : "frame 0 (" + names.front() + ")";
  for (size_t k = 0; k < names.size(); ++k)
  {
    progress.report(static_cast<double>(k) / static_cast<double>(names.size()));
    const std::string frameName = "frame " + std::to_string(k) + " (" + names[k] + ")";
    MeshFile mesh;
    try
    {
      mesh = readFrameFile((folder / names[k]).string());
    }
    catch (const InputError& error)
    {
      throw InputError(frameName + " of the sequence cannot be read: " + error.what());
    }
    if (k == 0)
    {
      out.soup = std::move(mesh.soup);
      out.attributes = std::move(mesh.attributes);
      out.texture = std::move(mesh.texture);
      for (const std::string& warning : mesh.warnings)
      {
        out.warnings.push_back(firstName + ": " + warning);
      }
    }
    const PolygonSoup& soup = k == 0 ? out.soup : mesh.soup;
    const std::string difference = connectivityDifference(soup, out.soup, firstName);
    if (!difference.empty())
    {
      throw InputError(frameName + " " + difference +
        ": every frame of a sequence must have the same connectivity");
    }
    out.frames.emplace_back(soup.points.begin(), soup.points.end());
    out.times.push_back(static_cast<double>(k));
    out.frameNames.push_back(names[k]);
  }
  progress.report(1.0);
  return out;
}
} // namespace

const char* sequenceFrameExtensions()
{
  return kFrameExtensions;
}

bool isSequencePath(const std::string& path)
{
  std::error_code ec;
  return fs::is_directory(path, ec) || path.find_first_of("*?") != std::string::npos ||
    (path.size() > 4 && hasExtension(path, ".md2"));
}

DeformingSequence readSequence(const std::string& path, const Progress& progress)
{
  std::error_code ec;
  if (path.find_first_of("*?") == std::string::npos && hasExtension(path, ".md2"))
  {
    return readMD2Sequence(path, progress);
  }
  std::vector<std::string> warnings;
  fs::path folder;
  std::vector<std::string> names;
  std::string source;
  if (path.find_first_of("*?") != std::string::npos)
  {
    names = patternFiles(path, folder, warnings);
    source = "pattern";
  }
  else if (fs::is_directory(path, ec))
  {
    folder = path;
    names = filesOf(folder, isFrameFile);
    source = "folder";
  }
  else
  {
    throw InputError("'" + path + "' is no sequence: give a folder of frame files, a pattern " +
      "such as dir/f_*.obj, or an .md2 file");
  }
  if (names.empty())
  {
    throw InputError("'" + path + "' has no frame file: a sequence needs at least one file " +
      "with one of the extensions " + kFrameExtensions);
  }
  DeformingSequence out = readFrames(folder, names, progress);
  out.warnings.insert(out.warnings.begin(), warnings.begin(), warnings.end());
  out.source = source;
  return out;
}
} // namespace tc
