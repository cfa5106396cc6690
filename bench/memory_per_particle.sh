#!/usr/bin/env bash
# Bytes per particle of the run's state (timing.json bytes_per_particle:
# particle fields + pair data, after set-up) and the process's peak resident
# memory per particle (set-up copies included), per method, dimension and
# precision, from one step of each scene, and the seed 001 cantilever plate at
# its resolution (1,934,400 particles; issue 24 item 6: it must fit in 4 GB).
# docs/performance.md, "Memory per particle".
# Usage: bench/memory_per_particle.sh [BINARY]   (default build/mfsd)
set -euo pipefail
B=${1:-$(dirname "$0")/../build/mfsd}
C=$(dirname "$0")/../configs
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "binary: $("$B" --version | head -1)"
echo "| scene | method | particles | neighbours | precision | state [B/particle] | peak RSS [B/particle] | peak RSS [GB] |"
echo "|---|---|---|---|---|---|---|---|"
for case in "oscillating_plate_2d.json constants.H_over_dp=80" "bending_column_3d.json constants.H_over_dp=24" \
            "oscillating_plate_ulsph_2d.json constants.H_over_dp=80" "bending_column_ulsph_3d.json constants.H_over_dp=24" \
            "cantilever_plate_3d.json constants.dp=0.5e-3"; do
  set -- $case
  for precision in double float; do
    rss=$( { /usr/bin/time -f %M "$B" run "$C/$1" -q -o "$out/r" --threads 1 --max-steps 1 --precision $precision \
             --set output.vtu=false --set "$2" > /dev/null; } 2>&1 | tail -1)
    python3 - "$out/r" "$1" "$precision" "$rss" <<'PY'
import json, sys
t = json.load(open(sys.argv[1] + "/timing.json"))
r = json.load(open(sys.argv[1] + "/run.json"))
method = "ulsph" if "ulsph" in sys.argv[2] else "tlsph"
n = t["particles"]
print(f"| {sys.argv[2]} | {method} | {n} | {r['neighbors']['mean']:.0f} | {sys.argv[3]} | "
      f"{t['bytes_per_particle']:.0f} | {1024 * float(sys.argv[4]) / n:.0f} | {1024 * float(sys.argv[4]) / 1e9:.3f} |")
PY
  done
done
