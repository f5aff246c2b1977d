#include <lodestone/vision/depth/DepthCloud.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <vector>

namespace lodestone::vision {

DepthCloud DepthCloud::transformed(const Eigen::Isometry3f& T) const {
    DepthCloud out;
    out.points = (T.linear() * points).colwise() + T.translation();
    out.normals = T.linear() * normals;
    out.sigma = sigma;
    out.normalVariance = normalVariance;
    return out;
}

DepthCloud sampleDepthCloud(const RgbdFrame& frame, const DepthSampling& sampling) {
    DepthCloud cloud;
    const cv::Mat& depth = frame.depth;
    if (depth.empty() || depth.type() != CV_32FC1 || sampling.columns < 2) return cloud;
    const CameraIntrinsics& K = frame.intrinsics;
    const int step = std::max(1, depth.cols / sampling.columns);
    const auto valid = [&](float z) { return std::isfinite(z) && z > 0 && z <= sampling.maxDepth; };
    const auto point = [&](int u, int v, float z) {
        return Eigen::Vector3f(static_cast<float>((u - K.cx) / K.fx) * z,
                               static_cast<float>((v - K.cy) / K.fy) * z, z);
    };
    // The depth averaged over a cell around each pixel (where it is known), for the normals.
    cv::Mat known = (depth > 0) & (depth <= sampling.maxDepth);  // NaN compares false
    cv::Mat knownF, masked = cv::Mat::zeros(depth.size(), CV_32FC1), sum, count;
    known.convertTo(knownF, CV_32FC1, 1.0 / 255);
    depth.copyTo(masked, known);
    const int window = 2 * (step / 2) + 1;  // odd: centred on the pixel
    cv::boxFilter(masked, sum, CV_32F, cv::Size(window, window), cv::Point(-1, -1), false);
    cv::boxFilter(knownF, count, CV_32F, cv::Size(window, window), cv::Point(-1, -1), false);
    const auto smooth = [&](int u, int v) {
        const float c = count.at<float>(v, u);
        return c >= 0.5f ? sum.at<float>(v, u) / c : 0.0f;
    };
    // A point's depth: the mean inverse depth over its cell, of pixels in pairs mirrored about
    // it that are both known. Inverse depth is linear across a plane and the pairs are
    // symmetric, so the mean is the plane's at the centre, holes or not; and it is what
    // structured light measures. A single pixel's depth comes in disparity steps, and the
    // alignment of two such clouds snaps to them.
    const int half = window / 2;
    const auto cellMeanDepth = [&](int u, int v, float z) {
        double inverseSum = 1.0 / z;
        int n = 1;
        for (int dv = 0; dv <= half; ++dv) {
            const float* ahead = depth.ptr<float>(v + dv);
            const float* behind = depth.ptr<float>(v - dv);
            for (int du = dv == 0 ? 1 : -half; du <= half; ++du) {
                const float z1 = ahead[u + du], z2 = behind[u - du];
                if (!valid(z1) || !valid(z2)) continue;
                inverseSum += 1.0 / z1 + 1.0 / z2;
                n += 2;
            }
        }
        return static_cast<float>(n / inverseSum);
    };
    std::vector<Eigen::Vector3f> pts, nrm;
    std::vector<float> sig, nvar;
    const float edge = static_cast<float>(sampling.edgeRatio);
    const int margin = step + window / 2;  // the averages stay inside the image
    for (int v = margin; v + margin < depth.rows; v += step) {
        const float* above = depth.ptr<float>(v - step);
        const float* row = depth.ptr<float>(v);
        const float* below = depth.ptr<float>(v + step);
        for (int u = margin; u + margin < depth.cols; u += step) {
            const float z = row[u];
            if (!valid(z)) continue;
            const float zl = row[u - step], zr = row[u + step], zu = above[u], zd = below[u];
            if (!valid(zl) || !valid(zr) || !valid(zu) || !valid(zd)) continue;
            const float limit = edge * z;
            if (std::abs(zl - z) > limit || std::abs(zr - z) > limit || std::abs(zu - z) > limit ||
                std::abs(zd - z) > limit) {
                continue;
            }
            const float zp = sampling.pointsFromCellMean ? cellMeanDepth(u, v, z) : z;
            const Eigen::Vector3f p = point(u, v, zp);
            const Eigen::Vector3f du =
                point(u + step, v, smooth(u + step, v)) - point(u - step, v, smooth(u - step, v));
            const Eigen::Vector3f dv =
                point(u, v + step, smooth(u, v + step)) - point(u, v - step, smooth(u, v - step));
            Eigen::Vector3f n = du.cross(dv);
            const float len = n.norm();
            if (!(len > 0)) continue;
            n /= len;
            if (n.dot(p) > 0) n = -n;
            // Seen nearly edge-on (beyond 80 deg), a surface's depth is mostly noise.
            if (-n.dot(p) < 0.17f * p.norm()) continue;
            pts.push_back(p);
            nrm.push_back(n);
            const double sigma = sampling.noiseFloor + sampling.depthNoise * z * z;
            sig.push_back(static_cast<float>(sigma));
            // Each end of a difference averages window^2 pixels; the ends are 2 steps apart.
            const double sigmaEnd = sigma / window, baseline = 2.0 * step * z / K.fx;
            nvar.push_back(static_cast<float>(2 * sigmaEnd * sigmaEnd / (baseline * baseline)));
        }
    }
    const auto n = static_cast<Eigen::Index>(pts.size());
    cloud.points.resize(3, n);
    cloud.normals.resize(3, n);
    cloud.sigma.resize(n);
    cloud.normalVariance.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        cloud.points.col(i) = pts[static_cast<std::size_t>(i)];
        cloud.normals.col(i) = nrm[static_cast<std::size_t>(i)];
        cloud.sigma(i) = sig[static_cast<std::size_t>(i)];
        cloud.normalVariance(i) = nvar[static_cast<std::size_t>(i)];
    }
    return cloud;
}

}  // namespace lodestone::vision
