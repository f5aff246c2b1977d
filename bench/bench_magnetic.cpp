// Magnetic loop closure on real recordings (issue: magnetic loop closure, paper 000 §2.2).
//   bench_magnetic recordings DATA_DIR OUT_DIR [SEEDS [INI [ONLY]]]   Aalto trials 1-9 and Kok's
//   walks:
//       each imported with the drift model for seeds 1..SEEDS, run through lodestone-slam's code
//       path with odometry_only.ini and magnetic_gp.ini; median ATEs, closures, and how far
//       the accepted closures are from the ground truth, and how much of each path comes back
//       near an earlier pass (same direction / reversed / crossing) - what any loop closer
//       has to work with; then a synthetic long walk (two laps of 120 m, the first revisit
//       after 120 m: the situation of long real walks). INI (a config_ini/ name, or a path)
//       replaces magnetic_gp.ini; ONLY keeps the recordings whose name contains it.
//   bench_magnetic timing                                 time per new supernode (KD-tree
//       search + costs + bundle + GP alignment) with 1 000 and 10 000 supernodes stored, and
//       of one field-map search.
//   bench_magnetic timing-run OUT_DIR [INI]               the ERD's own time per new supernode
//       on a 2 530 m walk (over 10 000 supernodes stored by its end).
#include "magnetic_recordings.h"

#include <lodestone/datasets/MagneticRecordingImport.h>
#include <lodestone/io/TumTrajectory.h>
#include <lodestone/magnetic/FieldMapSearch.h>
#include <lodestone/magnetic/GpShiftCorrection.h>
#include <lodestone/magnetic/PlanarAlignment.h>
#include <lodestone/magnetic/SupernodeIndex.h>
#include <lodestone/magnetic/SupernodeTrack.h>
#include <lodestone/obs/registerAllClasses.h>
#include <lodestone/slamapp/SlamRun.h>
#include <mrpt/graphs/CNetworkOfPoses.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <functional>
#include <iostream>
#include <random>
#include <sstream>

namespace fs = std::filesystem;
using namespace lodestone;

namespace {
double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty()      ? 0
           : v.size() % 2 ? v[v.size() / 2]
                          : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// The true pose at time t (nearest ground-truth sample; they are 10-50 Hz).
mrpt::poses::CPose3D truthAt(const std::vector<io::TumPose>& gt, double t) {
    const auto it = std::lower_bound(
        gt.begin(), gt.end(), t, [](const io::TumPose& p, double v) { return p.timestamp < v; });
    if (it == gt.end()) return gt.back().pose;
    if (it != gt.begin() && t - (it - 1)->timestamp < it->timestamp - t) return (it - 1)->pose;
    return it->pose;
}

struct ClosureErrors {
    std::size_t count{0}, over05{0}, alongOver05{0};
    double median{0}, max{0};
    double alongMedian{0}, alongMax{0};  ///< the part along the target's path
};

// Loop-closure edges of the written graph (non-consecutive nodes) against the true relative
// position of their nodes.
ClosureErrors closureErrors(const std::string& dir, const std::vector<io::TumPose>& gt) {
    mrpt::graphs::CNetworkOfPoses3DInf g;
    g.loadFromTextFile(dir + "/graph.graph");
    const auto nodes = io::readTumTrajectory(dir + "/trajectory.tum");
    std::vector<double> err, along;
    ClosureErrors r;
    for (const auto& [ids, c] : g.edges) {
        const auto [from, to] = ids;
        if (to == from + 1 || from >= nodes.size() || to >= nodes.size()) continue;
        const auto truth = truthAt(gt, nodes[to].timestamp) - truthAt(gt, nodes[from].timestamp);
        const double e = std::hypot(truth.x() - c.mean.x(), truth.y() - c.mean.y());
        err.push_back(e);
        r.over05 += e > 0.5;
        r.max = std::max(r.max, e);
        // The matcher places the node along the target's path; across it a walker may have
        // passed anywhere within a stride. Along: the error's part in the path direction at
        // the target (the true motion's direction from `from` to its successor).
        const auto next =
            truthAt(gt, nodes[std::min<std::size_t>(from + 1, nodes.size() - 1)].timestamp) -
            truthAt(gt, nodes[from].timestamp);
        const double len = std::hypot(next.x(), next.y());
        if (len > 1e-6) {
            const double a = std::abs(
                ((truth.x() - c.mean.x()) * next.x() + (truth.y() - c.mean.y()) * next.y()) / len);
            along.push_back(a);
            r.alongOver05 += a > 0.5;
            r.alongMax = std::max(r.alongMax, a);
        }
    }
    r.count = err.size();
    r.median = median(err);
    r.alongMedian = median(along);
    return r;
}

/** How much of the path passes within `radius` of where it was at least `gap` metres of travel
 * earlier: in the same direction (within 45 deg), reversed (within 45 deg of opposite) or
 * crossing [m of path]. A sequence matcher can only close the first (and, mirrored, the second). */
struct Revisits {
    double same{0}, reversed{0}, crossing{0};
};
Revisits revisits(const datasets::MagneticRecording& rec, double radius = 0.2, double gap = 4.0) {
    const double step = 0.05;
    std::vector<Eigen::Vector2d> p;
    for (const auto& s : rec.samples) {
        const Eigen::Vector2d q(s.x, s.y);
        if (p.empty() || (q - p.back()).norm() >= step) p.push_back(q);
    }
    const auto n = p.size();
    const auto dir = [&](std::size_t i) {
        const Eigen::Vector2d d = p[std::min(i + 4, n - 1)] - p[i >= 4 ? i - 4 : 0];
        return std::atan2(d.y(), d.x());
    };
    const auto skip = static_cast<std::size_t>(gap / step);
    Revisits r;
    for (std::size_t i = skip; i < n; ++i) {
        bool same = false, rev = false, cross = false;
        for (std::size_t j = 0; j + skip <= i; ++j) {
            if ((p[i] - p[j]).norm() >= radius) continue;
            const double a = std::abs(std::remainder(dir(i) - dir(j), 2 * M_PI));
            (a < M_PI / 4 ? same : a > 3 * M_PI / 4 ? rev : cross) = true;
        }
        r.same += same * step;
        r.reversed += rev * step;
        r.crossing += cross * step;
    }
    return r;
}

int recordings(const std::string& data, const std::string& out, int seeds,
               const std::string& magneticIni, const std::string& only) {
    registerAllClasses();
    const auto recs = benchRecordings(data);
    std::printf(
        "| recording | path [m] | seeds | ATE odometry [m] | ATE magnetic [m]: median / worst | "
        "magnetic / odometry: median / worst | "
        "closure edges per run | closure error: median / max [m] | > 0.5 m | along the path: "
        "median / max [m] | > 0.5 m | real-time factor | path within 0.2 m of an earlier pass: "
        "same direction / reversed / crossing [m] |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& rec : recs) {
        if (!only.empty() && rec.name.find(only) == std::string::npos) continue;
        const auto recording = rec.read();
        const auto seen = revisits(recording);
        std::vector<double> odo, mag, ratio, med, worst, rt, amed, aworst;
        std::size_t edges = 0, over = 0, aover = 0;
        for (int seed = 1; seed <= seeds; ++seed) {
            const std::string stem = out + "/" + rec.name.substr(0, rec.name.find(' ')) +
                                     rec.name.substr(rec.name.find(' ') + 1) + "_s" +
                                     std::to_string(seed);
            const auto imported = importSeed(recording, stem + ".rawlog", seed);
            const auto gt = io::readTumTrajectory(imported.groundTruth);
            double ate[2] = {0, 0};
            for (int k = 0; k < 2; ++k) {
                const auto run = runImported(imported, k == 0 ? "odometry_only.ini" : magneticIni,
                                             stem + (k == 0 ? "_odo" : "_mag"));
                const auto& o = run.options;
                const auto& r = run.result;
                const double wall = run.wallSeconds;
                if (!run.ok()) {
                    std::cerr << rec.name << ": " << run.errors;
                    return 1;
                }
                ate[k] = *r.ateRmse;
                if (k == 1) {
                    rt.push_back(imported.duration / wall);
                    const auto ce = closureErrors(o.outDir, gt);
                    edges += ce.count;
                    over += ce.over05;
                    aover += ce.alongOver05;
                    med.push_back(ce.median);
                    worst.push_back(ce.max);
                    amed.push_back(ce.alongMedian);
                    aworst.push_back(ce.alongMax);
                }
            }
            odo.push_back(ate[0]);
            mag.push_back(ate[1]);
            ratio.push_back(ate[1] / ate[0]);
        }
        std::printf(
            "| %s | %.1f | %d | %.3f | %.3f / %.3f | %.2f / %.2f | %.1f | %.3f / %.3f | %zu | %.3f / "
            "%.3f | %zu | %.0fx | %.1f / %.1f / %.1f |\n",
            rec.name.c_str(), recording.pathLength(), seeds, median(odo), median(mag),
            *std::max_element(mag.begin(), mag.end()), median(ratio),
            *std::max_element(ratio.begin(), ratio.end()), double(edges) / seeds, median(med),
            *std::max_element(worst.begin(), worst.end()), over, median(amed),
            *std::max_element(aworst.begin(), aworst.end()), aover, median(rt), seen.same,
            seen.reversed, seen.crossing);
        std::fflush(stdout);
    }
    return 0;
}

int timing() {
    // A long synthetic path: smooth random field, 0.05 m resampling, supernodes every 0.25 m.
    std::mt19937 rng(3);
    std::normal_distribution<double> n(0, 1);
    magnetic::SupernodeTrack track({0.05, 2.0, 0.25}, 2);
    magnetic::SupernodeIndex index(2, track.samplesPerSupernode());
    Eigen::Vector2d f(50, -40), v(0, 0);
    std::printf(
        "| supernodes stored | queries | KD-tree + costs ms: mean / max | path GP alignment ms: "
        "mean / max | plane alignment ms: mean / max | total ms: mean / max | field-map search ms "
        "(once per metre, map_search = true): mean / max |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    double s = 0;
    for (const std::size_t target : {std::size_t{1000}, std::size_t{10000}}) {
        while (index.size() < target) {
            s += 0.01;
            v = 0.98 * v + 0.4 * Eigen::Vector2d(n(rng), n(rng));  // correlated anomalies
            for (const auto& sn : track.add(s, f + v, 0, 0)) index.add(sn);
        }
        const auto& samples = track.samples();
        double searchSum = 0, searchMax = 0, gpSum = 0, gpMax = 0, planeSum = 0, planeMax = 0,
               totalMax = 0, mapSum = 0, mapMax = 0;
        const int queries = 200;
        for (int q = 0; q < queries; ++q) {
            const auto& probe =
                track.supernodes()[static_cast<std::size_t>(q) * 37 % track.supernodes().size()];
            const auto t0 = std::chrono::steady_clock::now();
            float best = 1e9;
            for (const auto id : index.nearest(probe, 20)) {
                // (as the ERD costs a candidate: at its best alignment within half a stride)
                best = std::min(best, track.alignedCost(probe, track.supernodes()[id],
                                                        track.halfStrideSamples())
                                          .first);
            }
            const auto t1 = std::chrono::steady_clock::now();
            // The alignment the ERD runs on a bundle: GP over 3 m + margins, scan +-0.5 m.
            const std::size_t end = std::min(samples.size(), probe.last + 20);
            const std::size_t begin = end >= 60 + 24 ? end - 60 - 24 : 0;
            std::vector<double> tx, qx;
            Eigen::MatrixXd T(static_cast<Eigen::Index>(end - begin), 2), Q(60, 2);
            for (std::size_t i = begin; i < end; ++i) {
                tx.push_back(samples[i].s);
                T.row(static_cast<Eigen::Index>(i - begin)) =
                    samples[i].value.cast<double>().transpose();
            }
            for (std::size_t i = 0; i < 60; ++i) {
                qx.push_back(samples[begin + 12 + i].s);
                Q.row(static_cast<Eigen::Index>(i)) =
                    samples[begin + 12 + i].value.cast<double>().transpose();
            }
            magnetic::GaussianProcess1D gp({4.0, 0.3, 0.5, 10.0});
            gp.fit(tx, T);
            const auto shift = magnetic::scanShift(gp, qx, Q, {0.5, 0.02, 0.01});
            const auto t2 = std::chrono::steady_clock::now();
            // Then the plane refinement (alignment = plane): a 2-D GP over three earlier passes
            // 0.25 m apart, every second reading, and the query stretch moved against it.
            std::vector<Eigen::Vector2d> at;
            std::vector<int> rows;
            for (const double y : {0.0, 0.25, -0.25}) {
                for (std::size_t i = 0; i < tx.size(); i += 2) {
                    at.emplace_back(tx[i], y);
                    rows.push_back(static_cast<int>(i));
                }
            }
            Eigen::MatrixX2d P(static_cast<Eigen::Index>(at.size()), 2), start(60, 2);
            Eigen::MatrixXd Y(static_cast<Eigen::Index>(at.size()), 2);
            for (std::size_t i = 0; i < at.size(); ++i) {
                P.row(static_cast<Eigen::Index>(i)) = at[i].transpose();
                Y.row(static_cast<Eigen::Index>(i)) = T.row(rows[i]);
            }
            for (Eigen::Index i = 0; i < 60; ++i) start.row(i) << qx[static_cast<std::size_t>(i)] + 0.05, 0.1;
            magnetic::GaussianProcess2D gp2({4.0, 0.3, 0.5, 10.0});
            gp2.fit(P, Y);
            const auto moved = magnetic::alignInPlane(gp2, start, Q, {});
            const auto t3 = std::chrono::steady_clock::now();
            // The field map's search (MagneticGpERDFieldMap.cpp): the same three passes as the
            // map, every second query reading placed inside a gate of 0.5 m sigma (its floor).
            magnetic::GaussianProcess2D map(gp2.hyperparameters());
            map.fit(P, Y);
            Eigen::MatrixX2d half(30, 2);
            Eigen::MatrixXd halfQ(30, 2);
            for (Eigen::Index i = 0; i < 30; ++i) {
                half.row(i) = start.row(2 * i);
                halfQ.row(i) = Q.row(2 * i);
            }
            magnetic::searchFieldMap(map, half, halfQ, 0.25 * Eigen::Matrix2d::Identity(), {});
            const double d = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t3).count();
            mapSum += d;
            mapMax = std::max(mapMax, d);
            const double a = std::chrono::duration<double, std::milli>(t1 - t0).count();
            const double b = std::chrono::duration<double, std::milli>(t2 - t1).count();
            const double c = std::chrono::duration<double, std::milli>(t3 - t2).count();
            searchSum += a;
            gpSum += b;
            planeSum += c;
            searchMax = std::max(searchMax, a);
            gpMax = std::max(gpMax, b);
            planeMax = std::max(planeMax, c);
            totalMax = std::max(totalMax, a + b + c);
            if (best > 1e8 || !shift.valid || !moved.valid)
                std::cerr << "query " << q << " found nothing\n";
        }
        std::printf("| %zu | %d | %.3f / %.3f | %.3f / %.3f | %.3f / %.3f | %.3f / %.3f | %.3f / %.3f |\n",
                    index.size(), queries, searchSum / queries, searchMax, gpSum / queries, gpMax,
                    planeSum / queries, planeMax, (searchSum + gpSum + planeSum) / queries,
                    totalMax, mapSum / queries, mapMax);
    }
    return 0;
}

/** The ERD's own time per new supernode (search + matching + alignment, as report.json's
 * query_ms) on a walk long enough to store 10 000 supernodes: 21 laps of the long walk's
 * rectangle (2 530 m), through lodestone-slam's code path with magnetic_gp.ini. */
int timingRun(const std::string& out, const std::string& magneticIni) {
    registerAllClasses();
    datasets::OdometryDriftModel model;
    model.seed = 1;
    fs::create_directories(out);
    const auto imported = datasets::writeMagneticRecording(syntheticLongWalk(21), out + "/laps21.rawlog", model);
    slamapp::SlamRunOptions o;
    o.rawlog = imported.rawlog;
    o.config = magneticIni.find('/') != std::string::npos
                   ? magneticIni
                   : std::string(LODESTONE_CONFIG_INI_DIR) + "/slam/" + magneticIni;
    o.outDir = out + "/laps21_mag";
    o.quiet = true;
    std::ostringstream sout, serr;
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = slamapp::runSlam(o, sout, serr);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (r.exitCode != 0) {
        std::cerr << serr.str();
        return 1;
    }
    // report.json: MagneticGpERD's describe() under the edge decider's children.
    std::ifstream in(o.outDir + "/report.json");
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto number = [&](const std::string& key) {
        const auto at = json.find("\"" + key + "\"");
        return at == std::string::npos ? -1.0 : std::atof(json.c_str() + json.find(':', at) + 1);
    };
    std::printf("| walk | path [m] | supernodes stored at the end | time per new supernode ms: mean / max | real-time factor |\n");
    std::printf("|---|---|---|---|---|\n");
    std::printf("| 21 laps of 120 m | %.0f | %.0f | %.3f / %.3f | %.0fx |\n", syntheticLongWalk(21).pathLength(),
                number("supernodes"), number("query_ms_mean"), number("query_ms_max"),
                imported.duration / wall);
    return 0;
}
}  // namespace

int main(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "recordings" && argc >= 4) {
        return recordings(argv[2], argv[3], argc > 4 ? std::atoi(argv[4]) : 5,
                          argc > 5 ? argv[5] : "magnetic_gp.ini", argc > 6 ? argv[6] : "");
    }
    if (mode == "timing") return timing();
    if (mode == "timing-run" && argc >= 3) return timingRun(argv[2], argc > 3 ? argv[3] : "magnetic_gp.ini");
    std::cerr << "usage: bench_magnetic recordings DATA_DIR OUT_DIR [SEEDS] | timing | timing-run OUT_DIR [INI]\n";
    return 2;
}
