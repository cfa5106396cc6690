#!/usr/bin/env bash
# Benchmarks: builds Release (with the triad and the Google Benchmark
# microbenchmarks), then runs a suite of bench/run.py.
#   scripts/bench.sh [throughput|scaling|accuracy|roofline|scenes|fracture|micro|all] [--quick] [--backend cuda] [--repeats N]
# Results go to bench/results/<suite>-<date>.{json,md,png} (micro: .json).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
suite=${1:-throughput}
shift || true
mfsd_ensure_dependencies
mfsd_build -DMFSD_BENCH=ON
export MFSD_BINARY="$MFSD_BUILD/mfsd"
if [[ $suite == micro ]]; then
  exe="$MFSD_BUILD/bench/mfsd_microbench"
  [[ -x $exe ]] || { mfsd_log "microbenchmarks not built (is libbenchmark-dev installed?)"; exit 1; }
  mkdir -p "$MFSD_ROOT/bench/results"
  out="$MFSD_ROOT/bench/results/micro-$(date +%F).json"
  "$exe" --benchmark_out="$out" --benchmark_out_format=json "$@"
  mfsd_log "wrote ${out#$MFSD_ROOT/}"
  python3 "$MFSD_ROOT/bench/micro_table.py" "$out"
  exit 0
fi
exec python3 "$MFSD_ROOT/bench/run.py" "$suite" "$@"
