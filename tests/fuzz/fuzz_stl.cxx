// SPDX-License-Identifier: BSD-3-Clause
// Fuzzing the STL path of tcMeshReader (VTK's vtkSTLReader behind it), in process:
//
//   tc_fuzz_stl INPUT...                    replays every input once (the regression test)
//   tc_fuzz_stl --seconds S [--seed N] [--timeout T] [--artifacts DIR] SEED...
//                                           mutates the seeds for S seconds
//
// An in-process loop, not libFuzzer: vtkSTLReader lives in ParaView's prebuilt VTK, whose code
// has no coverage instrumentation for libFuzzer to steer by, and building VTK instrumented is
// hours per CI run. The loop knows the format instead: ASCII keywords and awkward numbers, and
// the binary file's 80-byte header ("solid" in a binary header is the classic trap) and its
// triangle count. Every input is read into triangles whose corners exist, or refused with an
// error that names the file; a crash saves the input as crash-N.stl, a hang as timeout-N.stl.
#include "fuzz_support.h"
#include "mutation_loop.h"

#include "tcMeshReader.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPolyData.h>

namespace
{
/// The text of the reader's last error ("" if none).
struct ErrorText
{
  std::string text;
  static void record(vtkObject*, unsigned long, void* self, void* message)
  {
    static_cast<ErrorText*>(self)->text = static_cast<const char*>(message);
  }
};

/// Reads `path` with tcMeshReader and checks the contract; returns whether it was refused.
bool readAndCheck(const std::string& path)
{
  vtkNew<tcMeshReader> reader;
  ErrorText error;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetCallback(&ErrorText::record);
  onError->SetClientData(&error);
  reader->AddObserver(vtkCommand::ErrorEvent, onError);
  reader->SetFileName(path.c_str());
  reader->Update();
  if (!error.text.empty())
  {
    if (error.text.find(path) == std::string::npos)
    {
      std::fprintf(
        stderr, "tc_fuzz: a refusal that does not name the file: %s\n", error.text.c_str());
      std::abort();
    }
    return true;
  }
  vtkPolyData* mesh = reader->GetOutput();
  const vtkIdType points = mesh->GetNumberOfPoints();
  auto cells = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    cells->GetCurrentCell(n, ids);
    for (vtkIdType k = 0; k < n; ++k)
    {
      if (ids[k] < 0 || ids[k] >= points)
      {
        std::fprintf(stderr, "tc_fuzz: a triangle refers to point %lld of %lld\n",
          static_cast<long long>(ids[k]), static_cast<long long>(points));
        std::abort();
      }
    }
  }
  if (mesh->GetNumberOfPolys() == 0)
  {
    std::fprintf(stderr, "tc_fuzz: no polygons and no error\n");
    std::abort();
  }
  return false;
}

tcfuzz::Mutator stlMutator(uint64_t seed, size_t triangles)
{
  const std::vector<std::string> tokens = { "solid", "endsolid", "facet", "endfacet", "normal",
    "outer", "loop", "endloop", "vertex", "0", "-0", "1", "1e38", "3.5e38", "-1e-45", "1e-320",
    "1e309", "nan", "-nan", "inf", "-inf", "0x1p3", "1,5", "99999999999999999999", "\n", "\r\n",
    "\t", "" };
  const uint32_t n = static_cast<uint32_t>(triangles);
  std::vector<tcfuzz::Mutator::Field> fields = {
    { 80,
      { 0, 1, 2, n - 1, n + 1, 2 * n, 0x7fffffffu, 0x80000000u, 0xffffffffu, 1u << 24,
        0x0a0a0a0au } },
    { 0, { 0x696c6f73u /* "soli" */, 0x20202020u, 0 } },
  };
  for (uint32_t t = 0; t < std::min<uint32_t>(n, 4); ++t) // a triangle's attribute bytes
  {
    fields.push_back({ 84 + 50 * t + 46, { 0xffffffffu, 0 } });
  }
  return tcfuzz::Mutator(seed, tokens, fields);
}

struct Options
{
  double seconds = 0.0;
  uint64_t seed = 1;
  double timeout = 10.0;
  std::string artifacts = ".";
  std::vector<std::string> inputs;
};

Options parse(int argc, char** argv)
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool value = i + 1 < argc;
    if (arg == "--seconds" && value)
      o.seconds = std::atof(argv[++i]);
    else if (arg == "--seed" && value)
      o.seed = std::strtoull(argv[++i], nullptr, 10);
    else if (arg == "--timeout" && value)
      o.timeout = std::atof(argv[++i]);
    else if (arg == "--artifacts" && value)
      o.artifacts = argv[++i];
    else
      o.inputs.push_back(arg);
  }
  return o;
}
} // namespace

int main(int argc, char** argv)
{
  const Options options = parse(argc, argv);
  const std::vector<tcfuzz::Bytes> seeds = tcfuzz::readInputs(options.inputs);
  if (seeds.empty())
  {
    std::fprintf(stderr,
      "usage: %s [--seconds S] [--seed N] [--timeout T] [--artifacts DIR] "
      "INPUT...\n",
      argv[0]);
    return 1;
  }
  // VTK's warnings and the executive's failure lines: thousands a minute.
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  const tcfuzz::InputFile file(".stl");
  tcfuzz::Guard guard(file.path(), options.artifacts, ".stl", options.timeout);
  tcfuzz::Mutator mutator = stlMutator(options.seed, 4);
  std::mt19937_64 pick(options.seed);
  uint64_t executions = 0, refused = 0;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&start]
  { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  // Replay: each input once. Fuzz: mutated seeds until the time is up.
  while (options.seconds > 0.0 ? elapsed() < options.seconds : executions < seeds.size())
  {
    const tcfuzz::Bytes input = options.seconds > 0.0
      ? mutator.mutate(seeds[pick() % seeds.size()], seeds[pick() % seeds.size()])
      : seeds[executions];
    file.write(reinterpret_cast<const uint8_t*>(input.data()), input.size());
    guard.running(true, executions);
    refused += readAndCheck(file.path()) ? 1 : 0;
    guard.running(false, executions);
    ++executions;
  }
  const double seconds = elapsed();
  std::printf("tc_fuzz_stl: %llu executions in %.1f s (%.0f/s), %llu refused, %llu read, "
              "0 crashes, 0 hangs\n",
    static_cast<unsigned long long>(executions), seconds, executions / std::max(seconds, 1e-9),
    static_cast<unsigned long long>(refused),
    static_cast<unsigned long long>(executions - refused));
  return 0;
}
