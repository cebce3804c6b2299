#!/usr/bin/env bash
# Starts the README's quick-start command twice on one bus, the second 0.5 s after the first, N times, and counts
# what each pair ended as: the issue's expectation is one PASSED and one refused ("has a run in progress"), every
# time; anything else is listed with its lines. Not part of the test command; figures go in
# src/site/markdown/benchmarks.md. Needs `mvn -B -q -DskipTests package` first.
#
#   scripts/two-testers.sh [-n TRIES] [-g SECONDS] [-l]
#
#   -n TRIES    how many pairs (default 10)
#   -g SECONDS  the gap between the two starts (default 0.5)
#   -l          keep both cores busy meanwhile
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# shellcheck source=lib/busy.sh
source "$root/scripts/lib/busy.sh"
tries=10 gap=0.5
while getopts "n:g:l" opt; do
    case "$opt" in
        n) tries=$OPTARG ;;
        g) gap=$OPTARG ;;
        l) busy_option "$opt" ;;
        *) echo "usage: $0 [-n TRIES] [-g SECONDS] [-l]" >&2; exit 1 ;;
    esac
done
jar=$root/dtron-cli/target/dtron.jar
[ -e "$jar" ] || { echo "$0: $jar is missing: run mvn -B -q -DskipTests package" >&2; exit 1; }
out=$(mktemp -d /tmp/two-testers.XXXXXX)
trap busy_stop EXIT
busy_start
run() {
    java -jar "$jar" "$root/models/src/main/resources/io/dtron/models/ticker.xml" --classpath "$root/models/target/classes" \
        --adapter io.dtron.models.ticker.TickerBusAdapter --timeunit 10000 --timeout 300 --delay-policy eager \
        --cluster "$1" > "$2" 2>&1 || true
}
good=0
echo "two testers on one bus, ${gap} s apart, $tries tries; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for i in $(seq 1 "$tries"); do
    cluster=two-$$-$i
    run "$cluster" "$out/$i-first.log" & first=$!
    sleep "$gap"
    run "$cluster" "$out/$i-second.log"
    wait "$first"
    verdicts=""
    for who in first second; do
        log=$out/$i-$who.log
        if grep -q "has a run in progress" "$log"; then v=refused
        else v=$(grep -m1 -oE "^(PASSED|FAILED|INCONCLUSIVE)" "$log" || echo none); fi
        verdicts="$verdicts $who=$v"
    done
    case "$verdicts" in
        *" first=PASSED second=refused"|*" first=refused second=PASSED") good=$((good + 1)); mark=ok ;;
        *) mark=UNEXPECTED ;;
    esac
    echo "try $i:$verdicts $mark"
done
echo "$good of $tries tries: one PASSED and one refused; logs in $out; load after: $(cut -d' ' -f1-3 /proc/loadavg)"
