#!/usr/bin/env bash
# Validates and measures the CUDA build on a machine with a GPU, in one command:
#   scripts/gpu_check.sh [--prebuilt DIR] [--out DIR] [--quick] [--repeats N] [--studies]
# 1. the device (nvidia-smi) and the binary's backends (mfsd --version);
# 2. the cross-backend tests (tests/gpu) with MFSD_REQUIRE_GPU=1, so that a
#    missing device fails instead of skipping;
# 3. the throughput suite on the GPU (bench/run.py throughput --backend cuda),
#    particle-steps/s and the time per stage;
# 4. where the tests fail: scripts/gpu_divergence.py, the step at which the
#    backends part and the particle that differs most;
# 5. with --studies: the fracture studies at the seeds' resolutions, which only
#    a GPU runs in minutes (crack branching at dx = 0.06125 mm, 1.1 M particles;
#    Kalthoff-Winkler at 0.125 mm, 640,000 particles; four-point bending at
#    0.5 mm for the three slit angles).
# Without --prebuilt it builds Release into build/ first (scripts/common.sh);
# with --prebuilt DIR it runs the binaries packed by scripts/gpu_pack.sh (for a
# machine without our Debian packages). Logs and results go to --out (default
# out/gpu_check); the exit status is that of the tests.
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
prebuilt="" out="$root/out/gpu_check" quick="" studies="" repeats=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --prebuilt) prebuilt=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --quick) quick=--quick; shift ;;
    --studies) studies=1; shift ;;
    --repeats) repeats=(--repeats "$2"); shift 2 ;;
    *) echo "[gpu_check] unknown option $1 (expected --prebuilt DIR, --out DIR, --quick, --repeats N, --studies)" >&2; exit 2 ;;
  esac
done
mkdir -p "$out"
log() { printf '[gpu_check] %s\n' "$*" | tee -a "$out/summary.txt" >&2; }
: >"$out/summary.txt"

if [[ -n $prebuilt ]]; then
  prebuilt=$(cd "$prebuilt" && pwd)
  for f in "$prebuilt"/*.xz; do [[ -e $f ]] && xz -d -k -f "$f"; done
  chmod +x "$prebuilt"/mfsd "$prebuilt"/mfsd_gpu_tests 2>/dev/null
  export LD_LIBRARY_PATH="$prebuilt/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  mfsd="$prebuilt/mfsd" tests="$prebuilt/mfsd_gpu_tests"
else
  # shellcheck source=common.sh
  source "$here/common.sh"
  mfsd_ensure_dependencies
  mfsd_build -DMFSD_CUDA=ON
  mfsd="$MFSD_BUILD/mfsd" tests="$MFSD_BUILD/tests/mfsd_gpu_tests"
fi

log "date $(date -u +%FT%TZ), host $(hostname), $(nproc) cores"
if command -v nvidia-smi >/dev/null; then
  nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm --format=csv,noheader | tee -a "$out/summary.txt"
else
  log "nvidia-smi not found"
fi
"$mfsd" --version 2>&1 | tee -a "$out/summary.txt"

# 2. Cross-backend agreement (the test binary reads configs/ from this checkout).
start=$(date +%s)
MFSD_REQUIRE_GPU=1 MFSD_SOURCE_DIR="$root" OMP_NUM_THREADS=$(nproc) \
  "$tests" --gtest_output=xml:"$out/gpu_tests.xml" >"$out/gpu_tests.log" 2>&1
status=$?
grep -E '^\[ *(OK|FAILED|SKIPPED|PASSED) ' "$out/gpu_tests.log" | tee -a "$out/summary.txt"
log "cross-backend tests: exit $status in $(( $(date +%s) - start )) s"

# 3. Throughput on the GPU (quick: two sizes per scene, one repeat; else three
#    sizes, --repeats of each, default 3).
start=$(date +%s)
MFSD_BINARY="$mfsd" python3 "$root/bench/run.py" throughput --backend cuda ${quick} "${repeats[@]}" \
  >"$out/throughput.log" 2>&1
log "throughput suite: exit $? in $(( $(date +%s) - start )) s"
latest=$(ls -t "$root"/bench/results/throughput-*.md 2>/dev/null | head -1)
if [[ -n $latest ]]; then
  cp "$latest" "$out/throughput.md"
  cp "${latest%.md}.json" "$out/throughput.json" 2>/dev/null
  cat "$out/throughput.md" >>"$out/summary.txt"
fi
if [[ $status -ne 0 ]]; then
  python3 "$here/gpu_divergence.py" --binary "$mfsd" --out "$out/divergence_runs" >"$out/divergence.txt" 2>&1
  log "divergence report: exit $? ($out/divergence.txt)"
  rm -rf "$out/divergence_runs"
fi

if [[ -n $studies ]]; then
  for study in "crack_branching --dp 0.06125" "kalthoff_winkler --dp 0.125" "four_point_bending --dp 0.5"; do
    name=${study%% *}
    start=$(date +%s)
    MFSD_BINARY="$mfsd" python3 "$root/scripts/validation/$name.py" ${study#* } --backend cuda \
      --out "$out/${name}_seed" >"$out/${name}_seed.log" 2>&1
    log "study $name at the seed's resolution: exit $? in $(( $(date +%s) - start )) s"
  done
fi
exit $status
