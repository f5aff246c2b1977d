// The dense model of real Kinect frames (../shared/data/rgbd/3dmatch, read in place): the
// sequence's frames fused at the poses it gives, with one volume, meshed; the wall time of each
// step, the volume's memory and the process's resident memory before and after; and, leaving
// each frame out in turn, how near that frame's depth lies to the mesh of the others (its
// pixels every 4th each way, within the fused range and where the others' mesh is within 5 cm:
// the overlap) - the real data has no surface to measure against but its own frames.
// Prints one markdown row.
//   bench_mesh_real DATA_DIR blocks|open3d [MESH.ply]
#include <lodestone/dense/TsdfFusion.h>
#include <lodestone/vision/RgbdFrame.h>

#include <nanoflann.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

using namespace lodestone;
namespace fs = std::filesystem;

namespace {

struct Frame {
    cv::Mat depth, bgr;
    Eigen::Isometry3d pose;  ///< the camera's optical frame in the world, as the data gives it
};

/** Every frame of seq-01 (frame-NNNNNN.{color,depth}.png, .pose.txt), by name. */
std::vector<Frame> loadSequence(const fs::path& dir) {
    std::vector<std::string> bases;
    for (const auto& entry : fs::directory_iterator(dir / "seq-01")) {
        const std::string name = entry.path().string();
        const std::string suffix = ".depth.png";
        if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
            bases.push_back(name.substr(0, name.size() - suffix.size()));
    }
    std::sort(bases.begin(), bases.end());
    std::vector<Frame> out;
    for (const std::string& base : bases) {
        Frame f;
        f.bgr = cv::imread(base + ".color.png");
        f.depth = vision::depthToMetres(cv::imread(base + ".depth.png", cv::IMREAD_UNCHANGED), 0.001);
        std::ifstream in(base + ".pose.txt");
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) in >> f.pose.matrix()(r, c);
        if (f.bgr.empty() || f.depth.empty() || !in) throw std::runtime_error(base + ": unreadable frame");
        out.push_back(f);
    }
    return out;
}

const vision::CameraIntrinsics kKinect{570.342205, 570.342205, 320.0, 240.0, 640, 480};

double residentMb() {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024;
    return 0;
}

double since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

struct Cloud {
    std::vector<Eigen::Vector3f> v;
    std::size_t kdtree_get_point_count() const { return v.size(); }
    float kdtree_get_pt(std::size_t i, std::size_t d) const { return v[i][static_cast<Eigen::Index>(d)]; }
    template <class B>
    bool kdtree_get_bbox(B&) const {
        return false;
    }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Cloud>, Cloud, 3>;

/** The distances from frame `f`'s depth points to the mesh's nearest vertex, where within 5 cm. */
void distancesToMesh(const Frame& f, const dense::Mesh& mesh, double farthest, std::vector<double>& out) {
    Cloud cloud{mesh.vertices};
    Tree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    tree.buildIndex();
    const auto& K = kKinect;
    for (int y = 0; y < f.depth.rows; y += 4)
        for (int x = 0; x < f.depth.cols; x += 4) {
            const float z = f.depth.at<float>(y, x);
            if (!(z > 0.3f) || z > farthest) continue;
            const Eigen::Vector3f p =
                (f.pose * Eigen::Vector3d((x - K.cx) / K.fx * z, (y - K.cy) / K.fy * z, z)).cast<float>();
            std::size_t index = 0;
            float d2 = 0;
            nanoflann::KNNResultSet<float> result(1);
            result.init(&index, &d2);
            tree.findNeighbors(result, p.data(), nanoflann::SearchParams());
            if (d2 <= 0.05f * 0.05f) out.push_back(std::sqrt(d2));
        }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::cerr << "usage: bench_mesh_real DATA_DIR blocks|open3d [MESH.ply]\n";
        return 2;
    }
    try {
        const std::vector<Frame> frames = loadSequence(argv[1]);
        if (frames.empty()) throw std::runtime_error(std::string(argv[1]) + ": no seq-01 frames");
        dense::DenseParams params;
        const std::string volume = argv[2];
        if (volume != "blocks" && volume != "open3d") throw std::runtime_error("volume: blocks or open3d");
        params.volume = volume == "open3d" ? dense::DenseParams::Volume::Open3d : dense::DenseParams::Volume::Blocks;
        const double before = residentMb();
        double integrate = 0, meshing = 0;
        std::size_t vertices = 0, volumeBytes = 0;
        {
            dense::TsdfFusion fusion(params);
            auto t = std::chrono::steady_clock::now();
            for (const Frame& f : frames) fusion.integrate(f.depth, f.bgr, kKinect, f.pose);
            integrate = since(t);
            t = std::chrono::steady_clock::now();
            const dense::Mesh mesh = fusion.extractMesh();
            meshing = since(t);
            vertices = mesh.vertices.size();
            volumeBytes = fusion.memoryBytes();
            if (argc > 3) dense::writeMeshPly(argv[3], mesh);
        }
        const double after = residentMb();
        // Each frame against the mesh of the others.
        std::vector<double> d;
        for (std::size_t out = 0; out < frames.size(); ++out) {
            dense::TsdfFusion others(params);
            for (std::size_t k = 0; k < frames.size(); ++k)
                if (k != out) others.integrate(frames[k].depth, frames[k].bgr, kKinect, frames[k].pose);
            distancesToMesh(frames[out], others.extractMesh(), params.fusedDepthLimit(), d);
        }
        std::sort(d.begin(), d.end());
        const auto at = [&](double q) { return d.empty() ? 0.0 : d[static_cast<std::size_t>(q * (d.size() - 1))]; };
        std::size_t within1 = 0;
        for (const double x : d) within1 += x <= 0.01;
        std::printf("| %s | %zu | %zu | %.1f | %.2f | %s | %.0f | %.4f / %.4f | %.3f |\n", volume.c_str(), frames.size(),
                    vertices, 1e3 * integrate / double(frames.size()), meshing,
                    volumeBytes ? std::to_string(volumeBytes >> 20).c_str() : "-", after - before, at(0.5), at(0.95),
                    d.empty() ? 0.0 : double(within1) / double(d.size()));
    } catch (const std::exception& e) {
        std::cerr << "bench_mesh_real: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
