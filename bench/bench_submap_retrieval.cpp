// Candidate retrieval of the visual loop closer (SubmapCatalog: KD-tree over submap centres +
// LSH appearance index) as the number of submaps grows, on synthetic submaps: random
// 256-bit descriptors (300 per submap, what the appearance index keeps of each) at random
// positions in a 200 m x 200 m map. A query is a keyframe's 600 descriptors: half copied from
// one stored submap with 3 bits flipped each, half random. Prints one markdown row per size:
//   submaps | queries | retrieval ms per query: mean / max | right submap first (of queries)
//   bench_submap_retrieval [SUBMAPS ...]   (default 100 1000 10000)
#include <lodestone/vision/SubmapCatalog.h>

#include <chrono>
#include <cstdio>
#include <random>

using namespace lodestone;

int main(int argc, char** argv) {
    std::vector<int> sizes;
    for (int i = 1; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
    if (sizes.empty()) sizes = {100, 1000, 10000};
    for (const int n : sizes) {
        std::mt19937_64 rng(42);
        std::uniform_int_distribution<int> byte(0, 255), bit(0, 255);
        std::uniform_real_distribution<double> pos(-100, 100);
        vision::SubmapCatalog catalog;
        std::vector<cv::Mat> stored;
        for (int s = 0; s < n; ++s) {
            auto features = std::make_shared<vision::FrameFeatures>();
            features->descriptors.create(300, 32, CV_8U);
            for (int r = 0; r < 300; ++r)
                for (int b = 0; b < 32; ++b) features->descriptors.at<std::uint8_t>(r, b) = static_cast<std::uint8_t>(byte(rng));
            features->points = Eigen::Matrix3Xf::Random(3, 300);
            features->keypoints.resize(300);
            auto submap = std::make_shared<vision::FeatureSubmap>();
            submap->add(s, Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), features);
            stored.push_back(features->descriptors);
            catalog.add(submap, Eigen::Vector3d(pos(rng), pos(rng), 0));
        }
        const int queries = 200;
        double sum = 0, worst = 0;
        int right = 0;
        for (int q = 0; q < queries; ++q) {
            const std::size_t target = static_cast<std::size_t>(q * 7919) % stored.size();
            cv::Mat d(600, 32, CV_8U);
            for (int r = 0; r < 600; ++r) {
                if (r < 300) {
                    stored[target].row(r).copyTo(d.row(r));
                    for (int k = 0; k < 3; ++k) {
                        const int b = bit(rng);
                        d.at<std::uint8_t>(r, b / 8) ^= static_cast<std::uint8_t>(1 << (b % 8));
                    }
                } else {
                    for (int b = 0; b < 32; ++b) d.at<std::uint8_t>(r, b) = static_cast<std::uint8_t>(byte(rng));
                }
            }
            const Eigen::Vector3d here(pos(rng), pos(rng), 0);
            const auto t0 = std::chrono::steady_clock::now();
            const auto c = catalog.candidates(here, 3.0, d, 2, 3, 12, [](std::size_t) { return true; });
            const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            sum += ms;
            worst = std::max(worst, ms);
            right += !c.empty() && c[0].submap == target;
        }
        std::printf("| %d | %d | %.3f / %.3f | %d of %d |\n", n, queries, sum / queries, worst, right, queries);
        std::fflush(stdout);
    }
    return 0;
}
