// The camera-only runs the CameraOnlySlam tests share: the office as the camera alone sees it,
// rgbd_only.ini with keys changed, and what a run's outputs say.
#include "CameraOnlyRuns.h"

#include <gtest/gtest.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/io/RawlogWriter.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/odometry/FadingVelocity.h>
#include <mrpt/graphs/CNetworkOfPoses.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationIMU.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <map>
#include <regex>
#include <sstream>


namespace lodestone::test::camera_only {
namespace fs = std::filesystem;

/** The office seen by the camera alone at 320x240 / 15 Hz (its RGB-D frames kept, and a gyro's
 * samples when `simFlags` asks for one; the ground truth beside); frames [blankFrom, blankTo)
 * covered: a plain grey image and, unless `keepDepth`, no depth either (a covered sensor) - or
 * with `noise`, each frame a new picture of noise (features, none of which match the next
 * frame's). Returns the camera-only rawlog's path. */
std::string cameraOnlyOffice(const lodestone::test::TempDir& dir, int blankFrom, int blankTo,
                             bool keepDepth, const std::string& simFlags, bool noise) {
    const auto sim = lodestone::test::runCommand(kSim + " -c " + kConfigDir + "/scenarios/office.ini -o " +
                                                 dir.file("office.rawlog") +
                                                 " --camera 320x240@15 --embedded-images " + simFlags);
    EXPECT_EQ(sim.exitCode, 0) << sim.output;
    lodestone::registerAllClasses();
    const std::string out = dir.file("camera.rawlog");
    lodestone::io::RawlogSource in(dir.file("office.rawlog"));
    lodestone::io::RawlogWriter writer(out, {0});
    int frame = 0;
    while (auto obs = in.next()) {
        auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs);
        if (!scan) {
            if (std::dynamic_pointer_cast<mrpt::obs::CObservationIMU>(obs)) writer.write(*obs);  // a gyro
            continue;
        }
        if (frame >= blankFrom && frame < blankTo) {
            // A lens covered: a plain grey image, nothing for VO to track.
            cv::Mat image(static_cast<int>(scan->cameraParams.nrows),
                          static_cast<int>(scan->cameraParams.ncols), CV_8UC3, cv::Scalar(128, 128, 128));
            if (noise) cv::RNG(static_cast<std::uint64_t>(frame)).fill(image, cv::RNG::UNIFORM, 0, 256);
            scan->intensityImage = mrpt::img::CImage(image, mrpt::img::DEEP_COPY);
            if (!keepDepth) scan->rangeImage.setZero();
        }
        writer.write(*scan);
        ++frame;
    }
    writer.close();
    fs::copy_file(dir.file("office.gt.tum"), dir.file("camera.gt.tum"));
    return out;
}

double ateOf(const std::string& output) {
    std::smatch m;
    return std::regex_search(output, m, std::regex("ATE RMSE ([0-9.]+) m")) ? std::stod(m[1]) : -1;
}

/** rgbd_only.ini with `key = value` set in it, written to `path`. */
std::string rgbdOnlyWith(const std::string& path, const std::vector<std::pair<std::string, std::string>>& keys) {
    std::ifstream base(kConfigDir + "/slam/rgbd_only.ini");
    std::string ini((std::istreambuf_iterator<char>(base)), std::istreambuf_iterator<char>());
    for (const auto& [key, value] : keys) {
        const std::regex line("\n" + key + " *= *[0-9.a-z]+");
        EXPECT_TRUE(std::regex_search(ini, line)) << key;
        ini = std::regex_replace(ini, line, "\n" + key + " = " + value);
    }
    std::ofstream(path) << ini;
    return path;
}

/** The office carried by hand at 320x240 / 15 Hz with a gyro and accelerometer: hand.rawlog and
 * hand.gt.tum in `dir`. */
bool handHeldOfficeWithImu(const lodestone::test::TempDir& dir) {
    const auto sim = lodestone::test::runCommand(kSim + " -c " + kConfigDir + "/scenarios/office.ini -o " +
                                                 dir.file("hand.rawlog") +
                                                 " --camera 320x240@15 --embedded-images --handheld --gyro");
    EXPECT_EQ(sim.exitCode, 0) << sim.output;
    return sim.exitCode == 0;
}

std::string reportOf(const std::string& dir) {
    std::ifstream in(dir + "/report.json");
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/** lodestone-slam on `dir`'s hand.rawlog (handHeldOfficeWithImu) with rgbd_only.ini and `keys`
 * set in it, into `dir`/`name`: its report.json and how many nodes it made. */
std::pair<std::string, int> runHandHeld(
    const lodestone::test::TempDir& dir, const std::string& name,
    const std::vector<std::pair<std::string, std::string>>& keys) {
    const auto run = lodestone::test::runCommand(
        kSlam + " --rawlog " + dir.file("hand.rawlog") + " --config " +
        rgbdOnlyWith(dir.file(name + ".ini"), keys) + " --out " + dir.file(name) +
        " --ground-truth " + dir.file("hand.gt.tum") + " --quiet");
    EXPECT_EQ(run.exitCode, 0) << run.output;
    std::smatch nodes;
    EXPECT_TRUE(std::regex_search(run.output, nodes, std::regex("([0-9]+) nodes"))) << run.output;
    return std::make_pair(reportOf(dir.file(name)), nodes.size() > 1 ? std::stoi(nodes[1]) : -1);
}

/** A whole-number value of `key` in a report (-1: not there). */
int countIn(const std::string& report, const std::string& key) {
    std::smatch m;
    return std::regex_search(report, m, std::regex("\"" + key + "\": ([0-9]+)")) ? std::stoi(m[1])
                                                                                 : -1;
}

/** A run's node timestamps, from its nodes.csv. */
std::map<mrpt::graphs::TNodeID, double> nodeStamps(const std::string& dir) {
    std::map<mrpt::graphs::TNodeID, double> stamps;
    std::ifstream nodes(dir + "/nodes.csv");
    std::string line;
    std::getline(nodes, line);  // (header)
    while (std::getline(nodes, line)) {
        std::istringstream fields(line);
        std::string id, stamp;
        std::getline(fields, id, ',');
        std::getline(fields, stamp, ',');
        stamps[std::stoul(id)] = std::stod(stamp);
    }
    return stamps;
}

}  // namespace lodestone::test::camera_only
