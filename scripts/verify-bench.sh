#!/usr/bin/env bash
# Runs `dtron verify` on the shared benchmark models, one fresh JVM per model, and prints wall time and maximum
# resident set (from /usr/bin/time, as the TChecker figures in ../shared/models/benchmarks/README.md were taken)
# next to the checker's own figures. Not part of the test command; see src/site/markdown/benchmarks.md.
#
#   scripts/verify-bench.sh [MODEL.xml...]     (default: the Fischer, CSMA/CD and FDDI sizes of benchmarks.md)
#
# Needs dtron-cli/target/dtron.jar (mvn -B -q -DskipTests package) and the models in ../shared/models/benchmarks.
# JAVA_OPTS is passed to the JVM (e.g. JAVA_OPTS=-Xmx256m).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
jar="$here/dtron-cli/target/dtron.jar"
models_dir="$here/../shared/models/benchmarks"
[ -f "$jar" ] || { echo "no $jar: build it with mvn -B -q -DskipTests package" >&2; exit 1; }
if [ $# -eq 0 ]; then
    set -- fischer-6.xml fischer-7.xml fischer-8.xml fischer-9.xml fischer-10.xml csmacd-6.xml csmacd-8.xml \
        csmacd-9.xml csmacd-10.xml fddi-8.xml fddi-10.xml fddi-12.xml
fi
printf "%-14s %-10s %12s %10s %10s %10s\n" model answer explored stored "wall s" "max RSS"
for m in "$@"; do
    f="$models_dir/$m"
    # Fischer: its first query (mutual exclusion); the others have none: the whole state space
    if grep -q "<formula>" "$f"; then
        q=$(sed -n 's/.*<formula>\(A\[\] forall.*\)/\1/p' "$f" | head -1 | sed 's/&lt;/</g; s/&gt;/>/g; s/&amp;/\&/g')
    else
        q="A[] true"
    fi
    out=$( { /usr/bin/time -f "TIME %e %M" java ${JAVA_OPTS:-} -jar "$jar" verify "$f" --query "$q" --trace none; } 2>&1 || true)
    answer=$(echo "$out" | grep -o "satisfied\|NOT satisfied\|unknown" | head -1 || true)
    explored=$(echo "$out" | sed -n 's/.*(\([0-9,]*\) states explored.*/\1/p' | head -1 || true)
    stored=$(echo "$out" | sed -n 's/.*([0-9,]* states explored, \([0-9,]*\) stored.*/\1/p' | head -1 || true)
    wall=$(echo "$out" | sed -n 's/^TIME \([0-9.]*\) .*/\1/p' || true)
    rss=$(echo "$out" | sed -n 's/^TIME [0-9.]* \([0-9]*\)/\1/p')
    printf "%-14s %-10s %12s %10s %10s %7s MB\n" "$m" "$answer" "$explored" "$stored" "$wall" "$((rss / 1024))"
done
