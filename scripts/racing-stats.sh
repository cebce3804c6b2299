#!/usr/bin/env bash
# Counts the verdicts of the racing sample: inputs in a window of 2 time units (9 <= e <= 11) racing the system's
# timeout, with the system's adapter in a JVM of its own and a fresh dtron.jar JVM as the tester, each started anew
# for every run (a fresh JVM's first compilations and collections are part of what is measured). The runs and the
# counting are scripts/verdict-stats.sh's. Needs `mvn -DskipTests install` and dtron-cli's test classes
# (`mvn -pl dtron-cli test-compile`). Not part of the test command; figures go in src/site/markdown/benchmarks.md.
#
#   scripts/racing-stats.sh [-n RUNS] [-l | -b BUSY] [-u TIMEUNIT_US] [-v correct|late] [-t TIMEOUT_UNITS]
#
#   -n RUNS      how many runs (default 20)
#   -l           keep both cores busy during the runs (verdict-stats.sh -l)
#   -b BUSY      keep BUSY busy processes running during the runs (-b 1: one busy core)
#   -u US        microseconds per time unit (default 10000)
#   -v VARIANT   correct (default) or late: done 3 units after the model's deadline, FAILED whenever its input landed
#   -t UNITS     the timeout of each run in time units (default 200)
#
# The adapter's JVM compiles with C1 alone (-XX:TieredStopAtLevel=1), as adapters.md advises at time units of a few
# ms; RACING_ADAPTER_JAVA_OPTS replaces that option (empty: the JVM's defaults), RACING_TESTER_JAVA_OPTS adds options
# to the tester's JVM (-XX:TieredStopAtLevel=4 keeps its C2, see tester.md).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jar=$root/dtron-cli/target/dtron.jar
classes=$root/dtron-cli/target/test-classes
model=$classes/io/dtron/cli/racing.xta

if [ "${1:-}" = "--one" ]; then
    # one run: the adapter in its own JVM, then the tester; the adapter is stopped when the tester is done
    shift
    unit=$1 variant=$2 timeout=$3
    cluster=racing-$$-$RANDOM
    adapter_log=$(mktemp /tmp/racing-adapter.XXXXXX)
    java ${RACING_ADAPTER_JAVA_OPTS--XX:TieredStopAtLevel=1} -cp "$classes:$jar" io.dtron.cli.RacingAdapterMain "$cluster" "$variant" > "$adapter_log" 2>&1 &
    adapter=$!
    trap 'kill "$adapter" 2>/dev/null || true; rm -f "$adapter_log"' EXIT
    set +e
    java ${RACING_TESTER_JAVA_OPTS:-} -jar "$jar" run "$model" --cluster "$cluster" --timeunit "$unit" --timeout "$timeout" --wait-timeout 60
    code=$?
    set -e
    # the adapter's warnings (an output it sent after its deadline: its JVM was held up) go in the run's log
    grep WARN "$adapter_log" || true
    exit $code
fi

runs=20 load="" unit=10000 variant=correct timeout=200
while getopts "n:lb:u:v:t:" opt; do
    case "$opt" in
        n) runs=$OPTARG ;;
        l) load="-b 2" ;;
        b) load="-b $OPTARG" ;;
        u) unit=$OPTARG ;;
        v) variant=$OPTARG ;;
        t) timeout=$OPTARG ;;
        *) echo "usage: $0 [-n RUNS] [-l | -b BUSY] [-u TIMEUNIT_US] [-v correct|late] [-t TIMEOUT_UNITS]" >&2; exit 1 ;;
    esac
done
for f in "$jar" "$model"; do
    [ -e "$f" ] || { echo "$0: $f is missing: run mvn -DskipTests install and mvn -pl dtron-cli test-compile" >&2; exit 1; }
done
echo "racing sample: $variant, $unit us per unit, $timeout units, $runs runs; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
"$root/scripts/verdict-stats.sh" -n "$runs" $load -- "$0" --one "$unit" "$variant" "$timeout" || true
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
