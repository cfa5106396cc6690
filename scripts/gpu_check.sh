#!/usr/bin/env bash
# Validates and measures the CUDA build on a machine with a GPU, in one command:
#   scripts/gpu_check.sh [--prebuilt DIR] [--out DIR] [--quick]
# 1. the device (nvidia-smi) and the binary's backends (mfsd --version);
# 2. the cross-backend tests (tests/gpu) with MFSD_REQUIRE_GPU=1, so that a
#    missing device fails instead of skipping;
# 3. the throughput suite on the GPU (bench/run.py throughput --backend cuda),
#    particle-steps/s and the time per stage.
# Without --prebuilt it builds Release into build/ first (scripts/common.sh);
# with --prebuilt DIR it runs the binaries packed by scripts/gpu_pack.sh (for a
# machine without our Debian packages). Logs and results go to --out (default
# out/gpu_check); the exit status is that of the tests.
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
prebuilt="" out="$root/out/gpu_check" quick=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --prebuilt) prebuilt=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --quick) quick=--quick; shift ;;
    *) echo "[gpu_check] unknown option $1 (expected --prebuilt DIR, --out DIR, --quick)" >&2; exit 2 ;;
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

# 3. Throughput on the GPU (quick: two sizes per scene, one repeat).
start=$(date +%s)
MFSD_BINARY="$mfsd" python3 "$root/bench/run.py" throughput --backend cuda ${quick} >"$out/throughput.log" 2>&1
log "throughput suite: exit $? in $(( $(date +%s) - start )) s"
latest=$(ls -t "$root"/bench/results/throughput-*.md 2>/dev/null | head -1)
if [[ -n $latest ]]; then
  cp "$latest" "$out/throughput.md"
  cp "${latest%.md}.json" "$out/throughput.json" 2>/dev/null
  cat "$out/throughput.md" >>"$out/summary.txt"
fi
exit $status
