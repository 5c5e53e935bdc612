// SPDX-License-Identifier: BSD-3-Clause
/// @file sequence_io.h
/// Deforming sequences: one surface whose points move from frame to frame over one fixed
/// connectivity, read from a folder of frame files, a glob pattern of them, or the vertex
/// keyframes of a Quake II MD2 model (Assimp reads only an MD2 file's first frame).
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"
#include "tc/io/mesh_file.h"

#include <string>
#include <vector>

namespace tc
{
/// A surface whose points move from frame to frame over one fixed connectivity.
struct DeformingSequence
{
  PolygonSoup soup; ///< frame 0's points and the one connectivity of every frame
  /// Per frame, #V x 3 positions, xyz interleaved, in the units of the files; frames[0] holds
  /// soup.points rounded to float.
  std::vector<std::vector<float>> frames;
  /// Per frame, in seconds: frame k at time k, as none of the formats read here stores times.
  std::vector<double> times;
  /// Per frame: the file name (without its folder) for a folder or a pattern, the frame's name
  /// as the file stores it for MD2.
  std::vector<std::string> frameNames;
  PointAttributes attributes;        ///< of frame 0 (texture coordinates where the format has them)
  BaseColorTexture texture;          ///< of frame 0's file (OBJ map_Kd, PLY TextureFile, MD2 skin)
  std::vector<std::string> warnings; ///< what the readers left out or doubted, one sentence each
  std::string source;                ///< how the frames were found: "folder", "pattern" or "md2"

  int64_t numFrames() const { return static_cast<int64_t>(frames.size()); }
};

/// File extensions a frame file of a folder or a pattern may have, space-separated, without
/// dots.
const char* sequenceFrameExtensions();

/// True if `path` names a sequence for readSequence: an existing folder, a path with a '*' or
/// '?' wildcard (a glob pattern; readSequence refuses one whose wildcard is in the folder part),
/// or a name ending (case-insensitively) in ".md2". Only the folder case looks at the disk.
bool isSequencePath(const std::string& path);

/// Reads a deforming sequence from `path`:
/// - a folder: every file in it (not in its subfolders; hidden files skipped) whose extension is
///   one of sequenceFrameExtensions(), read with readOBJFile, readPLYFile or readOFF, in natural
///   order (digits compared as numbers, so f_2 comes before f_10);
/// - a glob pattern (`dir/f_*.obj`): the same, over the files of the folder whose name matches
///   (fnmatch(3)); the wildcards are allowed in the file name only, and a matching file of
///   another extension is skipped with a warning;
/// - an MD2 file: every vertex keyframe, position = byte * scale + translate, with frame 0 as
///   tc::readScene (Assimp 5.2) reads the file: its (x, z, -y) axes, each triangle's corners
///   reversed, u = s / skinwidth and v = 1 - t / skinheight. One point per distinct (vertex,
///   texture coordinate) pair the triangles use, the same ids in every frame.
///
/// Every frame must have frame 0's point count and polygons (the same corners in the same
/// order). A single frame is a sequence of one.
///
/// @param[in] path      a folder, a pattern or an MD2 file (see isSequencePath)
/// @param[in] progress  reported once per frame; may abort (tc::Aborted)
/// @throws tc::InputError  for a missing folder or file, a pattern with a wildcard in its
///   folder, a folder or pattern without a frame file, a frame its reader refuses (the message
///   names the frame), a frame whose connectivity differs from frame 0's (naming the frame and
///   the first difference); for MD2, a header or data the file does not hold (offsets, counts,
///   indices out of range, a frame size under 40 + 4 x vertices, no frame, no triangle, a
///   non-finite scale or translation), each said in one sentence
DeformingSequence readSequence(const std::string& path, const Progress& progress = {});
} // namespace tc
