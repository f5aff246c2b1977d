#include <lodestone/io/RawlogPaths.h>
#include <lodestone/io/RawlogWriter.h>
#include <lodestone/datasets/TimeAssociation.h>
#include <lodestone/datasets/TumRgbdImport.h>
#include <lodestone/io/TumTrajectory.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace lodestone::datasets {

namespace fs = std::filesystem;

namespace {
struct Stamped {
    double t;
    std::string file;
};

// "timestamp filename" lines; '#' comments.
std::vector<Stamped> readList(const fs::path& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path.string() + ": cannot open");
    std::vector<Stamped> out;
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        std::istringstream s(line);
        Stamped e;
        if (!(s >> e.t >> e.file) || !std::isfinite(e.t)) {
            throw std::runtime_error(path.string() + ": line " + std::to_string(n) +
                                     ": expected 'timestamp filename'");
        }
        out.push_back(e);
    }
    return out;
}

}  // namespace

TumIntrinsics TumIntrinsics::parse(const std::string& text) {
    const auto of = [](double fx, double fy, double cx, double cy) {
        TumIntrinsics k;
        k.fx = fx;
        k.fy = fy;
        k.cx = cx;
        k.cy = cy;
        return k;
    };
    if (text == "fr1") return of(517.3, 516.5, 318.6, 255.3);
    if (text == "fr2") return of(520.9, 521.0, 325.1, 249.7);
    if (text == "fr3") return of(535.4, 539.2, 320.1, 247.6);
    if (text == "default") return {};
    TumIntrinsics k;
    char c1 = 0, c2 = 0, c3 = 0;
    std::istringstream s(text);
    if ((s >> k.fx >> c1 >> k.fy >> c2 >> k.cx >> c3 >> k.cy) && c1 == ',' && c2 == ',' &&
        c3 == ',' && s.peek() == EOF && k.fx > 0 && k.fy > 0) {
        return k;
    }
    throw std::invalid_argument("intrinsics '" + text +
                                "': expected fr1, fr2, fr3, default or fx,fy,cx,cy");
}

TumImportResult importTumRgbd(const std::string& sequenceDir, const std::string& outRawlog,
                              const TumImportOptions& o) {
    const fs::path dir = fs::absolute(sequenceDir);
    const auto rgb = readList(dir / "rgb.txt");
    const auto depth = readList(dir / "depth.txt");
    std::vector<double> rgbTimes, depthTimes;
    for (const auto& e : rgb) rgbTimes.push_back(e.t);
    for (const auto& e : depth) depthTimes.push_back(e.t);
    if (!std::is_sorted(rgbTimes.begin(), rgbTimes.end()) ||
        !std::is_sorted(depthTimes.begin(), depthTimes.end())) {
        throw std::runtime_error(dir.string() + ": rgb.txt / depth.txt are not in time order");
    }
    const auto pairs = associateByTime(rgbTimes, depthTimes, o.maxTimeDifference);

    TumImportResult r;
    r.rawlog = outRawlog;
    r.unmatchedRgb = rgb.size() - pairs.size();
    r.unmatchedDepth = depth.size() - pairs.size();
    std::string stem = outRawlog;
    for (const std::string ext : {".gz", ".rawlog"}) {
        if (stem.size() > ext.size() &&
            stem.compare(stem.size() - ext.size(), ext.size(), ext) == 0) {
            stem.resize(stem.size() - ext.size());
        }
    }
    if (fs::exists(dir / "groundtruth.txt")) {
        r.groundTruth = stem + ".gt.tum";
        const auto gt = io::readTumTrajectory((dir / "groundtruth.txt").string());
        io::TumTrajectoryWriter writer(r.groundTruth);
        for (const auto& p : gt) writer.write(p.timestamp, p.pose);
        writer.close();
        r.groundTruthPoses = gt.size();
    }

    io::RawlogWriter writer(outRawlog, {io::isGzipPath(outRawlog) ? 1 : 0});
    RgbdFrameOptions frame;
    frame.intrinsics = o.intrinsics;
    frame.depthScale = o.depthScale;
    frame.registration = o.registration;
    frame.sensorLabel = o.sensorLabel;
    for (const auto& [i, j] : pairs) {
        const fs::path rgbFile = dir / rgb[i].file, depthFile = dir / depth[j].file;
        if (!fs::exists(rgbFile))
            throw std::runtime_error(rgbFile.string() + ": missing (listed in rgb.txt)");
        writeRgbdFrame(writer, rgb[i].t, rgbFile.string(), depthFile.string(), frame);
        ++r.frames;
    }
    writer.close();
    return r;
}

}  // namespace lodestone::datasets
