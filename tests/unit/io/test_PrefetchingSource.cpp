// Decode-ahead: a rawlog read through io::PrefetchingSource gives byte for byte
// what the rawlog gives read in the caller's thread - the same entries, the same decoded
// pixels, the same fault at the same place - with at most `depth` observations ahead. (A colour
// PNG it decoded with its own reader is held in memory rather than as its file's name.)
#include <gtest/gtest.h>
#include <lodestone/io/PrefetchingSource.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/io/CMemoryStream.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <opencv2/core.hpp>
#include <thread>

#include "RawlogTestHelpers.h"
#include "SampleObservations.h"
#include "TestPaths.h"

using namespace lodestone;

namespace {
std::string bytesOf(const mrpt::obs::CObservation& o) {
    mrpt::io::CMemoryStream buffer;
    auto archive = mrpt::serialization::archiveFrom(buffer);
    archive << o;
    return std::string(static_cast<const char*>(buffer.getRawBufferData()), buffer.getTotalBytesCount());
}

cv::Mat pixelsOf(const mrpt::obs::CObservation::Ptr& o) {
    auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(o);
    if (!scan) return {};
    return scan->intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
}

/** 40 RGB-D frames with colour as PNG files beside the rawlog (MRPT's `_Images` folder),
 * magnetometer samples between them. */
std::string rawlogWithExternalImages(const test::TempDir& dir) {
    const auto path = dir.file("ext.rawlog");
    const auto images = dir.path() / "ext_Images";
    std::filesystem::create_directories(images);
    std::vector<mrpt::obs::CObservation::Ptr> obs;
    for (int k = 0; k < 40; ++k) {
        auto scan = test::makeRangeScan(k * 0.1, 64, 48, 1.0 + 0.01 * k);
        cv::Mat noise(48, 64, CV_8UC3);
        cv::randu(noise, 0, 255);  // (different pixels in every frame)
        scan->intensityImage = mrpt::img::CImage(noise, mrpt::img::DEEP_COPY);
        const std::string name = "rgb_" + std::to_string(k) + ".png";
        scan->intensityImage.saveToFile((images / name).string());
        scan->intensityImage.setExternalStorage(name);
        obs.push_back(scan);
        obs.push_back(test::makeMagnetometer(k * 0.1 + 0.05, "MAG", k));
    }
    test::writeRawlog(path, obs);
    return path;
}

/** Every test runs with one, two and three workers: several decode at once, one reads. */
class PrefetchingSource : public ::testing::TestWithParam<std::size_t> {};

/** A source counting how often it was asked, endless: RGB-D frames, or magnetometer samples. */
class CountingSource : public io::DataSource {
  public:
    explicit CountingSource(bool frames) : frames_(frames) {}
    std::atomic<int> calls{0};
    mrpt::obs::CObservation::Ptr next() override {
        ++calls;
        if (frames_) return test::makeRangeScan(calls * 0.01, 8, 6, 1.0);
        return test::makeMagnetometer(calls * 0.01, "MAG", 1.0);
    }
    std::string name() const override { return "counting"; }

  private:
    bool frames_;
};
}  // namespace

TEST_P(PrefetchingSource, GivesByteForByteWhatTheRawlogGives) {
    registerAllClasses();
    test::TempDir dir;
    const auto path = rawlogWithExternalImages(dir);
    io::RawlogSource direct(path);
    auto inner = std::make_unique<io::RawlogSource>(path);
    const io::RawlogSource* rawlog = inner.get();
    io::PrefetchingSource ahead(std::move(inner), 3, [rawlog] { return rawlog->fractionRead(); },
                                GetParam());
    std::size_t n = 0;
    for (;;) {
        auto a = direct.next();
        auto b = ahead.next();
        ASSERT_EQ(static_cast<bool>(a), static_cast<bool>(b)) << "entry " << n;
        if (!a) break;
        a->load();  // (the prefetching source did this on its worker)
        if (auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(a)) {
            // The colour PNG read by io::decodeRgbPng is held in memory, not as its file: so
            // compared, every other byte the same, and the pixels below.
            const auto other = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(b);
            ASSERT_TRUE(other);
            EXPECT_FALSE(other->intensityImage.isExternallyStored()) << "entry " << n;
            scan->intensityImage = mrpt::img::CImage(
                scan->intensityImage.asCvMat<cv::Mat>(mrpt::img::DEEP_COPY), mrpt::img::SHALLOW_COPY);
        }
        EXPECT_EQ(bytesOf(*a), bytesOf(*b)) << "entry " << n;
        const cv::Mat pa = pixelsOf(a), pb = pixelsOf(b);
        ASSERT_EQ(pa.empty(), pb.empty());
        if (!pa.empty()) {
            ASSERT_EQ(pa.size(), pb.size());
            EXPECT_EQ(cv::norm(pa, pb, cv::NORM_INF), 0.0) << "entry " << n;
        }
        ++n;
    }
    EXPECT_EQ(n, 80u);
    EXPECT_EQ(ahead.name(), path);
    EXPECT_NEAR(ahead.progress(), 1.0, 1e-9);
}

TEST_P(PrefetchingSource, AFaultComesAfterEverythingBeforeIt) {
    registerAllClasses();
    test::TempDir dir;
    const auto good = rawlogWithExternalImages(dir);
    const auto bytes = test::readBytes(good);
    const auto cut = dir.file("ext_cut.rawlog");
    test::writeBytes(cut, bytes.substr(0, bytes.size() * 2 / 3));  // ends inside an entry
    std::filesystem::create_directory_symlink(dir.path() / "ext_Images", dir.path() / "ext_cut_Images");
    io::RawlogSource direct(cut);
    const auto expected = test::drain(direct);
    ASSERT_FALSE(expected.error.empty());
    io::PrefetchingSource ahead(std::make_unique<io::RawlogSource>(cut), 4, {}, GetParam());
    const auto got = test::drain(ahead);
    EXPECT_EQ(got.observations.size(), expected.observations.size());
    EXPECT_EQ(got.error, expected.error);
    EXPECT_EQ(got.errorEntry, expected.errorEntry);
    EXPECT_EQ(ahead.next(), nullptr);  // thrown once; exhausted after it
}

namespace {
/** An error's message without MRPT's call stack (addresses differ from call site to call site). */
std::string messageOf(const std::exception& e) {
    const std::string w = e.what();
    const auto at = w.find("Message:");
    return at == std::string::npos ? w : w.substr(at, w.find('\n', at) - at);
}

/** What a caller meets loading an observation's images and looking at the colour one. */
std::string whatLoadingGives(const mrpt::obs::CObservation::Ptr& o) {
    std::string what;
    try {
        o->load();
        what += "loaded;";
    } catch (const std::exception& e) {
        what += "load threw: " + messageOf(e) + ";";
    }
    try {
        const cv::Mat m = pixelsOf(o);
        what += m.empty() ? "no pixels" : "pixels " + std::to_string(m.cols) + "x" + std::to_string(m.rows);
    } catch (const std::exception& e) {
        what += "pixels threw: " + messageOf(e);
    }
    return what;
}
}  // namespace

TEST_P(PrefetchingSource, AMissingImageIsMetAsWithoutPrefetching) {
    registerAllClasses();
    test::TempDir dir;
    const auto path = rawlogWithExternalImages(dir);
    std::filesystem::remove(dir.path() / "ext_Images" / "rgb_3.png");
    io::RawlogSource direct(path);
    io::PrefetchingSource ahead(std::make_unique<io::RawlogSource>(path), 8, {}, GetParam());
    for (int k = 0; k < 80; ++k) {
        const auto a = direct.next(), b = ahead.next();
        ASSERT_TRUE(a && b);
        const std::string got = whatLoadingGives(b), expected = whatLoadingGives(a);
        EXPECT_EQ(got, expected) << "entry " << k;
        if (k == 6) {
            EXPECT_EQ(got.find("pixels 64x48"), std::string::npos) << got;  // frame 3
        }
        if (k == 8) {
            EXPECT_NE(got.find("pixels 64x48"), std::string::npos) << got;  // frame 4
        }
    }
}

TEST_P(PrefetchingSource, StaysWithinItsDepthAndStopsCleanly) {
    for (const bool frames : {true, false}) {
        auto counting = std::make_unique<CountingSource>(frames);
        const CountingSource* inner = counting.get();
        {
            io::PrefetchingSource ahead(std::move(counting), 5, {}, GetParam());
            ASSERT_TRUE(ahead.next());
            std::this_thread::sleep_for(std::chrono::milliseconds(200));
            // One handed over, five frames queued (light observations: 64 per frame), at most
            // one more being read: never more.
            const int depth = frames ? 5 : 5 * static_cast<int>(io::PrefetchingSource::kLightPerFrame);
            EXPECT_LE(inner->calls.load(), depth + 2) << (frames ? "frames" : "light");
            EXPECT_GE(inner->calls.load(), depth + 1) << (frames ? "frames" : "light");
        }  // destroyed with a full queue and an endless source: joins, no hang
    }
}

TEST_P(PrefetchingSource, ImagesAreDecodedOnTheWorkerNotWhenFirstTouched) {
    // MRPT decodes a delay-loaded image when its pixels are first touched; the worker must do
    // that itself, or the decoding stays in the caller's loop. Seen from outside: once handed
    // over, a frame's pixels are there even if its file is gone.
    registerAllClasses();
    test::TempDir dir;
    const auto path = rawlogWithExternalImages(dir);
    io::PrefetchingSource ahead(std::make_unique<io::RawlogSource>(path), 2, {}, GetParam());
    int frames = 0;
    while (auto obs = ahead.next()) {
        auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs);
        if (!scan) continue;
        std::filesystem::remove(dir.path() / "ext_Images" / ("rgb_" + std::to_string(frames) + ".png"));
        EXPECT_EQ(pixelsOf(obs).cols, 64) << "frame " << frames;
        ++frames;
    }
    EXPECT_EQ(frames, 40);
}

INSTANTIATE_TEST_SUITE_P(Workers, PrefetchingSource, ::testing::Values(1u, 2u, 3u));
