#include <lodestone/config/IniSection.h>
#include <lodestone/graphslam/erd/magnetic/MagneticFieldMapERD.h>
#include <lodestone/magnetic/PassNoiseEstimate.h>
#include <lodestone/magnetic/HyperparameterFit.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "../../Stopwatch.h"

namespace lodestone::graphslam {

namespace {
constexpr double kFitStep = 0.05;  // [m] the grid's readings, averaged by travel
}  // namespace

MagneticFieldMapERD::MagneticFieldMapERD() { setClassName("MagneticFieldMapERD"); }

void MagneticFieldMapERD::configure(const mrpt::config::CConfigFileBase& ini) {
    config::IniSection s(ini, "MagneticFieldMapERD", config::sourceName(ini));
    Params p = params_;
    p.sensorLabel = s.getString("sensor_label", p.sensorLabel);
    p.saturation = s.getDouble("saturation", p.saturation);
    p.filter.particles =
        static_cast<std::size_t>(s.getDouble("particles", static_cast<double>(p.filter.particles)));
    p.filter.passSigma = s.getDouble("pass_sigma", p.filter.passSigma);
    p.passSigmaFromMap = s.getBool("pass_sigma_from_map", p.passSigmaFromMap);
    p.filter.tailDof = s.getDouble("tail_dof", p.filter.tailDof);
    p.filter.updateSpacing = s.getDouble("update_spacing", p.filter.updateSpacing);
    p.filter.convergedSigma = s.getDouble("converged_sigma", p.filter.convergedSigma);
    p.filter.convergedYawSigma =
        s.getDouble("converged_yaw_sigma_deg", p.filter.convergedYawSigma * 180 / M_PI) * M_PI /
        180;
    p.filter.seed =
        static_cast<std::uint64_t>(s.getDouble("seed", static_cast<double>(p.filter.seed)));
    p.grid.cell = s.getDouble("grid_cell", p.grid.cell);
    p.grid.maxCells = static_cast<std::size_t>(
        s.getDouble("grid_max_cells", static_cast<double>(p.grid.maxCells)));
    p.closureEvery = s.getDouble("closure_every", p.closureEvery);
    p.sigmaFloor = s.getDouble("sigma_floor", p.sigmaFloor);
    if (!(p.saturation > 0)) s.fail("saturation", "must be > 0");
    if (!(p.filter.particles >= 100 && p.filter.particles <= 10'000'000))
        s.fail("particles", "must be in [100, 1e7]");
    if (!(p.filter.passSigma >= 0)) s.fail("pass_sigma", "must be >= 0");
    if (!(p.filter.tailDof >= 0)) s.fail("tail_dof", "must be >= 0 (0: Gaussian)");
    if (!(p.filter.updateSpacing >= 0)) s.fail("update_spacing", "must be >= 0");
    if (!(p.filter.convergedSigma >= 0)) s.fail("converged_sigma", "must be >= 0");
    if (!(p.filter.convergedYawSigma > 0)) s.fail("converged_yaw_sigma_deg", "must be > 0");
    if (!(p.grid.cell > 0.005 && p.grid.cell <= 1)) s.fail("grid_cell", "must be in (0.005, 1]");
    if (!(p.grid.maxCells >= 1)) s.fail("grid_max_cells", "must be >= 1");
    if (!(p.closureEvery > 0)) s.fail("closure_every", "must be > 0");
    if (!(p.sigmaFloor > 0)) s.fail("sigma_floor", "must be > 0");
    s.finish();
    params_ = p;
}

bool MagneticFieldMapERD::updateState(mrpt::obs::CActionCollection::Ptr,
                                      mrpt::obs::CSensoryFrame::Ptr, mrpt::obs::CObservation::Ptr) {
    const std::size_t before = stats_.closures;
    for (; seen_ < m_graph->nodes.size() && nodes_ && nodes_->has(seen_); ++seen_) onNode(seen_);
    return stats_.closures > before;
}

void MagneticFieldMapERD::onNode(TNodeID id) {
    const NodeRecord& rec = nodes_->at(id);
    const bool newSegment = path_.segment.empty() || rec.segment != path_.segment.back();
    last_reading_.reset();
    path_.addNode(
        id, *m_graph, *nodes_, params_.saturation,
        [&](const MagneticSample& m) {
            if (params_.sensorLabel.empty()) params_.sensorLabel = m.sensorLabel;
            return m.sensorLabel == params_.sensorLabel;
        },
        [&](const MagneticSample&, double s, const Eigen::Vector3d& b) {
            if (id >= map_nodes_) {
                last_reading_ = b;
                return;
            }
            const Eigen::Vector3d pose = path_.poseAt(*m_graph, id, s);
            const double c = std::cos(pose.z()), sn = std::sin(pose.z());
            map_readings_.push_back({pose.head<2>(),
                                     {c * b.x() - sn * b.y(), sn * b.x() + c * b.y(), b.z()},
                                     s,
                                     rec.segment});
        });
    if (id < map_nodes_) return;
    if (id == map_nodes_) buildFieldMap();
    if (!filter_) return;
    if (newSegment || id == map_nodes_) {
        filter_->reset();  // nothing says where a segment starts, nor which way it faces
        ++stats_.resets;
        segment_travel_ = 0;
        last_closure_travel_ = -std::numeric_limits<double>::infinity();
        converged_since_ = std::numeric_limits<double>::infinity();
        anchored_ = false;
    } else if (const auto e = m_graph->edges.find({id - 1, id}); e != m_graph->edges.end()) {
        const auto& step = e->second;
        constexpr int kAt[3] = {0, 1, 3};  // x, y, yaw in MRPT's 6D order
        Eigen::Matrix3d info;
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) info(r, k) = step.cov_inv(kAt[r], kAt[k]);
        filter_->move({step.mean.x(), step.mean.y(), step.mean.yaw()}, info.inverse());
        segment_travel_ += std::hypot(step.mean.x(), step.mean.y());
    }
    if (last_reading_) {
        const auto t0 = Clock::now();
        if (filter_->measure(*last_reading_)) {
            ++stats_.weighings;
            stats_.weighMs.push_back(msSince(t0));
        }
    }
    const auto e = filter_->estimate();
    // Once the segment was placed (the cloud held one place: position and heading) and joined,
    // it is tracked: a closure whenever the position is one place, the heading's uncertainty
    // carried in the closure's covariance rather than stopping them - without them the graph drifts
    // on the odometry alone while the cloud still knows where it is.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> spread(e.covariance.topLeftCorner<2, 2>());
    // Only once the relocalizer joined the segment to the map: before that a closure is its
    // evidence, and that asks for one place in heading too.
    const bool tracking =
        anchored_ && sameFrame(path_.segment.front(), path_.segment[id]) &&
        std::sqrt(std::max(0.0, spread.eigenvalues().maxCoeff())) < filter_->convergedSigma();
    if (!e.converged) converged_since_ = std::numeric_limits<double>::infinity();
    if (!e.converged && !tracking) return;
    if (e.converged) {
        anchored_ = true;
        if (std::isnan(stats_.firstConvergedTravel)) stats_.firstConvergedTravel = segment_travel_;
        converged_since_ = std::min(converged_since_, segment_travel_);
    }
    if (segment_travel_ - last_closure_travel_ >= params_.closureEvery) propose(id, e);
}

void MagneticFieldMapERD::buildFieldMap() {
    if (map_readings_.empty()) return;  // a map without this magnetometer: nothing to localize in
    const auto t0 = Clock::now();
    // The hyperparameters from the map's own readings along its path.
    std::vector<double> travel;
    std::vector<int> segment;
    std::vector<Eigen::Vector3d> field;
    for (const auto& r : map_readings_) {
        travel.push_back(r.travel);
        segment.push_back(r.segment);
        field.push_back(r.field);
    }
    const auto stretches = fieldFitStretches(travel, segment, field);
    magnetic::GpHyperparameters h;
    if (!stretches.empty()) {
        const auto fit = magnetic::fitHyperparameters(stretches, h);
        if (fit.hyperparameters.valid()) h = fit.hyperparameters;
    }
    stats_.fitted = h;
    // The grid's readings: averaged over kFitStep of travel. A cell conditions on its nearest
    // few readings, and at 50 Hz those would span a few centimetres of one pass.
    std::vector<Eigen::Vector2d> points;
    std::vector<Eigen::Vector3d> fields;
    std::vector<double> binTravel;
    std::vector<int> binSegment;
    std::size_t inBin = 0;
    double binStart = 0;
    for (std::size_t i = 0; i < map_readings_.size(); ++i) {
        const auto& r = map_readings_[i];
        const bool startsBin =
            i == 0 || r.segment != map_readings_[i - 1].segment || r.travel - binStart >= kFitStep;
        if (startsBin) {
            if (inBin) {
                points.back() /= double(inBin);
                fields.back() /= double(inBin);
            }
            points.push_back(Eigen::Vector2d::Zero());
            fields.push_back(Eigen::Vector3d::Zero());
            binTravel.push_back(r.travel);
            binSegment.push_back(r.segment);
            inBin = 0;
            binStart = r.travel;
        }
        points.back() += r.position;
        fields.back() += r.field;
        ++inBin;
    }
    points.back() /= double(inBin);
    fields.back() /= double(inBin);
    Eigen::MatrixX2d P(static_cast<Eigen::Index>(points.size()), 2);
    Eigen::MatrixX3d F(static_cast<Eigen::Index>(points.size()), 3);
    for (std::size_t i = 0; i < points.size(); ++i) {
        P.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
        F.row(static_cast<Eigen::Index>(i)) = fields[i].transpose();
    }
    std::shared_ptr<magnetic::PlanarFieldGrid> grid;
    try {
        grid = std::make_shared<magnetic::PlanarFieldGrid>(P, F, h, params_.grid);
    } catch (const std::invalid_argument& e) {
        // A map too large for the raster (or a fit gone wrong): the run goes on without this
        // localizer - the other loop closers still relocate it - and says why.
        stats_.disabled = e.what();
        MRPT_LOG_WARN_STREAM("MagneticFieldMapERD: no field map, localizer off: " << e.what());
        map_readings_ = {};
        return;
    }
    stats_.mapReadings = map_readings_.size();
    stats_.gridReadings = points.size();
    stats_.gridCells = grid->cells();
    // What a later pass reads beyond the map and the reading noise, from the map's own passes
    // where they overlap (per reading, the fitted reading noise taken out).
    auto filter = params_.filter;
    if (params_.passSigmaFromMap) {
        const auto repeatability = magnetic::passRepeatabilityAcrossPasses(
            points, fields, binTravel, binSegment, h.lengthScale / 4, 4 * h.lengthScale);
        if (repeatability) {
            stats_.mapRepeatability = *repeatability;
            filter.passSigma = std::sqrt(
                std::max(0.0, *repeatability * *repeatability - h.sigmaN * h.sigmaN));
        }
    }
    stats_.passSigma = filter.passSigma;
    filter_ = std::make_unique<magnetic::FieldParticleFilter>(grid, filter);
    map_readings_ = {};
    stats_.buildSeconds = msSince(t0) / 1e3;
}

void MagneticFieldMapERD::propose(TNodeID id, const magnetic::FieldParticleFilter::Estimate& e) {
    TNodeID best = 0;
    double bestD2 = std::numeric_limits<double>::infinity();
    for (TNodeID k = 0; k < map_nodes_; ++k) {
        const auto& p = m_graph->nodes.at(k);
        const double d2 = std::pow(p.x() - e.pose.x(), 2) + std::pow(p.y() - e.pose.y(), 2);
        if (d2 < bestD2) {
            bestD2 = d2;
            best = k;
        }
    }
    const auto& m = m_graph->nodes.at(best);
    // The cloud's covariance (map frame) in the map node's frame.
    const auto z = closureFrom({m.x(), m.y(), m.yaw()}, e.pose, e.covariance, params_.sigmaFloor);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> spread(e.covariance.topLeftCorner<2, 2>());
    // Strong - the relocalizer may merge on it alone - once the cloud has held one place over
    // `closure_every` of travel: the filter weighed the whole way, so a second closure of it
    // would not be independent evidence anyway, only the same posterior later.
    const bool strong = segment_travel_ - converged_since_ >= params_.closureEvery;
    stats_.strongClosures += strong;
    registerClosure(best, id, planarConstraint(z), stats_.closures, strong,
                    -std::sqrt(std::max(0.0, spread.eigenvalues().maxCoeff())));
    ++stats_.closures;
    last_closure_travel_ = segment_travel_;
}

JsonObject MagneticFieldMapERD::describe() const {
    JsonObject params;
    params.set("sensor_label", params_.sensorLabel)
        .set("particles", params_.filter.particles)
        .set("pass_sigma", params_.filter.passSigma)
        .set("pass_sigma_from_map", params_.passSigmaFromMap)
        .set("tail_dof", params_.filter.tailDof)
        .set("update_spacing", params_.filter.updateSpacing)
        .set("converged_sigma", params_.filter.convergedSigma)
        .set("converged_yaw_sigma_deg", params_.filter.convergedYawSigma * 180 / M_PI)
        .set("grid_cell", params_.grid.cell)
        .set("grid_max_cells", params_.grid.maxCells)
        .set("closure_every", params_.closureEvery)
        .set("sigma_floor", params_.sigmaFloor)
        .set("seed", static_cast<std::size_t>(params_.filter.seed));
    JsonObject stats;
    path_.describeCounts(stats)
        .set("map_readings", stats_.mapReadings)
        .set("grid_readings", stats_.gridReadings)
        .set("grid_cells", stats_.gridCells)
        .set("fitted_sigma_f", stats_.fitted.sigmaF)
        .set("fitted_length_scale", stats_.fitted.lengthScale)
        .set("fitted_sigma_n", stats_.fitted.sigmaN)
        .set("map_repeatability", stats_.mapRepeatability)
        .set("pass_sigma_in_use", stats_.passSigma)
        .set("build_seconds", stats_.buildSeconds)
        .set("resets", stats_.resets)
        .set("weighings", stats_.weighings)
        .set("closures", stats_.closures)
        .set("strong_closures", stats_.strongClosures)
        .set("first_converged_travel", stats_.firstConvergedTravel)
        .set("disabled", stats_.disabled);
    describeQueryTimes(stats, stats_.weighMs);
    JsonObject out;
    out.set("class", getClassName()).set("params", params).set("stats", stats);
    return out;
}

}  // namespace lodestone::graphslam
