#include <lodestone/eval/TrajectoryPlot.h>

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>

namespace lodestone::eval {

namespace {
constexpr int kPanel = 460, kMargin = 40;

void text(cv::Mat3b& img, const std::string& s, cv::Point at, double scale = 0.45) {
    cv::putText(img, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}
}  // namespace

cv::Mat3b plotTrajectories(const std::vector<io::TumPose>& est, const std::vector<io::TumPose>& gt,
                           const AteResult& ate) {
    cv::Mat3b img(kPanel + 2 * kMargin, 2 * kPanel + 3 * kMargin, cv::Vec3b(255, 255, 255));
    // Top view: common bounds of both trajectories, equal scale on x and y.
    std::vector<Eigen::Vector2d> g, e;
    for (const auto& p : gt) g.emplace_back(p.pose.x(), p.pose.y());
    for (const auto& p : est) {
        const Eigen::Vector3d a =
            ate.alignment * Eigen::Vector3d(p.pose.x(), p.pose.y(), p.pose.z());
        e.emplace_back(a.x(), a.y());
    }
    Eigen::Vector2d lo(1e18, 1e18), hi(-1e18, -1e18);
    for (const auto* v : {&g, &e}) {
        for (const auto& p : *v) {
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
    }
    const double span = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-3});
    const auto px = [&](const Eigen::Vector2d& p) {
        return cv::Point(kMargin + static_cast<int>((p.x() - lo.x()) / span * kPanel),
                         kMargin + kPanel - static_cast<int>((p.y() - lo.y()) / span * kPanel));
    };
    cv::rectangle(img, cv::Rect(kMargin, kMargin, kPanel, kPanel), cv::Scalar(200, 200, 200));
    for (std::size_t i = 1; i < g.size(); ++i)
        cv::line(img, px(g[i - 1]), px(g[i]), cv::Scalar(0, 0, 0), 2, cv::LINE_AA);
    for (std::size_t i = 1; i < e.size(); ++i)
        cv::line(img, px(e[i - 1]), px(e[i]), cv::Scalar(40, 40, 220), 1, cv::LINE_AA);
    char s[160];
    std::snprintf(s, sizeof(s), "top view: ground truth black, estimate red (%.2f m across)", span);
    text(img, s, cv::Point(kMargin, kMargin - 12));

    // Error over time.
    const int x0 = 2 * kMargin + kPanel;
    cv::rectangle(img, cv::Rect(x0, kMargin, kPanel, kPanel), cv::Scalar(200, 200, 200));
    if (!ate.errors.empty()) {
        const double t0 = ate.times.front(), t1 = std::max(ate.times.back(), t0 + 1e-3);
        const double emax = std::max(ate.max, 1e-6);
        const auto q = [&](std::size_t i) {
            return cv::Point(x0 + static_cast<int>((ate.times[i] - t0) / (t1 - t0) * kPanel),
                             kMargin + kPanel - static_cast<int>(ate.errors[i] / emax * kPanel));
        };
        for (std::size_t i = 1; i < ate.errors.size(); ++i)
            cv::line(img, q(i - 1), q(i), cv::Scalar(40, 40, 220), 1, cv::LINE_AA);
        std::snprintf(s, sizeof(s), "absolute error [m] over %.1f s: RMSE %.3f, max %.3f", t1 - t0,
                      ate.rmse, ate.max);
        text(img, s, cv::Point(x0, kMargin - 12));
        std::snprintf(s, sizeof(s), "%.3f", emax);
        text(img, s, cv::Point(x0 + 4, kMargin + 14), 0.4);
    }
    return img;
}

}  // namespace lodestone::eval
