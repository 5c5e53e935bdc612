// SPDX-License-Identifier: BSD-3-Clause
// The main of a fuzz target built without libFuzzer (GCC, or clang without libclang-rt-14-dev):
// it replays every input it is given, once, the way `target -runs=0 DIR...` does under
// libFuzzer, so that the seed corpora and the crash inputs found run as regression tests in
// any build. Arguments starting with '-' (libFuzzer's options) are ignored, so one command line
// serves both mains.
#include "input_files.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace fs = std::filesystem;

int main(int argc, char** argv)
{
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i)
  {
    if (argv[i][0] != '-')
    {
      args.emplace_back(argv[i]);
    }
  }
  const std::vector<fs::path> inputs = tcfuzz::inputFiles(args);
  if (inputs.empty())
  {
    std::fprintf(stderr, "usage: %s FILE|FOLDER...: no input to replay\n", argv[0]);
    return 1;
  }
  for (const fs::path& input : inputs)
  {
    std::ifstream in(input, std::ios::binary);
    if (!in)
    {
      std::fprintf(stderr, "cannot read %s\n", input.c_str());
      return 1;
    }
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
    // Where the process dies, the last line names the input that killed it.
    std::fprintf(stderr, "replaying %s\n", input.c_str());
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("replayed %zu inputs\n", inputs.size());
  return 0;
}
