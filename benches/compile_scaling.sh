#!/usr/bin/env bash
# Compile scaling in instructions (benches/README.md): runs `basr compile`
# under callgrind for 4, 26 and 100 letters (the messages of
# benches/compile.rs) and prints the instructions of compile_job less the
# one-off font parse, per letter, and the ratio of per-letter cost at 26 and
# 100 letters to that at 4. Needs valgrind; takes ~2 minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v valgrind >/dev/null || { echo "needs valgrind (apt-get install valgrind)" >&2; exit 2; }
cargo build --release --quiet
bin=$PWD/target/release/basr
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

alphabet="ABCDE FGHIJ KLMNO PQRST UVWXY Z"
corridor="STOP AHEAD SCHOOL XING SLOW BUS ONLY PED XING KEEP CLEAR SIGNAL AHEAD YIELD AHEAD BIKE LANE TURN ONLY RIGHT TURN ONLY STOP"

# Inclusive instruction count of the first function whose name matches $2.
ir() { awk -v pat="$2" '$0 ~ pat { gsub(",", "", $1); print $1; exit }' "$1"; }

base=""
printf '%-8s %8s %16s %16s %8s\n' letters strokes "Ir compile" "Ir per letter" ratio
for case in "4|STOP" "26|$alphabet" "100|$corridor"; do
    n=${case%%|*}
    msg=${case#*|}
    valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" \
        "$bin" compile -q -o "$tmp/job.json" "$msg" >/dev/null 2>&1
    callgrind_annotate --inclusive=yes "$tmp/cg.out" >"$tmp/cg.txt" 2>/dev/null
    job=$(ir "$tmp/cg.txt" 'plan::compile::compile_job ')
    font=$(ir "$tmp/cg.txt" 'Font::from_toml_str ')
    strokes=$(grep -o '"strokes": [0-9]*' "$tmp/job.json" | tail -1 | grep -o '[0-9]*$')
    per=$(((job - font) / n))
    [ -z "$base" ] && base=$per
    printf '%-8s %8s %16s %16s %8s\n' "$n" "$strokes" "$((job - font))" "$per" \
        "$(awk -v a="$per" -v b="$base" 'BEGIN { printf "%.2f", a / b }')"
done
