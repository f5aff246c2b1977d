// Descriptor matching: the packed XOR-popcount kernel against OpenCV's BFMatcher
// with the same gates, at VO's size (600 x 600 ORB descriptors) and submap phase 1's (1000
// submap features x 600 of a keyframe). Google Benchmark; scripts/bench/matching.sh prints the
// table.
#include <benchmark/benchmark.h>
#include <lodestone/vision/DescriptorMatcher.h>

#include <opencv2/features2d.hpp>

namespace {
cv::Mat descriptors(int n, int seed) {
    cv::setRNGSeed(seed);
    cv::Mat d(n, 32, CV_8UC1);
    cv::randu(d, 0, 256);
    return d;
}

lodestone::vision::DescriptorMatcher::Params params(double ratio) {
    lodestone::vision::DescriptorMatcher::Params p;
    p.ratio = ratio;
    return p;
}

void packed(benchmark::State& state) {
    const cv::Mat q = descriptors(static_cast<int>(state.range(0)), 1);
    const cv::Mat t = descriptors(static_cast<int>(state.range(1)), 2);
    const lodestone::vision::DescriptorMatcher matcher(params(state.range(2) / 10.0));
    for (auto _ : state) benchmark::DoNotOptimize(matcher.match(q, t));
}

void openCv(benchmark::State& state) {
    const cv::Mat q = descriptors(static_cast<int>(state.range(0)), 1);
    const cv::Mat t = descriptors(static_cast<int>(state.range(1)), 2);
    const bool ratio = state.range(2) > 0;
    for (auto _ : state) {
        cv::BFMatcher m(cv::NORM_HAMMING, !ratio);
        if (ratio) {
            std::vector<std::vector<cv::DMatch>> knn;
            std::vector<cv::DMatch> back;
            m.knnMatch(q, t, knn, 2);
            m.match(t, q, back);
            benchmark::DoNotOptimize(knn);
        } else {
            std::vector<cv::DMatch> all;
            m.match(q, t, all);
            benchmark::DoNotOptimize(all);
        }
    }
}
}  // namespace

// args: query rows, train rows, ratio x 10 (0: cross-check only, VO's; 8: ratio 0.8 + cross-check, submaps')
BENCHMARK(packed)->Args({600, 600, 0})->Args({600, 1000, 8})->Unit(benchmark::kMillisecond);
BENCHMARK(openCv)->Args({600, 600, 0})->Args({600, 1000, 8})->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
