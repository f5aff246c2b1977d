#include <lodestone/dense/KeyframeFusion.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace lodestone::dense {

namespace {

/** Frames waiting for their first fusion before add() waits for the worker: the memory a
 * worker slower than the run may hold (a 640x480 frame is 2.1 MB). */
constexpr std::size_t kMaxFresh = 8;

double since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

KeyframeFusion::KeyframeFusion(const DenseParams& params, const std::string& spillPath)
    : params_(params), fusion_(params), spillPath_(spillPath) {
    if (params.volume != DenseParams::Volume::Blocks)
        throw std::invalid_argument("dense fusion while running needs [dense] volume = blocks (it takes frames out)");
    spill_.open(spillPath, std::ios::in | std::ios::out | std::ios::binary | std::ios::trunc);
    if (!spill_) throw std::runtime_error(spillPath + ": the dense model's frame store cannot be written");
    worker_ = std::thread([this] { work(); });
}

KeyframeFusion::~KeyframeFusion() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    worker_.join();
    spill_.close();
    std::remove(spillPath_.c_str());
}

double KeyframeFusion::displacement(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) const {
    const double angle = Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
    return (a.translation() - b.translation()).norm() + angle * params_.fusedDepthLimit();
}

void KeyframeFusion::add(std::uint64_t id, const cv::Mat& depth, const cv::Mat& colourBgr,
                         const vision::CameraIntrinsics& intrinsics,
                         const std::optional<Eigen::Isometry3d>& T_world_optical) {
    if (depth.type() != CV_32FC1 || depth.cols != intrinsics.width || depth.rows != intrinsics.height)
        throw std::invalid_argument("dense fusion: depth must be CV_32FC1 metres of the intrinsics' size");
    if (!colourBgr.empty() && (colourBgr.type() != CV_8UC3 || colourBgr.size() != depth.size()))
        throw std::invalid_argument("dense fusion: colour must be CV_8UC3 of the depth's size");
    if (kept_.count(id)) throw std::invalid_argument("dense fusion: keyframe " + std::to_string(id) + " added twice");
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [&] { return fresh_.size() < kMaxFresh; });
    fresh_[id] = {depth.clone(), colourBgr.empty() ? cv::Mat() : colourBgr.clone()};
    kept_[id] = {intrinsics, !colourBgr.empty(), T_world_optical};
    tasks_.push_back({id, true, std::nullopt, T_world_optical});
    wake_.notify_all();
}

std::size_t KeyframeFusion::refuseMoved(const PoseOf& poseOf, std::size_t budget) {
    std::vector<std::pair<double, std::uint64_t>> moved;
    std::map<std::uint64_t, Eigen::Isometry3d> now;
    const double tolerance = params_.voxelSize / 2;
    for (const auto& [id, kept] : kept_) {
        const auto pose = poseOf(id);
        if (!pose) continue;
        // (a frame kept without a pose that now has one comes first)
        const double d = kept.fusedAt ? displacement(*kept.fusedAt, *pose) : HUGE_VAL;
        if (d > tolerance) {
            moved.emplace_back(d, id);
            now[id] = *pose;
        }
    }
    // The farthest moved first; ties by ID (a stable order, whatever the map's).
    std::sort(moved.begin(), moved.end(),
              [](const auto& a, const auto& b) { return a.first != b.first ? a.first > b.first : a.second < b.second; });
    if (budget > 0 && moved.size() > budget) moved.resize(budget);
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [d, id] : moved) {
        Kept& kept = kept_.at(id);
        tasks_.push_back({id, false, kept.fusedAt, now.at(id)});
        kept.fusedAt = now.at(id);
    }
    wake_.notify_all();
    return moved.size();
}

void KeyframeFusion::wait() {
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [&] { return tasks_.empty() && !busy_; });
}

Mesh KeyframeFusion::extractMesh() {
    wait();
    return fusion_.extractMesh();
}

KeyframeFusion::Stats KeyframeFusion::stats() {
    wait();
    Stats s = stats_;
    s.volumeBytes = fusion_.memoryBytes();
    return s;
}

void KeyframeFusion::readBack(std::uint64_t offset, const Kept& kept, cv::Mat& depth, cv::Mat& colour) {
    const auto& K = kept.intrinsics;
    depth.create(K.height, K.width, CV_32FC1);
    spill_.seekg(static_cast<std::streamoff>(offset));
    spill_.read(reinterpret_cast<char*>(depth.data), static_cast<std::streamsize>(depth.total() * depth.elemSize()));
    colour.release();
    if (kept.colour) {
        colour.create(K.height, K.width, CV_8UC3);
        spill_.read(reinterpret_cast<char*>(colour.data), static_cast<std::streamsize>(colour.total() * colour.elemSize()));
    }
    if (!spill_) {
        spill_.clear();
        throw std::runtime_error(spillPath_ + ": the dense model's frame store cannot be read back");
    }
}

void KeyframeFusion::store(std::uint64_t id, const cv::Mat& depth, const cv::Mat& colour,
                           std::map<std::uint64_t, std::uint64_t>& offsets) {
    const std::uint64_t end = stats_.spillBytes;
    spill_.seekp(static_cast<std::streamoff>(end));
    spill_.write(reinterpret_cast<const char*>(depth.data), static_cast<std::streamsize>(depth.total() * depth.elemSize()));
    if (!colour.empty())
        spill_.write(reinterpret_cast<const char*>(colour.data),
                     static_cast<std::streamsize>(colour.total() * colour.elemSize()));
    if (!spill_) {
        spill_.clear();
        throw std::runtime_error(spillPath_ + ": the dense model's frame store cannot be written");
    }
    offsets[id] = end;
    stats_.spillBytes = end + depth.total() * depth.elemSize() + colour.total() * colour.elemSize();
}

void KeyframeFusion::run(const Task& task, const Kept& kept, cv::Mat& depth, cv::Mat& colour,
                         std::map<std::uint64_t, std::uint64_t>& offsets) {
    auto t = std::chrono::steady_clock::now();
    if (task.store) {
        store(task.id, depth, colour, offsets);
    } else {
        const auto at = offsets.find(task.id);
        if (at == offsets.end()) throw std::runtime_error("keyframe " + std::to_string(task.id) + " was not stored");
        readBack(at->second, kept, depth, colour);
    }
    stats_.spillSeconds += since(t);
    t = std::chrono::steady_clock::now();
    if (task.takeOutAt) fusion_.deintegrate(depth, colour, kept.intrinsics, *task.takeOutAt);
    if (task.fuseAt) {
        const bool fused = fusion_.integrate(depth, colour, kept.intrinsics, *task.fuseAt) > 0;
        if (task.takeOutAt) ++stats_.refusions;
        else if (fused) ++stats_.keyframes;
        else ++stats_.withoutDepth;
    }
    stats_.fuseSeconds += since(t);
}

void KeyframeFusion::work() {
    // The worker alone touches the store, the volume and the stats. It reads `kept_` under the
    // lock; the run's thread changes it only under the lock.
    std::map<std::uint64_t, std::uint64_t> offsets;
    for (;;) {
        Task task;
        Kept kept;
        cv::Mat depth, colour;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || !tasks_.empty(); });
            if (tasks_.empty()) return;
            task = tasks_.front();
            tasks_.pop_front();
            busy_ = true;
            kept = kept_.at(task.id);
            if (task.store) {
                auto node = fresh_.extract(task.id);
                depth = node.mapped().first;
                colour = node.mapped().second;
                idle_.notify_all();
            }
        }
        try {
            run(task, kept, depth, colour, offsets);
        } catch (const std::exception& e) {
            // (a frame the store lost stays as it was fused; the run goes on and says so)
            ++stats_.failures;
            stats_.lastFailure = e.what();
        }
        std::lock_guard<std::mutex> lock(mutex_);
        busy_ = false;
        idle_.notify_all();
    }
}

}  // namespace lodestone::dense
