#!/usr/bin/env bash
# Checkpoint size and write time of shipped scenes at their resolution
# (docs/tutorial.md, "Long runs"): each runs 5 steps and writes one checkpoint
# at its stop; the figures are run.json's "checkpoints" section.
#   scripts/checkpoint_cost.sh [SCENE.json[@path=value,...] ...]
# (default: the plate, the crack-branching plate and the bending column at H/dp = 24, 84,672 particles)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
mfsd_ensure_dependencies
mfsd_build >/dev/null
scenes=("$@")
[[ ${#scenes[@]} -eq 0 ]] && scenes=("$MFSD_ROOT/configs/oscillating_plate_2d.json"
  "$MFSD_ROOT/configs/crack_branching_2d.json" "$MFSD_ROOT/configs/bending_column_3d.json@constants.H_over_dp=24")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '%-28s %10s %12s %10s %14s\n' scene particles "checkpoint" "write" "bytes/particle"
for spec in "${scenes[@]}"; do
  s=${spec%%@*}
  sets=()
  if [[ $spec == *@* ]]; then
    IFS=, read -ra assignments <<<"${spec#*@}"
    for a in "${assignments[@]}"; do sets+=(--set "$a"); done
  fi
  name=$(basename "$s" .json)
  "$MFSD_BUILD/mfsd" run "$s" "${sets[@]}" -q -o "$out/$name" --max-steps 5 --checkpoint-every 1e9 >/dev/null
  python3 - "$out/$name/run.json" "$name" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
c = j["checkpoints"]
print("%-28s %10d %9.1f MB %8.3f s %14.0f" % (sys.argv[2], j["particles"], c["bytes"] / 1e6, c["seconds"],
                                              c["bytes"] / j["particles"]))
PY
done
