// Writes the fuzz targets' seed corpora (tests/fuzz/corpus) and the regression inputs built
// from the first fuzzing's findings (tests/fuzz/regression): small, and reproducible from this file.
//   make_fuzz_seeds <tests/fuzz> <repository root>
// The committed files are this tool's output; rerun it when a format changes.
#include <lodestone/obs/CObservationWheelDrop.h>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "../FuzzInput.h"
#include "MrptBytes.h"
#include "SampleObservations.h"

namespace fs = std::filesystem;
using namespace lodestone;

namespace {
fs::path fuzzRoot, repoRoot;

void write(const std::string& kind, const std::string& target, const std::string& name,
           const std::string& bytes) {
    const fs::path dir = fuzzRoot / kind / target;
    fs::create_directories(dir);
    std::ofstream(dir / name, std::ios::binary | std::ios::trunc) << bytes;
    std::cout << (dir / name).string() << " (" << bytes.size() << " bytes)\n";
}

std::string fileBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

using test::framedObject;
using test::nullObjectBytes;
using test::rawBytes;
using test::serializedBytes;

/** An object's version byte and body: what fuzz_observation takes after its class byte. */
std::string versionAndBody(const std::string& bytes) {
    const std::size_t nameLength = static_cast<unsigned char>(bytes[0]) & 0x7F;
    return bytes.substr(1 + nameLength, bytes.size() - 1 - nameLength - 1);
}

std::string rawlogOf(const std::vector<mrpt::obs::CObservation::Ptr>& observations) {
    std::string bytes;
    for (const auto& o : observations) bytes += serializedBytes(*o);
    return bytes;
}

obs::CObservationWheelDrop::Ptr wheelDrop(double t, bool dropped) {
    auto w = obs::CObservationWheelDrop::Create();
    w->timestamp = mrpt::Clock::fromDouble(t);
    w->sensorLabel = "DROP";
    w->leftDropped = dropped;
    w->rightDropped = dropped;
    return w;
}

std::string actionsAndFrames() {
    std::string bytes;
    for (int k = 0; k < 2; ++k) {
        mrpt::obs::CActionCollection actions;
        mrpt::obs::CActionRobotMovement2D move;
        move.computeFromOdometry(mrpt::poses::CPose2D(0.1, 0, 0.05), {});
        move.timestamp = mrpt::Clock::fromDouble(1.7e9 + k);
        move.hasEncodersInfo = true;
        move.encoderLeftTicks = 100;
        move.encoderRightTicks = 110;
        actions.insert(move);
        mrpt::obs::CSensoryFrame frame;
        frame.insert(test::makeMagnetometer(1.7e9 + k + 0.5, "MAG", k));
        bytes += serializedBytes(actions) + serializedBytes(frame);
    }
    return bytes;
}

void rawlogSeeds() {
    const std::string observations = rawlogOf({test::makeMagnetometer(1.7e9, "MAG_LEFT", 1),
                                               test::makeImu(1.7e9 + 0.01, "IMU", 2),
                                               test::makeOdometry(1.7e9 + 0.02, 3),
                                               wheelDrop(1.7e9 + 0.03, true),
                                               test::makeRangeScan(1.7e9 + 0.04, 8, 6, 4)});
    write("corpus", "fuzz_rawlog", "observations.rawlog", observations);
    write("corpus", "fuzz_rawlog", "actions_frames.rawlog", actionsAndFrames());
    const auto* o = reinterpret_cast<const std::uint8_t*>(observations.data());
    write("corpus", "fuzz_rawlog_gz", "compress_here", std::string(1, '\0') + observations);
    write("corpus", "fuzz_rawlog_gz", "gzip_bytes", "\x01" + fuzz::gzipCompress(o, observations.size()));
}

void regressionRawlogs() {
    // The first fuzzing's findings, rebuilt: each crashed or ran away before the guards.
    const std::string nullPdf =
        framedObject("CActionCollection", 0,
               rawBytes<std::uint32_t>(1) +
                   framedObject("CActionRobotMovement2D", 1,
                          nullObjectBytes() + rawBytes<std::int32_t>(0) + rawBytes<std::uint8_t>(1) + rawBytes(0.f) +
                              rawBytes(0.f) + rawBytes<std::uint8_t>(0) + rawBytes<std::int32_t>(0) + rawBytes<std::int32_t>(0)));
    write("regression", "fuzz_rawlog", "action2d_v1_null_pdf.rawlog", nullPdf);
    write("regression", "fuzz_rawlog", "action2d_v0_null_pdf.rawlog",
          framedObject("CActionCollection", 0,
                 rawBytes<std::uint32_t>(1) + framedObject("CActionRobotMovement2D", 0, nullObjectBytes() + rawBytes<std::int32_t>(0))));
    write("regression", "fuzz_rawlog", "action_collection_null_action.rawlog",
          framedObject("CActionCollection", 0, rawBytes<std::uint32_t>(1) + nullObjectBytes()));
    write("regression", "fuzz_rawlog", "action_collection_count_ffffffff.rawlog",
          framedObject("CActionCollection", 0, rawBytes<std::uint32_t>(0xFFFFFFFFu)));
    write("regression", "fuzz_rawlog", "sensory_frame_null_observation.rawlog",
          framedObject("CSensoryFrame", 2, rawBytes<std::uint32_t>(1) + nullObjectBytes()));
    // A magnetometer whose label length reads 0xF0000000.
    std::string label = rawlogOf({test::makeMagnetometer(1.0, "MAGB", 2)});
    const std::string length4 = rawBytes<std::uint32_t>(4) + "MAGB";
    label.replace(label.find(length4), length4.size(), rawBytes<std::uint32_t>(0xF0000000u) + "MAGB");
    write("regression", "fuzz_rawlog", "magnetometer_label_f0000000.rawlog", label);
    // A range image of 100 000 x 100 000 pixels.
    std::string range = rawlogOf({test::makeRangeScan(2.0, 64, 48, 1.0)});
    const std::string dims = rawBytes<std::uint32_t>(48) + rawBytes<std::uint32_t>(64);
    if (const auto at = range.find(dims); at != std::string::npos) {
        range.replace(at, dims.size(), rawBytes<std::uint32_t>(100000) + rawBytes<std::uint32_t>(100000));
        write("regression", "fuzz_rawlog", "range_image_100000_squared.rawlog", range);
    }
    // A wheel-drop flag byte of 127 (MRPT copies bytes into bools).
    std::string bad = rawlogOf({wheelDrop(3.0, true)});
    if (const auto at = bad.rfind(std::string("\x01\x01", 2)); at != std::string::npos) {
        bad[at] = 127;
        write("regression", "fuzz_rawlog", "wheel_drop_bool_127.rawlog", bad);
    }
    // A gzip stream cut in the middle, and one with garbage after its end.
    const std::string gz = fuzz::gzipCompress(reinterpret_cast<const std::uint8_t*>(label.data()), label.size());
    write("regression", "fuzz_rawlog_gz", "truncated", "\x01" + gz.substr(0, gz.size() / 2));
    write("regression", "fuzz_rawlog_gz", "garbage_appended", "\x01" + gz + "garbage after the gzip member");
    write("regression", "fuzz_rawlog_gz", "empty_gzip", "\x01" + fuzz::gzipCompress(nullptr, 0));
}

void observationSeeds() {
    write("corpus", "fuzz_observation", "magnetometer",
          std::string(1, '\0') + versionAndBody(serializedBytes(*test::makeMagnetometer(1.7e9, "MAG", 1))));
    write("corpus", "fuzz_observation", "wheel_drop", "\x01" + versionAndBody(serializedBytes(*wheelDrop(1.7e9, true))));
    write("corpus", "fuzz_observation", "magnetometer_v0",
          std::string(1, '\0') + versionAndBody(fileBytes(repoRoot / "tests/data/CObservationMagnetometer_v0.bin")));
}

void textSeeds() {
    write("corpus", "fuzz_magnetic_csv", "kok",
          std::string(1, '\0') +
              "t,tm,px,py,pz,q0,q1,q2,q3,mx,my,mz\n"
              "0.00,0.00,0.0,0.0,1.0,1,0,0,0,20.1,1.5,-40.2\n"
              "0.01,0.01,0.01,0.0,1.0,1,0,0,0,20.3,1.4,-40.1\n"
              "0.02,0.02,0.02,0.0,1.0,0.9998,0,0,0.02,20.4,1.2,-40.3\n");
    write("corpus", "fuzz_magnetic_csv", "aalto",
          "\x01"
          "0\n0.01\n0.02\n0.03\n%%\n0,0\n0.01,0\n0.02,0.001\n0.03,0.002\n%%\n"
          "20,0,-40\n20.5,0.2,-40.1\n21,0.1,-39.8\n20.7,0.3,-40\n");
    write("corpus", "fuzz_tum_trajectory", "trajectory.tum",
          "# timestamp tx ty tz qx qy qz qw\n"
          "1305031102.175304 1.3405 0.6266 1.6575 0.6574 0.6126 -0.2949 -0.3248\n"
          "1305031102.211214 1.3303 0.6256 1.6464 0.6579 0.6161 -0.2932 -0.3189\n"
          "1305031102.275326 1.3160 0.6254 1.6302 0.6609 0.6199 -0.2893 -0.3086\n");
    write("corpus", "fuzz_tum_rgbd", "sequence",
          "# color images\n1305031102.175304 rgb/1305031102.175304.png\n"
          "1305031102.211214 rgb/1305031102.211214.png\n%%\n"
          "# depth maps\n1305031102.160407 depth/1305031102.160407.png\n"
          "1305031102.226738 depth/1305031102.226738.png\n%%\n"
          "1305031102.1758 1.3405 0.6266 1.6575 0.6574 0.6126 -0.2949 -0.3248\n");
    write("corpus", "fuzz_ini", "slam.ini", std::string(1, '\0') + fileBytes(repoRoot / "config_ini/slam/slam.ini"));
    write("corpus", "fuzz_ini", "office_scenario.ini", "\x01" + fileBytes(repoRoot / "config_ini/scenarios/office.ini"));
    write("regression", "fuzz_tum_trajectory", "zero_quaternion.tum", "1.0 0 0 0 0 0 0 0\n");
    write("regression", "fuzz_tum_trajectory", "huge_x.tum", "1.0 1e308 0 0 0 0 0 1\n");
    write("regression", "fuzz_tum_trajectory", "time_backwards.tum", "2.0 0 0 0 0 0 0 1\n1.0 0 0 0 0 0 0 1\n");
    write("regression", "fuzz_magnetic_csv", "kok_header_only", std::string(1, '\0') + "t,tm,px,py,pz,q0,q1,q2,q3,mx,my,mz\n");
    write("regression", "fuzz_magnetic_csv", "kok_inf",
          std::string(1, '\0') + "t,tm,px,py,pz,q0,q1,q2,q3,mx,my,mz\n0,0,inf,0,0,1,0,0,0,1,2,3\n1,1,0,0,0,1,0,0,0,1,2,3\n");
}
}  // namespace

// A saved map (lodestone-slam --map-out) as fuzz_map reads it: manifest.ini, config.ini,
// graph.bin and nodes.bin of the golden map (tests/data/map_v1) joined by "%%" lines.
void mapSeeds() {
    const fs::path golden = repoRoot / "tests" / "data" / "map_v1";
    std::string joined;
    for (const char* name : {"manifest.ini", "config.ini", "graph.bin", "nodes.bin"}) {
        if (!joined.empty()) joined += "\n%%\n";
        joined += fileBytes(golden / name);
    }
    write("corpus", "fuzz_map", "map_v1", joined);
    // Found by fuzz_map: MRPT's INI parser throws on an unclosed "$env{" in the manifest.
    write("regression", "fuzz_map", "manifest_env",
          fileBytes(golden / "manifest.ini") + "x = $env{resGSO\n%%\n");
    // Found by fuzz_map: a bool field read as the byte 111 (undefined behaviour, UBSan). The
    // first node's keyframe flag: after its class name, version byte and 40 bytes of fields.
    std::string nodes = fileBytes(golden / "nodes.bin");
    nodes[nodes.find("CMapNode") + 8 + 1 + 40] = 111;
    joined.clear();
    for (const char* name : {"manifest.ini", "config.ini", "graph.bin"}) {
        joined += fileBytes(golden / name) + "\n%%\n";
    }
    write("regression", "fuzz_map", "keyframe_not_bool", joined + nodes);
    // Found by fuzz_map: the node file's header string asking for 2 GB (its length, the first
    // four bytes), read before the per-node allocation budget.
    std::string header = fileBytes(golden / "nodes.bin");
    header.replace(0, 4, std::string("\xff\xff\xff\x7f", 4));
    write("regression", "fuzz_map", "header_length", joined + header);
    // Found by fuzz_map: a count in the manifest beyond size_t's range (undefined behaviour
    // when cast).
    std::string manifest = fileBytes(golden / "manifest.ini");
    manifest.replace(manifest.find("nodes             = 12"), 22, "nodes             = 4e92");
    write("regression", "fuzz_map", "count_too_large", manifest + "%%\n");
    // Found by fuzz_map: a magnetometer label holding a line break read, then written into
    // the manifest where it began a section of its own.
    std::string label = fileBytes(golden / "nodes.bin");
    label.replace(label.find("MAG_L"), 5, "M\n[x]");
    write("regression", "fuzz_map", "label_line_break", joined + label);
    // Found by fuzz_map: a label ending in a backslash, which continued the manifest's
    // magnetometers line over the next key (node_decider) when the map was written back.
    std::string backslash = fileBytes(golden / "nodes.bin");
    backslash.replace(backslash.find("MAG_L"), 5, "MAG_\\");
    write("regression", "fuzz_map", "label_backslash", joined + backslash);
}

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: make_fuzz_seeds <tests/fuzz> <repository root>\n";
        return 2;
    }
    fuzzRoot = argv[1];
    repoRoot = argv[2];
    registerAllClasses();
    rawlogSeeds();
    regressionRawlogs();
    observationSeeds();
    textSeeds();
    mapSeeds();
    return 0;
}
