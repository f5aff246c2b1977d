#include <lodestone/config/ProgressBar.h>
#include <lodestone/eval/FieldMapPlot.h>
#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/eval/TrajectoryPlot.h>
#include <lodestone/inspect/RawlogSummary.h>
#include <lodestone/inspect/report/RawlogReport.h>
#include <lodestone/inspect/report/ReportCharts.h>
#include <lodestone/inspect/report/ReportHtml.h>
#include <lodestone/inspect/report/SeriesCollectors.h>
#include <lodestone/inspect/report/SensorTimeline.h>
#include <lodestone/inspect/report/SlamOutputs.h>
#include <lodestone/view/SceneBuilder.h>
#include <lodestone/view/Snapshot.h>
#include <lodestone/inspect/report/Thumbnails.h>
#include <lodestone/io/EntryContents.h>
#include <lodestone/io/ImagesDirectory.h>
#include <lodestone/io/RawlogPaths.h>
#include <lodestone/io/RawlogReadError.h>
#include <lodestone/io/RawlogReader.h>
#include <lodestone/obs/CObservationMagnetometer.h>
#include <mrpt/img/CImage.h>
#include <mrpt/obs/CActionCollection.h>

#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace lodestone::inspect::report {

namespace fs = std::filesystem;

namespace {
void writePng(const fs::path& dir, const std::string& name, const cv::Mat& image,
              std::vector<Figure>& figures, const std::string& caption) {
    const fs::path path = dir / name;
    if (!cv::imwrite(path.string(), image)) throw std::runtime_error(path.string() + ": cannot write PNG");
    figures.push_back({name, caption});
}

std::string fileSafe(const std::string& label) {
    std::string s;
    for (const char c : label) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return s.empty() ? "unlabelled" : s;
}

// `t0`: the rawlog's first timestamp [s]; the page gives times since it.
void slamFigures(const SlamOutputs& slam, const std::optional<eval::FieldMapBuilder>& fieldMap,
                 double t0, const fs::path& dir, ReportPage& page) {
    page.hasSlam = true;
    page.slamDir = slam.dir;
    page.slamFacts = slam.facts;
    page.slamFacts.insert(page.slamFacts.begin(), {"nodes in trajectory.tum", std::to_string(slam.trajectory.size())});
    for (const auto& m : slam.missing) page.slamNotes.push_back("not shown: " + m);
    if (!slam.groundTruth.empty()) {
        const auto ate = eval::absoluteTrajectoryError(slam.trajectory, slam.groundTruth);
        if (ate.pairs >= 3) {
            page.slamFacts.push_back({"ATE RMSE against " + slam.groundTruthPath,
                                      fixedText(ate.rmse, 4) + " m over " + std::to_string(ate.pairs) + " nodes"});
            writePng(dir, "slam_trajectory.png", eval::plotTrajectories(slam.trajectory, slam.groundTruth, ate),
                     page.slamFigures,
                     "Optimized trajectory (red) against the ground truth (black), aligned (Horn); absolute error over time.");
        } else {
            page.slamNotes.push_back("ground truth " + slam.groundTruthPath + ": only " +
                                     std::to_string(ate.pairs) + " nodes match it in time; no ATE");
        }
    }
    writePng(dir, "slam_graph.png", graphChart(slam), page.slamFigures,
             "The pose graph from above with every loop closure proposed, coloured by the decider "
             "that proposed it; closures not in the final graph are thin with a cross.");
    try {
        view::RunReadOptions options;
        options.groundTruth = slam.groundTruthPath;
        const view::SceneContent content = view::readRunFolder(slam.dir, options);
        const mrpt::img::CImage image =
            view::renderScene(*view::buildScene(content), view::framing(content), 1280, 960);
        const bool mesh = content.mesh.size() > 0;
        if (mesh) page.slamFacts.push_back({"dense model (mesh.ply)", std::to_string(content.mesh.size()) + " triangles shown"});
        writePng(dir, "slam_view3d.png", image.asCvMatRef(), page.slamFigures,
                 std::string("The run in 3D, as lodestone-view draws it: ") +
                     (mesh ? "the dense model (mesh.ply: the keyframes fused on their optimized poses)"
                           : "the keyframe clouds on the optimized poses") +
                     ", the nodes coloured by their error against the ground truth (or by segment "
                     "without one), loop closures in their closer's colour, the truth's path in grey.");
    } catch (const std::exception& e) {
        page.slamNotes.push_back(std::string("not shown: the 3D view (") + e.what() + ")");
    }
    if (fieldMap && fieldMap->placed() > 0) {
        writePng(dir, "slam_field_map.png", fieldMap->render("|B| on the optimized trajectory"),
                 page.slamFigures,
                 "The magnetic field map: every magnetometer reading's |B| placed where its sensor "
                 "was on the optimized trajectory, averaged per cell.");
        if (fieldMap->unplaced()) {
            page.slamNotes.push_back(std::to_string(fieldMap->unplaced()) + " of " +
                                     std::to_string(fieldMap->placed() + fieldMap->unplaced()) +
                                     " magnetometer readings not placed: outside the trajectory's "
                                     "time or inside a kidnap.");
        }
    }
    if (fieldMap && fieldMap->placed() == 0 && fieldMap->unplaced() > 0) {
        page.slamNotes.push_back("no magnetometer reading of the rawlog falls within the SLAM "
                                 "trajectory's time: is the run one of this rawlog?");
    }
    if (!slam.nodes.empty()) {
        writePng(dir, "slam_node_time.png", nodeTimeChart(slam.nodes), page.slamFigures,
                 "Engine time per node: what the deciders and the optimizer spent from one node to the next.");
    }
    for (const auto& k : slam.kidnaps) {
        page.relocations.push_back(
            {std::to_string(k.segment), fixedText(k.liftTime - t0, 2), fixedText(k.putDownTime - t0, 2),
             k.relocated ? "yes" : (k.mergedLate ? "after the segment ended" : "no"),
             k.relocated ? fixedText(k.relocationTime - k.putDownTime, 2) : "-",
             k.relocated ? fixedText(k.travel, 2) : "-",
             k.relocated ? fixedText(k.x, 2) + ", " + fixedText(k.y, 2) + ", " + fixedText(k.yaw * 180 / M_PI, 1) : "-"});
    }
}
// What an earlier report in the same folder wrote (and only that: the folder may hold other
// files), so no stale chart or thumbnail sits beside the new page.
void removePreviousReport(const fs::path& dir) {
    const auto ours = [](const std::string& name) {
        const auto ends = [&](const char* e) {
            const std::string s(e);
            return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
        };
        return name == "index.html" || name == "index.html.partial" || name == "timeline.png" ||
               name == "odometry.png" || (name.rfind("magnetometer_", 0) == 0 && ends(".png")) ||
               (name.rfind("slam_", 0) == 0 && ends(".png")) || ends("_rgb.jpg") ||
               ends("_depth.png");
    };
    std::error_code ec;
    for (const fs::path& folder : {dir, dir / "thumbs"}) {
        if (!fs::is_directory(folder, ec)) continue;
        for (const auto& e : fs::directory_iterator(folder, ec)) {
            if (e.is_regular_file(ec) && ours(e.path().filename().string())) fs::remove(e.path(), ec);
        }
    }
}
}  // namespace

ReportResult writeRawlogReport(const ReportOptions& options, std::ostream& progressOut) {
    // Everything that can be refused is refused before the pass.
    io::RawlogReader reader(options.rawlog);
    const fs::path dir(options.outDir);
    io::prepareOutputFile((dir / "index.html").string());
    std::optional<SlamOutputs> slam;
    if (!options.slamDir.empty()) slam = readSlamOutputs(options.slamDir, options.groundTruth);
    std::optional<eval::FieldMapBuilder> fieldMap;
    if (slam) fieldMap.emplace(slam->trajectory, options.fieldCell);
    removePreviousReport(dir);

    mrpt::img::CImage::setImagesPathBase(io::findImagesDirectory(options.rawlog));
    RawlogSummaryBuilder summary(options.rawlog, reader.fileSize(), reader.isCompressed());
    TimelineBuilder timelines(options.gapFactor);
    SeriesCollectors series;
    ThumbnailOptions thumbOptions;
    thumbOptions.every = options.thumbnailEvery;
    thumbOptions.depthMax = options.depthMax;
    ThumbnailSampler thumbnails(dir, "thumbs", thumbOptions);
    config::ProgressBar progress(progressOut, options.terminal, options.quiet);

    std::optional<std::string> error;
    double t0 = NAN, dataSeconds = 0;
    try {
        while (auto entry = reader.next()) {
            summary.add(*entry);
            series.addActions(*entry->object);
            for (const auto& obs : io::observationsOf(entry->object)) {
                const double abs = obs->timestamp == INVALID_TIMESTAMP
                                       ? NAN
                                       : mrpt::Clock::toDouble(obs->timestamp);
                if (std::isnan(t0) && std::isfinite(abs)) t0 = abs;
                const double t = abs - t0;
                if (std::isfinite(t)) dataSeconds = std::max(dataSeconds, t);
                const bool afterGap = timelines.wouldBeGap(obs->sensorLabel, t);
                timelines.add(*obs, t);
                series.addObservation(*obs, t);
                thumbnails.add(obs, t, afterGap);
                if (fieldMap) {
                    if (const auto* m = dynamic_cast<const obs::CObservationMagnetometer*>(obs.get())) {
                        fieldMap->add(abs, m->sensorPose.translation(), m->magnitude(), m->sensorLabel);
                    }
                }
            }
            progress.update(reader.fractionRead(), dataSeconds);
        }
    } catch (const io::RawlogReadError& e) {
        error = e.what();
    }
    progress.finish(dataSeconds);

    ReportPage page;
    page.summary = summary.finish(error, reader.bytesRead());
    page.gapFactor = options.gapFactor;
    page.timelines = timelines.finish();
    page.thumbnails = thumbnails.thumbnails();
    page.thumbnailEvery = options.thumbnailEvery;
    page.depthMax = options.depthMax;
    page.extraSections = options.extraSections;
    page.unreadableFrames = thumbnails.unreadable();
    writePng(dir, "timeline.png", timelineChart(page.timelines, dataSeconds), page.rawlogFigures,
             "Every sensor over time: sample density, gaps (red), backwards timestamps (orange "
             "triangles), wheel drops (x lifted, o down).");
    for (const auto& m : series.magnetometers()) {
        writePng(dir, "magnetometer_" + fileSafe(m.label) + ".png", magnetometerChart(m),
                 page.rawlogFigures,
                 m.label + ": " + std::to_string(m.count) + " readings; field components and |B|.");
    }
    const auto paths = series.odometry();
    if (!paths.empty()) {
        writePng(dir, "odometry.png", odometryChart(paths), page.rawlogFigures,
                 "Odometry from above, as each source reported or integrated it (no SLAM).");
    }
    if (slam) slamFigures(*slam, fieldMap, t0, dir, page);

    ReportResult result;
    result.index = (dir / "index.html").string();
    writeReportHtml(result.index, page);
    result.readError = error;
    result.entries = page.summary.entries;
    result.thumbnails = page.thumbnails.size();
    result.figures = page.rawlogFigures.size() + page.slamFigures.size();
    return result;
}

}  // namespace lodestone::inspect::report
