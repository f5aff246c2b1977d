#include <lodestone/dense/VoxelBlockVolume.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

namespace lodestone::dense {

namespace {

constexpr double kTsdfScale = 32767.0;
constexpr int kMaxWeight = 65535;

/** Blocks are keyed by their coordinates, 21 bits each (+-1 million blocks a side). */
constexpr std::int64_t kKeyBias = 1 << 20;

int floorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

/** Each pixel's weight (0 where it is not fused): kFullWeight at the nearest fused depth,
 * falling as 1/sigma^2 with the depth's noise model, never below 1. */
cv::Mat pixelWeights(const cv::Mat& depth, const VoxelBlockVolume::Settings& s) {
    const auto sigma = [&](double z) { return s.noiseFloor + s.depthNoise * z * z; };
    const double best = sigma(s.nearest);
    cv::Mat w(depth.size(), CV_8UC1);
    for (int y = 0; y < depth.rows; ++y) {
        const float* d = depth.ptr<float>(y);
        std::uint8_t* out = w.ptr<std::uint8_t>(y);
        for (int x = 0; x < depth.cols; ++x) {
            if (!(d[x] > 0)) {
                out[x] = 0;
                continue;
            }
            const double ratio = best > 0 ? best / sigma(d[x]) : 1.0;
            out[x] = static_cast<std::uint8_t>(
                std::clamp<long>(std::lround(VoxelBlockVolume::kFullWeight * ratio * ratio), 1,
                                 VoxelBlockVolume::kFullWeight));
        }
    }
    return w;
}

}  // namespace

VoxelBlockVolume::VoxelBlockVolume(const Settings& settings) : settings_(settings) {
    if (!(settings.voxelSize > 0) || !(settings.truncation >= settings.voxelSize))
        throw std::invalid_argument("VoxelBlockVolume: truncation must be at least one voxel");
}

std::uint64_t VoxelBlockVolume::keyOf(const Eigen::Vector3i& b) {
    const auto part = [](int v) { return static_cast<std::uint64_t>((v + kKeyBias) & 0x1FFFFF); };
    return part(b.x()) << 42 | part(b.y()) << 21 | part(b.z());
}

std::uint32_t VoxelBlockVolume::touch(const Eigen::Vector3i& block) {
    const auto [it, added] = index_.try_emplace(keyOf(block), static_cast<std::uint32_t>(blocks_.size()));
    if (added) {
        blocks_.push_back(std::make_unique<Block>());
        coords_.push_back(block);
        stamp_.push_back(0);
    }
    return it->second;
}

const VoxelBlockVolume::Block* VoxelBlockVolume::find(const Eigen::Vector3i& block) const {
    const auto it = index_.find(keyOf(block));
    return it == index_.end() ? nullptr : blocks_[it->second].get();
}

const VoxelBlockVolume::Voxel* VoxelBlockVolume::voxelAt(const Eigen::Vector3d& p) const {
    const Eigen::Vector3i g = (p / settings_.voxelSize).array().round().cast<int>();
    const Eigen::Vector3i b(floorDiv(g.x(), kSide), floorDiv(g.y(), kSide), floorDiv(g.z(), kSide));
    const Block* block = find(b);
    if (!block) return nullptr;
    const Eigen::Vector3i l = g - kSide * b;
    return &(*block)[l.x() + kSide * (l.y() + kSide * l.z())];
}

std::size_t VoxelBlockVolume::memoryBytes() const {
    // (a hash node: the key, the index and the bucket's pointers)
    return blocks_.size() * (sizeof(Block) + sizeof(Eigen::Vector3i) + sizeof(std::uint32_t) + 48) +
           index_.bucket_count() * sizeof(void*);
}

std::size_t VoxelBlockVolume::integrate(const cv::Mat& depth, const cv::Mat& colourBgr,
                                        const vision::CameraIntrinsics& K,
                                        const Eigen::Isometry3d& T_world_optical, int sign) {
    if (sign != 1 && sign != -1) throw std::invalid_argument("VoxelBlockVolume: sign must be +1 or -1");
    ++frame_;
    // The blocks within the truncation band of any pixel's surface point, along its ray
    // (every second pixel each way: at 3.5 m two pixels span 1.3 cm of an 8-voxel block).
    const double v = settings_.voxelSize, tau = settings_.truncation;
    const double blockEdge = kSide * v;
    const double step = std::min(tau, blockEdge / 2);
    const int samples = static_cast<int>(std::ceil(tau / step));
    const Eigen::Vector3d centre = T_world_optical.translation();
    std::vector<std::uint32_t> touched;
    std::vector<std::uint64_t> lastKey(2 * samples + 1, ~0ULL);
    for (int y = 0; y < depth.rows; y += 2) {
        const float* d = depth.ptr<float>(y);
        for (int x = 0; x < depth.cols; x += 2) {
            if (!(d[x] > 0)) continue;
            const Eigen::Vector3d ray((x - K.cx) / K.fx, (y - K.cy) / K.fy, 1.0);
            const Eigen::Vector3d surface = T_world_optical * (ray * d[x]);
            const Eigen::Vector3d along = (surface - centre).normalized();
            for (int k = -samples; k <= samples; ++k) {
                const Eigen::Vector3d p = surface + along * (k * step);
                const Eigen::Vector3i g = (p / v).array().round().cast<int>();
                const Eigen::Vector3i b(floorDiv(g.x(), kSide), floorDiv(g.y(), kSide), floorDiv(g.z(), kSide));
                const std::uint64_t key = keyOf(b);
                if (key == lastKey[k + samples]) continue;
                lastKey[k + samples] = key;
                const std::uint32_t i = touch(b);
                if (stamp_[i] == frame_) continue;
                stamp_[i] = frame_;
                touched.push_back(i);
            }
        }
    }
    // Each touched block's voxels against the frame; blocks are independent, so the field does
    // not depend on how the two threads split them.
    const cv::Mat weights = pixelWeights(depth, settings_);
    const Eigen::Isometry3d T_optical_world = T_world_optical.inverse();
    const auto work = [&](std::size_t from, std::size_t to) {
        for (std::size_t i = from; i < to; ++i)
            updateBlock(touched[i], depth, colourBgr, K, T_optical_world, sign, weights);
    };
    const std::size_t half = touched.size() / 2;
    std::thread other(work, half, touched.size());
    work(0, half);
    other.join();
    return touched.size();
}

void VoxelBlockVolume::updateBlock(std::uint32_t index, const cv::Mat& depth, const cv::Mat& colourBgr,
                                   const vision::CameraIntrinsics& K, const Eigen::Isometry3d& T_optical_world,
                                   int sign, const cv::Mat& weights) {
    Block& block = *blocks_[index];
    const double v = settings_.voxelSize;
    const double tau = settings_.truncation;
    const Eigen::Matrix3d R = T_optical_world.linear();
    const Eigen::Vector3d origin = T_optical_world * (coords_[index].cast<double>() * (kSide * v));
    const Eigen::Vector3d dx = R.col(0) * v, dy = R.col(1) * v, dz = R.col(2) * v;
    const bool grey = colourBgr.empty();
    int n = 0;
    for (int z = 0; z < kSide; ++z)
        for (int y = 0; y < kSide; ++y) {
            Eigen::Vector3d p = origin + dy * y + dz * z;
            for (int x = 0; x < kSide; ++x, ++n, p += dx) {
                if (p.z() <= 0) continue;
                const double u = K.fx * p.x() / p.z() + K.cx, w = K.fy * p.y() / p.z() + K.cy;
                const int px = static_cast<int>(std::floor(u + 0.5)), py = static_cast<int>(std::floor(w + 0.5));
                if (px < 0 || py < 0 || px >= depth.cols || py >= depth.rows) continue;
                const float d = depth.at<float>(py, px);
                if (!(d > 0)) continue;
                const double sdf = d - p.z();
                if (sdf < -tau) continue;
                const int wq = sign * weights.at<std::uint8_t>(py, px);
                Voxel& vox = block[n];
                const int W = vox.weight;
                const int Wn = W + wq;
                if (Wn > kMaxWeight) continue;  // saturated: the voxel has seen enough
                if (Wn <= 0) {
                    vox = Voxel{};
                    continue;
                }
                const auto average = [&](int old, double value) {
                    return static_cast<int>(std::lround((double(old) * W + value * wq) / Wn));
                };
                const int t = static_cast<int>(std::lround(std::min(1.0, sdf / tau) * kTsdfScale));
                vox.tsdf = static_cast<std::int16_t>(std::clamp(average(vox.tsdf, t), -32767, 32767));
                const std::uint8_t* c = grey ? nullptr : colourBgr.ptr<std::uint8_t>(py) + 3 * px;
                for (int k = 0; k < 3; ++k)
                    vox.rgb[k] = static_cast<std::uint8_t>(std::clamp(average(vox.rgb[k], c ? c[2 - k] : 128), 0, 255));
                vox.weight = static_cast<std::uint16_t>(Wn);
            }
        }
}

}  // namespace lodestone::dense
