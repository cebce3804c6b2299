#!/usr/bin/env bash
# Runs the live monitor (dtron monitor --cluster) beside live runs of the bundled samples on a JGroups bus, each run
# with a fresh monitor JVM and a fresh tester JVM (dtron run with the sample's bus adapter in it), and counts how the
# monitor's verdict compares with the tester's: the ticker (correct, and slow: a tick 13 units after the last,
# beyond the model's 10 +/- 2), the smart lamp on TRON's LightContr (correct, and late: levels reported 20 units
# late) and the street-light application in headless Chromium (one operator, and four with the session mix-up).
# A monitor's alarm where the tester PASSED is a false alarm, the worst result; no alarm where the tester FAILED is
# a miss. Needs `mvn -DskipTests install` (models' classes and their dependencies; the script asks Maven for their
# classpath once, with $MAVEN_ARGS, e.g. -Dmaven.repo.local=...). Not part of the test command; figures go in
# src/site/markdown/benchmarks.md.
#
#   scripts/monitor-stats.sh [-n RUNS] [-l | -b BUSY] [-s SAMPLES]
#
#   -n RUNS      runs of each sample and variant (default 10)
#   -l           keep both cores busy during the runs (two busy processes)
#   -b BUSY      keep BUSY busy processes running during the runs
#   -s SAMPLES   which samples, comma-separated: ticker,lamp,streetlight (default all three)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
shared=${DTRON_SHARED:-$root/../shared}/models
classes=$root/models/target/classes
cpfile=$root/models/target/monitor-stats.classpath

# shellcheck source=lib/busy.sh
source "$root/scripts/lib/busy.sh"

runs=10 samples=ticker,lamp,streetlight
while getopts "n:lb:s:" opt; do
    case "$opt" in
        n) runs=$OPTARG ;;
        l | b) busy_option "$opt" ;;
        s) samples=$OPTARG ;;
        *) echo "usage: $0 [-n RUNS] [-l | -b BUSY] [-s ticker,lamp,streetlight]" >&2; exit 1 ;;
    esac
done
[ -d "$classes" ] || { echo "$0: $classes is missing: run mvn -DskipTests install" >&2; exit 1; }
if [ ! -s "$cpfile" ]; then
    # shellcheck disable=SC2086
    (cd "$root" && mvn -B -q ${MAVEN_ARGS:-} -pl models dependency:build-classpath -Dmdep.outputFile="$cpfile") \
        || { echo "$0: cannot get the classpath of models from Maven" >&2; exit 1; }
fi
cp="$classes:$(cat "$cpfile")"
dtron() {
    java -cp "$cp" io.dtron.cli.DtronCommand "$@"
}

monitor_pid=""
stop_all() {
    busy_stop
    if [ -n "$monitor_pid" ]; then kill "$monitor_pid" 2>/dev/null || true; fi
}
trap stop_all EXIT
busy_start
out=$(mktemp -d /tmp/monitor-stats.XXXXXX)

# one run: MODEL, MONITOR_OPTIONS (a string), and the tester's arguments after the model
one() {
    local name=$1 model=$2 monitor_options=$3
    shift 3
    local cluster=monitor-$$-$RANDOM log_m="$out/$name-monitor.log" log_t="$out/$name-tester.log"
    # shellcheck disable=SC2086
    dtron monitor "$model" --cluster "$cluster" $monitor_options > "$log_m" 2>&1 &
    monitor_pid=$!
    # the monitor is on the bus once it printed its first line (its member id)
    for _ in $(seq 1 600); do
        grep -qs " as dtron-" "$log_m" && break
        kill -0 "$monitor_pid" 2>/dev/null || break
        sleep 0.1
    done
    set +e
    dtron run "$model" --cluster "$cluster" "$@" > "$log_t" 2>&1
    tester=$?
    # the monitor ends when the run's end reached it and was a reorder window old; it is given a minute
    for _ in $(seq 1 600); do
        kill -0 "$monitor_pid" 2>/dev/null || break
        sleep 0.1
    done
    kill "$monitor_pid" 2>/dev/null
    wait "$monitor_pid"
    monitor=$?
    set -e
    monitor_pid=""
    echo "$tester $monitor"
}

agreed=0 false_alarms=0 misses=0 other=0
count() {
    local what=$1 tester=$2 monitor=$3
    local result
    if { [ "$tester" = 0 ] && [ "$monitor" = 0 ]; } || { [ "$tester" = 2 ] && [ "$monitor" = 2 ]; }; then
        agreed=$((agreed + 1)) result=agreed
    elif [ "$tester" = 0 ] && [ "$monitor" = 2 ]; then
        false_alarms=$((false_alarms + 1)) result="FALSE ALARM"
    elif [ "$tester" = 2 ] && [ "$monitor" = 0 ]; then
        misses=$((misses + 1)) result=MISSED
    else
        other=$((other + 1)) result=other
    fi
    printf '%s: tester exit %s, monitor exit %s: %s\n' "$what" "$tester" "$monitor" "$result"
}

echo "monitor stats: $runs runs of each sample and variant ($samples), $busy_count busy processes;" \
    "load before: $(cut -d' ' -f1-3 /proc/loadavg); logs in $out"
start=$(date +%s)
for i in $(seq 1 "$runs"); do
    case ",$samples," in *,ticker,*)
        model=$classes/io/dtron/models/ticker.xml
        for variant in correct slow; do
            read -r t m < <(one "ticker-$variant-$i" "$model" "" --adapter \
                "io.dtron.models.ticker.TickerBusAdapter:$variant" --timeunit 10000 --timeout 300 --delay-policy eager)
            count "ticker $variant $i" "$t" "$m"
        done ;;
    esac
    case ",$samples," in *,lamp,*)
        model=$shared/tron/LightContr.xml
        for variant in correct late; do
            read -r t m < <(one "lamp-$variant-$i" "$model" "--interface $shared/tron/LightContr.trn" \
                --interface "$shared/tron/LightContr.trn" --adapter "io.dtron.models.lamp.LampBusAdapter:$variant" \
                --timeunit 10000 --timeout 1000 --delay-policy eager)
            count "lamp $variant $i" "$t" "$m"
        done ;;
    esac
    case ",$samples," in *,streetlight,*)
        for variant in 1 4,mixup; do
            users=${variant%%,*}
            model=$out/streetlight-$users.xml
            # the model for USERS operators, as StreetLightModel.write makes it
            [ -e "$model" ] || sed "s/const int USERS = 2;/const int USERS = $users;/" \
                "$classes/io/dtron/models/streetlight/streetlight.xml" > "$model"
            read -r t m < <(one "streetlight-${variant/,/-}-$i" "$model" "" --adapter \
                "io.dtron.models.streetlight.StreetLightWebTest:$variant" --timeunit 100000 --timeout 200 \
                --delay-policy random-bounded --delay-bound 4)
            count "street light $variant $i" "$t" "$m"
        done ;;
    esac
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg); $(( $(date +%s) - start )) s"
echo "$agreed agreed, $false_alarms false alarms, $misses missed, $other other (a tester's INCONCLUSIVE, an error)"
