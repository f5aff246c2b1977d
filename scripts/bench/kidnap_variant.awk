# Writes a variant of a kidnap scenario INI (scripts/bench/kidnap.sh --variants): another
# simulator seed and, for every kidnap_<n> line, another put-down drawn at random on the
# scenario's waypoint loop (a leg chosen by length, 15-85 % along it; with min_leg set, only on
# legs at least that long, 20-80 % along: the corridor's plain stretches), facing the loop's way
# within +-15 deg, and the lift time moved by up to +-15 s. Lift order and carry time are kept.
#   awk -v variant=N [-v min_leg=M] -f kidnap_variant.awk SCENARIO.ini > VARIANT.ini
BEGIN {
    srand(1000 + variant)
    if (min_leg == "") min_leg = 0
}
function strip(s) { sub(/;.*/, "", s); return s }
/^[ \t]*waypoints[ \t]*=/ {
    line = strip($0); sub(/^[^=]*=/, "", line)
    n = split(line, v, /[ \t]+/)
    m = 0
    for (i = 1; i <= n; ++i) if (v[i] != "") w[m++] = v[i] + 0
    points = m / 2
}
/^[ \t]*seed[ \t]*=/ { print "seed = " (variant * 7919 + 17); next }
/^[ \t]*kidnap_[0-9]+[ \t]*=/ {
    split(strip($0), kv, "=")
    split(kv[2], f, " ")
    name = kv[1]; gsub(/[ \t]/, "", name)
    # a leg of the closed loop, chosen with probability proportional to its length
    total = 0
    for (k = 0; k < points; ++k) {
        j = (k + 1) % points
        len[k] = sqrt((w[2*j] - w[2*k])^2 + (w[2*j+1] - w[2*k+1])^2)
        if (len[k] >= min_leg) total += len[k]
    }
    r = rand() * total
    for (k = 0; k < points; ++k) {
        if (len[k] < min_leg) continue
        if (r <= len[k]) break
        r -= len[k]
    }
    if (k >= points) k = points - 1
    j = (k + 1) % points
    lo = min_leg > 0 ? 0.2 : 0.15
    t = lo + rand() * (1 - 2 * lo)
    x = w[2*k] + t * (w[2*j] - w[2*k]); y = w[2*k+1] + t * (w[2*j+1] - w[2*k+1])
    yaw = atan2(w[2*j+1] - w[2*k+1], w[2*j] - w[2*k]) * 180 / 3.14159265358979 + (rand() * 30 - 15)
    lift = f[1] + (rand() * 30 - 15)
    printf "%s = %.1f %s  %.2f %.2f  %.1f\n", name, lift, f[2], x, y, yaw
    next
}
{ print }
