// SPDX-License-Identifier: BSD-3-Clause
#include "tc/skinning/proxy_bones.h"

#include "skinning/bone_transforms.h"
#include "skinning/sequence_checks.h"
#include "skinning/weight_fit.h"

#include "tc/common/errors.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace tc
{
namespace
{
using namespace detail::proxy;

void validateOptions(const ProxyBonesOptions& o)
{
  if (o.maxInfluences < 1 || o.maxInfluences > kMaxInfluences || o.iterations < 1 ||
    !(o.affineRegularization > 0.0))
  {
    throw InputError("fitProxyBones: invalid options: need maxInfluences in [1, " +
      std::to_string(kMaxInfluences) + "], iterations >= 1 and affineRegularization > 0");
  }
}

// The fitted weights as a skin: floats that sum to 1 (the largest takes the rounding).
SkinWeights toSkin(const Influences& in)
{
  const int64_t nv = static_cast<int64_t>(in.bones.size()) / in.slots;
  SkinWeights skin;
  std::vector<std::pair<int32_t, float>> influences;
  for (int64_t v = 0; v < nv; ++v)
  {
    double total = 0.0;
    for (int s = 0; s < in.slots; ++s)
    {
      total += in.weights[in.slots * v + s];
    }
    influences.clear();
    double rest = 1.0;
    for (int s = 1; s < in.slots; ++s)
    {
      const float w = static_cast<float>(in.weights[in.slots * v + s] / total);
      influences.emplace_back(in.bones[in.slots * v + s], w);
      rest -= w;
    }
    // Slot 0 holds the largest weight (fitWeights() sorts them).
    influences.emplace_back(in.bones[in.slots * v], static_cast<float>(rest));
    addSkinPoint(influences, in.bones[in.slots * v], skin);
  }
  return skin;
}

// The skin's weights in the fit's form.
Influences toInfluences(const SkinWeights& skin)
{
  Influences in;
  in.slots = kMaxInfluences;
  in.bones = skin.joints;
  in.weights.assign(skin.weights.begin(), skin.weights.end());
  return in;
}

// Every point bound to its own bone alone.
SkinWeights rigidSkin(const std::vector<int32_t>& pointBone)
{
  SkinWeights skin;
  for (int32_t b : pointBone)
  {
    addSkinPoint({ { b, 1.0f } }, b, skin);
  }
  return skin;
}

Skeleton proxySkeleton(int32_t numBones)
{
  Skeleton skeleton;
  skeleton.joints.resize(numBones);
  for (int32_t b = 0; b < numBones; ++b)
  {
    skeleton.joints[b].name = proxyJointName(b);
    skeleton.joints[b].restLocal = identityMatrix();
    skeleton.joints[b].inverseBind = identityMatrix();
  }
  return skeleton;
}

// The rest frame posed by `skin` with each frame's matrices.
std::vector<std::vector<double>> posedFrames(const std::vector<float>& rest,
  const SkinWeights& skin, const std::vector<std::vector<Matrix4>>& matrices)
{
  const std::vector<double> bind(rest.begin(), rest.end());
  std::vector<std::vector<double>> posed;
  for (const std::vector<Matrix4>& frame : matrices)
  {
    posed.push_back(skinPoints(bind, skin, frame));
  }
  return posed;
}
} // namespace

ProxyBonesResult fitProxyBones(const std::vector<int32_t>& triangles,
  const std::vector<std::vector<float>>& frames, const ProxyBonesOptions& options,
  const Progress& progress)
{
  detail::requireSequence("fitProxyBones: ", triangles, frames);
  validateOptions(options);
  ProxyBonesResult result;

  // 1. One bone per deformation cluster, and each point's own bone.
  result.clusters =
    clusterDeformation(triangles, frames, options.clustering, progress.sub(0.0, 0.4));
  const std::vector<int32_t>& clusterId = result.clusters.clusterId;
  const int32_t nb = result.clusters.numClusters;
  result.skeleton = proxySkeleton(nb);

  // 2. The rigid motion of every cluster: over all its points for the baseline, over its
  // interior points for the first bone transforms of the skin.
  result.rigidMatrices =
    rigidTransforms(frames, bonePoints(triangles, clusterId, nb), progress.sub(0.4, 0.43));
  result.pointBone = pointBones(triangles, clusterId, frames, result.rigidMatrices);
  const int64_t nv = static_cast<int64_t>(frames[0].size() / 3);
  const std::vector<std::vector<Matrix4>> start = rigidTransforms(
    frames, interiorBonePoints(triangles, clusterId, nb, nv), progress.sub(0.43, 0.45));

  // 3-6. Weights and transforms in turn, from the rigid transforms.
  const Candidates candidates = candidateBones(triangles, clusterId, result.pointBone, nb);
  const double step = 0.5 / (options.iterations + 1);
  Influences weights =
    fitWeights(frames, start, candidates, options.maxInfluences, progress.sub(0.45, 0.45 + step));
  for (int i = 1; i <= options.iterations; ++i)
  {
    const Progress part = progress.sub(0.45 + i * step, 0.45 + (i + 1) * step);
    const std::vector<std::vector<Matrix4>> matrices =
      affineTransforms(frames, weights, start, options.affineRegularization, part.sub(0.0, 0.3));
    weights = fitWeights(frames, matrices, candidates, options.maxInfluences, part.sub(0.3, 1.0));
  }
  result.skin = toSkin(weights);
  result.frameMatrices = affineTransforms(frames, toInfluences(result.skin), start,
    options.affineRegularization, progress.sub(0.95, 0.97));

  // 7. The errors of the fit and of the rigid baseline.
  result.lbs = measureFit(posedFrames(frames[0], result.skin, result.frameMatrices), frames);
  result.rigid =
    measureFit(posedFrames(frames[0], rigidSkin(result.pointBone), result.rigidMatrices), frames);
  progress.report(1.0);
  return result;
}

ProxyBonesResult fitProxyBones(
  const DeformingSequence& sequence, const ProxyBonesOptions& options, const Progress& progress)
{
  return fitProxyBones(fanTriangles(sequence.soup), sequence.frames, options, progress);
}

FitError measureFit(
  const std::vector<std::vector<double>>& fitted, const std::vector<std::vector<float>>& frames)
{
  if (fitted.size() != frames.size() || frames.empty())
  {
    throw InputError("measureFit: " + std::to_string(fitted.size()) + " fitted frames for " +
      std::to_string(frames.size()) + " input frames; give one fitted frame per input frame");
  }
  FitError e;
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (size_t i = 0; i < frames[0].size(); ++i)
  {
    lo[i % 3] = std::min(lo[i % 3], double(frames[0][i]));
    hi[i % 3] = std::max(hi[i % 3], double(frames[0][i]));
  }
  e.diagonal = frames[0].empty()
    ? 0.0
    : std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
        (hi[2] - lo[2]) * (hi[2] - lo[2]));
  double squares = 0.0, count = 0.0;
  for (size_t k = 0; k < frames.size(); ++k)
  {
    if (fitted[k].size() != frames[k].size())
    {
      throw InputError("measureFit: fitted frame " + std::to_string(k) + " holds " +
        std::to_string(fitted[k].size()) + " coordinates, the input " +
        std::to_string(frames[k].size()));
    }
    double frameSquares = 0.0, frameMax = 0.0;
    for (size_t v = 0; 3 * v < frames[k].size(); ++v)
    {
      double d2 = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        const double d = fitted[k][3 * v + c] - frames[k][3 * v + c];
        d2 += d * d;
      }
      frameSquares += d2;
      frameMax = std::max(frameMax, d2);
    }
    const double n = std::max(1.0, static_cast<double>(frames[k].size() / 3));
    e.rms.push_back(std::sqrt(frameSquares / n));
    e.max.push_back(std::sqrt(frameMax));
    e.totalMax = std::max(e.totalMax, e.max.back());
    if (k > 0 || frames.size() == 1)
    {
      squares += frameSquares;
      count += n;
    }
  }
  e.totalRms = std::sqrt(squares / count);
  return e;
}

std::string proxyJointName(int32_t bone)
{
  return "proxy " + std::to_string(bone);
}

bool isProxyRig(const Rig& rig)
{
  const std::vector<Joint>& joints = rig.skeleton.joints;
  for (size_t b = 0; b < joints.size(); ++b)
  {
    if (joints[b].name != proxyJointName(static_cast<int32_t>(b)) || joints[b].parent != -1)
    {
      return false;
    }
  }
  return !joints.empty();
}

Rig proxyRig(const ProxyBonesResult& fit, const std::vector<double>& times, const std::string& name)
{
  if (times.size() != fit.frameMatrices.size() || !std::is_sorted(times.begin(), times.end()) ||
    times.empty())
  {
    throw InputError("the proxy bones were fitted to " + std::to_string(fit.frameMatrices.size()) +
      " frames, and " + std::to_string(times.size()) + " ascending frame times are needed");
  }
  Rig rig;
  rig.skeleton = fit.skeleton;
  Animation animation;
  animation.name = name;
  animation.duration = std::max(0.0, times.back());
  animation.ticksPerSecond = 1.0;
  animation.frameTimes = times;
  // The proxy joints are roots bound at the rest frame: their global transforms are the fitted
  // skinning matrices.
  animation.frameGlobals = fit.frameMatrices;
  rig.animations.push_back(std::move(animation));
  return rig;
}
} // namespace tc
