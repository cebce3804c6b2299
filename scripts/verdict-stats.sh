#!/usr/bin/env bash
# Runs one dtron command many times and counts its verdicts, optionally with both cores kept busy, to prove that
# a correct system never gets FAILED under load. Not part of the test command: run it before a submission that
# touches real time, the bus or the tester, and report its figures.
#
#   scripts/verdict-stats.sh [-n RUNS] [-l | -b BUSY] [-o DIR] -- COMMAND...
#
#   -n RUNS   how many runs (default 20)
#   -l        keep two busy processes running (as many as this 2-core machine has cores) during the runs
#   -b BUSY   keep BUSY busy processes running during the runs (-l is -b 2)
#   -o DIR    where each run's output goes (default: a new folder under /tmp); FAILED and INCONCLUSIVE runs are
#             listed with their verdict lines at the end
#
# Example, the README's main command at 1 ms per time unit, 100 runs under load:
#   scripts/verdict-stats.sh -n 100 -l -- java -jar dtron-cli/target/dtron.jar \
#       models/src/main/resources/io/dtron/models/ticker.xml --classpath models/target/classes \
#       --adapter io.dtron.models.ticker.TickerBusAdapter --timeunit 1000 --timeout 300 --delay-policy eager
set -euo pipefail
# shellcheck source=lib/busy.sh
source "$(dirname "$0")/lib/busy.sh"
runs=20
out=""
while getopts "n:lb:o:" opt; do
    case "$opt" in
        n) runs=$OPTARG ;;
        l | b) busy_option "$opt" ;;
        o) out=$OPTARG ;;
        *) echo "usage: $0 [-n RUNS] [-l | -b BUSY] [-o DIR] -- COMMAND..." >&2; exit 1 ;;
    esac
done
shift $((OPTIND - 1))
[ "${1:-}" = "--" ] && shift
if [ $# -eq 0 ]; then
    echo "usage: $0 [-n RUNS] [-l | -b BUSY] [-o DIR] -- COMMAND..." >&2
    exit 1
fi
out=${out:-$(mktemp -d /tmp/verdict-stats.XXXXXX)}
mkdir -p "$out"

trap busy_stop EXIT
busy_start

passed=0 failed=0 inconclusive=0 other=0
start=$(date +%s)
for i in $(seq 1 "$runs"); do
    log="$out/run-$i.log"
    set +e
    "$@" > "$log" 2>&1
    code=$?
    set -e
    case $code in
        0) passed=$((passed + 1)) ;;
        2) failed=$((failed + 1)) ;;
        3) inconclusive=$((inconclusive + 1)) ;;
        *) other=$((other + 1)) ;;
    esac
    printf 'run %d/%d: exit %d (passed %d, failed %d, inconclusive %d, other %d)\n' "$i" "$runs" "$code" \
        "$passed" "$failed" "$inconclusive" "$other"
done
echo "command: $*"
echo "busy processes: $busy_count; runs: $runs; $(( $(date +%s) - start )) s; logs in $out"
for log in "$out"/run-*.log; do
    if grep -qE '^(FAILED|INCONCLUSIVE)' "$log"; then
        echo "$(basename "$log"): $(grep -E '^(FAILED|INCONCLUSIVE)' "$log" | head -1)"
        { grep -E 'WARN' "$log" || true; } | head -3 | sed 's/^/    /'
    fi
done
echo "$passed passed, $failed failed, $inconclusive inconclusive, $other other"
