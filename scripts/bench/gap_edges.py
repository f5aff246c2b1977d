#!/usr/bin/env python3
"""The edges a lodestone-slam run bridged VO's gaps with, against the truth: every odometry edge
(node k to k + 1) spanning at least MIN seconds, its translation against the true translation
between the two nodes (in the first node's frame), and its turn against the true turn. Prints one
line: the count, the error's median, maximum and RMS [m], the error per axis (RMS, the first
node's x, y, z), and the turn's error (the angle of est^T true: median, maximum [deg]).
Usage: scripts/bench/gap_edges.py RUN_DIR GROUND_TRUTH.tum [MIN_SECONDS (default 1.0)]"""
import bisect
import math
import sys


def rotation(qx, qy, qz, qw):
    return [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
            [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
            [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]]


def euler(roll, pitch, yaw):
    """Rz(yaw) Ry(pitch) Rx(roll), as MRPT's CPose3D."""
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch),
                              math.cos(yaw), math.sin(yaw))
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]


def angle_between(A, B):
    """The angle of A^T B [deg]."""
    trace = sum(A[r][c] * B[r][c] for r in range(3) for c in range(3))
    return math.degrees(math.acos(max(-1.0, min(1.0, (trace - 1) / 2))))


def main():
    run, truth_path = sys.argv[1], sys.argv[2]
    min_seconds = float(sys.argv[3]) if len(sys.argv) > 3 else 1.0
    stamps = {}
    for line in open(run + "/nodes.csv"):
        if line.startswith("node"):
            continue
        f = line.split(",")
        stamps[int(f[0])] = float(f[1])
    truth = [list(map(float, l.split()[:8])) for l in open(truth_path)
             if l.strip() and not l.startswith("#")]
    times = [r[0] for r in truth]

    def at(t):
        return truth[min(bisect.bisect_left(times, t - 1e-4), len(truth) - 1)]

    errors, axes, turns = [], [0.0, 0.0, 0.0], []
    for line in open(run + "/graph.graph"):
        f = line.split()
        if not f or f[0] != "EDGE3":
            continue
        a, b = int(f[1]), int(f[2])
        if b != a + 1 or stamps[b] - stamps[a] < min_seconds:
            continue
        edge = list(map(float, f[3:6]))
        A, B = at(stamps[a]), at(stamps[b])
        R = rotation(*A[4:8])
        d = [B[i] - A[i] for i in (1, 2, 3)]
        true = [sum(R[r][c] * d[r] for r in range(3)) for c in range(3)]
        errors.append(math.dist(edge, true))
        RB = rotation(*B[4:8])
        true_turn = [[sum(R[k][r] * RB[k][c] for k in range(3)) for c in range(3)] for r in range(3)]
        turns.append(angle_between(euler(*map(float, f[6:9])), true_turn))
        for k in range(3):
            axes[k] += (edge[k] - true[k]) ** 2
    if not errors:
        print("0 edges")
        return
    n = len(errors)
    errors.sort()
    turns.sort()
    print("%d edges, error median %.3f max %.3f RMS %.3f m; per axis RMS x %.3f y %.3f z %.3f m; "
          "turn error median %.2f max %.2f deg" % (
              n, errors[n // 2], errors[-1], math.sqrt(sum(e * e for e in errors) / n),
              *(math.sqrt(s / n) for s in axes), turns[n // 2], turns[-1]))


if __name__ == "__main__":
    main()
