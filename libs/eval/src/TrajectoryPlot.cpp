#include <lodestone/eval/TrajectoryPlot.h>
#include <lodestone/plot/Axes.h>
#include <lodestone/plot/Colormap.h>

#include <algorithm>
#include <cstdio>
#include <map>

namespace lodestone::eval {

namespace {
constexpr int kHeight = 560, kMapWidth = 620, kBarRoom = 90, kErrorWidth = 560;
const cv::Scalar kTruthColour(150, 150, 150), kUnmatchedColour(200, 200, 255);
}  // namespace

cv::Mat3b plotTrajectories(const std::vector<io::TumPose>& est, const std::vector<io::TumPose>& gt,
                           const AteResult& ate) {
    cv::Mat3b img(kHeight, kMapWidth + kBarRoom + kErrorWidth, cv::Vec3b(255, 255, 255));
    // Each associated estimate pose's error, by its timestamp (unique in an estimate).
    std::map<double, double> errorAt;
    for (std::size_t i = 0; i < ate.times.size() && i < ate.errors.size(); ++i) {
        errorAt[ate.times[i]] = ate.errors[i];
    }

    // Top view, equal axes, centred: the truth in grey, the aligned estimate coloured by its
    // error (as evo draws it; poses with no truth near in time in light red).
    std::vector<cv::Point2d> truth, aligned;
    plot::Bounds bounds;
    for (const auto& p : gt) {
        truth.emplace_back(p.pose.x(), p.pose.y());
        bounds.add(p.pose.x(), p.pose.y());
    }
    for (const auto& p : est) {
        const Eigen::Vector3d a = ate.alignment * Eigen::Vector3d(p.pose.x(), p.pose.y(), p.pose.z());
        aligned.emplace_back(a.x(), a.y());
        bounds.add(a.x(), a.y());
    }
    plot::Axes map(img, cv::Rect(0, 0, kMapWidth, kHeight));
    map.setLimitsEqualAspect(bounds.empty() ? plot::Bounds{0, 1, 0, 1} : bounds.padded(0.04, 1.0));
    map.drawFrame("top view: truth (grey), estimate by its error", "x [m]", "y [m]");
    map.line(truth, kTruthColour, 2);
    const plot::Colormap colours(0.0, std::max(ate.max, 1e-6));
    for (std::size_t i = 1; i < aligned.size(); ++i) {
        const auto e = errorAt.find(est[i].timestamp);
        const cv::Scalar colour = e == errorAt.end() ? kUnmatchedColour : cv::Scalar(colours(e->second));
        map.segment(aligned[i - 1], aligned[i], colour, 2);
    }
    colours.drawBar(img, cv::Rect(kMapWidth + 10, map.plotArea().y, 16, map.plotArea().height),
                    "error [m]");

    // The error over time.
    plot::Axes errors(img, cv::Rect(kMapWidth + kBarRoom, 0, kErrorWidth, kHeight));
    char title[160];
    std::snprintf(title, sizeof title, "absolute error: RMSE %.3f m, max %.3f m", ate.rmse, ate.max);
    if (ate.errors.empty()) {
        errors.setLimits({0, 1, 0, 1});
        errors.drawFrame(title, "t [s]", "[m]");
        return img;
    }
    const double t0 = ate.times.front();
    std::vector<cv::Point2d> series;
    plot::Bounds range;
    range.add(0, 0);
    for (std::size_t i = 0; i < ate.errors.size(); ++i) {
        series.emplace_back(ate.times[i] - t0, ate.errors[i]);
        range.add(ate.times[i] - t0, ate.errors[i]);
    }
    plot::Bounds limits = range.padded(0.03, 1e-3);
    limits.y0 = 0;
    errors.setLimits(limits);
    errors.drawFrame(title, "t [s] from the first pose", "[m]");
    errors.line(series, cv::Scalar(40, 40, 220), 1);
    return img;
}

}  // namespace lodestone::eval
