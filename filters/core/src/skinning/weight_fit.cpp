// SPDX-License-Identifier: BSD-3-Clause
#include "skinning/weight_fit.h"

#include "tc/common/mesh_topology.h"
#include "tc/common/parallel.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace tc
{
namespace detail
{
namespace proxy
{
namespace
{
Eigen::Vector3d transformPoint(const Matrix4& m, const Eigen::Vector3d& p)
{
  return { m[0] * p.x() + m[1] * p.y() + m[2] * p.z() + m[3],
    m[4] * p.x() + m[5] * p.y() + m[6] * p.z() + m[7],
    m[8] * p.x() + m[9] * p.y() + m[10] * p.z() + m[11] };
}

double faceArea(const std::vector<float>& rest, const std::vector<int32_t>& triangles, int64_t f)
{
  const Eigen::Vector3d a = pointOf(rest, triangles[3 * f]);
  return 0.5 *
    (pointOf(rest, triangles[3 * f + 1]) - a).cross(pointOf(rest, triangles[3 * f + 2]) - a).norm();
}

// The bone whose rigid motion carries rest point v closest to its positions over the frames.
int32_t bestRigidBone(const std::vector<std::vector<float>>& frames,
  const std::vector<std::vector<Matrix4>>& rigid, int64_t v)
{
  int32_t best = 0;
  double bestError = HUGE_VAL;
  for (size_t b = 0; b < rigid[0].size(); ++b)
  {
    double error = 0.0;
    for (size_t k = 1; k < frames.size(); ++k)
    {
      error +=
        (transformPoint(rigid[k][b], pointOf(frames[0], v)) - pointOf(frames[k], v)).squaredNorm();
    }
    if (error < bestError)
    {
      bestError = error;
      best = static_cast<int32_t>(b);
    }
  }
  return best;
}

// Pairs of bones whose clusters share a mesh vertex, both directions, as CSR over bones.
std::vector<std::vector<int32_t>> adjacentBones(
  const VertexFaces& vf, const std::vector<int32_t>& clusterId, int32_t numBones)
{
  std::vector<std::vector<int32_t>> adjacent(numBones);
  std::vector<int32_t> around;
  for (size_t v = 0; v + 1 < vf.offsets.size(); ++v)
  {
    around.clear();
    for (int64_t i = vf.offsets[v]; i < vf.offsets[v + 1]; ++i)
    {
      around.push_back(clusterId[vf.faceIds[i]]);
    }
    for (int32_t a : around)
    {
      adjacent[a].insert(adjacent[a].end(), around.begin(), around.end());
    }
  }
  for (std::vector<int32_t>& row : adjacent)
  {
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
  }
  return adjacent;
}

// Step 2 of simplexLeastSquares: the minimizer over the free weights with sum 1, reached from
// the feasible w by steps that stop where a weight reaches 0 (which is then fixed at 0).
void descend(const Eigen::MatrixXd& g, const Eigen::VectorXd& h, std::vector<uint8_t>& isFree,
  Eigen::VectorXd& w)
{
  const int m = static_cast<int>(h.size());
  for (int pass = 0; pass <= m; ++pass)
  {
    std::vector<int> f;
    for (int i = 0; i < m; ++i)
    {
      if (isFree[i])
      {
        f.push_back(i);
      }
    }
    const int n = static_cast<int>(f.size());
    // KKT system of min 1/2 z^T G z - h^T z subject to sum z = 1 on the free set.
    Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + 1, n + 1);
    Eigen::VectorXd rhs(n + 1);
    for (int i = 0; i < n; ++i)
    {
      for (int j = 0; j < n; ++j)
      {
        kkt(i, j) = g(f[i], f[j]);
      }
      kkt(i, n) = kkt(n, i) = 1.0;
      rhs(i) = h(f[i]);
    }
    rhs(n) = 1.0;
    const Eigen::VectorXd z = kkt.fullPivLu().solve(rhs).head(n);
    double alpha = 1.0;
    int blocking = -1;
    for (int i = 0; i < n; ++i)
    {
      if (z(i) <= 0.0 && w(f[i]) - z(i) > 0.0 && w(f[i]) / (w(f[i]) - z(i)) < alpha)
      {
        alpha = w(f[i]) / (w(f[i]) - z(i));
        blocking = f[i];
      }
    }
    for (int i = 0; i < n; ++i)
    {
      w(f[i]) += alpha * (z(i) - w(f[i]));
    }
    if (blocking < 0)
    {
      return;
    }
    w(blocking) = 0.0;
    isFree[blocking] = 0;
  }
}

// The weights of one point's candidates (index 0 its own bone); see fitWeights().
Eigen::VectorXd pointWeights(const std::vector<std::vector<float>>& frames,
  const std::vector<std::vector<Matrix4>>& matrices, const int32_t* bones, int m, int64_t v)
{
  // Columns relative to the own bone's prediction: with sum w = 1, sum w_b (a_b - a_0) =
  // y - a_0 is the same problem, and G then measures only how the bones' motions differ.
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd h = Eigen::VectorXd::Zero(m);
  Eigen::Matrix3Xd d(3, m);
  const Eigen::Vector3d p = pointOf(frames[0], v);
  for (size_t k = 1; k < frames.size(); ++k)
  {
    const Eigen::Vector3d own = transformPoint(matrices[k][bones[0]], p);
    for (int b = 0; b < m; ++b)
    {
      d.col(b) = transformPoint(matrices[k][bones[b]], p) - own;
    }
    g.noalias() += d.transpose() * d;
    h.noalias() += d.transpose() * (pointOf(frames[k], v) - own);
  }
  // The pull towards the own bone: far below any difference of motion that the frames
  // resolve, it decides between bones that move the point alike (G singular).
  const double ridge = 1e-10 * g.diagonal().maxCoeff();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m);
  w(0) = 1.0;
  if (!(ridge > 0.0))
  {
    return w;
  }
  g.diagonal().tail(m - 1).array() += ridge;
  return simplexLeastSquares(g, h, 0);
}

// Keeps the `keep` largest of w (ties to the lower index) and solves again on them alone.
Eigen::VectorXd limitInfluences(const std::vector<std::vector<float>>& frames,
  const std::vector<std::vector<Matrix4>>& matrices, const int32_t* bones, const Eigen::VectorXd& w,
  int keep, int64_t v, std::vector<int32_t>& kept)
{
  std::vector<int> order(w.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return w(a) > w(b); });
  order.resize(keep);
  // The own bone's index first, as pointWeights() wants it, when it is among those kept.
  std::sort(order.begin(), order.end());
  kept.clear();
  for (int i : order)
  {
    kept.push_back(bones[i]);
  }
  return pointWeights(frames, matrices, kept.data(), keep, v);
}
} // namespace

std::vector<int32_t> pointBones(const std::vector<int32_t>& triangles,
  const std::vector<int32_t>& clusterId, const std::vector<std::vector<float>>& frames,
  const std::vector<std::vector<Matrix4>>& rigid)
{
  const int64_t nv = static_cast<int64_t>(frames[0].size() / 3);
  const VertexFaces vf = buildVertexFaces(triangles, nv);
  std::vector<int32_t> bone(nv, 0);
  parallel_for(nv,
    [&](int64_t v)
    {
      if (vf.offsets[v] == vf.offsets[v + 1])
      {
        bone[v] = bestRigidBone(frames, rigid, v);
        return;
      }
      std::vector<std::pair<int32_t, double>> area;
      for (int64_t i = vf.offsets[v]; i < vf.offsets[v + 1]; ++i)
      {
        area.emplace_back(clusterId[vf.faceIds[i]], faceArea(frames[0], triangles, vf.faceIds[i]));
      }
      std::sort(area.begin(), area.end());
      double best = -1.0;
      for (size_t i = 0; i < area.size();)
      {
        double sum = 0.0;
        size_t j = i;
        for (; j < area.size() && area[j].first == area[i].first; ++j)
        {
          sum += area[j].second;
        }
        if (sum > best)
        {
          best = sum;
          bone[v] = area[i].first;
        }
        i = j;
      }
    });
  return bone;
}

Candidates candidateBones(const std::vector<int32_t>& triangles,
  const std::vector<int32_t>& clusterId, const std::vector<int32_t>& pointBone, int32_t numBones)
{
  const int64_t nv = static_cast<int64_t>(pointBone.size());
  const VertexFaces vf = buildVertexFaces(triangles, nv);
  const std::vector<std::vector<int32_t>> adjacent = adjacentBones(vf, clusterId, numBones);
  Candidates out;
  out.offsets.assign(nv + 1, 0);
  std::vector<int32_t> set;
  for (int64_t v = 0; v < nv; ++v)
  {
    set.clear();
    for (int64_t i = vf.offsets[v]; i < vf.offsets[v + 1]; ++i)
    {
      const std::vector<int32_t>& near = adjacent[clusterId[vf.faceIds[i]]];
      set.insert(set.end(), near.begin(), near.end());
    }
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    set.erase(std::remove(set.begin(), set.end(), pointBone[v]), set.end());
    out.bones.push_back(pointBone[v]);
    out.bones.insert(out.bones.end(), set.begin(), set.end());
    out.offsets[v + 1] = static_cast<int64_t>(out.bones.size());
  }
  return out;
}

Eigen::VectorXd simplexLeastSquares(const Eigen::MatrixXd& g, const Eigen::VectorXd& h, int start)
{
  const int m = static_cast<int>(h.size());
  Eigen::VectorXd w = Eigen::VectorXd::Zero(m);
  w(start) = 1.0;
  std::vector<uint8_t> isFree(m, 0);
  isFree[start] = 1;
  const double tolerance =
    1e-12 * std::max(g.diagonal().cwiseAbs().maxCoeff(), h.cwiseAbs().maxCoeff());
  for (int iteration = 0; iteration < 3 * m + 10; ++iteration)
  {
    // 1. The multipliers of the weights held at 0: lambda_j = grad_j + nu, nu the multiplier of
    // sum w = 1 (grad + nu vanishes on the free weights at their optimum). The most negative
    // one is freed; none negative is the optimum (KKT).
    const Eigen::VectorXd grad = g * w - h;
    double nu = 0.0;
    int numFree = 0;
    for (int i = 0; i < m; ++i)
    {
      nu -= isFree[i] ? grad(i) : 0.0;
      numFree += isFree[i];
    }
    nu /= numFree;
    int enter = -1;
    double most = -tolerance;
    for (int j = 0; j < m; ++j)
    {
      if (!isFree[j] && grad(j) + nu < most)
      {
        most = grad(j) + nu;
        enter = j;
      }
    }
    if (enter < 0)
    {
      break;
    }
    isFree[enter] = 1;
    // 2. The optimum over the free weights, stopping at the bounds.
    descend(g, h, isFree, w);
  }
  return w;
}

Influences fitWeights(const std::vector<std::vector<float>>& frames,
  const std::vector<std::vector<Matrix4>>& matrices, const Candidates& candidates,
  int maxInfluences, const Progress& progress)
{
  const int64_t nv = static_cast<int64_t>(candidates.offsets.size()) - 1;
  Influences out;
  out.slots = maxInfluences;
  out.bones.assign(nv * maxInfluences, 0);
  out.weights.assign(nv * maxInfluences, 0.0);
  parallel_for(
    nv,
    [&](int64_t v)
    {
      const int32_t* bones = candidates.bones.data() + candidates.offsets[v];
      const int m = static_cast<int>(candidates.offsets[v + 1] - candidates.offsets[v]);
      Eigen::VectorXd w = pointWeights(frames, matrices, bones, m, v);
      std::vector<int32_t> kept(bones, bones + m);
      if ((w.array() > 0.0).count() > maxInfluences)
      {
        w = limitInfluences(frames, matrices, bones, w, maxInfluences, v, kept);
      }
      // Slots in descending weight; unused slots keep the own bone with weight 0.
      std::vector<int> order(kept.size());
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return w(a) > w(b); });
      for (int s = 0; s < maxInfluences; ++s)
      {
        const bool used = s < static_cast<int>(order.size()) && w(order[s]) > 0.0;
        out.bones[maxInfluences * v + s] = used ? kept[order[s]] : bones[0];
        out.weights[maxInfluences * v + s] = used ? w(order[s]) : 0.0;
      }
    },
    progress);
  return out;
}
} // namespace proxy
} // namespace detail
} // namespace tc
