#include <lodestone/eval/TrajectoryError.h>
#include <lodestone/datasets/TimeAssociation.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace lodestone::eval {

namespace {
Eigen::Isometry3d toEigen(const mrpt::poses::CPose3D& p) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = p.getRotationMatrix().asEigen();
    T.translation() = Eigen::Vector3d(p.x(), p.y(), p.z());
    return T;
}

double rms(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x * x;
    return v.empty() ? 0 : std::sqrt(s / v.size());
}
}  // namespace

const io::TumPose* truthAt(const std::vector<io::TumPose>& truth, double t, double maxDt) {
    return io::poseNearest(truth, t, maxDt);
}

std::vector<std::pair<std::size_t, std::size_t>> associate(const std::vector<io::TumPose>& est,
                                                           const std::vector<io::TumPose>& gt,
                                                           double maxDt) {
    std::vector<double> a, b;
    for (const auto& p : est) a.push_back(p.timestamp);
    for (const auto& p : gt) b.push_back(p.timestamp);
    return datasets::associateByTime(a, b, maxDt);
}

AteResult absoluteTrajectoryError(const std::vector<io::TumPose>& est,
                                  const std::vector<io::TumPose>& gt, double maxDt) {
    AteResult r;
    const auto pairs = associate(est, gt, maxDt);
    r.pairs = pairs.size();
    if (pairs.empty()) return r;
    Eigen::Matrix3Xd e(3, pairs.size()), g(3, pairs.size());
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const auto& pe = est[pairs[k].first].pose;
        const auto& pg = gt[pairs[k].second].pose;
        e.col(static_cast<Eigen::Index>(k)) = Eigen::Vector3d(pe.x(), pe.y(), pe.z());
        g.col(static_cast<Eigen::Index>(k)) = Eigen::Vector3d(pg.x(), pg.y(), pg.z());
    }
    if (pairs.size() >= 3) r.alignment.matrix() = Eigen::umeyama(e, g, false);
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const auto c = static_cast<Eigen::Index>(k);
        r.errors.push_back((r.alignment * e.col(c) - g.col(c)).norm());
        r.times.push_back(est[pairs[k].first].timestamp);
    }
    r.rmse = rms(r.errors);
    std::vector<double> sorted = r.errors;
    std::sort(sorted.begin(), sorted.end());
    r.median = sorted[sorted.size() / 2];
    r.max = sorted.back();
    double sum = 0;
    for (double x : sorted) sum += x;
    r.mean = sum / sorted.size();
    return r;
}

RpeResult relativePoseError(const std::vector<io::TumPose>& est, const std::vector<io::TumPose>& gt,
                            RpeInterval kind, double interval, double maxDt) {
    RpeResult r;
    const auto pairs = associate(est, gt, maxDt);
    if (pairs.size() < 2) return r;
    // Travelled ground-truth distance at each associated pose.
    std::vector<double> travelled(pairs.size(), 0.0);
    for (std::size_t k = 1; k < pairs.size(); ++k) {
        const auto& a = gt[pairs[k - 1].second].pose;
        const auto& b = gt[pairs[k].second].pose;
        travelled[k] =
            travelled[k - 1] + std::hypot(std::hypot(b.x() - a.x(), b.y() - a.y()), b.z() - a.z());
    }
    const auto key = [&](std::size_t k) {
        return kind == RpeInterval::Seconds ? est[pairs[k].first].timestamp : travelled[k];
    };
    std::vector<double> te, re;
    std::size_t j = 0;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        if (j < i) j = i;
        while (j < pairs.size() && key(j) - key(i) < interval - 1e-9) ++j;  // (not a rounding step)
        if (j >= pairs.size()) break;
        const Eigen::Isometry3d Ei = toEigen(est[pairs[i].first].pose);
        const Eigen::Isometry3d Ej = toEigen(est[pairs[j].first].pose);
        const Eigen::Isometry3d Gi = toEigen(gt[pairs[i].second].pose);
        const Eigen::Isometry3d Gj = toEigen(gt[pairs[j].second].pose);
        const Eigen::Isometry3d E = (Gi.inverse() * Gj).inverse() * (Ei.inverse() * Ej);
        te.push_back(E.translation().norm());
        re.push_back(Eigen::AngleAxisd(E.linear()).angle());
    }
    r.pairs = te.size();
    r.translationRmse = rms(te);
    r.rotationRmse = rms(re);
    return r;
}

}  // namespace lodestone::eval
