#!/usr/bin/env bash
# Shared cores: the default plate (configs/oscillating_plate_2d.json, no VTU)
# run alone with 2 threads, and two runs of it at once (a parameter study run
# in parallel), with the thread count left to mfsd (the governor), fixed at
# 2 threads each, fixed at 1 thread each, and fixed at 2 with libgomp's
# passive wait. Prints wall seconds per run. docs/performance.md, "Shared cores".
# Usage: bench/shared_cores.sh [BINARY]   (default build/mfsd)
set -euo pipefail
B=${1:-$(dirname "$0")/../build/mfsd}
S=$(dirname "$0")/../configs/oscillating_plate_2d.json
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
one() { # name, extra arguments...
  local name=$1; shift
  local t0=$(date +%s.%N)
  "$B" run "$S" -q -o "$out/$name" --set output.vtu=false "$@"
  echo "$(echo "$(date +%s.%N) - $t0" | bc)"
}
pair() { one a "$@" > "$out/ta" & one b "$@" > "$out/tb" & wait; printf '%.2f %.2f' "$(cat "$out/ta")" "$(cat "$out/tb")"; }
echo "binary: $("$B" --version | head -1); $(nproc) cores; load average $(cut -d' ' -f1 /proc/loadavg)"
printf 'alone, governed (no --threads):        %.2f s\n' "$(one a)"
printf 'alone, --threads 2:                    %.2f s\n' "$(one a --threads 2)"
echo "two at once, governed:                 $(pair) s"
echo "two at once, --threads 2 each:         $(pair --threads 2) s"
echo "two at once, --threads 1 each:         $(pair --threads 1) s"
printf 'alone, --threads 2, OMP_WAIT_POLICY=passive: %.2f s\n' "$(OMP_WAIT_POLICY=passive one a --threads 2)"
echo "two at once, --threads 2 each, passive: $(OMP_WAIT_POLICY=passive pair --threads 2) s"
