// A TUM-layout sequence rendered by the simulator imports into a rawlog whose frames and ground
// truth are the simulator's.
#include <gtest/gtest.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/datasets/TumRgbdImport.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/sim/RgbdRenderer.h>
#include <lodestone/sim/SimulatorSource.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <fstream>
#include <iomanip>
#include <opencv2/imgcodecs.hpp>

#include "TestPaths.h"

using namespace lodestone;
namespace fs = std::filesystem;

TEST(TumFromSimulator, RenderedSequenceImportsWithItsGroundTruth) {
    registerAllClasses();
    sim::Scenario sc = sim::Scenario::load(std::string(LODESTONE_CONFIG_INI_DIR) + "/scenarios/office.ini");
    sc.camera.resize(160, 120);
    sim::SimulatorSource source(sc, 1);
    const sim::RgbdRenderer renderer(source.world(), sc.camera, 1);
    test::TempDir dir;
    const fs::path seq = dir.path() / "office_tum";
    fs::create_directories(seq / "rgb");
    fs::create_directories(seq / "depth");
    std::ofstream rgb(seq / "rgb.txt"), depth(seq / "depth.txt");
    rgb << std::fixed << std::setprecision(6);  // as TUM writes them: seconds, 6 decimals
    depth << std::fixed << std::setprecision(6);
    io::TumTrajectoryWriter gt((seq / "groundtruth.txt").string());
    std::vector<cv::Mat_<uint16_t>> rendered;
    sim::Random rng(1);
    for (int k = 0; k < 10; ++k) {
        const double t = 0.5 * k;
        const auto p = source.truePose(t);
        const auto& m = sc.camera.pose;
        const auto s = sim::sensorInWorld(p, m.x, m.y, m.z, m.yaw);
        cv::Mat3b colour;
        cv::Mat_<uint16_t> mm;
        renderer.render(s.position, s.yaw, rng, colour, mm);
        rendered.push_back(mm);
        cv::Mat tum;
        mm.convertTo(tum, CV_16U, 5.0);
        const std::string name = std::to_string(k) + ".png";
        cv::imwrite((seq / "rgb" / name).string(), colour);
        cv::imwrite((seq / "depth" / name).string(), tum);
        rgb << sc.startTime + t << " rgb/" << name << "\n";
        depth << sc.startTime + t + 0.003 << " depth/" << name << "\n";
        gt.write(sc.startTime + t,
                 mrpt::poses::CPose3D(s.position.x(), s.position.y(), s.position.z(), s.yaw, 0, 0));
    }
    rgb.close();
    depth.close();
    gt.close();
    datasets::TumImportOptions o;
    o.intrinsics = {sc.camera.fx, sc.camera.fy, sc.camera.cx, sc.camera.cy};
    const auto r = datasets::importTumRgbd(seq.string(), dir.file("office.rawlog"), o);
    ASSERT_EQ(r.frames, 10u);
    ASSERT_EQ(r.groundTruthPoses, 10u);
    io::RawlogSource rawlog(r.rawlog);
    for (int k = 0; k < 10; ++k) {
        auto s = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(rawlog.next());
        ASSERT_TRUE(s);
        EXPECT_NEAR(mrpt::Clock::toDouble(s->timestamp), sc.startTime + 0.5 * k, 1e-5);
        for (const auto& [y, x] : {std::pair{60, 80}, {100, 20}}) {
            EXPECT_NEAR(s->rangeImage(y, x) * s->rangeUnits, rendered[k](y, x) / 1000.0, 1e-6);
        }
    }
    const auto truth = io::readTumTrajectory(r.groundTruth);
    ASSERT_EQ(truth.size(), 10u);
    EXPECT_NEAR(truth[3].pose.yaw(), sim::sensorInWorld(source.truePose(1.5), 0.1, 0, 0.45, 0).yaw,
                1e-6);
}
