#!/usr/bin/env bash
# Runs `dtron mutants` on LightContr (../shared/models/tron) and the bundled ticker and street-light models, each in
# a fresh JVM, on 1 thread and on all the machine's processors, and prints the mutants, the score and the rate of
# the mutation runs (mutants per second of wall time, without the JVM's start and the checker's searches for
# equivalent mutants). Not part of the test command; see src/site/markdown/benchmarks.md.
#
#   scripts/mutants-bench.sh [SEEDS] [BUDGET]     (default: 10 seeds of 2000 time units each, first seed 1)
#
# Needs dtron-cli/target/dtron.jar (mvn -B -q -DskipTests package). JAVA_OPTS is passed to the JVM.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
jar="$here/dtron-cli/target/dtron.jar"
[ -f "$jar" ] || { echo "no $jar: build it with mvn -B -q -DskipTests package" >&2; exit 1; }
seeds=${1:-10}
budget=${2:-2000}
tron="$here/../shared/models/tron"
bundled="$here/models/src/main/resources/io/dtron/models"
cores=$(nproc)
printf "%-16s %7s %8s %-14s %s\n" model threads mutants score "runs, time, rates"
run() {
    local name=$1 threads=$2
    shift 2
    out=$(java ${JAVA_OPTS:-} -jar "$jar" mutants "$@" --seeds "$seeds" --seed 1 --budget "$budget" \
        --threads "$threads")
    count=$(echo "$out" | sed -n 's/^\([0-9]*\) mutants, .*/\1/p')
    score=$(echo "$out" | sed -n 's/^mutation score: \([^:]*\):.*/\1/p')
    rate=$(echo "$out" | sed -n 's/^[0-9]* mutants, \(.*\)$/\1/p')
    printf "%-16s %7s %8s %-14s %s\n" "$name" "$threads" "$count" "$score" "$rate"
}
for threads in 1 "$cores"; do
    run LightContr "$threads" "$tron/LightContr.xml" --interface "$tron/LightContr.trn"
    run ticker "$threads" "$bundled/ticker.xml"
    run streetlight "$threads" "$bundled/streetlight/streetlight.xml"
done
