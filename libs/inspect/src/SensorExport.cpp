#include <lodestone/inspect/SensorExport.h>
#include <lodestone/inspect/TimeText.h>
#include <lodestone/io/RawlogReadError.h>
#include <lodestone/io/RawlogPaths.h>
#include <lodestone/io/RawlogSource.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>

namespace lodestone::inspect {

namespace fs = std::filesystem;

namespace {
// MRPT's text export separates columns with runs of spaces; CSV wants commas.
std::string toCsv(const std::string& text) {
    std::istringstream in(text);
    std::string out, word;
    while (in >> word) out += (out.empty() ? "" : ",") + word;
    return out;
}

std::string frameName(std::size_t n) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%06zu.png", n);
    return buf;
}

void writePng(const fs::path& path, const cv::Mat& image) {
    if (!cv::imwrite(path.string(), image)) {
        throw std::runtime_error(path.string() + ": cannot write PNG");
    }
}

class Exporter {
  public:
    Exporter(const fs::path& dir, const std::string& label) : dir_(dir), label_(label) {}

    void add(const mrpt::obs::CObservation& obs) {
        if (const auto* scan = dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&obs)) {
            addFrame(*scan);
        } else if (obs.exportTxtSupported()) {
            addRow(obs);
        } else {
            ++result_.skipped;
        }
    }

    /** Closes the CSV files; `complete` (the rawlog was read to its end): renamed from
     * .partial to their names, else left .partial beside the frames written so far. */
    SensorExportResult finish(bool complete) {
        close(series_, result_.seriesFile, complete);
        close(frames_, result_.framesIndex, complete);
        return result_;
    }

  private:
    static void close(std::ofstream& file, const std::string& path, bool complete) {
        if (!file.is_open()) return;
        file.close();
        if (!file) throw std::runtime_error(io::partialPath(path) + ": write error");
        if (complete) io::commitPartial(path);
    }

    void addRow(const mrpt::obs::CObservation& obs) {
        if (!series_.is_open()) {
            result_.seriesFile = (dir_ / (label_ + ".csv")).string();
            series_.open(io::partialPath(result_.seriesFile));
            series_ << "timestamp," << toCsv(obs.exportTxtHeader()) << "\n";
        }
        series_ << secondsText(obs.timestamp) << "," << toCsv(obs.exportTxtDataRow()) << "\n";
        ++result_.seriesRows;
    }

    void addFrame(const mrpt::obs::CObservation3DRangeScan& scan) {
        if (!frames_.is_open()) {
            fs::create_directories(dir_ / "rgb");
            fs::create_directories(dir_ / "depth");
            result_.framesIndex = (dir_ / (label_ + "_frames.csv")).string();
            frames_.open(io::partialPath(result_.framesIndex));
            frames_ << "timestamp,rgb,depth,depth_units_m\n";
        }
        scan.load();  // delay-loaded images live in the external images folder
        const std::string name = frameName(result_.frames);
        std::string rgbFile = "-", depthFile = "-";
        if (scan.hasIntensityImage && !scan.intensityImage.isEmpty()) {
            rgbFile = "rgb/" + name;
            writePng(dir_ / rgbFile, scan.intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY));
        }
        if (scan.hasRangeImage && scan.rangeImage.rows() > 0) {
            cv::Mat depth(static_cast<int>(scan.rangeImage.rows()),
                          static_cast<int>(scan.rangeImage.cols()), CV_16UC1);
            for (int r = 0; r < depth.rows; ++r) {
                for (int c = 0; c < depth.cols; ++c)
                    depth.at<uint16_t>(r, c) = scan.rangeImage(r, c);
            }
            depthFile = "depth/" + name;
            writePng(dir_ / depthFile, depth);
        }
        scan.unload();
        frames_ << secondsText(scan.timestamp) << "," << rgbFile << "," << depthFile << ","
                << scan.rangeUnits << "\n";
        ++result_.frames;
    }

    fs::path dir_;
    std::string label_;
    std::ofstream series_, frames_;
    SensorExportResult result_;
};
}  // namespace

SensorExportResult exportSensor(const std::string& rawlogPath, const std::string& label,
                                const std::string& outDir) {
    io::RawlogSource source(rawlogPath);
    fs::create_directories(outDir);
    Exporter exporter(outDir, label);
    std::set<std::string> otherLabels;
    std::size_t matched = 0;
    try {
        while (auto obs = source.next()) {
            if (obs->sensorLabel != label) {
                otherLabels.insert(obs->sensorLabel);
                continue;
            }
            ++matched;
            exporter.add(*obs);
        }
    } catch (const io::RawlogReadError&) {
        exporter.finish(false);  // keep what was exported before the fault, as .partial
        throw;
    }
    auto result = exporter.finish(true);
    if (matched == 0) {
        std::string labels;
        for (const auto& l : otherLabels) labels += (labels.empty() ? "" : ", ") + ("'" + l + "'");
        throw std::runtime_error(rawlogPath + ": no observation has sensor label '" + label +
                                 "' (labels present: " + (labels.empty() ? "none" : labels) + ")");
    }
    return result;
}

}  // namespace lodestone::inspect
