#!/usr/bin/env bash
# Coverage against random, and the cost of a step of the coverage strategy: the two bench mains of
# src/site/markdown/benchmarks.md ("Steering: coverage against random" and "Planning cost of a step"). Not part of the
# test command.
#
#   scripts/coverage-bench.sh [SEEDS] [ROUNDS]     (default: 20 seeds per model and strategy, 200 rounds of steps)
#
# Builds what it needs with Maven (MAVEN_OPTS and MVN_ARGS are passed on, e.g. MVN_ARGS=-Dmaven.repo.local=...); the
# shared models must be in ../shared/models. JAVA_OPTS is passed to the JVMs.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
shared=$(cd "$here/../shared" && pwd)
seeds=${1:-20}
rounds=${2:-200}
cd "$here"
mvn -B -q ${MVN_ARGS:-} -DskipTests install -pl models -am
for module in dtron-engine models; do
    mvn -B -q ${MVN_ARGS:-} -pl "$module" test-compile dependency:build-classpath -Dmdep.includeScope=test \
        -Dmdep.outputFile=target/bench-cp.txt
done
echo "== planning cost of a step (dtron-engine SteeringBench, $rounds rounds)"
(cd dtron-engine && java ${JAVA_OPTS:-} -Ddtron.shared="$shared" \
    -cp "target/test-classes:target/classes:$(cat target/bench-cp.txt)" io.dtron.engine.internal.tester.SteeringBench "$rounds")
echo "== coverage against random (models CoverageBench, $seeds seeds)"
(cd models && java ${JAVA_OPTS:-} -Ddtron.shared="$shared" -Dorg.slf4j.simpleLogger.defaultLogLevel=warn \
    -cp "target/test-classes:target/classes:$(cat target/bench-cp.txt)" io.dtron.models.streetlight.CoverageBench "$seeds")
