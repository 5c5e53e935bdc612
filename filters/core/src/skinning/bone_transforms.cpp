// SPDX-License-Identifier: BSD-3-Clause
#include "skinning/bone_transforms.h"

#include "tc/common/parallel.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <utility>

namespace tc
{
namespace detail
{
namespace proxy
{
namespace
{
Matrix4 toMatrix4(const Eigen::Matrix3d& linear, const Eigen::Vector3d& translation)
{
  Matrix4 m = identityMatrix();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m[4 * r + c] = linear(r, c);
    }
    m[4 * r + 3] = translation(r);
  }
  return m;
}

// Kabsch: the rotation R and translation t minimizing sum |R p_i + t - q_i|^2.
Matrix4 kabsch(const std::vector<float>& rest, const std::vector<float>& frame,
  const int32_t* points, int64_t count)
{
  Eigen::Vector3d p0 = Eigen::Vector3d::Zero(), q0 = Eigen::Vector3d::Zero();
  for (int64_t i = 0; i < count; ++i)
  {
    p0 += pointOf(rest, points[i]);
    q0 += pointOf(frame, points[i]);
  }
  p0 /= static_cast<double>(std::max<int64_t>(count, 1));
  q0 /= static_cast<double>(std::max<int64_t>(count, 1));
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (int64_t i = 0; i < count; ++i)
  {
    h += (pointOf(rest, points[i]) - p0) * (pointOf(frame, points[i]) - q0).transpose();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  const Eigen::Matrix3d r = svd.matrixV() * d * svd.matrixU().transpose();
  return toMatrix4(r, q0 - r * p0);
}

// Points in the coordinates of the affine solve: (p - centre) / scale, so that the linear and
// the translation columns of the normal equations have comparable sizes.
struct Normalization
{
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double scale = 1.0;
};

Normalization normalization(const std::vector<float>& rest)
{
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  for (size_t v = 0; 3 * v < rest.size(); ++v)
  {
    lo = lo.cwiseMin(pointOf(rest, static_cast<int64_t>(v)));
    hi = hi.cwiseMax(pointOf(rest, static_cast<int64_t>(v)));
  }
  Normalization n;
  n.centre = 0.5 * (lo + hi);
  const double half = 0.5 * (hi - lo).norm();
  n.scale = half > 0.0 ? half : 1.0;
  return n;
}

// The 4 coordinates [(p - centre) / scale; 1] of point v.
Eigen::Vector4d normalized(const std::vector<float>& rest, int64_t v, const Normalization& n)
{
  Eigen::Vector4d x;
  x.head<3>() = (pointOf(rest, v) - n.centre) / n.scale;
  x(3) = 1.0;
  return x;
}

// The 4 x 3 block of a matrix M in normalized coordinates: M p = X^T [(p - c) / s; 1].
Eigen::Matrix<double, 4, 3> toNormalized(const Matrix4& m, const Normalization& n)
{
  Eigen::Matrix3d linear;
  Eigen::Vector3d translation;
  for (int r = 0; r < 3; ++r)
  {
    translation(r) = m[4 * r + 3];
    for (int c = 0; c < 3; ++c)
    {
      linear(r, c) = m[4 * r + c];
    }
  }
  Eigen::Matrix<double, 4, 3> x;
  x.topRows<3>() = (linear * n.scale).transpose();
  x.row(3) = (translation + linear * n.centre).transpose();
  return x;
}

Matrix4 fromNormalized(const Eigen::Matrix<double, 4, 3>& x, const Normalization& n)
{
  const Eigen::Matrix3d linear = x.topRows<3>().transpose() / n.scale;
  return toMatrix4(linear, x.row(3).transpose() - linear * n.centre);
}

// The normal matrix A^T A of the affine fit (rows a_v: w_vb [(p - c) / s; 1] in bone b's 4
// columns) plus the regularization, and that regularization per bone.
Eigen::MatrixXd normalMatrix(const std::vector<float>& rest, const Influences& in,
  const Normalization& norm, int64_t nb, double regularization, Eigen::VectorXd& lambda)
{
  Eigen::MatrixXd n = Eigen::MatrixXd::Zero(4 * nb, 4 * nb);
  const int64_t nv = static_cast<int64_t>(rest.size() / 3);
  for (int64_t v = 0; v < nv; ++v)
  {
    const Eigen::Vector4d x = normalized(rest, v, norm);
    const Eigen::Matrix4d xx = x * x.transpose();
    for (int i = 0; i < in.slots; ++i)
    {
      const double wi = in.weights[in.slots * v + i];
      for (int j = 0; j < in.slots && wi > 0.0; ++j)
      {
        const double wj = in.weights[in.slots * v + j];
        n.block<4, 4>(4 * in.bones[in.slots * v + i], 4 * in.bones[in.slots * v + j]) +=
          (wi * wj) * xx;
      }
    }
  }
  lambda.resize(nb);
  for (int64_t b = 0; b < nb; ++b)
  {
    // A bone no point is weighted to keeps its rigid transform (any positive weight does).
    const double trace = n.block<4, 4>(4 * b, 4 * b).trace();
    lambda(b) = trace > 0.0 ? regularization * trace / 4.0 : 1.0;
    n.block<4, 4>(4 * b, 4 * b).diagonal().array() += lambda(b);
  }
  return n;
}

// A^T Y for frame `frame` plus the pull towards the rigid transforms: #B 4 x 3 blocks.
Eigen::MatrixXd rightHandSide(const std::vector<float>& rest, const std::vector<float>& frame,
  const Influences& in, const Normalization& norm, const std::vector<Matrix4>& rigid,
  const Eigen::VectorXd& lambda)
{
  const int64_t nb = lambda.size();
  Eigen::MatrixXd rhs(4 * nb, 3);
  for (int64_t b = 0; b < nb; ++b)
  {
    rhs.block<4, 3>(4 * b, 0) = lambda(b) * toNormalized(rigid[b], norm);
  }
  const int64_t nv = static_cast<int64_t>(rest.size() / 3);
  for (int64_t v = 0; v < nv; ++v)
  {
    const Eigen::Vector4d x = normalized(rest, v, norm);
    const Eigen::RowVector3d q = pointOf(frame, v).transpose();
    for (int i = 0; i < in.slots; ++i)
    {
      const double w = in.weights[in.slots * v + i];
      if (w > 0.0)
      {
        rhs.block<4, 3>(4 * in.bones[in.slots * v + i], 0) += (w * x) * q;
      }
    }
  }
  return rhs;
}
} // namespace

BonePoints bonePoints(
  const std::vector<int32_t>& triangles, const std::vector<int32_t>& clusterId, int32_t numBones)
{
  std::vector<std::pair<int32_t, int32_t>> pairs;
  pairs.reserve(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i)
  {
    pairs.emplace_back(clusterId[i / 3], triangles[i]);
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  BonePoints out;
  out.offsets.assign(numBones + 1, 0);
  out.points.reserve(pairs.size());
  for (const auto& [bone, point] : pairs)
  {
    ++out.offsets[bone + 1];
    out.points.push_back(point);
  }
  for (int32_t b = 0; b < numBones; ++b)
  {
    out.offsets[b + 1] += out.offsets[b];
  }
  return out;
}

BonePoints interiorBonePoints(const std::vector<int32_t>& triangles,
  const std::vector<int32_t>& clusterId, int32_t numBones, int64_t nv)
{
  // The one cluster around each point, -1 for none, -2 for several.
  std::vector<int32_t> only(nv, -1);
  for (size_t i = 0; i < triangles.size(); ++i)
  {
    int32_t& o = only[triangles[i]];
    o = o == -1 || o == clusterId[i / 3] ? clusterId[i / 3] : -2;
  }
  const BonePoints all = bonePoints(triangles, clusterId, numBones);
  std::vector<std::vector<int32_t>> inside(numBones);
  for (int64_t v = 0; v < nv; ++v)
  {
    if (only[v] >= 0)
    {
      inside[only[v]].push_back(static_cast<int32_t>(v));
    }
  }
  BonePoints out;
  out.offsets.assign(numBones + 1, 0);
  for (int32_t b = 0; b < numBones; ++b)
  {
    if (inside[b].size() >= 3)
    {
      out.points.insert(out.points.end(), inside[b].begin(), inside[b].end());
    }
    else
    {
      out.points.insert(out.points.end(), all.points.begin() + all.offsets[b],
        all.points.begin() + all.offsets[b + 1]);
    }
    out.offsets[b + 1] = static_cast<int64_t>(out.points.size());
  }
  return out;
}

std::vector<std::vector<Matrix4>> rigidTransforms(
  const std::vector<std::vector<float>>& frames, const BonePoints& bones, const Progress& progress)
{
  const int64_t nk = static_cast<int64_t>(frames.size());
  const int64_t nb = bones.numBones();
  std::vector<std::vector<Matrix4>> out(nk, std::vector<Matrix4>(nb, identityMatrix()));
  parallel_for((nk - 1) * nb,
    [&](int64_t i)
    {
      const int64_t k = 1 + i / nb;
      const int64_t b = i % nb;
      out[k][b] = kabsch(frames[0], frames[k], bones.points.data() + bones.offsets[b],
        bones.offsets[b + 1] - bones.offsets[b]);
    },
    progress);
  return out;
}

std::vector<double> rigidResiduals(const std::vector<std::vector<float>>& frames,
  const BonePoints& bones, const std::vector<std::vector<Matrix4>>& rigid)
{
  const int64_t nb = bones.numBones();
  std::vector<double> out(nb, 0.0);
  parallel_for(nb,
    [&](int64_t b)
    {
      double squares = 0.0;
      for (size_t k = 1; k < frames.size(); ++k)
      {
        const Matrix4& m = rigid[k][b];
        for (int64_t i = bones.offsets[b]; i < bones.offsets[b + 1]; ++i)
        {
          const Eigen::Vector3d p = pointOf(frames[0], bones.points[i]);
          for (int r = 0; r < 3; ++r)
          {
            const double q = m[4 * r] * p.x() + m[4 * r + 1] * p.y() + m[4 * r + 2] * p.z() +
              m[4 * r + 3] - frames[k][3 * bones.points[i] + r];
            squares += q * q;
          }
        }
      }
      const double count =
        static_cast<double>((bones.offsets[b + 1] - bones.offsets[b]) * (frames.size() - 1));
      out[b] = count > 0.0 ? std::sqrt(squares / count) : 0.0;
    });
  return out;
}

std::vector<std::vector<Matrix4>> affineTransforms(const std::vector<std::vector<float>>& frames,
  const Influences& influences, const std::vector<std::vector<Matrix4>>& rigid,
  double regularization, const Progress& progress)
{
  const int64_t nk = static_cast<int64_t>(frames.size());
  const int64_t nb = static_cast<int64_t>(rigid[0].size());
  const Normalization norm = normalization(frames[0]);
  Eigen::VectorXd lambda;
  const Eigen::LDLT<Eigen::MatrixXd> factor(
    normalMatrix(frames[0], influences, norm, nb, regularization, lambda));
  progress.report(0.2);
  std::vector<std::vector<Matrix4>> out(nk, std::vector<Matrix4>(nb, identityMatrix()));
  parallel_for(
    nk - 1,
    [&](int64_t i)
    {
      const int64_t k = i + 1;
      const Eigen::MatrixXd x =
        factor.solve(rightHandSide(frames[0], frames[k], influences, norm, rigid[k], lambda));
      for (int64_t b = 0; b < nb; ++b)
      {
        out[k][b] = fromNormalized(x.block<4, 3>(4 * b, 0), norm);
      }
    },
    progress.sub(0.2, 1.0));
  return out;
}
} // namespace proxy
} // namespace detail
} // namespace tc
