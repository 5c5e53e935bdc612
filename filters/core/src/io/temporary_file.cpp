// SPDX-License-Identifier: BSD-3-Clause
#include "tc/io/temporary_file.h"

#include "tc/common/errors.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>

namespace tc
{
namespace detail
{
namespace
{
/// Creates a new empty file `path`.tmp-XXXXXX`suffix` beside `path` and opens it. Not mkstemp: that
/// creates the file with mode 0600, and the atlas would keep it after the rename; open with
/// O_EXCL and mode 0666 gives the mode the user's umask asks for, like any new file.
std::FILE* createTemporary(const std::string& path, const std::string& suffix,
  const std::string& error, std::string& temporary)
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
    temporary += suffix;
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0)
    {
      std::FILE* file = ::fdopen(fd, "wb");
      if (!file)
      {
        const int code = errno;
        ::close(fd);
        ::unlink(temporary.c_str());
        errno = code;
        break;
      }
      return file;
    }
    if (errno != EEXIST)
    {
      break;
    }
  }
  throw InputError(
    error + ": " + std::strerror(errno) + " (does the folder exist and is it writable?)");
}
} // namespace

TemporaryFile::TemporaryFile(
  const std::string& target, const std::string& error, const std::string& suffix)
  : Target(target)
  , Error(error)
{
  File = createTemporary(target, suffix, error, Path);
}

TemporaryFile::~TemporaryFile()
{
  if (File)
  {
    std::fclose(File);
  }
  if (!Committed && !Path.empty())
  {
    ::unlink(Path.c_str());
  }
}

void TemporaryFile::write(const char* data, size_t n)
{
  if (n > 0 && std::fwrite(data, 1, n, File) != n)
  {
    fail();
  }
}

uint64_t TemporaryFile::tell()
{
  const off_t at = ftello(File);
  if (at < 0)
  {
    fail();
  }
  return static_cast<uint64_t>(at);
}

void TemporaryFile::seek(uint64_t position)
{
  if (fseeko(File, static_cast<off_t>(position), SEEK_SET) != 0)
  {
    fail();
  }
}

void TemporaryFile::finish()
{
  if (Failed.empty() && (std::fflush(File) != 0 || std::ferror(File) || ::fsync(fileno(File)) != 0))
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
    throw InputError(
      Error + ": " + Failed + " (is the disk full or the folder no longer writable?)");
  }
}

void TemporaryFile::commit()
{
  if (std::rename(Path.c_str(), Target.c_str()) != 0)
  {
    throw InputError(Error + ": " + std::strerror(errno) +
      " when replacing it (is it a folder, or is the folder no longer writable?)");
  }
  Committed = true;
}

void TemporaryFile::fail()
{
  if (Failed.empty())
  {
    Failed = std::strerror(errno);
  }
  throw InputError(Error + ": " + Failed + " (is the disk full or the folder no longer writable?)");
}
} // namespace detail
} // namespace tc
