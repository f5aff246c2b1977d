#include "RunParts.h"

#include <algorithm>

namespace lodestone::slamapp::detail {

namespace {

using graphslam::JsonObject;

struct Percentiles {
    double p50{0}, p99{0}, max{0}, mean{0};
};
Percentiles percentiles(std::vector<float> v) {
    Percentiles p;
    if (v.empty()) return p;
    std::sort(v.begin(), v.end());
    const auto at = [&](double q) {
        return static_cast<double>(v[std::min(v.size() - 1, static_cast<std::size_t>(q * v.size()))]);
    };
    p.p50 = at(0.5);
    p.p99 = at(0.99);
    p.max = v.back();
    double sum = 0;
    for (float x : v) sum += x;
    p.mean = sum / v.size();
    return p;
}

/** Mean engine time per node in each tenth of the run: flat means no growth with the graph. */
std::vector<double> decileMeans(const std::vector<float>& v) {
    std::vector<double> out;
    if (v.size() < 10) return out;
    for (int d = 0; d < 10; ++d) {
        const std::size_t a = v.size() * d / 10, b = v.size() * (d + 1) / 10;
        double sum = 0;
        for (std::size_t i = a; i < b; ++i) sum += v[i];
        out.push_back(sum / std::max<std::size_t>(1, b - a));
    }
    return out;
}

}  // namespace

JsonObject timingJson(const graphslam::SlamEngine::Stats& s, const LoopOutcome& loop,
                      const io::PrefetchingSource* prefetcher) {
    const double wall = loop.wallSeconds, data = loop.dataSeconds;
    const auto frames = percentiles(s.frameMs), nodes = percentiles(s.nodeMs);
    JsonObject timing;
    timing.set("wall_s", wall)
        // Waiting for the next observation: reading and decoding it in the frame loop, or with
        // --decode-ahead what the worker had not done yet.
        .set("source_s", loop.sourceSeconds)
        .set("source_ms_per_observation",
             s.observations > 0
                 ? 1e3 * loop.sourceSeconds / static_cast<double>(s.observations)
                 : 0.0)
        .set("data_s", data)
        .set("real_time_factor", wall > 0 ? data / wall : 0.0)
        .set("frame_ms", JsonObject()
                             .set("mean", frames.mean)
                             .set("p50", frames.p50)
                             .set("p99", frames.p99)
                             .set("max", frames.max))
        .set("node_ms", JsonObject().set("mean", nodes.mean).set("p99", nodes.p99).set("max", nodes.max))
        .set("node_ms_by_decile", decileMeans(s.nodeMs));
    if (prefetcher) {
        // The workers' CPU time: what reading, decoding and preparing frames cost, off the
        // frame loop.
        const auto w = prefetcher->workerTime();
        timing.set("worker_read_s", w.readSeconds)
            .set("worker_decode_s", w.decodeSeconds)
            .set("worker_prepare_s", w.prepareSeconds);
    }
    return timing;
}

}  // namespace lodestone::slamapp::detail
