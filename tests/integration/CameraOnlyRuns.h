// The camera-only runs the CameraOnlySlam tests share (test_CameraOnly*.cpp).
#pragma once

#include <mrpt/graphs/TNodeID.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "StockTools.h"
#include "TestPaths.h"

namespace lodestone::test::camera_only {

inline const std::string kSim = LODESTONE_SIM_BINARY;
inline const std::string kSlam = LODESTONE_SLAM_BINARY;
inline const std::string kConfigDir = LODESTONE_CONFIG_INI_DIR;

/** The office seen by the camera alone at 320x240 / 15 Hz (its RGB-D frames kept, and a gyro's
 * samples when `simFlags` asks for one; the ground truth beside); frames [blankFrom, blankTo)
 * covered: a plain grey image and, unless `keepDepth`, no depth either (a covered sensor) - or
 * with `noise`, each frame a new picture of noise (features, none of which match the next
 * frame's). Returns the camera-only rawlog's path. */
std::string cameraOnlyOffice(const lodestone::test::TempDir& dir, int blankFrom = -1,
                             int blankTo = -1, bool keepDepth = false,
                             const std::string& simFlags = "", bool noise = false);
/** The ATE a lodestone-slam run printed (-1: none). */
double ateOf(const std::string& output);
/** rgbd_only.ini with `key = value` set in it, written to `path`. */
std::string rgbdOnlyWith(const std::string& path,
                         const std::vector<std::pair<std::string, std::string>>& keys);
/** The office carried by hand at 320x240 / 15 Hz with a gyro and accelerometer: hand.rawlog and
 * hand.gt.tum in `dir`. */
bool handHeldOfficeWithImu(const lodestone::test::TempDir& dir);
/** A run folder's report.json, whole. */
std::string reportOf(const std::string& dir);
/** lodestone-slam on `dir`'s hand.rawlog (handHeldOfficeWithImu) with rgbd_only.ini and `keys`
 * set in it, into `dir`/`name`: its report.json and how many nodes it made. */
std::pair<std::string, int> runHandHeld(
    const lodestone::test::TempDir& dir, const std::string& name,
    const std::vector<std::pair<std::string, std::string>>& keys);
/** A whole-number value of `key` in a report (-1: not there). */
int countIn(const std::string& report, const std::string& key);
/** A run's node timestamps, from its nodes.csv. */
std::map<mrpt::graphs::TNodeID, double> nodeStamps(const std::string& dir);

}  // namespace lodestone::test::camera_only
