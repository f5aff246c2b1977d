// Storage of RGB-D frames: what each choice costs per frame on disk and to decode,
// on frames of a simulated scenario (every 10th of its first 400): colour as PNG (level 1, what
// lodestone-sim writes by default) or JPEG at several qualities; depth raw in the rawlog or
// deflated (a .rawlog.gz: zlib level 1, as RawlogWriter writes it). Prints a markdown table.
// Usage: bench_storage SCENARIO.ini [FRAMES]
#include <lodestone/sim/Scenario.h>
#include <lodestone/sim/SimulatorSource.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <zlib.h>

#include <chrono>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Row {
    std::string what;
    double bytes{0}, decodeMs{0};
};

Row colour(const std::vector<cv::Mat>& frames, const std::string& what, const std::string& ext,
           const std::vector<int>& params) {
    Row r{what};
    for (const auto& f : frames) {
        std::vector<uchar> buf;
        cv::imencode(ext, f, buf, params);
        r.bytes += static_cast<double>(buf.size());
        const auto t0 = Clock::now();
        for (int k = 0; k < 3; ++k) {
            const cv::Mat back = cv::imdecode(buf, cv::IMREAD_COLOR);
            if (back.empty()) throw std::runtime_error("decode failed");
        }
        r.decodeMs += msSince(t0) / 3;
    }
    r.bytes /= static_cast<double>(frames.size());
    r.decodeMs /= static_cast<double>(frames.size());
    return r;
}

Row depth(const std::vector<cv::Mat>& frames, bool deflate) {
    Row r{deflate ? "depth, 16-bit, deflated (.rawlog.gz)" : "depth, 16-bit, raw (.rawlog)"};
    for (const auto& d : frames) {
        const auto size = static_cast<uLong>(d.total() * d.elemSize());
        if (!deflate) {
            r.bytes += static_cast<double>(size);
            continue;  // (read as it is: no decoding)
        }
        std::vector<Bytef> packed(compressBound(size));
        uLongf packedSize = static_cast<uLongf>(packed.size());
        compress2(packed.data(), &packedSize, d.ptr(), size, 1);
        r.bytes += static_cast<double>(packedSize);
        std::vector<Bytef> back(size);
        const auto t0 = Clock::now();
        uLongf backSize = size;
        uncompress(back.data(), &backSize, packed.data(), packedSize);
        r.decodeMs += msSince(t0);
    }
    r.bytes /= static_cast<double>(frames.size());
    r.decodeMs /= static_cast<double>(frames.size());
    return r;
}
}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_storage SCENARIO.ini [FRAMES]\n");
        return 2;
    }
    const std::size_t wanted = argc > 2 ? std::stoul(argv[2]) : 40;
    const auto scenario = lodestone::sim::Scenario::load(argv[1]);
    lodestone::sim::SimulatorSource source(scenario, scenario.seed);
    std::vector<cv::Mat> colours, depths;
    std::size_t seen = 0;
    while (colours.size() < wanted) {
        const auto obs = source.next();
        if (!obs) break;
        const auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs);
        if (!scan || seen++ % 10 != 0) continue;
        colours.push_back(scan->intensityImage.asCvMat<cv::Mat>(mrpt::img::DEEP_COPY));
        cv::Mat d(static_cast<int>(scan->rangeImage.rows()), static_cast<int>(scan->rangeImage.cols()), CV_16UC1);
        for (int y = 0; y < d.rows; ++y)
            for (int x = 0; x < d.cols; ++x) d.at<std::uint16_t>(y, x) = scan->rangeImage(y, x);
        depths.push_back(d);
    }
    std::vector<Row> rows;
    rows.push_back(colour(colours, "colour, PNG level 1 (default)", ".png", {cv::IMWRITE_PNG_COMPRESSION, 1}));
    rows.push_back(colour(colours, "colour, PNG level 6", ".png", {cv::IMWRITE_PNG_COMPRESSION, 6}));
    for (const int q : {95, 90, 75}) {
        rows.push_back(colour(colours, "colour, JPEG quality " + std::to_string(q), ".jpg",
                              {cv::IMWRITE_JPEG_QUALITY, q}));
    }
    rows.push_back(depth(depths, false));
    rows.push_back(depth(depths, true));
    std::printf("| %s, %dx%d, %zu frames | bytes per frame | decode ms per frame |\n|---|---|---|\n",
                scenario.name.c_str(), scenario.camera.width, scenario.camera.height, colours.size());
    for (const auto& r : rows) std::printf("| %s | %.0f KB | %.2f |\n", r.what.c_str(), r.bytes / 1024, r.decodeMs);
    return 0;
}
