#!/usr/bin/env python3
"""How much of each Aalto trial runs along a line trial 1 drove (the Vicon reference of both):
the share of a trial's places (every 0.05 m of its path) within 0.1 m of trial 1's path, and
the share that also runs along one of trial 1's lines for 2 m - within 0.2 m of it 1 m before
and 1 m after, either way - which a window of 2 m of field needs to be compared along its
length. Prints a markdown table; reads ../shared/data/magnetic/aalto/invensense in place (exits
0 with a note when it is absent).
Usage: scripts/bench/aalto_overlap.py [TRIAL ...]   (default 2-9)"""
import math
import os
import sys

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../../shared/data/magnetic/aalto/invensense")
STEP, NEAR, ALONG, REACH = 0.05, 0.1, 0.2, 20  # m, m, m, samples (1 m at 0.05 m)


def path(trial):
    with open(os.path.join(DATA, f"{trial}-loc.csv")) as f:
        points = [tuple(map(float, line.split(","))) for line in f if line.strip()]
    out, travelled = [points[0]], 0.0
    for a, b in zip(points, points[1:]):
        travelled += math.dist(a, b)
        if travelled >= STEP:
            out.append(b)
            travelled = 0.0
    return out


def main():
    if not os.path.isdir(DATA):
        print(f"aalto_overlap.py: {DATA} is absent; nothing measured")
        return 0
    trials = [int(a) for a in sys.argv[1:]] or list(range(2, 10))
    first = path(1)
    grid = {}
    for i, p in enumerate(first):
        grid.setdefault((int(p[0] // NEAR), int(p[1] // NEAR)), []).append(i)
    print("| trial | places | within 0.1 m of trial 1's path | along one of its lines for 2 m |")
    print("|---|---|---|---|")
    for k in trials:
        places = path(k)
        counted = near = along = 0
        for j in range(REACH, len(places) - REACH):
            counted += 1
            p = places[j]
            cx, cy = int(p[0] // NEAR), int(p[1] // NEAR)
            found = lined = False
            for dx in (-1, 0, 1):
                for dy in (-1, 0, 1):
                    for i in grid.get((cx + dx, cy + dy), []):
                        if math.dist(first[i], p) > NEAR:
                            continue
                        found = True
                        if i < REACH or i + REACH >= len(first):
                            continue
                        before, after = places[j - REACH], places[j + REACH]
                        same = math.dist(first[i - REACH], before) < ALONG and math.dist(first[i + REACH], after) < ALONG
                        back = math.dist(first[i + REACH], before) < ALONG and math.dist(first[i - REACH], after) < ALONG
                        lined = lined or same or back
            near += found
            along += lined
        print(f"| {k} | {counted} | {near / counted:.2f} | {along / counted:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
