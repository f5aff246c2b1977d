# Sourced by the bench drivers that run one INI several ways (depth_alignment.sh, gravity.sh):
# with $base (the INI) and $out (a scratch folder) set,
#   variant NAME KEY=VALUE...   writes $out/NAME.ini: $base with those keys' values replaced
#   field REPORT KEY            the first number a report.json gives KEY
variant() {
    local name=$1
    shift
    cp "$base" "$out/$name.ini"
    for kv in "$@"; do
        grep -q "^${kv%%=*} *=" "$out/$name.ini" || { echo "no key ${kv%%=*} in $base" >&2; exit 1; }
        sed -i "s|^${kv%%=*} *=[^;]*|${kv%%=*} = ${kv#*=} |" "$out/$name.ini"
    done
}
field() { { grep -o "\"$2\": [0-9.e+-]*" "$1" || true; } | head -1 | awk '{print $2}'; }
