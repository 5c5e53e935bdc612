// SPDX-License-Identifier: BSD-3-Clause
// Proxy bones for deforming sequences without a skeleton (Feng et al. 2010, section 4.3, with
// the least-squares skin of James and Twigg 2005), through the core alone: tc::fitProxyBones on
// each sequence, then per frame the RMS and largest point error of the fitted linear blend skin
// and of the rigid baseline (each point moved by its own cluster's rigid transform), relative
// to the rest frame's bounding-box diagonal, the totals over frames 1.., their ratio against
// the goals (LBS RMS <= 0.5% of the diagonal and <= half the rigid RMS) and the time taken.
//
//   tc_bench_proxy_bones [--clusters K] [SEQUENCE_FOLDER...]
// Without folders: the two shared sequences under TC_SHARED_DATA_DIR/sequences.
#include "tc/common/errors.h"
#include "tc/io/sequence_io.h"
#include "tc/skinning/proxy_bones.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
constexpr double kMaxRelativeRms = 0.005; // goal: LBS RMS <= 0.5% of the diagonal
constexpr double kMaxRigidRatio = 0.5;    // goal: LBS RMS <= half the rigid baseline's

double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Fits one sequence and prints its table; returns whether it meets both goals.
bool benchSequence(const std::string& folder, int clusters)
{
  const auto readStart = std::chrono::steady_clock::now();
  const tc::DeformingSequence sequence = tc::readSequence(folder);
  const double readSeconds = secondsSince(readStart);
  tc::ProxyBonesOptions options;
  options.clustering.numClusters = clusters;
  const auto fitStart = std::chrono::steady_clock::now();
  const tc::ProxyBonesResult fit = tc::fitProxyBones(sequence, options);
  const double fitSeconds = secondsSince(fitStart);

  const tc::FitError& lbs = fit.lbs;
  const tc::FitError& rigid = fit.rigid;
  std::printf("\n%s: %lld frames, %lld points, %d proxy bones, %lld boundary lines\n",
    folder.c_str(), static_cast<long long>(sequence.numFrames()),
    static_cast<long long>(sequence.soup.numPoints()), fit.clusters.numClusters,
    static_cast<long long>(fit.clusters.numLines()));
  std::printf("%6s %12s %12s %12s %12s   (%% of the diagonal %.4g)\n", "frame", "LBS rms",
    "LBS max", "rigid rms", "rigid max", lbs.diagonal);
  for (size_t k = 0; k < lbs.rms.size(); ++k)
  {
    std::printf("%6zu %12.4f %12.4f %12.4f %12.4f\n", k, 100 * lbs.relative(lbs.rms[k]),
      100 * lbs.relative(lbs.max[k]), 100 * rigid.relative(rigid.rms[k]),
      100 * rigid.relative(rigid.max[k]));
  }
  const double relative = lbs.relative(lbs.totalRms);
  const double ratio = rigid.totalRms > 0.0 ? lbs.totalRms / rigid.totalRms : 0.0;
  const bool ok = relative <= kMaxRelativeRms && ratio <= kMaxRigidRatio;
  std::printf("%6s %12.4f %12.4f %12.4f %12.4f\n", "total", 100 * relative,
    100 * lbs.relative(lbs.totalMax), 100 * rigid.relative(rigid.totalRms),
    100 * rigid.relative(rigid.totalMax));
  std::printf("LBS / rigid RMS %.3f; goals: LBS rms <= %.2f%% and ratio <= %.2f: %s\n", ratio,
    100 * kMaxRelativeRms, kMaxRigidRatio, ok ? "ok" : "MISSED");
  std::printf("time: read %.2f s, fit %.2f s\n", readSeconds, fitSeconds);
  return ok;
}
} // namespace

int main(int argc, char* argv[])
{
  int clusters = 0;
  std::vector<std::string> folders;
  for (int a = 1; a < argc; ++a)
  {
    const std::string arg = argv[a];
    if (arg == "--clusters" && a + 1 < argc)
    {
      clusters = std::atoi(argv[++a]);
    }
    else
    {
      folders.push_back(arg);
    }
  }
  if (folders.empty())
  {
    folders = { std::string(TC_SHARED_DATA_DIR) + "/sequences/snake_closed_21f",
      std::string(TC_SHARED_DATA_DIR) + "/sequences/frankie_run_19f" };
  }
  bool ok = true;
  for (const std::string& folder : folders)
  {
    try
    {
      ok = benchSequence(folder, clusters) && ok;
    }
    catch (const tc::InputError& e)
    {
      std::fprintf(stderr, "%s: %s\n", folder.c_str(), e.what());
      ok = false;
    }
  }
  return ok ? 0 : 1;
}
