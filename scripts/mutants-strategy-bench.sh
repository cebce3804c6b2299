#!/usr/bin/env bash
# The mutation score of the random and the coverage strategy within the same budget of time units: `dtron mutants`
# with --strategy random and --strategy coverage, the same seeds, on LightContr (../shared/models/tron) and on
# Uppaal's boxes, gearbox and train-gate demo models (../shared/models/uppaal-examples) with the interfaces written
# below.
# Prints one line per model and strategy: killed / counted, and the wall time of the mutation runs. Not part of the
# test command; see src/site/markdown/benchmarks.md ("Mutation score of the strategies").
#
#   scripts/mutants-strategy-bench.sh [SEEDS]     (default: 5 seeds from 1)
#
# Needs dtron-cli/target/dtron.jar (mvn -B -q -DskipTests package). JAVA_OPTS is passed to the JVM.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
jar="$here/dtron-cli/target/dtron.jar"
[ -f "$jar" ] || { echo "no $jar: build it with mvn -B -q -DskipTests package" >&2; exit 1; }
seeds=${1:-5}
shared="$here/../shared/models"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# boxes: the guard that lets a box in (ok) is the environment; the belt, the boxes, the piston and the tasks are the
# system, which says when a black or a red box passes its sensor
cat > "$work/boxes.trn" <<'TRN'
input ok(); output blck(), red(); precision 1000; timeout 1000;
TRN
# the gearbox: the driver's requests of a new gear (Interface) are the environment; the gear controller, engine,
# gearbox and clutch are the system, which says when the new gear is in
cat > "$work/gearbox.trn" <<'TRN'
input ReqNewGear(FromGear, ToGear); output NewGear(); precision 1000; timeout 5000;
TRN
# the gear controller with the engine: the driver, the clutch and the gearbox are the environment, so the tester
# answers the controller's requests to the clutch and the gearbox (and chooses when)
cat > "$work/controller.trn" <<'TRN'
input ReqNewGear(FromGear, ToGear), ClutchIsOpen(), ClutchIsClosed(), GearNeu(), GearSet();
output NewGear(), OpenClutch(), CloseClutch(), ReqNeu(), ReqSet(); precision 1000; timeout 5000;
TRN
# train-gate: the trains (approaching, leaving; arrays of channels, one element per train) are the environment, the
# gate with its queue the system, which tells a train to stop and to go
cat > "$work/train-gate.trn" <<'TRN'
input appr(), leave(); output stop(), go(); precision 1000; timeout 1000;
TRN
printf "%-12s %8s %-9s %-22s %s\n" model budget strategy "killed / counted" "mutants, runs, wall time"
run() {
    local name=$1 budget=$2 model=$3 trn=$4
    for strategy in random coverage; do
        out=$(java ${JAVA_OPTS:-} -jar "$jar" mutants "$model" --interface "$trn" --seeds "$seeds" --seed 1 \
            --budget "$budget" --strategy "$strategy")
        score=$(echo "$out" | sed -n 's/^mutation score: \([^:]*\):.*/\1/p')
        rate=$(echo "$out" | sed -n 's/^\([0-9]* mutants, [0-9]* runs\) of [0-9]* time units, in \([0-9.]* s\) .*/\1, \2/p')
        printf "%-12s %8s %-9s %-22s %s\n" "$name" "$budget" "$strategy" "$score" "$rate"
    done
}
run LightContr 2000 "$shared/tron/LightContr.xml" "$shared/tron/LightContr.trn"
run boxes 1000 "$shared/uppaal-examples/boxes.xml" "$work/boxes.trn"
run gearbox 5000 "$shared/uppaal-examples/engine-classic.xml" "$work/gearbox.trn"
run controller 5000 "$shared/uppaal-examples/engine-classic.xml" "$work/controller.trn"
run train-gate 1000 "$shared/uppaal-examples/train-gate.xml" "$work/train-gate.trn"
