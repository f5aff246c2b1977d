#include <lodestone/io/RawlogPaths.h>
#include <lodestone/datasets/SevenScenesImport.h>
#include <lodestone/io/TumTrajectory.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>

namespace lodestone::datasets {

namespace fs = std::filesystem;

namespace {
/** The 4 x 4 row-major matrix of a pose file; nullopt if any entry is not finite (3DMatch
 * marks frames without a pose with -inf). */
std::optional<mrpt::poses::CPose3D> readPoseMatrix(const fs::path& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path.string() + ": cannot open");
    mrpt::math::CMatrixDouble44 M;
    bool finite = true;
    for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) {
            std::string word;
            if (!(in >> word))
                throw std::runtime_error(path.string() + ": expected 16 numbers (a 4 x 4 matrix)");
            try {
                M(r, c) = std::stod(word);
            } catch (const std::exception&) {
                throw std::runtime_error(path.string() + ": '" + word + "' is not a number");
            }
            finite = finite && std::isfinite(M(r, c));
        }
    }
    if (!finite) return std::nullopt;
    return mrpt::poses::CPose3D(M);
}

std::string stemOf(const std::string& rawlog) {
    std::string stem = rawlog;
    for (const std::string ext : {".gz", ".rawlog"}) {
        if (stem.size() > ext.size() && stem.compare(stem.size() - ext.size(), ext.size(), ext) == 0)
            stem.resize(stem.size() - ext.size());
    }
    return stem;
}
}  // namespace

PinholeIntrinsics readCameraMatrix(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    double K[9];
    for (double& v : K) {
        if (!(in >> v) || !std::isfinite(v))
            throw std::runtime_error(path + ": expected a 3 x 3 camera matrix (9 numbers)");
    }
    if (!(K[0] > 0) || !(K[4] > 0) || K[8] != 1)
        throw std::runtime_error(path + ": not a camera matrix (fx 0 cx / 0 fy cy / 0 0 1)");
    PinholeIntrinsics k;
    k.fx = K[0];
    k.fy = K[4];
    k.cx = K[2];
    k.cy = K[5];
    return k;
}

SevenScenesImportResult importSevenScenes(const std::string& sequenceDir, const std::string& outRawlog,
                                          const SevenScenesImportOptions& o) {
    const fs::path dir = fs::absolute(sequenceDir);
    if (!fs::is_directory(dir)) throw std::runtime_error(dir.string() + ": not a folder");
    // frame-NNNNNN.color.(png|jpg), in index order.
    const std::regex colour(R"(frame-(\d+)\.color\.(png|jpg))");
    std::vector<std::pair<long, fs::path>> frames;
    for (const auto& e : fs::directory_iterator(dir)) {
        std::smatch m;
        const std::string name = e.path().filename().string();
        if (std::regex_match(name, m, colour)) frames.emplace_back(std::stol(m[1].str()), e.path());
    }
    if (frames.empty())
        throw std::runtime_error(dir.string() + ": no frame-NNNNNN.color.png (or .jpg) images");
    std::sort(frames.begin(), frames.end());

    SevenScenesImportResult r;
    r.rawlog = outRawlog;
    if (o.intrinsics) {
        r.intrinsics = *o.intrinsics;
        r.intrinsicsSource = "--intrinsics";
    } else {
        r.intrinsicsSource = "7-Scenes default";
        r.intrinsics.fx = r.intrinsics.fy = 585.0;
        r.intrinsics.cx = 320.0;
        r.intrinsics.cy = 240.0;
        for (const fs::path& f : {dir / "camera-intrinsics.txt", dir.parent_path() / "camera-intrinsics.txt"}) {
            if (fs::exists(f)) {
                r.intrinsics = readCameraMatrix(f.string());
                r.intrinsicsSource = f.string();
                break;
            }
        }
    }
    RgbdFrameOptions frame;
    frame.intrinsics = r.intrinsics;
    frame.depthScale = o.depthScale;
    frame.registration = o.registration;
    frame.sensorLabel = o.sensorLabel;
    r.groundTruth = stemOf(outRawlog) + ".gt.tum";
    io::TumTrajectoryWriter truth(r.groundTruth);
    io::RawlogWriter writer(outRawlog, {io::isGzipPath(outRawlog) ? 1 : 0});
    for (const auto& [index, colourPath] : frames) {
        char stem[32];
        std::snprintf(stem, sizeof(stem), "frame-%06ld", index);
        const double t = double(index) / o.rate;
        writeRgbdFrame(writer, t, colourPath.string(), (dir / (std::string(stem) + ".depth.png")).string(),
                       frame);
        ++r.frames;
        const fs::path pose = dir / (std::string(stem) + ".pose.txt");
        if (!fs::exists(pose)) continue;
        if (const auto p = readPoseMatrix(pose)) {
            truth.write(t, *p);
            ++r.groundTruthPoses;
        }
    }
    writer.close();
    truth.close();
    return r;
}

}  // namespace lodestone::datasets
