#!/bin/sh
# End-to-end time of `dtron check` on the generated models of LoadBench, JVM start included.
# Usage: scripts/check-bench.sh [RUNS]   (after `mvn -B -DskipTests install`; uses ~/.m2 unless M2 is set)
# Prints the minimum and the median wall time of RUNS runs (default 15) of `java -jar dtron.jar check -q`.
set -eu
runs=${1:-15}
m2=${M2:-$HOME/.m2/repository}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
antlr=$m2/org/antlr/antlr4-runtime/4.13.2/antlr4-runtime-4.13.2.jar
java -cp xtaapi/target/test-classes:xtaapi/target/classes:antlrxta/target/classes:"$antlr" \
    io.dtron.model.bench.LoadBench --write "$dir"
echo "machine: $(nproc) cores, $(java -version 2>&1 | head -1), load average $(cut -d' ' -f1-3 /proc/loadavg)"
for model in many large; do
    : > "$dir/times"
    i=0
    while [ "$i" -lt "$runs" ]; do
        start=$(date +%s%N)
        java -jar dtron-cli/target/dtron.jar check -q "$dir/$model.xml"
        end=$(date +%s%N)
        echo $(( (end - start) / 1000000 )) >> "$dir/times"
        i=$((i + 1))
    done
    sort -n "$dir/times" > "$dir/sorted"
    echo "$model.xml ($(( $(wc -c < "$dir/$model.xml") / 1024 )) KiB): min $(head -1 "$dir/sorted") ms," \
        "median $(sed -n "$(( (runs + 1) / 2 ))p" "$dir/sorted") ms over $runs runs"
done
