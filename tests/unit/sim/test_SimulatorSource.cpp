#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <lodestone/obs/CObservationWheelDrop.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/sim/ScenarioRecorder.h>
#include <lodestone/sim/SimulatorSource.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "RawlogTestHelpers.h"
#include "SampleObservations.h"
#include "SimTestWorlds.h"
#include "TestPaths.h"

using namespace lodestone;
using namespace lodestone::sim;

namespace {
const std::string kConfigDir = LODESTONE_CONFIG_INI_DIR;

// office.ini with a tiny, slow camera: the whole run in well under a second.
Scenario quickOffice() {
    Scenario sc = Scenario::load(kConfigDir + "/scenarios/office.ini");
    sc.camera.resize(64, 48);
    sc.camera.rate = 2;
    sc.camera.externalImages = false;
    return sc;
}
}  // namespace

TEST(SimulatorSource, ObservationsComeInTimeOrderAtTheConfiguredRates) {
    registerAllClasses();
    SimulatorSource source(quickOffice(), 1);
    std::map<std::string, int> counts;
    mrpt::Clock::time_point last{};
    while (auto o = source.next()) {
        EXPECT_GE(o->timestamp, last);
        last = o->timestamp;
        ++counts[o->sensorLabel];
    }
    const double T = source.duration();
    EXPECT_NEAR(counts["MAG_LEFT"], std::floor(T * 100) + 1, 1);
    EXPECT_NEAR(counts["WHEELS"], std::floor(T * 50) + 1, 1);
    EXPECT_NEAR(counts["RGBD"], std::floor(T * 2) + 1, 1);
    EXPECT_EQ(counts.count("WHEEL_DROP"), 0u);  // no kidnaps in the office
}

TEST(SimulatorSource, SameSeedSameBytesOtherSeedOtherBytes) {
    registerAllClasses();
    test::TempDir dir;
    const auto run = [&](std::uint64_t seed, const std::string& name) {
        SimulatorSource source(quickOffice(), seed);
        const auto out = dir.file(name + ".rawlog");
        recordScenario(source, out);
        return std::make_pair(test::readBytes(out), test::readBytes(dir.file(name + ".gt.tum")));
    };
    const auto a = run(11, "a"), b = run(11, "b"), c = run(12, "c");
    EXPECT_GT(a.first.size(), 100000u);
    EXPECT_TRUE(a.first == b.first) << "same seed, different rawlog";
    EXPECT_TRUE(a.second == b.second) << "same seed, different ground truth";
    EXPECT_FALSE(a.first == c.first) << "the seed changes nothing";
    EXPECT_TRUE(a.second == c.second);  // the path is the INI's, not random
}

TEST(SimulatorSource, NoiseFreeTicksDeadReckonTheGroundTruth) {
    registerAllClasses();
    Scenario sc = quickOffice();
    sc.encoders.slipStd = 0;
    sc.encoders.leftScale = sc.encoders.rightScale = 1.0;
    sc.encoders.ticksPerRev = 1e6;  // quantization far below the check
    SimulatorSource source(sc, 1);
    const double r = sc.motion.wheelRadius, b = sc.motion.wheelBase;
    double x = 0, y = 0, yaw = 0;
    bool first = true;
    int lastL = 0, lastR = 0, checked = 0;
    while (auto o = source.next()) {
        auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o);
        if (!odo) continue;
        const RobotPose truth = source.truePose(source.lastTime());
        if (first) {
            x = truth.x, y = truth.y, yaw = truth.yaw;
            first = false;
        } else {
            // Paper 003 eq. (1): wheel travel from tick increments, midpoint heading.
            const double k = 2 * M_PI * r / sc.encoders.ticksPerRev;
            const double dl = (odo->encoderLeftTicks - lastL) * k;
            const double dr = (odo->encoderRightTicks - lastR) * k;
            const double ds = (dl + dr) / 2, dth = (dr - dl) / b;
            x += ds * std::cos(yaw + dth / 2);
            y += ds * std::sin(yaw + dth / 2);
            yaw += dth;
        }
        lastL = odo->encoderLeftTicks;
        lastR = odo->encoderRightTicks;
        EXPECT_NEAR(x, truth.x, 2e-3);
        EXPECT_NEAR(y, truth.y, 2e-3);
        EXPECT_NEAR(std::remainder(yaw - truth.yaw, 2 * M_PI), 0, 2e-3);
        // The base's own odometry field agrees too.
        EXPECT_NEAR(odo->odometry.x(), truth.x, 2e-3);
        EXPECT_NEAR(odo->odometry.y(), truth.y, 2e-3);
        ++checked;
    }
    EXPECT_GT(checked, 1000);
}

TEST(SimulatorSource, NoisyTicksDrift) {
    registerAllClasses();
    SimulatorSource source(quickOffice(), 1);  // 2 % slip, 0.4 % / 0.3 % wheel scale errors
    double worst = 0;
    while (auto o = source.next()) {
        if (auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o)) {
            const RobotPose t = source.truePose(source.lastTime());
            worst = std::max(worst, std::hypot(odo->odometry.x() - t.x, odo->odometry.y() - t.y));
        }
    }
    EXPECT_GT(worst, 0.01);  // odometry has to be fused with something
    EXPECT_LT(worst, 0.5);   // but it is still odometry
}

TEST(SimulatorSource, KidnapsShowAsWheelDropsWhereTheEventsSay) {
    registerAllClasses();
    Scenario sc = quickOffice();
    KidnapSpec k;
    k.name = "kidnap_1";
    k.start = 8.0;
    k.duration = 4.0;
    k.putDown = {1.5, 2.5, M_PI / 2, 0};
    sc.kidnaps = {k};
    SimulatorSource source(sc, 1);
    const auto events = source.kidnapEvents();
    ASSERT_EQ(events.size(), 1u);
    EXPECT_NEAR(events[0].start - sc.startTime, 8.0, 1e-9);
    EXPECT_NEAR(events[0].end - sc.startTime, 12.0, 1e-9);
    std::vector<std::pair<double, bool>> drops;
    int ticksDuringCarry = -1;
    bool ticksChanged = false;
    while (auto o = source.next()) {
        const double t = mrpt::Clock::toDouble(o->timestamp);
        if (auto w = std::dynamic_pointer_cast<obs::CObservationWheelDrop>(o)) {
            drops.emplace_back(t, w->lifted());
        }
        if (auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o)) {
            if (t > events[0].start + 0.05 && t < events[0].end - 0.05) {
                if (ticksDuringCarry >= 0 && odo->encoderLeftTicks != ticksDuringCarry)
                    ticksChanged = true;
                ticksDuringCarry = odo->encoderLeftTicks;
            }
        }
    }
    ASSERT_EQ(drops.size(), 2u);
    EXPECT_NEAR(drops[0].first, events[0].start, 1e-6);
    EXPECT_TRUE(drops[0].second);
    EXPECT_NEAR(drops[1].first, events[0].end, 1e-6);
    EXPECT_FALSE(drops[1].second);
    EXPECT_FALSE(ticksChanged) << "encoders must stop while the robot is lifted";
    const RobotPose down = source.truePose(12.0);
    EXPECT_NEAR(down.x, 1.5, 1e-9);
    EXPECT_NEAR(down.y, 2.5, 1e-9);
}

TEST(SimulatorSource, MagnetometerReadsTheFieldInItsFrame) {
    registerAllClasses();
    Scenario sc = test::boxScenario();
    sc.field.dipoles.push_back({{2.0, 0.1, -0.2}, {0, 5, 10}});
    sc.camera.enabled = false;
    SimulatorSource source(sc, 1);
    int checked = 0;
    while (auto o = source.next()) {
        auto m = std::dynamic_pointer_cast<obs::CObservationMagnetometer>(o);
        if (!m) continue;
        const RobotPose p = source.truePose(source.lastTime());
        const Eigen::Vector3d sensor(p.x - 0.1 * std::sin(p.yaw), p.y + 0.1 * std::cos(p.yaw), 0.3);
        const Eigen::Vector3d w = source.world().field().at(sensor);
        const double c = std::cos(p.yaw), s = std::sin(p.yaw);
        EXPECT_NEAR(m->field.x, c * w.x() + s * w.y(), 1e-9);  // noise and bias are 0 here
        EXPECT_NEAR(m->field.y, -s * w.x() + c * w.y(), 1e-9);
        EXPECT_NEAR(m->field.z, w.z(), 1e-9);
        ++checked;
    }
    EXPECT_GT(checked, 100);
}

namespace {
using Scan = mrpt::obs::CObservation3DRangeScan;

/** Records `sc` (seed 4) to `path`, then replays the simulator beside the rawlog and hands each
 * RGB-D frame to `check` as rendered and as read back (not yet loaded). Returns the frames. */
template <typename Check>
std::size_t recordAndCompareFrames(const Scenario& sc, const std::string& path,
                                   RecordingSummary* summary, const Check& check) {
    {
        SimulatorSource source(sc, 4);
        const auto r = recordScenario(source, path);
        if (summary) *summary = r;
    }
    SimulatorSource again(sc, 4);
    io::RawlogSource rawlog(path);
    std::size_t frames = 0;
    while (auto expected = again.next()) {
        auto got = rawlog.next();
        EXPECT_TRUE(got);
        if (!got) break;
        auto e = std::dynamic_pointer_cast<Scan>(expected);
        if (!e) continue;
        auto g = std::dynamic_pointer_cast<Scan>(got);
        EXPECT_TRUE(g);
        if (!g) break;
        check(*e, *g, frames);
        ++frames;
    }
    EXPECT_FALSE(rawlog.next());
    return frames;
}
}  // namespace

TEST(SimulatorSource, RecordedFramesWithExternalImagesReadBackExactly) {
    registerAllClasses();
    Scenario sc = quickOffice();
    sc.camera.externalImages = true;
    test::TempDir dir;
    RecordingSummary r;
    const std::size_t frames = recordAndCompareFrames(
        sc, dir.file("office.rawlog"), &r, [](const Scan& e, Scan& g, std::size_t k) {
            ASSERT_TRUE(g.intensityImage.isExternallyStored());
            g.load();
            const cv::Mat a = e.intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
            const cv::Mat b = g.intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
            ASSERT_EQ(a.size(), b.size());
            EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0) << "frame " << k;
            EXPECT_TRUE(e.rangeImage == g.rangeImage);
        });
    EXPECT_EQ(std::filesystem::path(r.imagesDir), dir.path() / "office_Images");
    EXPECT_GT(r.frames, 10u);
    EXPECT_GT(frames, 10u);
}

TEST(SimulatorSource, JpegColourIsWrittenAsJpegAndReadsBackClose) {
    // --image-format jpg: the colour files are JPEGs, a fraction of a PNG's size, and decode to
    // the rendered image within JPEG's loss (quality 90: a few grey levels on average).
    registerAllClasses();
    Scenario sc = quickOffice();
    sc.camera.externalImages = true;
    ASSERT_TRUE(sc.camera.setImageFormat("jpg:90"));
    test::TempDir dir;
    const std::size_t frames = recordAndCompareFrames(
        sc, dir.file("office.rawlog"), nullptr, [](const Scan& e, Scan& g, std::size_t k) {
            EXPECT_NE(g.intensityImage.getExternalStorageFile().find(".jpg"), std::string::npos);
            g.load();
            const cv::Mat a = e.intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
            const cv::Mat b = g.intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
            ASSERT_EQ(a.size(), b.size());
            // What VO sees is the grey image (JPEG keeps luminance at full resolution; colour
            // is subsampled): its mean error, a few grey levels against the renderer's own
            // noise of 2 (measured 2.2-2.9 on this scenario).
            cv::Mat greyA, greyB;
            cv::cvtColor(a, greyA, cv::COLOR_BGR2GRAY);
            cv::cvtColor(b, greyB, cv::COLOR_BGR2GRAY);
            const double meanError =
                cv::norm(greyA, greyB, cv::NORM_L1) / static_cast<double>(greyA.total());
            EXPECT_GT(meanError, 0.0);  // lossy indeed
            EXPECT_LT(meanError, 4.0) << "frame " << k;
            EXPECT_TRUE(e.rangeImage == g.rangeImage);  // depth untouched
        });
    EXPECT_GT(frames, 10u);
}

TEST(SimulatorSource, AWorldSeedKeepsTheBuildingWhateverTheRunsSeed) {
    // Unset: each seed is another building. Set: one building, each seed its own noise.
    const Eigen::Vector3d probe(2.0, 1.5, 0.3);
    Scenario sc = quickOffice();
    const auto field = [&](const Scenario& s, std::uint64_t seed) {
        return SimulatorSource(s, seed).world().field().at(probe);
    };
    EXPECT_GT((field(sc, 1) - field(sc, 2)).norm(), 1e-6);
    sc.worldSeed = 7;
    EXPECT_LT((field(sc, 1) - field(sc, 2)).norm(), 1e-12);
    Scenario other = sc;
    other.worldSeed = 8;
    EXPECT_GT((field(sc, 1) - field(other, 1)).norm(), 1e-6);
    // ... and the runs still differ in their noise.
    registerAllClasses();
    const auto firstReading = [&](std::uint64_t seed) {
        SimulatorSource source(sc, seed);
        while (auto o = source.next()) {
            if (auto m = std::dynamic_pointer_cast<obs::CObservationMagnetometer>(o))
                return Eigen::Vector3d(m->field.x, m->field.y, m->field.z);
        }
        return Eigen::Vector3d(0, 0, 0);
    };
    EXPECT_GT((firstReading(1) - firstReading(2)).norm(), 1e-6);
    // In the INI: [scenario] world_seed, read strictly.
    test::TempDir dir;
    const std::string ini = dir.file("s.ini");
    std::ifstream in(kConfigDir + "/scenarios/office.ini");
    std::ostringstream text;
    text << in.rdbuf();
    std::string withSeed = text.str();
    withSeed.replace(withSeed.find("[scenario]"), 10, "[scenario]\nworld_seed = 3");
    std::ofstream(ini) << withSeed;
    EXPECT_EQ(Scenario::load(ini).worldSeed, std::optional<std::uint64_t>(3));
}
