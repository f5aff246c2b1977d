#include <lodestone/graphslam/erd/magnetic/PathUncertainty.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lodestone::graphslam::closure {

Eigen::Matrix3d planarCovariance(const Constraint& c) {
    constexpr int kAt[3] = {0, 1, 3};
    Eigen::Matrix3d info;
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) info(r, k) = c.cov_inv(kAt[r], kAt[k]);
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(info);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().array() > 0).all())
        return Eigen::Matrix3d::Identity() * 1e6;  // no information: anything goes
    return ldlt.solve(Eigen::Matrix3d::Identity());
}

PathUncertainty::Matrix4 PathUncertainty::startState() const {
    Matrix4 s = Matrix4::Zero();
    s(3, 3) = params_.headingBias * params_.headingBias;
    return s;
}

void PathUncertainty::addNode(TNodeID id, const Constraint* edge, double previousYaw) {
    if (id != steps_.size()) throw std::logic_error("PathUncertainty: nodes must come in order");
    Step s;
    if (edge && id > 0) {
        s.segmentStart = false;
        const Eigen::Vector2d local(edge->mean.x(), edge->mean.y());
        s.delta = Eigen::Rotation2Dd(previousYaw) * local;
        s.length = local.norm();
        s.previousYaw = previousYaw;
        s.stepCovariance = planarCovariance(*edge);
    }
    Prefix pre;
    if (!prefix_.empty()) {
        pre = prefix_.back();
        pre.weighted += pre.s * s.delta;
        pre.s += s.length;
        pre.p += s.delta;
    }
    prefix_.push_back(pre);
    steps_.push_back(s);
    sigma_.emplace_back();
    reference_.push_back(id);
    pinned_.push_back(false);
    propagate(id);
}

void PathUncertainty::propagate(std::size_t from) {
    for (std::size_t k = from; k < steps_.size(); ++k) {
        const Step& s = steps_[k];
        if (s.segmentStart) {
            sigma_[k] = startState();
            reference_[k] = static_cast<TNodeID>(k);
            continue;
        }
        // (a later pin is propagated over, as its covariance is: the newer pin decides)
        pinned_[k] = false;
        reference_[k] = reference_[k - 1];
        // x' = x + R(yaw) d, yaw' = yaw + dyaw + bias * length, bias' = bias.
        Matrix4 F = Matrix4::Identity();
        F(0, 2) = -s.delta.y();
        F(1, 2) = s.delta.x();
        F(2, 3) = s.length;
        Eigen::Matrix3d G = Eigen::Matrix3d::Identity();
        G.topLeftCorner<2, 2>() = Eigen::Rotation2Dd(s.previousYaw).toRotationMatrix();
        Matrix4 Q = Matrix4::Zero();
        Q.topLeftCorner<3, 3>() = G * s.stepCovariance * G.transpose();
        sigma_[k] = F * sigma_[k - 1] * F.transpose() + Q;
    }
}

void PathUncertainty::pin(TNodeID id, const Eigen::Matrix3d& covariance) {
    if (id >= steps_.size()) throw std::out_of_range("PathUncertainty::pin: unknown node");
    // The pinned node keeps the closure's covariance (or its own, if smaller already); the
    // bias is not observed by one closure and keeps its prior.
    Matrix4 s = startState();
    s.topLeftCorner<3, 3>() = covariance;
    if (sigma_[id].topLeftCorner<2, 2>().trace() < covariance.topLeftCorner<2, 2>().trace()) return;
    sigma_[id] = s;
    reference_[id] = id;
    pinned_[id] = true;
    if (id + 1 < steps_.size()) propagate(id + 1);
}

Eigen::Matrix3d PathUncertainty::covariance(TNodeID id) const {
    return sigma_.at(id).topLeftCorner<3, 3>();
}

Eigen::Matrix2d PathUncertainty::gateCovariance(TNodeID id) const {
    return sigma_.at(id).topLeftCorner<2, 2>() +
           params_.floor * params_.floor * Eigen::Matrix2d::Identity();
}

double PathUncertainty::gateDistance2(TNodeID id, const Eigen::Vector2d& d) const {
    return d.dot(gateCovariance(id).ldlt().solve(d));
}

double PathUncertainty::relativeGateDistance2(TNodeID target, TNodeID query,
                                              const Eigen::Vector2d& d) const {
    return d.dot(relativeGateCovariance(target, query).ldlt().solve(d));
}

Eigen::Matrix2d PathUncertainty::relativeGateCovariance(TNodeID target, TNodeID query) const {
    const Matrix4& Sa = sigma_.at(target);
    const Matrix4& Sb = sigma_.at(query);
    Eigen::Matrix2d S;
    if (reference_.at(query) <= target && target <= query) {
        // e_b = Phi e_a + w along the chain; the offset's error e_b,xy - e_a,xy has covariance
        // Sigma_b,xy - Sigma_a,xy - A Sigma_a E' - E Sigma_a A', with Phi = E + A on the
        // position rows: A carries a's heading and drift errors over the path between.
        const Prefix& a = prefix_[target];
        const Prefix& b = prefix_[query];
        const Eigen::Vector2d dp = b.p - a.p;
        const Eigen::Vector2d swung = (b.weighted - a.weighted) - a.s * dp;
        Eigen::Matrix<double, 2, 4> A = Eigen::Matrix<double, 2, 4>::Zero();
        A(0, 2) = -dp.y();
        A(1, 2) = dp.x();
        A(0, 3) = -swung.y();
        A(1, 3) = swung.x();
        const Eigen::Matrix2d cross = A * Sa.leftCols<2>();  // A Sigma_a E'
        S = Sb.topLeftCorner<2, 2>() - Sa.topLeftCorner<2, 2>() - cross - cross.transpose();
        // Second order: a heading error dpsi also pulls the far end back along the lever by
        // dpsi^2 / 2 times its length - along the axis the first order leaves thinnest (a
        // curved path's error is a banana). Its mean and spread, with dpsi ~ N(0, sigma^2):
        // (sigma^2 L / 2)^2 + sigma^4 L^2 / 2 along the lever.
        const double L = dp.norm();
        if (L > 1e-9) {
            const double v = Sb(2, 2) * Sb(2, 2) * L * L * 0.75;
            const Eigen::Vector2d u = dp / L;
            S += v * u * u.transpose();
        }
    } else {
        S = Sb.topLeftCorner<2, 2>() + Sa.topLeftCorner<2, 2>();
    }
    S += params_.floor * params_.floor * Eigen::Matrix2d::Identity();
    return S;
}

double PathUncertainty::segmentDistance2(const Eigen::Matrix2d& S, const Eigen::Vector2d& a,
                                         const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
    // The quadratic form along a + t (b - a) is least at t = r'M e / e'M e (M = S^-1),
    // clamped to the segment.
    const Eigen::LDLT<Eigen::Matrix2d> ldlt(S);
    const Eigen::Vector2d e = b - a, r = p - a, Me = ldlt.solve(e);
    const double eMe = e.dot(Me);
    const double t = eMe > 0 ? std::clamp(r.dot(Me) / eMe, 0.0, 1.0) : 0.0;
    const Eigen::Vector2d d = r - t * e;
    return d.dot(ldlt.solve(d));
}

}  // namespace lodestone::graphslam::closure
