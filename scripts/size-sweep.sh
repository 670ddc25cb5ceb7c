#!/usr/bin/env bash
# Issue 27's size table: every glyph A-Z 0-9 compiled alone (default robot,
# default lane) at each letter height given (default 6ft 7ft 8ft 9ft 10ft
# 2.5m 12ft), with `--no-size-search`. Prints, per height, how many glyphs
# compile READY, READY WITH NOTES, NOT READY or are refused (exit 2), the
# worst film cv and overspray among the compiled ones, and the glyphs that
# are not READY (or WITH NOTES). The film figures are compile's own
# (summary.film, measured as `basr preview` measures it). Two compiles at a
# time; about 5 minutes on 2 cores for the default heights.
#
#   scripts/size-sweep.sh                 # the default heights
#   scripts/size-sweep.sh 6ft 8ft         # these heights
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin="$PWD/target/release/basr"
heights=("$@")
[ ${#heights[@]} -gt 0 ] || heights=(6ft 7ft 8ft 9ft 10ft 2.5m 12ft)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
glyphs=$(echo {A..Z} {0..9})

# One compile: "<height> <glyph> <exit> <verdict> <cv> <overspray>".
one() {
    local h=$1 g=$2 dir rc=0
    dir=$(mktemp -d -p "$work")
    "$bin" compile "$g" --letter-height "$h" --no-size-search --json \
        -o "$dir/j.job.json" >"$dir/out.json" 2>/dev/null || rc=$?
    python3 - "$h" "$g" "$rc" "$dir/out.json" <<'EOF'
import json, sys
h, g, rc, path = sys.argv[1:]
try:
    v = json.load(open(path))
    film = v["summary"].get("film") or {}
    print(h, g, rc, v["verdict"].replace(" ", "_"), film.get("cv", "nan"), film.get("overspray", "nan"))
except Exception:
    print(h, g, rc, "refused", "nan", "nan")
EOF
    rm -rf "$dir"
}
export -f one
export bin work

for h in "${heights[@]}"; do
    for g in $glyphs; do echo "$h $g"; done
done | xargs -P 2 -n 2 bash -c 'one "$0" "$1"' >"$work/all.txt"

printf '%-6s %5s %5s %5s %7s %9s %10s  %s\n' height READY NOTES NOT refused "worst cv" "worst over" "not READY (or with notes)"
for h in "${heights[@]}"; do
    awk -v h="$h" '
        $1 == h {
            n[$4]++
            if ($4 != "refused") {
                if ($5 + 0 > cv) cv = $5 + 0
                if ($6 + 0 > ov) ov = $6 + 0
            }
            if ($4 != "ready") bad = bad " " $2 (($4 == "ready_with_notes") ? "*" : ($4 == "refused") ? "!" : "")
        }
        END {
            printf "%-6s %5d %5d %5d %7d %9.3f %10.3f %s\n", h, n["ready"], n["ready_with_notes"], n["not_ready"], n["refused"], cv, ov, bad
        }' <(sort -k2,2 "$work/all.txt")
done
echo "(* = READY WITH NOTES, ! = refused; the rest listed are NOT READY)"
