#pragma once

#include <lodestone/graphslam/EdgeDecider.h>
#include <lodestone/graphslam/erd/magnetic/MagneticPath.h>
#include <lodestone/magnetic/FieldParticleFilter.h>
#include <lodestone/magnetic/HyperparameterFit.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lodestone::graphslam {

/** Localization in a loaded map's field over the floor (a run started with --map-in): the map's
 * readings, placed where its nodes put them and turned into the map's frame, become a field map
 * (magnetic::PlanarFieldGrid, its hyperparameters fitted on those readings); the run - each
 * segment from its start, since nothing says where it began or which way it faced - is placed in
 * it by Monte Carlo localization (magnetic::FieldParticleFilter) on the graph's odometry steps and
 * the magnetometer's readings. Once the particle cloud holds one place (position and heading),
 * a closure from the map node nearest that place to the newest node is proposed every
 * `closure_every` metres of travel, and from then on whenever the position is one place (the
 * heading's spread in the closure's covariance):
 * the relocalizer merges the run into the map on two that agree, and after that they keep the run
 * on the map. Unlike the sequence matchers it needs no earlier pass along the same line: a path
 * that crosses the mapped ones is placed too, either way.
 *
 * Without a loaded map it does nothing. INI section [MagneticFieldMapERD]: sensor_label,
 * saturation, particles, pass_sigma, pass_sigma_from_map, tail_dof, update_spacing, converged_sigma,
 * converged_yaw_sigma_deg, grid_cell, grid_max_cells (a larger map's band: no field map, the
 * localizer off and report.json's `disabled` says why), closure_every, sigma_floor, seed. */
class MagneticFieldMapERD : public EdgeDecider {
  public:
    struct Params {
        std::string sensorLabel;    ///< the magnetometer used ("": the first one seen)
        double saturation{1000.0};  ///< [uT]
        magnetic::FieldParticleFilter::Params filter;
        magnetic::PlanarFieldGrid::Params grid;
        double closureEvery{1.0};  ///< [m] of travel between two closures
        double sigmaFloor{0.03};   ///< [m] added to a closure's position sigma
        /** The pass noise from the map's own readings where its passes overlap
         * (magnetic::passRepeatabilityAcrossPasses: readings a quarter of the fitted length
         * scale apart, passes four length scales of travel apart, less the fitted reading
         * noise); `pass_sigma` where the map has too few such pairs (a map walked once). */
        bool passSigmaFromMap{true};
    };
    struct Stats {
        std::size_t mapReadings{0}, gridReadings{0}, gridCells{0}, resets{0}, weighings{0},
            closures{0}, strongClosures{0};
        magnetic::GpHyperparameters fitted;
        double buildSeconds{0};
        /** [uT] the pass noise the filter weighs with (from the map, or pass_sigma), and the
         * map's repeatability it came from (NaN: too few overlapping passes). */
        double passSigma{NAN}, mapRepeatability{NAN};
        double firstConvergedTravel{NAN};  ///< [m] along the run's segment
        std::string disabled;  ///< why there is no field map (empty: there is one, or no map)
        std::vector<double> weighMs;
    };

    MagneticFieldMapERD();
    void configure(const mrpt::config::CConfigFileBase& ini) override;
    const Params& params() const { return params_; }
    bool updateState(mrpt::obs::CActionCollection::Ptr action,
                     mrpt::obs::CSensoryFrame::Ptr observations,
                     mrpt::obs::CObservation::Ptr observation) override;
    std::set<std::string> requiredObservations() const override {
        return {"CObservationMagnetometer"};
    }
    JsonObject describe() const override;
    /** Pins its path where any closer's kept closure placed a node (MagneticPath::pinKept). */
    void closuresKept(const std::vector<LoopClosure>& kept) override {
        path_.pinKept(kept, *m_graph);
    }
    const Stats& stats() const { return stats_; }

  private:
    struct MapReading {
        Eigen::Vector2d position;
        Eigen::Vector3d field;  ///< map frame
        double travel{0};       ///< along the map's path (per segment, for the fit)
        int segment{0};
    };
    void onNode(TNodeID id);
    void buildFieldMap();
    void propose(TNodeID id, const magnetic::FieldParticleFilter::Estimate& e);

    Params params_;
    Stats stats_;
    MagneticPath path_;
    TNodeID seen_{0};
    std::vector<MapReading> map_readings_;
    std::unique_ptr<magnetic::FieldParticleFilter> filter_;
    std::optional<Eigen::Vector3d> last_reading_;  ///< of the newest node, robot frame
    double segment_travel_{0}, last_closure_travel_{-INFINITY};
    double converged_since_{INFINITY};
    bool anchored_{false};  ///< the segment's cloud has held one place (then: tracked)  ///< [m] segment travel since which the cloud held one place
};

}  // namespace lodestone::graphslam
