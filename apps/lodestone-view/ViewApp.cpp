#include <ViewApp.h>
#include <ViewWindow.h>
#include <lodestone/config/CommandLine.h>
#include <lodestone/maps/SavedMap.h>
#include <lodestone/view/SceneBuilder.h>
#include <lodestone/view/Snapshot.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace lodestone::view {

namespace {

/** "WxH" -> width, height (each 16 to 8192). */
bool parseSize(const std::string& text, unsigned& width, unsigned& height) {
    unsigned w = 0, h = 0;
    char x = 0, rest = 0;
    if (std::sscanf(text.c_str(), "%u%c%u%c", &w, &x, &h, &rest) != 3 || x != 'x') return false;
    if (w < 16 || h < 16 || w > 8192 || h > 8192) return false;
    width = w;
    height = h;
    return true;
}

SceneContent readFolder(const std::string& dir, const RunReadOptions& options) {
    if (std::filesystem::exists(maps::pathIn(dir, maps::MapFile::Manifest)))
        return fromSavedMap(maps::readMap(dir));
    return readRunFolder(dir, options);
}

}  // namespace

int runViewApp(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    TCLAP::CmdLine cmd(
        "The 3D scene of a lodestone-slam output folder (graph.graph, nodes.csv, closures.csv,\n"
        "map.ply, ground_truth.tum) or of a saved map folder (--map-out): nodes by segment (by\n"
        "their error where there is a ground truth), odometry edges, closures in their closer's\n"
        "colour, refused closures in red, the keyframe cloud, the truth's path in grey.\n"
        "  lodestone-view DIR                      MRPT's window (needs a display)\n"
        "  lodestone-view DIR --screenshot OUT.png rendered off-screen (no display needed)\n"
        "  lodestone-view DIR --export OUT.3Dscene for MRPT's SceneViewer3D",
        ' ', "");
    TCLAP::UnlabeledValueArg<std::string> dirArg("DIR", "a run's output folder or a map folder", true, "",
                                                 "DIR", cmd);
    TCLAP::ValueArg<std::string> truthArg("g", "ground-truth",
                                          "ground truth (TUM); default DIR/ground_truth.tum if there",
                                          false, "", "TUM", cmd);
    TCLAP::ValueArg<std::string> shotArg("s", "screenshot", "render off-screen into this PNG", false, "",
                                         "PNG", cmd);
    TCLAP::ValueArg<std::string> exportArg("e", "export", "write the scene as MRPT's .3Dscene", false,
                                           "", "FILE", cmd);
    TCLAP::ValueArg<std::string> sizeArg("", "size", "screenshot size (default 1280x960)", false,
                                         "1280x960", "WxH", cmd);
    TCLAP::ValueArg<std::string> cameraArg(
        "", "camera",
        "AZ,EL[,DIST[,X,Y,Z]]: azimuth and elevation [deg], distance [m] and the point looked at "
        "[m] (default: every node in view, from -60, 50)",
        false, "", "CAM", cmd);
    TCLAP::ValueArg<std::size_t> pointsArg("", "max-points",
                                           "map.ply points drawn, evenly taken (0: no cloud)", false,
                                           200000, "N", cmd);
    const auto outcome = config::parseCommandLine(cmd, std::vector<std::string>(argv, argv + argc));
    if (outcome.kind == config::ParseOutcome::Kind::HelpShown) return 0;
    unsigned width = 0, height = 0;
    std::string usage = outcome.error;
    if (usage.empty() && !parseSize(sizeArg.getValue(), width, height))
        usage = "--size '" + sizeArg.getValue() + "': expected WxH, each 16 to 8192";
    if (outcome.kind == config::ParseOutcome::Kind::UsageError || !usage.empty()) {
        err << "lodestone-view: " << usage << " (see lodestone-view --help)\n";
        return 2;
    }
    const bool window = shotArg.getValue().empty() && exportArg.getValue().empty();
    if (window && !std::getenv("DISPLAY")) {
        err << "lodestone-view: no display (DISPLAY is not set): use --screenshot OUT.png or "
               "--export OUT.3Dscene\n";
        return 1;
    }
    try {
        RunReadOptions options;
        options.groundTruth = truthArg.getValue();
        options.maxPoints = pointsArg.getValue();
        const SceneContent content = readFolder(dirArg.getValue(), options);
        ViewCamera camera = framing(content);
        if (!cameraArg.getValue().empty()) camera = parseCamera(cameraArg.getValue(), camera);
        const auto scene = buildScene(content);
        if (!exportArg.getValue().empty()) {
            if (!scene->saveToFile(exportArg.getValue()))
                throw std::runtime_error(exportArg.getValue() + ": cannot be written");
            out << "scene -> " << exportArg.getValue() << "\n";
        }
        if (!shotArg.getValue().empty()) {
            writeScreenshot(*scene, camera, width, height, shotArg.getValue());
            out << "screenshot -> " << shotArg.getValue() << "\n";
        }
        if (window) showWindow(scene, camera, dirArg.getValue(), out);
    } catch (const std::exception& e) {
        err << "lodestone-view: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}

}  // namespace lodestone::view
