// SPDX-License-Identifier: BSD-3-Clause
/// @file temporary_file.h
/// A file written under a temporary name beside its target and renamed over it only when
/// complete and on disk (the atlas, glTF and mesh writers): on any error or exception the
/// temporary is removed and an existing target is left as it was. A writer that opens files by
/// name itself (VTK's) finishes the empty temporary, writes to path(), then commits.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

namespace tc
{
namespace detail
{
class TemporaryFile
{
public:
  /// Creates the new empty file `target`.tmp-XXXXXX`suffix` (6 random letters and digits) beside
  /// `target`, with the mode the user's umask gives a new file. `error` starts every message,
  /// e.g. "cannot write atlas <target>". A suffix keeps the extension for writers that add it
  /// when it is missing (VTK's PLY writer).
  /// @throws InputError  when the folder is missing or not writable
  TemporaryFile(
    const std::string& target, const std::string& error, const std::string& suffix = "");
  /// Closes the file and removes it unless commit() succeeded.
  ~TemporaryFile();
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  const std::string& path() const { return Path; }

  /// Writes n bytes at the current position; tell() and seek() move it. Each throws InputError
  /// on failure, and the failure stays recorded for finish() (OpenEXR swallows exceptions in
  /// the destructor that writes its offset tables).
  void write(const char* data, size_t n);
  uint64_t tell();
  void seek(uint64_t position);

  /// Flushes to disk (fsync) and closes; throws InputError if anything failed on the way.
  void finish();
  /// Renames the finished file over the target, which then stays.
  /// @throws InputError  when the rename fails (the target is a folder, or the folder is no
  ///   longer writable)
  void commit();

private:
  [[noreturn]] void fail();

  std::string Target;
  std::string Error;
  std::string Path;
  std::FILE* File = nullptr;
  std::string Failed; ///< the first failure (strerror), empty while all went well
  bool Committed = false;
};
} // namespace detail
} // namespace tc
