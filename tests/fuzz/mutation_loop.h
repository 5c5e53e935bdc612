// SPDX-License-Identifier: BSD-3-Clause
/// @file mutation_loop.h
/// An in-process fuzzing loop for readers libFuzzer cannot steer: its guidance is the coverage
/// of instrumented code, and the code under test here (ParaView's VTK) is not instrumented. So
/// the loop mutates the seeds blindly, knowing the format instead (tokens, counts, headers),
/// and does what libFuzzer does around each input: the input a crash or a hang stops on is
/// saved, an abort or a signal is reported, and the figures (executions, per second) printed.
#pragma once

#include "input_files.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace tcfuzz
{
using Bytes = std::string;

/// Mutations of a seed: byte-level ones (flips, interesting bytes, inserts, deletes, copies,
/// truncation, splicing with another seed) and format-level ones given as a dictionary of
/// tokens (keywords, awkward numbers) and of 32-bit fields (offset, interesting values).
class Mutator
{
public:
  struct Field
  {
    size_t offset;
    std::vector<uint32_t> values;
  };

  Mutator(uint64_t seed, std::vector<std::string> tokens, std::vector<Field> fields)
    : Random(seed)
    , Tokens(std::move(tokens))
    , Fields(std::move(fields))
  {
  }

  /// 1 to 4 stacked mutations of `seed`, `other` the material to splice from.
  Bytes mutate(const Bytes& seed, const Bytes& other)
  {
    Bytes out = seed;
    const int steps = 1 + static_cast<int>(below(4));
    for (int s = 0; s < steps; ++s)
    {
      mutateOnce(out, other);
    }
    return out;
  }

private:
  size_t below(size_t n) { return n == 0 ? 0 : static_cast<size_t>(Random() % n); }

  void mutateOnce(Bytes& b, const Bytes& other)
  {
    static const char interesting[] = { 0, '\xff', '\x7f', '\x80', '\n', '\r', ' ', '-', '.', 'e',
      '0', '9' };
    const size_t at = below(b.size() + 1);
    switch (below(b.empty() ? 3 : 10))
    {
      case 0: // insert bytes
        b.insert(at, Bytes(1 + below(8), static_cast<char>(Random())));
        break;
      case 1: // a token of the format
        b.insert(at, Tokens.empty() ? Bytes(" ") : " " + Tokens[below(Tokens.size())] + " ");
        break;
      case 2: // splice: this input's head, the other's tail
        b = b.substr(0, at) + other.substr(below(other.size() + 1));
        break;
      case 3: // flip bits
        for (size_t k = 1 + below(8); k > 0; --k)
        {
          b[below(b.size())] ^= static_cast<char>(1u << below(8));
        }
        break;
      case 4:
        b[below(b.size())] = interesting[below(sizeof interesting)];
        break;
      case 5: // delete a range
        b.erase(below(b.size()), 1 + below(std::min<size_t>(b.size(), 64)));
        break;
      case 6: // copy a range elsewhere
      {
        const Bytes chunk = b.substr(below(b.size()), 1 + below(64));
        b.insert(below(b.size() + 1), chunk);
        break;
      }
      case 7: // truncate
        b.resize(below(b.size()));
        break;
      case 8: // replace a whitespace-separated word by a token
        replaceWord(b);
        break;
      default: // set a field of the format to an interesting value
        setField(b);
        break;
    }
  }

  void replaceWord(Bytes& b)
  {
    if (Tokens.empty())
    {
      return;
    }
    size_t start = below(b.size());
    while (start > 0 && !std::isspace(static_cast<unsigned char>(b[start - 1])))
    {
      --start;
    }
    size_t end = start;
    while (end < b.size() && !std::isspace(static_cast<unsigned char>(b[end])))
    {
      ++end;
    }
    b.replace(start, end - start, Tokens[below(Tokens.size())]);
  }

  void setField(Bytes& b)
  {
    if (Fields.empty())
    {
      return;
    }
    const Field& field = Fields[below(Fields.size())];
    if (field.offset + 4 > b.size() || field.values.empty())
    {
      return;
    }
    uint32_t value = field.values[below(field.values.size())];
    uint32_t old;
    std::memcpy(&old, b.data() + field.offset, 4);
    value = below(3) == 0 ? old + static_cast<uint32_t>(below(5)) - 2 : value; // off by a few
    std::memcpy(&b[field.offset], &value, 4);
  }

  std::mt19937_64 Random;
  std::vector<std::string> Tokens;
  std::vector<Field> Fields;
};

/// Where a crash or a hang leaves the input it stopped on: the input file is copied to
/// `<artifacts>/crash-<n><ext>` from the signal handler (with async-signal-safe calls only),
/// or to `timeout-<n><ext>` by the watchdog, which then ends the process.
class Guard
{
public:
  Guard(const std::string& input, const std::string& artifacts, const std::string& extension,
    double timeoutSeconds)
  {
    Self = this;
    std::snprintf(Input, sizeof Input, "%s", input.c_str());
    std::snprintf(Prefix, sizeof Prefix, "%s/", artifacts.c_str());
    std::snprintf(Extension, sizeof Extension, "%s", extension.c_str());
    for (const int sig : { SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT })
    {
      std::signal(sig, &Guard::onSignal);
    }
    Timeout = timeoutSeconds;
    Watchdog = std::thread([this] { watch(); });
  }
  ~Guard()
  {
    Stop = true;
    Watchdog.join();
  }

  /// Marks the start (true) and the end (false) of one input's run.
  void running(bool on, uint64_t execution)
  {
    Execution = execution;
    Started = on ? now() : 0.0;
  }

private:
  static double now()
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
  }

  /// Copies the input to `<prefix><kind>-<execution><extension>` with open/read/write only.
  void save(const char* kind) const
  {
    char target[1200];
    std::snprintf(target, sizeof target, "%s%s-%llu%s", Prefix, kind,
      static_cast<unsigned long long>(Execution.load()), Extension);
    const int in = open(Input, O_RDONLY);
    const int out = open(target, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    char buffer[4096];
    ssize_t n = 0;
    while (in >= 0 && out >= 0 && (n = read(in, buffer, sizeof buffer)) > 0)
    {
      if (write(out, buffer, static_cast<size_t>(n)) != n)
      {
        break;
      }
    }
    close(in);
    close(out);
    const char note[] = "tc_fuzz: the input is saved as ";
    (void)!write(2, note, sizeof note - 1);
    (void)!write(2, target, std::strlen(target));
    (void)!write(2, "\n", 1);
  }

  static void onSignal(int sig)
  {
    Self->save("crash");
    std::signal(sig, SIG_DFL);
    raise(sig);
  }

  void watch()
  {
    while (!Stop)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      const double started = Started;
      if (started > 0.0 && now() - started > Timeout)
      {
        std::fprintf(stderr, "tc_fuzz: an input ran for more than %g s (a hang)\n", Timeout);
        save("timeout");
        std::_Exit(70);
      }
    }
  }

  static inline Guard* Self = nullptr;
  char Input[1024];
  char Prefix[1024];
  char Extension[32];
  double Timeout = 10.0;
  std::atomic<double> Started{ 0.0 };
  std::atomic<uint64_t> Execution{ 0 };
  std::atomic<bool> Stop{ false };
  std::thread Watchdog;
};

/// The bytes of every file named: a file itself, a folder's regular files in name order.
inline std::vector<Bytes> readInputs(const std::vector<std::string>& paths)
{
  namespace fs = std::filesystem;
  const std::vector<fs::path> files = inputFiles(paths);
  std::vector<Bytes> inputs;
  for (const fs::path& file : files)
  {
    std::ifstream in(file, std::ios::binary);
    if (!in)
    {
      std::fprintf(stderr, "tc_fuzz: cannot read %s\n", file.c_str());
      std::exit(1);
    }
    inputs.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  return inputs;
}
} // namespace tcfuzz
