#!/usr/bin/env bash
# Compile scaling (benches/README.md, issue 28): runs the release
# `basr compile` on messages of 4, 25, 50, 100 and 200 letters (the
# 100-letter corridor of benches/compile.rs, cut or repeated to the count)
# and prints, per message, the process's CPU seconds (user + system), its
# wall seconds, CPU per letter and its ratio to the 4-letter message's, its
# peak memory and the job file's size. The goal (issue 28): CPU per letter
# within 1.5x from 4 to 200 letters, 200 letters <= 20 s wall on 2 cores.
# With --memory, also the peak memory of `preview` and `simulate` of the
# 200-letter job beside its file size (goal: <= 1.5x the file).
# Needs GNU time (/usr/bin/time). Takes ~2 minutes on an idle 2-core machine.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x /usr/bin/time ] || { echo "needs GNU time at /usr/bin/time (apt-get install time)" >&2; exit 2; }
memory=false
[ "${1:-}" = "--memory" ] && memory=true
nice -n 10 cargo build --release --quiet
bin=$PWD/target/release/basr
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

corridor="STOP AHEAD SCHOOL XING SLOW BUS ONLY PED XING KEEP CLEAR SIGNAL AHEAD YIELD AHEAD BIKE LANE TURN ONLY RIGHT TURN ONLY STOP"
# The first $1 letters of the corridor, repeated as needed (the last word cut).
message() {
    local want=$1 out="" have=0 w
    while [ "$have" -lt "$want" ]; do
        for w in $corridor; do
            [ "$have" -ge "$want" ] && break
            w=${w:0:$((want - have))}
            out="$out $w"
            have=$((have + ${#w}))
        done
    done
    echo "${out# }"
}

# "cpu wall peak_kb" of the command (exit 1, a failed verdict, is a result).
measure() {
    local rc=0
    /usr/bin/time -f "%U %S %e %M" -o "$tmp/time" "$@" >/dev/null 2>"$tmp/err" || rc=$?
    if [ "$rc" -gt 1 ]; then
        cat "$tmp/err" >&2
        exit 1
    fi
    awk '{ printf "%.2f %.2f %d\n", $1 + $2, $3, $4 }' "$tmp/time"
}

base=""
printf '%-8s %8s %8s %8s %12s %8s %10s %10s\n' letters stations "CPU s" "wall s" "CPU/letter" ratio "peak MB" "job MB"
for n in 4 25 50 100 200; do
    read -r cpu wall kb < <(measure "$bin" compile -q -o "$tmp/job$n.json" "$(message "$n")")
    stations=$(python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['stations']))" "$tmp/job$n.json" 2>/dev/null || echo "?")
    per=$(awk -v c="$cpu" -v n="$n" 'BEGIN { printf "%.4f", c / n }')
    [ -z "$base" ] && base=$per
    printf '%-8s %8s %8s %8s %12s %8s %10.1f %10.1f\n' "$n" "$stations" "$cpu" "$wall" "$per" \
        "$(awk -v a="$per" -v b="$base" 'BEGIN { printf "%.2f", a / b }')" \
        "$(awk -v k="$kb" 'BEGIN { print k / 1024 }')" \
        "$(awk -v b="$(stat -c %s "$tmp/job$n.json")" 'BEGIN { print b / 1048576 }')"
done

if $memory; then
    job=$tmp/job200.json
    size=$(stat -c %s "$job")
    printf '\n%-10s %8s %8s %10s %10s %8s\n' command "CPU s" "wall s" "peak MB" "job MB" "peak/job"
    for cmd in compile preview simulate; do
        case $cmd in
            compile) args=(compile -q -o "$tmp/again.json" "$(message 200)") ;;
            preview) args=(preview -q "$job" -o "$tmp/preview.svg") ;;
            simulate) args=(simulate "$job") ;;
        esac
        read -r cpu wall kb < <(measure "$bin" "${args[@]}")
        printf '%-10s %8s %8s %10.1f %10.1f %8.2f\n' "$cmd" "$cpu" "$wall" \
            "$(awk -v k="$kb" 'BEGIN { print k / 1024 }')" \
            "$(awk -v b="$size" 'BEGIN { print b / 1048576 }')" \
            "$(awk -v k="$kb" -v b="$size" 'BEGIN { printf "%.2f", k * 1024 / b }')"
    done
fi
