// MagneticWindowERD's report.json part: its parameters, the funnel of its queries, the pass
// noise it used, its query times (and with the truth, the recall funnel).
#include <lodestone/graphslam/erd/magnetic/MagneticWindowERD.h>

#include <string>

namespace lodestone::graphslam {

JsonObject MagneticWindowERD::describe() const {
    JsonObject params;
    params.set("sensor_label", params_.sensorLabel)
        .set("resample_step", params_.step)
        .set("window_length", params_.window)
        .set("query_every", params_.queryEvery)
        .set("chain_windows", params_.chainWindows)
        .set("learn_noise", params_.learnNoise)
        .set("noise_prior_windows", params_.noisePriorWindows)
        .set("window_sigma", prior_sigma_)
        .set("window_bias_sigma", params_.noise.biasSigma)
        .set("window_trend_sigma", params_.noise.trendSigma)
        .set("gp_length_scale", params_.lengthScale)
        .set("null_model",
             params_.nullModel == Params::NullModel::Building ? "building" : "window")
        .set("null_odds", params_.nullOdds)
        .set("min_travel_gap", params_.minTravelGap)
        .set("gate_chi2", params_.gateChi2)
        .set("gate_heading_drift", params_.uncertainty.headingBias)
        .set("gate_floor", params_.uncertainty.floor)
        .set("test_quantile", params_.quantile)
        .set("min_posterior", params_.minPosterior)
        .set("distinct_radius", params_.distinctRadius)
        .set("closure_every", params_.closureEvery)
        .set("confirm", params_.confirm)
        .set("pass_displacement", params_.passDisplacement)
        .set("fine_amplitude", params_.fineAmplitude)
        .set("map_thinning_radius", params_.mapThinningRadius)
        .set("sigma_cross", params_.sigmaCross)
        .set("turn_floor_deg", params_.turnFloorDeg);
    JsonObject stats;
    path_.describeCounts(stats)
        .set("mirror_sensor", mirror_)
        .set("queries", stats_.queries)
        .set("flat", stats_.flat)
        .set("no_candidate", stats_.noCandidate)
        .set("no_fit", stats_.noFit)
        .set("ambiguous", stats_.ambiguous)
        .set("chained", stats_.chained)
        .set("chained_accepted", stats_.chainedAccepted)
        .set("window_sigma_in_use", params_.noise.sigma)
        .set("noise_learnt_from_readings", noise_ ? noise_->dof() : 0.0)
        .set("noise_updates", stats_.noiseUpdates)
        .set("accepted", stats_.accepted)
        .set("unmeasured", stats_.unmeasured)
        .set("confirmed", stats_.confirmed)
        .set("edges", stats_.edges)
        .set("forward_edges", stats_.forward)
        .set("backward_edges", stats_.backward)
        .set("map_readings", stats_.mapReadings)
        .set("map_readings_thinned", stats_.mapReadingsThinned);
    describeQueryTimes(stats, stats_.queryMs);
    JsonObject out;
    out.set("class", getClassName()).set("params", params).set("stats", stats);
    if (truth_) out.set("truth_funnel", describeTruth());
    return out;
}

}  // namespace lodestone::graphslam
