#pragma once

#include <lodestone/graphslam/EdgeDecider.h>
#include <lodestone/graphslam/erd/magnetic/MagneticPath.h>
#include <lodestone/magnetic/PlanarFieldGrid.h>
#include <lodestone/magnetic/StretchFieldMatcher.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace lodestone::graphslam {

/** Loop closure where a run crosses its own past: the run's earlier readings, placed where the
 * graph has them now, are a field map of the floor (magnetic::PlanarFieldGrid, hyperparameters
 * fitted on the run's own readings); every `query_every` metres the last `stretch_length`
 * metres of readings are placed in it near where the graph puts them (magnetic::matchStretch,
 * the gate the path's uncertainty since the place). A match decisive against a random place of
 * the map (log Bayes factor >= `min_log_evidence`) that holds one place (posterior sigma below
 * half the length scale and `converged_yaw_sigma_deg`) closes the loop from the earlier node
 * nearest it. Unlike the sequence matchers it needs no earlier pass along the same line - a path
 * crossing its earlier ones, at any angle, is placed - and a pass beside an earlier one is
 * placed beside it, where the map's field says so, not on it.
 *
 * INI section [MagneticCrossingERD]: sensor_label, saturation, stretch_length, query_every,
 * min_loop, min_log_evidence, min_support, converged_sigma, converged_yaw_sigma_deg, fit_after,
 * pass_sigma, tail_dof, max_offset, max_yaw_deg, sigma_floor, grid_cell. */
class MagneticCrossingERD : public EdgeDecider {
  public:
    struct Params {
        std::string sensorLabel;    ///< the magnetometer used ("": the first one seen)
        double saturation{1000.0};  ///< [uT]
        magnetic::StretchMatchParams match;
        magnetic::PlanarFieldGrid::Params grid;
        double stretchLength{3.0};  ///< [m] of recent readings placed
        double queryEvery{0.5};     ///< [m] of travel between two queries
        /** [m] the map's readings are at least this much travel before the stretch (closer
         * ones are the same pass, whose odometry needs no closing). */
        double minLoop{3.0};
        double minLogEvidence{std::log(1000.0)};
        double minSupport{1.0};    ///< length scales of the stretch on the map's band
        double convergedSigma{0};  ///< [m] 0: half the fitted length scale
        double convergedYawSigma{5 * M_PI / 180};
        double fitAfter{10.0};    ///< [m] of readings before the hyperparameters are fitted
        double sigmaFloor{0.03};  ///< [m] added to a closure's position sigma
    };
    struct Stats {
        std::size_t queries{0}, offMap{0}, notDecisive{0}, notOnePlace{0}, tooLittleSupport{0},
            ambiguous{0}, closures{0}, fits{0};
        magnetic::GpHyperparameters fitted;
        std::vector<double> queryMs;
    };

    MagneticCrossingERD();
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
    /** A reading averaged over `grid.cell` of travel, in the levelled robot frame (the maps'
     * cells: that, or a sixth of the fitted length scale if larger). */
    struct Reading {
        TNodeID node{0};
        double travel{0};
        int segment{0};
        Eigen::Vector3d field{Eigen::Vector3d::Zero()};
        int count{0};
    };
    /** Earlier readings within reach of a stretch, in the map's frame, pass by pass. */
    struct Passes {
        std::vector<Eigen::Vector2d> points;
        std::vector<Eigen::Vector3d> fields;
        std::vector<TNodeID> nodeOf;
        std::vector<std::size_t> start{0};  ///< each pass's first reading, then the end
    };
    /** A stretch matched against one pass's field map. */
    struct PassMatch {
        magnetic::StretchMatch m;
        std::size_t begin, end;
    };
    void onNode(TNodeID id);
    void fit();
    /** The stretch ending at node `id` matched against each earlier pass; a closure where one
     * place is decisive. */
    void query(TNodeID id);
    /** The readings of the last stretch_length in `segment`, relative to the anchor (x, y,
     * yaw); `first` set to the first of them. */
    std::vector<magnetic::StretchSample> recentStretch(int segment, const Eigen::Vector3d& anchor,
                                                       std::size_t& first) const;
    /** Readings before `first`, in the stretch's frame, min_loop behind it and within the
     * search's reach of one of its readings. */
    Passes earlierPasses(std::size_t first, int segment, const Eigen::Vector3d& anchor,
                         const std::vector<magnetic::StretchSample>& stretch) const;
    /** The stretch matched against each pass long enough (its field map, the path's gate). */
    std::vector<PassMatch> matchPasses(TNodeID id, const Eigen::Vector3d& anchor,
                                       const std::vector<magnetic::StretchSample>& stretch,
                                       const Passes& passes) const;
    /** The best pass's match as a closure if decisive, one place and no other pass as
     * decisive elsewhere (each loss counted). */
    void decide(TNodeID id, const std::vector<PassMatch>& matches, const Passes& passes);

    Params params_;
    Stats stats_;
    MagneticPath path_;
    TNodeID seen_{0};
    std::vector<Reading> readings_;
    std::optional<magnetic::GpHyperparameters> h_;
    double fitted_at_{0};  ///< [m] readings' travel at the last fit
    double total_travel_{0}, last_query_{-INFINITY}, next_allowed_{-INFINITY};
};

}  // namespace lodestone::graphslam
