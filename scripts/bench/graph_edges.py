#!/usr/bin/env python3
"""A lodestone-slam run's graph edges against the truth, each with the covariance it claimed:
does a covariance lie? Two markdown tables:
  1. loop closures, by closer (closures.csv's kept rows, their edges in graph.graph): the
     position error of the later node (median), the claimed position sigma (median, sqrt of
     the trace), NEES in x, y, yaw (mean; 3 if honest) and the share inside its own 99.73 %
     position ellipse;
  2. odometry edges (node k to k + 1), by the heading sigma they claimed: the heading error's
     RMS and sum, its NEES (mean; 1 if honest), and their length against the truth's (a scale
     bias: summed lengths, measured over true, minus one);
  3. the same edges split by whether they claim under half the truth's length (of those that
     moved 2 cm or more): how much of a run's shortness a few edges hold (a bridge from a
     standstill) and how much is spread over every step;
  4. the same edges split by the time they span (a gap's bridge spans more than 0.5 s, VO's
     steps less): their position error (x, y) against the truth, summed and RMS - where one
     bridge design's edges are nearer the truth than another's.
Errors are taken in the edge's own frame (planar: x, y, yaw). Kidnap edges (sigma > 1) are
left out.
Usage: scripts/bench/graph_edges.py RUN_DIR GROUND_TRUTH.tum"""
import bisect
import csv
import math
import sys


def read_tum(path):
    rows = []
    for line in open(path):
        if line.strip() and not line.startswith("#"):
            t, x, y, _, qx, qy, qz, qw = map(float, line.split()[:8])
            rows.append((t, x, y, math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))))
    return rows


def pose_at(tum, times, t):
    i = min(max(bisect.bisect_left(times, t), 1), len(tum) - 1)
    (ta, xa, ya, ca), (tb, xb, yb, cb) = tum[i - 1], tum[i]
    f = 0.0 if tb == ta else min(max((t - ta) / (tb - ta), 0.0), 1.0)
    turn = math.remainder(cb - ca, 2 * math.pi)
    return xa + f * (xb - xa), ya + f * (yb - ya), ca + f * turn


def relative(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return c * dx + s * dy, -s * dx + c * dy, math.remainder(b[2] - a[2], 2 * math.pi)


def inverse3(m):
    a, b, c = m[0]
    d, e, f = m[1]
    g, h, i = m[2]
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    return [[(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det],
            [(f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det],
            [(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det]]


def read_edges(path):
    """(from, to) -> [(x, y, yaw), covariance 3x3 of x, y, yaw] from EDGE3 lines."""
    edges = {}
    for line in open(path):
        p = line.split()
        if not p or p[0] != "EDGE3":
            continue
        v = list(map(float, p[3:]))
        info = [[0.0] * 6 for _ in range(6)]
        k = 6
        for r in range(6):
            for c in range(r, 6):
                info[r][c] = info[c][r] = v[k]
                k += 1
        planar = [[info[r][c] for c in (0, 1, 5)] for r in (0, 1, 5)]
        edges.setdefault((int(p[1]), int(p[2])), []).append(((v[0], v[1], v[5]), inverse3(planar)))
    return edges


def error_of(measured, truth):
    return measured[0] - truth[0], measured[1] - truth[1], math.remainder(measured[2] - truth[2], 2 * math.pi)


def nees(e, cov):
    inf = inverse3(cov)
    return sum(e[r] * inf[r][c] * e[c] for r in range(3) for c in range(3))


def nees_xy(e, cov):
    a, b, d = cov[0][0], cov[0][1], cov[1][1]
    det = a * d - b * b
    return (d * e[0] * e[0] - 2 * b * e[0] * e[1] + a * e[1] * e[1]) / det


def median(v):
    s = sorted(v)
    return s[len(s) // 2] if s else float("nan")


def main():
    run, gt = sys.argv[1], sys.argv[2]
    tum = read_tum(gt)
    times = [r[0] for r in tum]
    edges = read_edges(run + "/graph.graph")
    by_closer, used = {}, {}
    for r in csv.DictReader(open(run + "/closures.csv")):
        key = (int(r["from_node"]), int(r["to_node"]))
        i = used.get(key, 0)
        used[key] = i + 1
        if r["kept"] != "1" or i >= len(edges.get(key, [])):
            continue
        measured, cov = edges[key][i]
        truth = relative(pose_at(tum, times, float(r["from_time"])), pose_at(tum, times, float(r["to_time"])))
        e = error_of(measured, truth)
        by_closer.setdefault(r["source"], []).append(
            (math.hypot(e[0], e[1]), math.sqrt(cov[0][0] + cov[1][1]), nees(e, cov), nees_xy(e, cov) < 11.83))
    print("| closer | closures | position error median [m] | claimed position sigma median [m] | NEES x, y, yaw (3: honest) | inside its 99.73 % ellipse |")
    print("|---|---|---|---|---|---|")
    for name, rows in sorted(by_closer.items()):
        print("| %s | %d | %.3f | %.3f | %.2f | %.2f |" % (
            name, len(rows), median([r[0] for r in rows]), median([r[1] for r in rows]),
            sum(r[2] for r in rows) / len(rows), sum(r[3] for r in rows) / len(rows)))
    node_time = {int(r["node"]): float(r["timestamp"]) for r in csv.DictReader(open(run + "/nodes.csv"))}
    classes = [(0, 0.02), (0.02, 0.05), (0.05, 0.1), (0.1, 0.2), (0.2, 0.5), (0.5, 1e9)]
    stats = {c: [] for c in classes}
    halves = {"under half the truth's length": [], "the rest": []}
    spans = {"up to 0.5 s (VO's steps)": [], "over 0.5 s (gaps)": []}
    for k, t in node_time.items():
        if (k, k + 1) not in edges or k + 1 not in node_time:
            continue
        measured, cov = edges[(k, k + 1)][0]
        if cov[2][2] > 1:
            continue
        truth = relative(pose_at(tum, times, t), pose_at(tum, times, node_time[k + 1]))
        e = error_of(measured, truth)
        yaw_err = e[2]
        spans["over 0.5 s (gaps)" if node_time[k + 1] - t > 0.5 else "up to 0.5 s (VO's steps)"].append(
            math.hypot(e[0], e[1]))
        sigma = math.degrees(math.sqrt(cov[2][2]))
        lengths = (math.hypot(measured[0], measured[1]), math.hypot(truth[0], truth[1]))
        if lengths[1] >= 0.02:
            halves["under half the truth's length" if lengths[0] < 0.5 * lengths[1] else "the rest"].append(lengths)
        for c in classes:
            if c[0] <= sigma < c[1]:
                stats[c].append((math.degrees(yaw_err), yaw_err * yaw_err / cov[2][2], lengths))
    print()
    print("| odometry edges: claimed heading sigma [deg] | edges | heading error RMS [deg] | sum [deg] | heading NEES (1: honest) | length against the truth's |")
    print("|---|---|---|---|---|---|")
    for c in classes:
        v = stats[c]
        if v:
            true_length = sum(l[1] for _, _, l in v)
            print("| %s - %s | %d | %.3f | %+.2f | %.2f | %+.2f %% over %.1f m |" % (
                c[0], c[1] if c[1] < 1e9 else "", len(v), math.sqrt(sum(a * a for a, _, _ in v) / len(v)),
                sum(a for a, _, _ in v), sum(n for _, n, _ in v) / len(v),
                100 * (sum(l[0] for _, _, l in v) / true_length - 1) if true_length > 0 else 0, true_length))
    print()
    print("| odometry edges that moved >= 2 cm | edges | true length [m] | measured [m] | length against the truth's |")
    print("|---|---|---|---|---|")
    for name, v in halves.items():
        true_length, length = sum(l[1] for l in v), sum(l[0] for l in v)
        print("| %s | %d | %.2f | %.2f | %+.2f %% |" % (
            name, len(v), true_length, length, 100 * (length / true_length - 1) if true_length > 0 else 0))
    print()
    print("| odometry edges spanning | edges | position error sum [m] | RMS [m] |")
    print("|---|---|---|---|")
    for name, v in spans.items():
        if v:
            print("| %s | %d | %.3f | %.4f |" % (name, len(v), sum(v), math.sqrt(sum(a * a for a in v) / len(v))))


if __name__ == "__main__":
    main()
