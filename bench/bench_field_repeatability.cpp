// How well a recording's field repeats between passes of one place, against how far apart its
// reference trajectory says the passes ran - along the path and across it:
//   bench_field_repeatability CSV [CSV ...]      (Kok & Solin walk CSVs)
// Every revisit of the reference (a sample at least 5 m of travel after another, within 0.8 m
// of it and nearest to it there, heading within 45 deg of its way) gives a pair of 1.2 m windows
// in the earlier pass's path frame (along, left, up; the field turned from the levelled frame
// to the world and then into that frame). The query window is resampled at the same along
// coordinates as the target's; the pair's difference is the RMS of the three components' differences
// after each component's mean difference over the window is taken out (an offset between passes
// is not a place's signature). Two curves: pairs the reference places within 0.1 m across,
// compared with the query shifted along the path by 0 ... 0.4 m (and, for scale, the earlier
// window with itself shifted: what moving that far does to the field); and every pair unshifted,
// binned by how far across the reference places the query (the mean over the window). In a
// field that varies alike along and across (the isotropic model of magnetic::WindowDisplacement),
// the curves rise alike. Adjacent samples give overlapping pairs: the counts are of pairs,
// not of independent places.
#include <lodestone/datasets/MagneticRecording.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <string>
#include <vector>

using namespace lodestone;

namespace {

constexpr double kHalf = 0.6;     // [m] half a window
constexpr double kStep = 0.05;    // [m] resampling
constexpr double kMargin = 0.6;   // [m] of path kept beyond a window, for the shifts
constexpr double kNear = 0.8;     // [m] a revisit: within this of the earlier sample
constexpr double kGap = 5.0;      // [m] of travel between the two
constexpr double kMaxShift = 0.4; // [m]

struct Walk {
    std::vector<Eigen::Vector2d> p;
    std::vector<Eigen::Vector3d> world;  // the field, world frame
    std::vector<double> s;               // travel [m]
};

Walk toWalk(const datasets::MagneticRecording& rec) {
    Walk w;
    for (const auto& r : rec.samples) {
        const double c = std::cos(r.heading), sn = std::sin(r.heading);
        w.p.emplace_back(r.x, r.y);
        w.world.emplace_back(c * r.field.x - sn * r.field.y, sn * r.field.x + c * r.field.y,
                             r.field.z);
        w.s.push_back(w.s.empty() ? 0.0 : w.s.back() + (w.p.back() - w.p[w.p.size() - 2]).norm());
    }
    return w;
}

double travelDirection(const Walk& w, std::size_t i) {
    const std::size_t a = i >= 3 ? i - 3 : 0, b = std::min(i + 3, w.p.size() - 1);
    const Eigen::Vector2d d = w.p[b] - w.p[a];
    return std::atan2(d.y(), d.x());
}

/** A pass around sample `c` in the frame at `origin` facing `e`: along coordinate (increasing
 * along the pass, else empty), across coordinate and field components (along, left, up). */
struct Pass {
    std::vector<double> u, v;
    std::vector<Eigen::Vector3d> b;
    std::optional<Eigen::Vector4d> at(double x) const {  // (field, across) interpolated
        for (std::size_t k = 0; k + 1 < u.size(); ++k) {
            if (x < u[k] || x > u[k + 1]) continue;
            const double f = (x - u[k]) / (u[k + 1] - u[k]);
            Eigen::Vector4d r;
            r.head<3>() = b[k] + f * (b[k + 1] - b[k]);
            r[3] = v[k] + f * (v[k + 1] - v[k]);
            return r;
        }
        return std::nullopt;
    }
};

std::optional<Pass> passAround(const Walk& w, std::size_t c, const Eigen::Vector2d& origin,
                               const Eigen::Vector2d& e) {
    const Eigen::Vector2d n(-e.y(), e.x());
    Pass p;
    for (std::size_t k = 0; k < w.p.size(); ++k) {
        if (std::abs(w.s[k] - w.s[c]) > kHalf + kMargin) continue;
        const Eigen::Vector2d d = w.p[k] - origin;
        const double u = d.dot(e);
        if (!p.u.empty() && u <= p.u.back()) return std::nullopt;  // turns back: not one pass
        p.u.push_back(u);
        p.v.push_back(d.dot(n));
        const auto& m = w.world[k];
        p.b.emplace_back(m.x() * e.x() + m.y() * e.y(), m.x() * n.x() + m.y() * n.y(), m.z());
    }
    return p;
}

/** RMS differences of `query` shifted by `shift` against `target` - as they are, and with each
 * component's mean difference taken out - and the query's mean across coordinate. */
struct Difference {
    double rms[2]{0, 0};  // as they are, offsets out
    double across{0};
};

/** nullopt where a window runs off either pass. */
std::optional<Difference> difference(const Pass& target, const Pass& query, double shift) {
    std::vector<Eigen::Vector3d> d;
    double across = 0;
    for (double x = -kHalf; x <= kHalf + 1e-9; x += kStep) {
        const auto t = target.at(x), q = query.at(x + shift);
        if (!t || !q) return std::nullopt;
        d.push_back(q->head<3>() - t->head<3>());
        across += (*q)[3] - (*t)[3];
    }
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& v : d) mean += v;
    mean /= double(d.size());
    double raw = 0, centred = 0;
    for (const auto& v : d) {
        raw += v.squaredNorm();
        centred += (v - mean).squaredNorm();
    }
    Difference r;
    r.rms[0] = std::sqrt(raw / (3.0 * double(d.size())));
    r.rms[1] = std::sqrt(centred / (3.0 * double(d.size())));
    r.across = across / double(d.size());
    return r;
}

struct Curve {
    std::vector<double> sum;
    std::vector<int> n;
    explicit Curve(std::size_t bins) : sum(bins, 0.0), n(bins, 0) {}
    void add(std::size_t bin, double v) {
        if (bin >= sum.size()) return;
        sum[bin] += v;
        ++n[bin];
    }
    std::string cell(std::size_t bin) const {
        char b[48];
        if (n[bin] == 0) return "-";
        std::snprintf(b, sizeof b, "%d, %.2f", n[bin], sum[bin] / n[bin]);
        return b;
    }
};

void analyse(const std::string& csv) {
    const auto rec = datasets::readKokWalk(csv);
    const Walk w = toWalk(rec);
    const auto shifts = static_cast<std::size_t>(std::lround(kMaxShift / 0.1)) + 1;
    // [0]: the differences as they are (as MagneticWindowERD compares them), [1]: offsets out
    std::vector<Curve> along(2, Curve(shifts)), across(2, Curve(shifts)), self(2, Curve(shifts));
    const auto add = [](std::vector<Curve>& c, std::size_t bin, const Difference& d) {
        for (int m = 0; m < 2; ++m) c[m].add(bin, d.rms[m]);
    };
    // Where along the field puts the later pass: the best of the shifts, by the differences
    // as they are; per bin of its size, pairs, RMS at the reference's alignment and at the best,
    // and the later passes' times.
    struct Placed {
        int n{0};
        double atReference{0}, atBest{0};
        std::set<int> seconds;
    };
    std::vector<Placed> placed(shifts);
    std::size_t pairs = 0;
    for (std::size_t i = 0; i < w.p.size(); ++i) {
        const double hi = travelDirection(w, i);
        const Eigen::Vector2d e(std::cos(hi), std::sin(hi));
        for (std::size_t j = i + 1; j < w.p.size(); ++j) {
            if (w.s[j] - w.s[i] < kGap) continue;
            const double dist = (w.p[j] - w.p[i]).norm();
            if (dist > kNear) continue;
            // the nearest sample of this pass
            if (j > 0 && (w.p[j - 1] - w.p[i]).norm() < dist) continue;
            if (j + 1 < w.p.size() && (w.p[j + 1] - w.p[i]).norm() < dist) continue;
            if (std::abs(std::remainder(travelDirection(w, j) - hi, 2 * M_PI)) > M_PI / 4)
                continue;
            const auto target = passAround(w, i, w.p[i], e), query = passAround(w, j, w.p[i], e);
            if (!target || !query) continue;
            const auto base = difference(*target, *query, 0);
            if (!base) continue;
            ++pairs;
            double best = base->rms[0], bestShift = 0;
            for (double x = -kMaxShift; x <= kMaxShift + 1e-9; x += kStep) {
                const auto r = difference(*target, *query, x);
                if (r && r->rms[0] < best) {
                    best = r->rms[0];
                    bestShift = x;
                }
            }
            auto& bin = placed[std::min(shifts - 1, static_cast<std::size_t>(
                                                        std::abs(bestShift) / 0.1 + 1e-9))];
            ++bin.n;
            bin.atReference += base->rms[0];
            bin.atBest += best;
            bin.seconds.insert(static_cast<int>(rec.samples[j].t));
            add(across, static_cast<std::size_t>(std::abs(base->across) / 0.1), *base);
            if (std::abs(base->across) >= 0.1) continue;
            for (std::size_t k = 0; k < shifts; ++k) {
                // both ways along, each counted
                for (const double sign : {-1.0, 1.0}) {
                    if (const auto r = difference(*target, *query, sign * 0.1 * double(k)))
                        add(along, k, *r);
                    if (const auto r = difference(*target, *target, sign * 0.1 * double(k)))
                        add(self, k, *r);
                    if (k == 0) break;
                }
            }
        }
    }
    std::printf("\n%s, %zu revisit pairs: where along the field places the later pass (the "
                "best shift within %.1f m by the differences as they are)\n\n"
                "| shift [m] | pairs | RMS difference at the reference's alignment [uT] | at the "
                "best shift [uT] | the later passes' times [s] |\n|---|---|---|---|---|\n",
                rec.name.c_str(), pairs, kMaxShift);
    for (std::size_t k = 0; k < shifts; ++k) {
        const auto& b = placed[k];
        std::string times;
        for (const int t : b.seconds) times += (times.empty() ? "" : " ") + std::to_string(t);
        char range[32];
        if (k + 1 == shifts) {
            std::snprintf(range, sizeof range, "%.1f (the search's end)", kMaxShift);
        } else {
            std::snprintf(range, sizeof range, "%.1f - %.1f", 0.1 * double(k), 0.1 * double(k + 1));
        }
        std::printf("| %s | %d | %.2f | %.2f | %s |\n", range, b.n,
                    b.n ? b.atReference / b.n : NAN, b.n ? b.atBest / b.n : NAN,
                    k >= 2 ? times.c_str() : "");
    }
    for (int m = 0; m < 2; ++m) {
        std::printf("\n%s, %zu revisit pairs: RMS differences %s [uT]\n\n", rec.name.c_str(), pairs,
                    m == 0 ? "as they are" : "with each component's offset over the window out");
        std::printf(
            "| shifted along by [m] | one pass against itself: windows, RMS | the later pass "
            "(within 0.1 m across): pairs, RMS | across, by the reference [m] | every pair "
            "unshifted: pairs, RMS |\n|---|---|---|---|---|\n");
        for (std::size_t k = 0; k < shifts; ++k) {
            std::printf("| %.1f | %s | %s | %.1f - %.1f | %s |\n", 0.1 * double(k),
                        self[m].cell(k).c_str(), along[m].cell(k).c_str(), 0.1 * double(k),
                        0.1 * double(k + 1), across[m].cell(k).c_str());
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_field_repeatability CSV [CSV ...]\n");
        return 2;
    }
    try {
        for (int i = 1; i < argc; ++i) analyse(argv[i]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
