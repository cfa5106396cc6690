#!/usr/bin/env bash
# The genog force stage in the twisted column against the undeformed one
# (issue 24, item 2: the twisted state may cost no more than 1.15x).
#   bench/twisted_genog.sh [BINARY] [H_over_dp] [twist_time] [steps] [--set k=v ...]
# Runs configs/twisting_column_3d.json (genog, double, 2 threads) to
# twist_time with a checkpoint at the end, then times `steps` steps twice:
# from t = 0 and continued from the checkpoint (--restart). Prints the force
# stage's nanoseconds per particle-step of each and their ratio, and the
# share of particles the twisted state sends through genog's correction
# (timing.json `genog_active_share` where the binary reports it).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bin=${1:-$root/build/mfsd}
res=${2:-12}
twist=${3:-0.1}
steps=${4:-200}
shift $(($# < 4 ? $# : 4))
threads=${THREADS:-2}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
scene="$root/configs/twisting_column_3d.json"
common=(--set "constants.H_over_dp=$res" --set output.vtu=false --set output.interval=1e9
        --set output.probe_interval=1e9 --threads "$threads" -q "$@")
"$bin" run "$scene" "${common[@]}" --set "solver.end_time=$twist" \
  --set "output.checkpoint_interval=$twist" -o "$out/twisted"
"$bin" run "$scene" "${common[@]}" --max-steps $((steps + 5)) --warmup-steps 5 -o "$out/straight"
# --max-steps counts from the run's start: the checkpoint's steps plus these.
done_steps=$(python3 -c "import json; print(json.load(open('$out/twisted/timing.json'))['steps'])")
"$bin" run "$scene" "${common[@]}" --set "solver.end_time=$(python3 -c "print($twist * 2)")" \
  --max-steps $((done_steps + steps + 5)) --warmup-steps 5 --restart "$out/twisted" > /dev/null
python3 - "$out" "$bin" "$res" "$twist" <<'EOF'
import json, sys
out, binary, res, twist = sys.argv[1:]
def force(run):
    t = json.load(open(f"{out}/{run}/timing.json"))
    stage = {s["name"]: s for s in t["stages"]}["force"]
    return stage["nanoseconds_per_particle_step"], t["particles"], t.get("genog_active_share")
(a, n, sa), (b, _, sb) = force("straight"), force("twisted")
print(f"{binary}: twisting column H/dp = {res}, {n} particles, genog, double")
print(f"  force stage, undeformed: {a:.1f} ns per particle-step" + (f" (active share {sa:.3f})" if sa is not None else ""))
print(f"  force stage, twisted at t = {twist} s: {b:.1f} ns per particle-step" + (f" (active share {sb:.3f})" if sb is not None else ""))
print(f"  twisted / undeformed = {b / a:.3f} (issue 24 target: <= 1.15)")
EOF
