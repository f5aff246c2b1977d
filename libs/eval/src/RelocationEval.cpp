#include <lodestone/eval/RelocationEval.h>
#include <lodestone/eval/TrajectoryError.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <set>
#include <stdexcept>

namespace lodestone::eval {

namespace {

double numberOr(const nlohmann::json& o, const char* key, double fallback) {
    const auto it = o.find(key);
    return it != o.end() && it->is_number() ? it->get<double>() : fallback;
}

double wrap(double a) { return std::remainder(a, 2 * M_PI); }

double yawOf(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

}  // namespace

std::vector<ReportedKidnap> readReportedKidnaps(const std::string& reportJson) {
    std::ifstream in(reportJson);
    if (!in) throw std::runtime_error(reportJson + ": cannot open report");
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(reportJson + ": not JSON: " + e.what());
    }
    const nlohmann::json* kidnaps = nullptr;
    if (j.is_object() && j.contains("engine") && j["engine"].is_object() &&
        j["engine"].contains("relocalization") && j["engine"]["relocalization"].is_object()) {
        const auto& r = j["engine"]["relocalization"];
        if (r.contains("kidnaps") && r["kidnaps"].is_array()) kidnaps = &r["kidnaps"];
    }
    if (!kidnaps) {
        throw std::runtime_error(reportJson +
                                 ": no engine.relocalization.kidnaps (not a lodestone-slam report?)");
    }
    std::vector<ReportedKidnap> out;
    for (const auto& k : *kidnaps) {
        if (!k.is_object()) throw std::runtime_error(reportJson + ": a kidnap entry is not an object");
        ReportedKidnap r;
        r.segment = static_cast<int>(numberOr(k, "segment", 0));
        r.firstNode = static_cast<long long>(numberOr(k, "first_node", -1));
        r.liftTime = numberOr(k, "lift_time", NAN);
        r.putDownTime = numberOr(k, "put_down_time", NAN);
        r.relocated = k.value("relocated", false);
        r.mergedLate = k.value("merged_after_segment_ended", false);
        r.mergeTime = numberOr(k, "merge_time", NAN);
        r.relocationTime = numberOr(k, "relocation_time", NAN);
        r.travel = numberOr(k, "travel_to_relocation_m", NAN);
        r.x = numberOr(k, "x", 0);
        r.y = numberOr(k, "y", 0);
        r.yaw = numberOr(k, "yaw", 0);
        r.deciders = k.value("deciders", std::string());
        out.push_back(r);
    }
    return out;
}

RelocationEvaluation evaluateRelocations(const std::vector<ReportedKidnap>& reported,
                                         const std::vector<io::TumPose>& trajectory,
                                         const std::vector<io::TumPose>& mapBefore,
                                         const std::vector<io::TumPose>& truth,
                                         const std::vector<io::KidnapEventRecord>& events,
                                         const RelocationEvalOptions& o) {
    RelocationEvaluation e;
    if (trajectory.size() >= 3) {
        const auto ate = absoluteTrajectoryError(trajectory, truth, o.maxDt);
        if (ate.pairs >= 3) e.runAte = ate.rmse;
    }
    // The map frame against the truth: aligned on what was mapped before the first lift, as
    // it was then when known (relocations attach to that map; what later solves do to it is
    // the map-damage figure), else as it is at the end.
    const double firstLift = events.empty() ? INFINITY : events.front().liftTime;
    std::vector<io::TumPose> before;
    for (const auto& p : trajectory) {
        if (p.timestamp < firstLift) before.push_back(p);
    }
    const auto preLift = absoluteTrajectoryError(mapBefore.size() >= 3 ? mapBefore : before, truth, o.maxDt);
    const bool aligned = preLift.pairs >= 3;
    if (!mapBefore.empty()) {
        const auto then = absoluteTrajectoryError(mapBefore, truth, o.maxDt);
        std::set<double> stamps;
        for (const auto& p : mapBefore) stamps.insert(p.timestamp);
        std::vector<io::TumPose> now;
        for (const auto& p : trajectory) {
            if (stamps.count(p.timestamp)) now.push_back(p);
        }
        const auto after = absoluteTrajectoryError(now, truth, o.maxDt);
        if (then.pairs >= 3) e.mapAteBefore = then.rmse;
        if (after.pairs >= 3) e.mapAteAfter = after.rmse;
    }
    const auto firstNodeTime = [&](const ReportedKidnap& r) {
        return r.firstNode >= 0 && static_cast<std::size_t>(r.firstNode) < trajectory.size()
                   ? trajectory[static_cast<std::size_t>(r.firstNode)].timestamp
                   : NAN;
    };
    std::vector<bool> used(reported.size(), false);
    for (const auto& ev : events) {
        RelocationVerdict v;
        v.index = ev.index;
        // The segment this kidnap opened: by its lift time, or by its first node when the
        // detector did not say when the lift was.
        for (std::size_t k = 0; k < reported.size() && !v.detected; ++k) {
            const auto& r = reported[k];
            const bool byLift =
                std::isfinite(r.liftTime) && std::abs(r.liftTime - ev.liftTime) <= o.matchTolerance;
            const double t0 = firstNodeTime(r);
            const bool byNode = !std::isfinite(r.liftTime) && std::isfinite(t0) &&
                                t0 >= ev.liftTime - o.matchTolerance &&
                                t0 <= ev.putDownTime + 5 * o.matchTolerance;
            if (used[k] || !(byLift || byNode)) continue;
            used[k] = true;
            v.detected = true;
            v.relocated = r.relocated;
            v.mergedLate = r.mergedLate;
            if (r.mergedLate) v.secondsToMerge = r.mergeTime - ev.putDownTime;
            if (!r.relocated) break;
            v.secondsToRelocation = r.relocationTime - ev.putDownTime;
            v.travelToRelocation = r.travel;
            v.deciders = r.deciders;
            const io::TumPose* gt = truthAt(truth, r.relocationTime, o.maxDt);
            if (aligned && gt) {
                const Eigen::Matrix3d Rz =
                    Eigen::AngleAxisd(r.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
                const Eigen::Vector3d p = preLift.alignment * Eigen::Vector3d(r.x, r.y, 0);
                const Eigen::Matrix3d R = preLift.alignment.linear() * Rz;
                v.positionError = std::hypot(p.x() - gt->pose.x(), p.y() - gt->pose.y());
                v.yawError = std::abs(wrap(yawOf(R) - gt->pose.yaw()));
                v.wrong = v.positionError > o.wrongDistance || v.yawError > o.wrongYaw;
            }
        }
        e.kidnaps.push_back(v);
    }
    for (bool u : used) e.falseDetections += !u;
    return e;
}

std::string formatRelocationEvaluation(const RelocationEvaluation& e) {
    std::string out =
        "| kidnap | detected | relocated | s after put-down | m travelled | position error m | "
        "yaw error deg | wrong | deciders |\n|---|---|---|---|---|---|---|---|---|\n";
    std::size_t relocated = 0, wrong = 0;
    char line[300];
    for (const auto& v : e.kidnaps) {
        relocated += v.relocated;
        wrong += v.wrong;
        if (!v.relocated) {
            char note[96] = "";
            if (v.mergedLate) {
                std::snprintf(note, sizeof note,
                              "not while in it: merged %.0f s after put-down by a later pass",
                              v.secondsToMerge);
            }
            std::snprintf(line, sizeof line, "| %d | %s | no | | | | | | %s |\n", v.index,
                          v.detected ? "yes" : "no", note);
        } else {
            std::snprintf(line, sizeof line, "| %d | yes | yes | %.1f | %.2f | %.3f | %.2f | %s | %s |\n",
                          v.index, v.secondsToRelocation, v.travelToRelocation, v.positionError,
                          v.yawError * 180 / M_PI, v.wrong ? "**yes**" : "no", v.deciders.c_str());
        }
        out += line;
    }
    std::snprintf(line, sizeof line, "\nrelocated %zu of %zu, wrong %zu, false detections %zu\n",
                  relocated, e.kidnaps.size(), wrong, e.falseDetections);
    out += line;
    double seconds = 0, metres = 0, worstSeconds = 0, worstMetres = 0;
    for (const auto& v : e.kidnaps) {
        if (!v.relocated) continue;
        seconds += v.secondsToRelocation;
        metres += v.travelToRelocation;
        worstSeconds = std::max(worstSeconds, v.secondsToRelocation);
        worstMetres = std::max(worstMetres, v.travelToRelocation);
    }
    if (relocated) {
        std::snprintf(line, sizeof line,
                      "put-down to relocation: mean %.1f s (max %.1f), mean %.2f m of travel (max %.2f)\n",
                      seconds / double(relocated), worstSeconds, metres / double(relocated),
                      worstMetres);
        out += line;
    }
    if (e.mapAteBefore && e.mapAteAfter) {
        std::snprintf(line, sizeof line,
                      "map before the first lift: ATE %.4f m then, %.4f m at the end (change %+.4f m)\n",
                      *e.mapAteBefore, *e.mapAteAfter, *e.mapAteAfter - *e.mapAteBefore);
        out += line;
    }
    if (e.runAte) {
        std::snprintf(line, sizeof line, "whole run: ATE %.4f m\n", *e.runAte);
        out += line;
    }
    return out;
}

}  // namespace lodestone::eval
