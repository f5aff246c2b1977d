#include "HammingKernel.h"

#include <lodestone/vision/GuidedMatcher.h>

#include <Eigen/Dense>
#include <algorithm>
#include <climits>
#include <cmath>

namespace lodestone::vision {

namespace {

/** Current keypoints bucketed by grid cell (compressed rows: cell c holds
 * index[start[c] .. start[c+1])), in increasing keypoint order within a cell. */
struct KeypointGrid {
    int cell{16}, cols{0}, rows{0};
    std::vector<int> start, index;

    KeypointGrid(const std::vector<cv::KeyPoint>& kps, int width, int height, int cellSize)
        : cell(cellSize),
          cols(std::max(1, (width + cellSize - 1) / cellSize)),
          rows(std::max(1, (height + cellSize - 1) / cellSize)) {
        std::vector<int> cellOf(kps.size());
        start.assign(static_cast<std::size_t>(cols * rows + 1), 0);
        for (std::size_t i = 0; i < kps.size(); ++i) {
            const int cx = std::clamp(static_cast<int>(kps[i].pt.x) / cell, 0, cols - 1);
            const int cy = std::clamp(static_cast<int>(kps[i].pt.y) / cell, 0, rows - 1);
            cellOf[i] = cy * cols + cx;
            ++start[static_cast<std::size_t>(cellOf[i] + 1)];
        }
        for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
        index.resize(kps.size());
        std::vector<int> fill(start.begin(), start.end() - 1);
        for (std::size_t i = 0; i < kps.size(); ++i) {
            index[static_cast<std::size_t>(fill[static_cast<std::size_t>(cellOf[i])]++)] =
                static_cast<int>(i);
        }
    }
};

/** A reference feature's gate: predicted pixel, inverse covariance, cells it covers. */
struct Gate {
    int ref;
    float u, v, i00, i01, i11;
    int c0, c1, r0, r1;
};

/** Per reference feature the nearest current keypoint in its gate; per current keypoint the
 * nearest and second-nearest reference features among the gates holding it. */
struct Scan {
    Scan(int nCur, int nRef)
        : best(static_cast<std::size_t>(nRef), -1),
          bestDistance(static_cast<std::size_t>(nRef), INT_MAX),
          reverseBest(static_cast<std::size_t>(nCur), -1),
          reverseDistance(static_cast<std::size_t>(nCur), INT_MAX),
          reverseSecond(static_cast<std::size_t>(nCur), INT_MAX) {}
    std::vector<int> best, bestDistance, reverseBest, reverseDistance, reverseSecond;
    std::size_t compared{0};
};

// Compiled twice: with the popcnt instruction, and plain for CPUs without it (the loader picks).
__attribute__((target_clones("popcnt", "default"))) void scanGates(
    const std::vector<Gate>& gates, const KeypointGrid& grid, const float* xs, const float* ys,
    const std::uint64_t* cur, const std::uint64_t* ref, int words, float chi2, Scan& s) {
    for (const Gate& g : gates) {
        const int j = g.ref;
        const std::uint64_t* a = ref + static_cast<std::size_t>(j) * words;
        int& b = s.best[static_cast<std::size_t>(j)];
        int& db = s.bestDistance[static_cast<std::size_t>(j)];
        for (int r = g.r0; r <= g.r1; ++r) {
            for (int c = g.c0; c <= g.c1; ++c) {
                const int cell = r * grid.cols + c;
                for (int k = grid.start[static_cast<std::size_t>(cell)];
                     k < grid.start[static_cast<std::size_t>(cell) + 1]; ++k) {
                    const int i = grid.index[static_cast<std::size_t>(k)];
                    const float du = xs[i] - g.u, dv = ys[i] - g.v;
                    if (du * (g.i00 * du + g.i01 * dv) + dv * (g.i01 * du + g.i11 * dv) > chi2)
                        continue;
                    ++s.compared;
                    const int d = detail::hammingDistance(
                        a, cur + static_cast<std::size_t>(i) * words, words);
                    // Reference side, for the cross-check; ties keep the lowest index, whatever
                    // order the cells are visited in.
                    if (d < db || (d == db && i < b)) {
                        db = d;
                        b = i;
                    }
                    // Current side (the query, as DescriptorMatcher's); gates come in rising j,
                    // so a strict < keeps the lowest index.
                    int& d1 = s.reverseDistance[static_cast<std::size_t>(i)];
                    int& d2 = s.reverseSecond[static_cast<std::size_t>(i)];
                    if (d < d1) {
                        d2 = d1;
                        d1 = d;
                        s.reverseBest[static_cast<std::size_t>(i)] = j;
                    } else if (d < d2) {
                        d2 = d;
                    }
                }
            }
        }
    }
}

Eigen::Matrix3d skew(const Eigen::Vector3d& p) {
    Eigen::Matrix3d m;
    m << 0, -p.z(), p.y(), p.z(), 0, -p.x(), -p.y(), p.x(), 0;
    return m;
}

}  // namespace

GuidedMatcher::Result GuidedMatcher::match(const FrameFeatures& current,
                                           const FrameFeatures& reference,
                                           const CameraIntrinsics& K,
                                           const MotionPrior& prior) const {
    Result out;
    const int nCur = static_cast<int>(current.size()), nRef = static_cast<int>(reference.size());
    if (nCur == 0 || nRef == 0) return out;
    CV_Assert(current.descriptors.type() == CV_8U && reference.descriptors.type() == CV_8U &&
              current.descriptors.cols == reference.descriptors.cols &&
              current.descriptors.cols % 8 == 0);
    const int words = current.descriptors.cols / 8;
    const auto cur = detail::packed(current.descriptors, words);
    const auto ref = detail::packed(reference.descriptors, words);
    const KeypointGrid grid(current.keypoints, K.width, K.height, params_.cellSize);

    // Each reference feature's gate: its predicted pixel and the inverse of that prediction's
    // covariance.
    const Eigen::Isometry3d T_cur_ref = prior.T_ref_cur.inverse();
    const Eigen::Matrix3d R = T_cur_ref.linear();
    std::vector<double> levelVariance(32);
    for (std::size_t l = 0; l < levelVariance.size(); ++l) {
        const double s = params_.keypointSigma * std::pow(params_.scaleFactor, static_cast<double>(l));
        levelVariance[l] = s * s;
    }
    std::vector<Gate> gates;
    gates.reserve(static_cast<std::size_t>(nRef));
    for (int j = 0; j < nRef; ++j) {
        const Eigen::Vector3d pRef = reference.points.col(j).cast<double>();
        const Eigen::Vector3d p = T_cur_ref * pRef;
        if (!(p.z() > 1e-3)) continue;  // behind the camera: cannot be seen
        const double iz = 1.0 / p.z();
        const double u = K.fx * p.x() * iz + K.cx, v = K.fy * p.y() * iz + K.cy;
        Eigen::Matrix<double, 2, 3> Jpi;
        Jpi << K.fx * iz, 0, -K.fx * p.x() * iz * iz, 0, K.fy * iz, -K.fy * p.y() * iz * iz;
        // d p / d xi for T_ref_cur -> exp(xi) T_ref_cur: p -> R (pRef - w x pRef - v) + t.
        Eigen::Matrix<double, 3, 6> Jxi;
        Jxi.leftCols<3>() = R * skew(pRef);
        Jxi.rightCols<3>() = -R;
        const double sigmaPoint = params_.pointNoise + params_.depthNoise * pRef.z() * pRef.z();
        const Eigen::Matrix<double, 2, 6> J = Jpi * Jxi;
        const int level = std::clamp(reference.keypoints[static_cast<std::size_t>(j)].octave, 0, 31);
        const Eigen::Matrix2d S = J * prior.covariance * J.transpose() +
                                  sigmaPoint * sigmaPoint * Jpi * Jpi.transpose() +
                                  levelVariance[static_cast<std::size_t>(level)] *
                                      Eigen::Matrix2d::Identity();
        const double hu = std::sqrt(params_.gateChi2 * S(0, 0));
        const double hv = std::sqrt(params_.gateChi2 * S(1, 1));
        if (!std::isfinite(hu) || !std::isfinite(hv) || u + hu < 0 || v + hv < 0 ||
            u - hu >= K.width || v - hv >= K.height) {
            continue;
        }
        const Eigen::Matrix2d Si = S.inverse();
        const auto cellOf = [&](double x, int n) {  // clamped before the cast: gates can be huge
            return static_cast<int>(std::clamp(std::floor(x / grid.cell), 0.0, n - 1.0));
        };
        gates.push_back({j, static_cast<float>(u), static_cast<float>(v),
                         static_cast<float>(Si(0, 0)), static_cast<float>(Si(0, 1)),
                         static_cast<float>(Si(1, 1)), cellOf(u - hu, grid.cols),
                         cellOf(u + hu, grid.cols), cellOf(v - hv, grid.rows),
                         cellOf(v + hv, grid.rows)});
    }
    out.predicted = gates.size();

    std::vector<float> xs(static_cast<std::size_t>(nCur)), ys(static_cast<std::size_t>(nCur));
    for (int i = 0; i < nCur; ++i) {
        xs[static_cast<std::size_t>(i)] = current.keypoints[static_cast<std::size_t>(i)].pt.x;
        ys[static_cast<std::size_t>(i)] = current.keypoints[static_cast<std::size_t>(i)].pt.y;
    }
    Scan scan{nCur, nRef};
    scanGates(gates, grid, xs.data(), ys.data(), cur.data(), ref.data(), words,
              static_cast<float>(params_.gateChi2), scan);
    out.compared = scan.compared;
    const auto& best = scan.best;
    const auto& reverseBest = scan.reverseBest;
    const auto& reverseDistance = scan.reverseDistance;
    const auto& reverseSecond = scan.reverseSecond;

    for (int i = 0; i < nCur; ++i) {
        const int j = reverseBest[static_cast<std::size_t>(i)];
        const int d = reverseDistance[static_cast<std::size_t>(i)];
        if (j < 0 || d > params_.maxDistance) continue;
        const int d2 = reverseSecond[static_cast<std::size_t>(i)];
        if (params_.ratio > 0 && d2 != INT_MAX && d >= params_.ratio * d2) continue;
        if (params_.crossCheck && best[static_cast<std::size_t>(j)] != i) continue;
        out.matches.emplace_back(i, j, static_cast<float>(d));
    }
    return out;
}

}  // namespace lodestone::vision
