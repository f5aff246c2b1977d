#include <lodestone/config/CommandLine.h>
#include <lodestone/inspect/EntryText.h>
#include <InspectApp.h>
#include <lodestone/inspect/MagnetometerToImu.h>
#include <lodestone/inspect/RawlogSummary.h>
#include <lodestone/inspect/SensorExport.h>
#include <lodestone/inspect/report/RawlogReport.h>
#include <lodestone/io/EntryContents.h>
#include <lodestone/io/ImagesDirectory.h>
#include <lodestone/io/RawlogReadError.h>
#include <lodestone/io/RawlogReader.h>
#include <lodestone/maps/MapPicture.h>
#include <lodestone/maps/MapSummary.h>
#include <lodestone/maps/SavedMap.h>
#include <lodestone/dense/TsdfFusion.h>
#include <lodestone/graphslam/Se3Pose.h>
#include <lodestone/io/RawlogSource.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/outputs/NodeTable.h>
#include <lodestone/slamapp/KeyframeMeshPass.h>
#include <mrpt/config/CConfigFile.h>
#include <opencv2/imgcodecs.hpp>
#include <lodestone/obs/registerAllClasses.h>
#include <mrpt/img/CImage.h>
#include <mrpt/obs/CActionCollection.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <map>
#include <vector>

#include <unistd.h>

namespace lodestone::inspect {

namespace {

using Args = std::vector<std::string>;

// Thrown by a subcommand for bad input (missing file, label absent, ...): exit code 1.
struct BadInput : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Thrown for a command line that cannot be parsed: exit code 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Parses a subcommand's arguments; returns false after --help printed the usage.
bool parse(TCLAP::CmdLine& cmd, const std::string& name, const Args& args) {
    std::vector<std::string> words = {"lodestone-inspect " + name};
    words.insert(words.end(), args.begin(), args.end());
    const auto outcome = config::parseCommandLine(cmd, words);
    if (outcome.kind == config::ParseOutcome::Kind::UsageError) throw UsageError(outcome.error);
    return outcome.kind == config::ParseOutcome::Kind::Run;
}

// Two positional arguments, in command-line order. (One multi-argument rather than two
// single ones: MRPT's TCLAP was seen to fill two unlabeled arguments in reverse order in an
// ASan build.)
std::pair<std::string, std::string> twoPositionals(TCLAP::UnlabeledMultiArg<std::string>& a,
                                                   const std::string& names) {
    if (a.getValue().size() != 2) {
        throw UsageError("expected exactly two arguments: " + names);
    }
    return {a.getValue()[0], a.getValue()[1]};
}

int summary(const Args& args, std::ostream& out) {
    TCLAP::CmdLine cmd("Format, time span, classes and per-sensor rates and gaps of a rawlog", ' ',
                       "");
    TCLAP::UnlabeledValueArg<std::string> file("FILE", "rawlog (plain or .gz)", true, "", "FILE",
                                               cmd);
    if (!parse(cmd, "summary", args)) return kExitOk;
    const auto s = summarizeRawlog(file.getValue());
    printSummary(s, out);
    return s.error ? kExitBadInput : kExitOk;
}

int list(const Args& args, std::ostream& out) {
    TCLAP::CmdLine cmd("One line per entry: index, time, class, label, short content", ' ', "");
    TCLAP::UnlabeledValueArg<std::string> file("FILE", "rawlog (plain or .gz)", true, "", "FILE",
                                               cmd);
    TCLAP::ValueArg<std::size_t> from("", "from", "first entry index (default 0)", false, 0, "N",
                                      cmd);
    TCLAP::ValueArg<std::size_t> to("", "to", "last entry index (default: the end)", false,
                                    std::numeric_limits<std::size_t>::max(), "M", cmd);
    TCLAP::ValueArg<std::string> sensor("", "sensor", "only observations with this label", false,
                                        "", "LABEL", cmd);
    if (!parse(cmd, "list", args)) return kExitOk;
    io::RawlogReader reader(file.getValue());
    const auto wanted = [&](const mrpt::obs::CObservation& o) {
        return !sensor.isSet() || o.sensorLabel == sensor.getValue();
    };
    while (auto entry = reader.next()) {
        if (entry->index < from.getValue()) continue;
        if (entry->index > to.getValue()) break;
        const auto& object = entry->object;
        if (auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(object)) {
            if (wanted(*obs)) out << entry->index << "  " << observationLine(*obs) << "\n";
            continue;
        }
        const auto inside = io::observationsOf(object);
        if (auto acts = std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(object)) {
            if (sensor.isSet()) continue;
            out << entry->index << "  " << object->GetRuntimeClass()->className << "  "
                << acts->size() << " action(s):";
            for (const auto& a : *acts) out << " " << a->GetRuntimeClass()->className;
            out << "\n";
            continue;
        }
        if (!sensor.isSet()) {
            out << entry->index << "  " << object->GetRuntimeClass()->className << "  "
                << inside.size() << " observation(s)\n";
        }
        for (std::size_t j = 0; j < inside.size(); ++j) {
            if (wanted(*inside[j])) {
                out << entry->index << "." << j << "  " << observationLine(*inside[j]) << "\n";
            }
        }
    }
    return kExitOk;
}

int show(const Args& args, std::ostream& out) {
    TCLAP::CmdLine cmd("The full description of one entry", ' ', "");
    TCLAP::UnlabeledMultiArg<std::string> words("FILE_N", "FILE (rawlog) then N (entry index)",
                                                true, "FILE N", cmd);
    if (!parse(cmd, "show", args)) return kExitOk;
    const auto [file, n] = twoPositionals(words, "FILE N");
    std::size_t wanted = 0;
    try {
        std::size_t used = 0;
        wanted = std::stoul(n, &used);
        if (used != n.size()) throw std::invalid_argument(n);
    } catch (const std::exception&) {
        throw UsageError("N: expected an entry index, got '" + n + "'");
    }
    io::RawlogReader reader(file);
    mrpt::img::CImage::setImagesPathBase(io::findImagesDirectory(file));
    std::size_t seen = 0;
    while (auto entry = reader.next()) {
        ++seen;
        if (entry->index == wanted) {
            out << "Entry " << entry->index << " at byte offset " << entry->byteOffset << "\n";
            describeEntry(*entry->object, out);
            return kExitOk;
        }
    }
    throw BadInput(file + ": no entry " + std::to_string(wanted) + " (the rawlog has " +
                   std::to_string(seen) + " entries)");
}

int exportCmd(const Args& args, std::ostream& out) {
    TCLAP::CmdLine cmd(
        "Export one sensor: series (magnetometer, IMU, odometry, ...) as CSV, RGB-D frames as "
        "PNG (8-bit RGB, 16-bit depth)",
        ' ', "");
    TCLAP::UnlabeledValueArg<std::string> file("FILE", "rawlog (plain or .gz)", true, "", "FILE",
                                               cmd);
    TCLAP::ValueArg<std::string> sensor("", "sensor", "sensor label to export", true, "", "LABEL",
                                        cmd);
    TCLAP::ValueArg<std::string> dir("", "out", "output directory (created)", true, "", "DIR", cmd);
    if (!parse(cmd, "export", args)) return kExitOk;
    const auto r = exportSensor(file.getValue(), sensor.getValue(), dir.getValue());
    if (!r.seriesFile.empty()) out << r.seriesRows << " rows -> " << r.seriesFile << "\n";
    if (!r.framesIndex.empty()) out << r.frames << " RGB-D frames -> " << r.framesIndex << "\n";
    if (r.skipped) out << r.skipped << " observation(s) of a class with no export format\n";
    return kExitOk;
}

int toImu(const Args& args, std::ostream& out) {
    TCLAP::CmdLine cmd(
        "Rewrite magnetometers as CObservationIMU (IMU_MAG_X/Y/Z) so stock MRPT tools can open "
        "the rawlog",
        ' ', "");
    TCLAP::UnlabeledMultiArg<std::string> words(
        "FILE_OUT", "FILE (input rawlog) then OUT (output rawlog; .gz: compressed)", true,
        "FILE OUT", cmd);
    TCLAP::ValueArg<std::string> unit("", "unit",
                                      "IMU magnetometer unit: gauss (MRPT's documented unit), uT, "
                                      "T or normalized:<local field uT>",
                                      false, "gauss", "UNIT", cmd);
    if (!parse(cmd, "to-imu", args)) return kExitOk;
    lodestone::obs::MagneticUnit imuUnit;
    try {
        imuUnit = lodestone::obs::MagneticUnit::parse(unit.getValue());
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--unit: ") + e.what());
    }
    const auto [in, outFile] = twoPositionals(words, "FILE OUT");
    const auto r = magnetometersToImu(in, outFile, imuUnit);
    out << r.entries << " entries written to " << outFile << ", " << r.converted
        << " magnetometer observation(s) rewritten as CObservationIMU";
    if (r.commented) out << ", " << r.commented << " wheel drop(s) as CObservationComment";
    out << "\n";
    return kExitOk;
}

int reportCmd(const Args& args, std::ostream& out) {
    TCLAP::CmdLine cmd(
        "A visual report of a rawlog (and of a lodestone-slam run on it): DIR/index.html with "
        "PNG charts and camera thumbnails beside it, self-contained",
        ' ', "");
    TCLAP::UnlabeledValueArg<std::string> file("FILE", "rawlog (plain or .gz)", true, "", "FILE",
                                               cmd);
    TCLAP::ValueArg<std::string> dir("", "out", "report folder (created)", true, "", "DIR", cmd);
    TCLAP::ValueArg<std::string> slam("", "slam", "a lodestone-slam --out folder of a run on FILE",
                                      false, "", "SLAM_OUT", cmd);
    TCLAP::ValueArg<std::string> gt("", "ground-truth",
                                    "TUM trajectory to compare the SLAM run with (default: "
                                    "SLAM_OUT/ground_truth.tum if there)",
                                    false, "", "GT.tum", cmd);
    TCLAP::ValueArg<double> every("", "thumbnail-every", "seconds between camera thumbnails",
                                  false, 10.0, "S", cmd);
    TCLAP::ValueArg<double> gapFactor("", "gap-factor",
                                      "a gap is a step longer than this times the sensor's "
                                      "median step",
                                      false, 5.0, "K", cmd);
    TCLAP::ValueArg<double> cell("", "field-cell", "field map cell size [m]", false, 0.1, "M", cmd);
    TCLAP::ValueArg<std::string> mapDir("", "map",
                                        "a saved map (lodestone-slam --map-out) shown on the page: "
                                        "its summary and the map from above",
                                        false, "", "MAP_DIR", cmd);
    TCLAP::SwitchArg quiet("q", "quiet", "no progress bar", cmd);
    if (!parse(cmd, "report", args)) return kExitOk;
    if (!(every.getValue() > 0)) throw UsageError("--thumbnail-every: must be > 0");
    if (!(gapFactor.getValue() > 1)) throw UsageError("--gap-factor: must be > 1");
    if (!(cell.getValue() > 0)) throw UsageError("--field-cell: must be > 0");
    if (gt.isSet() && !slam.isSet()) throw UsageError("--ground-truth needs --slam");
    report::ReportOptions o;
    o.rawlog = file.getValue();
    o.outDir = dir.getValue();
    o.slamDir = slam.getValue();
    o.groundTruth = gt.getValue();
    o.thumbnailEvery = every.getValue();
    o.gapFactor = gapFactor.getValue();
    o.fieldCell = cell.getValue();
    o.quiet = quiet.getValue();
    o.terminal = ::isatty(STDERR_FILENO) != 0;
    if (mapDir.isSet()) {
        // Read (and refused if damaged) before any work; its picture goes beside the page.
        const auto map = maps::readMap(mapDir.getValue());
        std::ostringstream text;
        maps::printMapSummary(maps::summarizeMap(map, mapDir.getValue()), text);
        std::filesystem::create_directories(o.outDir);
        const std::string png = (std::filesystem::path(o.outDir) / "saved_map.png").string();
        if (!cv::imwrite(png, maps::drawMap(map))) throw BadInput(png + ": cannot be written");
        o.extraSections.push_back(
            {"Saved map", text.str(),
             {{"saved_map.png", "The saved map from above: |B| of its readings over the floor, "
                                "each session's path, keyframes"}}});
    }
    const auto r = report::writeRawlogReport(o, std::cerr);
    out << r.entries << " entries, " << r.figures << " charts, " << r.thumbnails
        << " thumbnails -> " << r.index << "\n";
    if (r.readError) {
        throw BadInput(*r.readError + " (the report shows what was read before it)");
    }
    return kExitOk;
}

int mapCmd(const Args& args, std::ostream& out) {
    TCLAP::CmdLine cmd("A saved map (lodestone-slam --map-out): sessions, nodes, keyframes, "
                       "readings, extent, sensors, configuration, size on disk",
                       ' ', "");
    TCLAP::UnlabeledValueArg<std::string> dir("DIR", "map folder", true, "", "DIR", cmd);
    TCLAP::ValueArg<std::string> picture("p", "plot",
                                         "the map from above: |B| over the floor, each session's "
                                         "path, keyframes",
                                         false, "", "PNG", cmd);
    if (!parse(cmd, "map", args)) return kExitOk;
    const auto map = maps::readMap(dir.getValue());
    maps::printMapSummary(maps::summarizeMap(map, dir.getValue()), out);
    if (picture.isSet() && !cv::imwrite(picture.getValue(), maps::drawMap(map)))
        throw BadInput(picture.getValue() + ": cannot be written");
    return kExitOk;
}

// The keyframes of a finished run's folder (nodes.csv at trajectory.tum's poses), by time; every
// `every`-th, the first segment's unless `allSegments`.
std::map<double, Eigen::Isometry3d> runKeyframes(const std::string& run, bool allSegments, int every) {
    const auto nodes = outputs::readNodeTable(run + "/nodes.csv");
    std::map<double, Eigen::Isometry3d> byTime, keyframes;
    for (const auto& p : io::readTumTrajectory(run + "/trajectory.tum")) byTime[p.timestamp] = graphslam::isometryOf(p.pose);
    int k = 0;
    for (const auto& n : nodes) {
        if (!n.keyframe || (n.segment != 0 && !allSegments)) continue;
        const auto it = byTime.lower_bound(n.timestamp - 1e-6);
        if (it == byTime.end() || std::abs(it->first - n.timestamp) > 1e-6) continue;  // (not in the trajectory)
        if (k++ % every == 0) keyframes[n.timestamp] = it->second;
    }
    if (keyframes.empty()) throw BadInput(run + "/nodes.csv: no keyframe with a pose in trajectory.tum");
    return keyframes;
}

// The keyframes of one session of a saved map, at the map's poses, by time.
std::map<double, Eigen::Isometry3d> mapKeyframes(const std::string& dir, std::uint32_t session, int every) {
    const auto map = maps::readMap(dir);
    std::map<double, Eigen::Isometry3d> keyframes;
    int k = 0;
    for (std::size_t id = 0; id < map.nodes.size(); ++id) {
        if (!map.nodes[id].keyframe || map.sessions[id] != session || !map.graph.nodes.count(id)) continue;
        if (k++ % every == 0) keyframes[map.nodes[id].timestamp] = graphslam::isometryOf(map.graph.nodes.at(id));
    }
    if (keyframes.empty())
        throw BadInput(dir + ": no keyframe in session " + std::to_string(session) + " of " +
                       std::to_string(map.manifest.sessions));
    return keyframes;
}

int meshCmd(const Args& args, std::ostream& out) {
    TCLAP::CmdLine cmd("The dense model of a finished run or a saved map: the keyframes' frames read from "
                       "the rawlog and fused at their optimized poses (as lodestone-slam --mesh) into "
                       "DIR/mesh.ply",
                       ' ', "");
    TCLAP::UnlabeledValueArg<std::string> dir(
        "DIR", "a lodestone-slam output folder (nodes.csv, trajectory.tum) or a saved map (--map-out)", true, "",
        "DIR", cmd);
    TCLAP::ValueArg<std::string> rawlog("r", "rawlog", "the rawlog the run read (a map: its session's)", true, "",
                                        "FILE", cmd);
    TCLAP::ValueArg<std::string> ini("c", "config", "an INI whose [dense] keys to use (default: their defaults)",
                                     false, "", "INI", cmd);
    TCLAP::ValueArg<std::string> meshOut("o", "out", "where to write the mesh (default DIR/mesh.ply)", false, "",
                                         "PLY", cmd);
    TCLAP::SwitchArg allSegments("", "all-segments",
                                 "a run: fuse every segment's keyframes, not only the first's (for runs whose "
                                 "kidnapped segments were all joined to the map)",
                                 cmd);
    TCLAP::ValueArg<unsigned> session("", "session", "a map: the session the rawlog recorded (0: the first)", false,
                                      0, "N", cmd);
    if (!parse(cmd, "mesh", args)) return kExitOk;
    const std::string where = dir.getValue();
    const dense::DenseParams params =
        ini.isSet() ? dense::DenseParams::read(mrpt::config::CConfigFile(ini.getValue())) : dense::DenseParams();
    const auto keyframes = std::filesystem::exists(where + "/nodes.csv")
                               ? runKeyframes(where, allSegments.getValue(), params.everyKeyframe)
                               : mapKeyframes(where, session.getValue(), params.everyKeyframe);
    io::RawlogSource source(rawlog.getValue());
    dense::TsdfFusion fusion(params);
    const auto pass = slamapp::fuseKeyframes(source, keyframes, fusion);
    if (pass.framesFound == 0)
        throw BadInput(rawlog.getValue() + ": none of the " + std::to_string(keyframes.size()) +
                       " keyframe times has an RGB-D frame - is this the run's rawlog?");
    const dense::Mesh mesh = fusion.extractMesh();
    if (mesh.empty()) throw BadInput(rawlog.getValue() + ": the keyframes' frames had no usable depth");
    const std::string path = meshOut.isSet() ? meshOut.getValue() : where + "/mesh.ply";
    dense::writeMeshPly(path, mesh);
    out << path << ": " << mesh.vertices.size() << " vertices, " << mesh.triangles.size() << " triangles from "
        << fusion.framesFused() << " of " << keyframes.size() << " keyframes\n";
    return kExitOk;
}

void printUsage(std::ostream& out) {
    out << "lodestone-inspect: look inside MRPT rawlogs (stock and Lodestone's)\n\n"
           "usage: lodestone-inspect <command> [options]   (<command> --help for its options)\n"
           "  summary FILE                        format, time span, classes, per-sensor rates\n"
           "  list FILE [--from N] [--to M] [--sensor LABEL]   one line per entry\n"
           "  show FILE N                         full description of entry N\n"
           "  export FILE --sensor LABEL --out DIR   CSV series / PNG frames of one sensor\n"
           "  to-imu FILE OUT [--unit gauss]      magnetometers as CObservationIMU\n"
           "  report FILE --out DIR [--slam SLAM_OUT] [--ground-truth GT.tum] [--map MAP_DIR]   HTML report\n"
           "  map DIR [--plot PNG]                a saved map (lodestone-slam --map-out)\n"
           "  mesh DIR --rawlog FILE [--config INI]   a finished run's or a saved map's dense model (mesh.ply)\n"
           "exit codes: 0 ok, 1 bad input, 2 usage\n";
}

}  // namespace

int runInspectApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    lodestone::registerAllClasses();
    const std::map<std::string, std::function<int(const Args&, std::ostream&)>> commands = {
        {"summary", summary},
        {"list", list},
        {"show", show},
        {"export", exportCmd},
        {"to-imu", toImu},
        {"report", reportCmd},
        {"map", mapCmd},
        {"mesh", meshCmd}};
    if (argc < 2) {
        printUsage(err);
        return kExitUsage;
    }
    const std::string name = argv[1];
    if (name == "--help" || name == "-h" || name == "help") {
        printUsage(out);
        return kExitOk;
    }
    const auto command = commands.find(name);
    if (command == commands.end()) {
        err << "lodestone-inspect: unknown command '" << name << "'\n";
        printUsage(err);
        return kExitUsage;
    }
    const Args args(argv + 2, argv + argc);
    try {
        return command->second(args, out);
    } catch (const UsageError& e) {
        err << "lodestone-inspect " << name << ": " << e.what() << "\n"
            << "(see lodestone-inspect " << name << " --help)\n";
        return kExitUsage;
    } catch (const std::exception& e) {
        out.flush();
        err << "lodestone-inspect " << name << ": error: " << e.what() << "\n";
        return kExitBadInput;
    }
}

}  // namespace lodestone::inspect
