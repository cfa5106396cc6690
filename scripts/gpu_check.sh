#!/usr/bin/env bash
# Validates and measures the CUDA build on a machine with a GPU, in one command,
# and writes one report (out/gpu_check/report.md, and report.json with the same
# data: scripts/gpu_report.py):
#   scripts/gpu_check.sh [--prebuilt DIR] [--out DIR] [--dry-run] [--quick | --full-bench]
#                        [--repeats N] [--studies] [--full-suite] [--budget SECONDS]
# Phases, each timed against the budget (default 480 s = 8 minutes; the report
# warns when the phases in it take longer):
#   setup       the binaries: built Release with CUDA into build/ (scripts/common.sh),
#               or --prebuilt DIR: a pack of scripts/gpu_pack.sh (mfsd.xz,
#               mfsd_gpu_tests.xz, lib/; for a machine without our Debian
#               packages) or an existing build folder (DIR/mfsd, DIR/tests/mfsd_gpu_tests);
#   probe       the device (nvidia-smi: name, memory, driver, its CUDA version),
#               nvcc, how the binaries were built, mfsd --version (backends and
#               the devices the binary sees), the tests and throughput cases planned;
#   tests       the cross-backend tests (tests/gpu, mfsd_gpu_tests) with
#               MFSD_REQUIRE_GPU=1, so that a missing device fails instead of
#               skipping; per test pass/fail and the worst difference (the
#               tests' gtest properties worst_difference_*, from the XML output);
#   throughput  bench/run.py throughput --backend cuda --quick (two sizes of the
#               bending column 3D and the oscillating plate 2D, double and float,
#               one repeat): particle-steps/s per case, the time per stage and
#               the host round trips per step (the runs' timing.json); then the
#               bending column with --pair-layout sliced (throughput_sliced.md);
#   divergence  only when the tests fail: scripts/gpu_divergence.py, the step at
#               which the backends part and the particle that differs most;
#   report      scripts/gpu_report.py write.
# Why only the GPU test binary and not scripts/test.sh --gpu (the whole ctest
# suite): every other ctest is CPU-only, runs in CI, and its binaries are not in
# a pack; on a device machine the full suite (build of all test binaries, the
# fuzz test's 150 s, the regression runs) would take the 8 minutes on its own.
# The required part is the GPU binary's tests. --full-suite adds the rest of
# the suite (ctest -LE validate with MFSD_REQUIRE_GPU=1; a build folder only),
# outside the budget; so do --studies (the fracture studies at the seeds'
# resolutions: crack branching at dx = 0.06125 mm, Kalthoff-Winkler at
# 0.125 mm, four-point bending at 0.5 mm) and --full-bench (three sizes,
# --repeats of each, default 3; --quick, the default, is kept as an option).
# Estimate on an H200 with a pack: setup 5 s, probe 5 s, tests 1-2 min,
# throughput 1 min, divergence (on failure) 1-2 min, report 1 s: 3-5 minutes.
# A build from source takes longer than the budget on its own: use the pack.
#
# --dry-run is the CPU half (in CI, seconds with --prebuilt build): the binaries
# exist (built unless --prebuilt), the tests and throughput cases it would run
# (listed), the report skeleton; exits 0 with or without a GPU.
# Exit status: 0 every test passed and the suite ran (or a dry run); 1 a test
# failed, the suite failed, or the binaries are missing or lack the CUDA
# backend; 2 no usable GPU here (no nvidia-smi, nvidia-smi lists none, or mfsd
# sees no CUDA device), said on stderr and in the report; 64 a wrong option.
# On a device machine with a pack in .gpu:
#   bash scripts/gpu_check.sh --prebuilt .gpu --out "$OUT/gpu_check"
set -uo pipefail
export LC_ALL=C
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
command_line="scripts/gpu_check.sh $*"
prebuilt="" out="$root/out/gpu_check" bench_size=--quick studies="" repeats=() dry_run="" full_suite=""
budget=480
usage() { sed -n '2,/^set -uo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//' >&2; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    --prebuilt | --build-dir) [[ $# -ge 2 ]] || { echo "[gpu_check] $1 needs a folder" >&2; exit 64; }
      prebuilt=$2; shift 2 ;;
    --out) [[ $# -ge 2 ]] || { echo "[gpu_check] --out needs a folder" >&2; exit 64; }
      out=$2; shift 2 ;;
    --quick) bench_size=--quick; shift ;;
    --full-bench) bench_size=""; shift ;;
    --studies) studies=1; shift ;;
    --full-suite) full_suite=1; shift ;;
    --dry-run) dry_run=1; shift ;;
    --repeats) [[ ${2:-} =~ ^[0-9]+$ ]] || { echo "[gpu_check] --repeats needs a number" >&2; exit 64; }
      repeats=(--repeats "$2"); shift 2 ;;
    --budget) [[ ${2:-} =~ ^[0-9]+$ ]] || { echo "[gpu_check] --budget needs seconds" >&2; exit 64; }
      budget=$2; shift 2 ;;
    -h | --help) usage; exit 0 ;;
    *) echo "[gpu_check] unknown option $1 (expected --prebuilt DIR, --out DIR, --dry-run, --quick, --full-bench," \
         "--repeats N, --studies, --full-suite, --budget S; --help)" >&2; exit 64 ;;
  esac
done
mkdir -p "$out" || exit 1
out=$(cd "$out" && pwd)
for f in summary.txt phases.tsv meta.env nvidia_smi.txt nvidia_smi_query.csv nvidia_smi_list.txt mfsd_version.txt \
  nvcc_version.txt build_info.txt tests_planned.txt throughput_planned.tsv gpu_tests.xml gpu_tests.log \
  throughput.log throughput.json throughput.md throughput_sliced.log throughput_sliced.json throughput_sliced.md divergence.txt full_suite.log report.md report.json; do
  rm -f "$out/$f"
done
rm -rf "${out:?}/throughput_timing" "${out:?}/divergence_runs" "${out:?}/bin"
: >"$out/summary.txt"
: >"$out/phases.tsv"
log() { printf '[gpu_check] %s\n' "$*" | tee -a "$out/summary.txt" >&2; }
now() { printf '%s' "${EPOCHREALTIME:-$(date +%s)}"; }
elapsed_in_budget() { awk -F'\t' '$4 == 1 { s += $2 } END { printf "%d", s }' "$out/phases.tsv"; }
phase_start=""
phase_begin() { phase_start=$(now); }
# phase_end NAME EXIT IN_BUDGET(1/0) [NOTE]
phase_end() {
  local secs
  secs=$(awk -v a="$phase_start" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }')
  printf '%s\t%s\t%s\t%s\t%s\n' "$1" "$secs" "$2" "$3" "${4:-}" >>"$out/phases.tsv"
  log "$1: exit $2 in $secs s${4:+ ($4)}"
}
# with_cap SECONDS CMD...: the command under a time limit (exit 124 past it).
with_cap() {
  local cap=$1; shift
  if command -v timeout >/dev/null; then timeout -k 10 "$cap" "$@"; else "$@"; fi
}

gpu=no gpu_reason="" binaries="" mfsd="" tests="" build_dir=""
write_meta() {
  {
    echo "date=$(date -u +%FT%TZ)"
    echo "host=$(hostname 2>/dev/null || cat /etc/hostname 2>/dev/null || echo unknown)"
    echo "cores=$(nproc 2>/dev/null || echo '?')"
    echo "command=$command_line"
    echo "binaries=${binaries:-n/a}"
    echo "gpu=$gpu"
    echo "gpu_reason=$gpu_reason"
  } >"$out/meta.env"
}
# report: writes report.md/.json (from the files above); returns gpu_report.py's status.
report() {
  write_meta
  python3 "$here/gpu_report.py" write "$out" --budget "$budget" ${dry_run:+--dry-run} 2>>"$out/summary.txt"
  local rc=$?
  # Not in phases.tsv (the report is written from it); under a second.
  if [[ $rc -le 2 ]]; then log "report: $out/report.md (and report.json)"; else log "report failed (exit $rc)"; fi
  return "$rc"
}
no_gpu_exit() {
  log "no usable GPU here: $gpu_reason. Nothing to check on this machine; the CPU half is --dry-run."
  report
  exit 2
}

# The device, before anything is built: nvidia-smi.
phase_begin
if ! command -v nvidia-smi >/dev/null 2>&1; then
  gpu_reason="nvidia-smi not found"
elif ! with_cap 60 nvidia-smi -L >"$out/nvidia_smi_list.txt" 2>&1 || ! grep -q '^GPU ' "$out/nvidia_smi_list.txt"; then
  gpu_reason="nvidia-smi lists no GPU: $(head -1 "$out/nvidia_smi_list.txt")"
else
  gpu=yes gpu_reason="nvidia-smi lists $(grep -c '^GPU ' "$out/nvidia_smi_list.txt") GPU(s)"
  with_cap 60 nvidia-smi >"$out/nvidia_smi.txt" 2>&1
  with_cap 60 nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm --format=csv,noheader \
    >"$out/nvidia_smi_query.csv" 2>&1
fi
phase_end device 0 1 "$gpu_reason"
[[ $gpu == no && -z $dry_run ]] && no_gpu_exit

# setup: the binaries.
phase_begin
status=0 note=""
if [[ -n $prebuilt ]]; then
  prebuilt=$(cd "$prebuilt" 2>/dev/null && pwd) || { log "--prebuilt: no folder $prebuilt"; exit 1; }
  if [[ -e $prebuilt/tests/mfsd_gpu_tests ]]; then
    build_dir=$prebuilt mfsd="$prebuilt/mfsd" tests="$prebuilt/tests/mfsd_gpu_tests"
    binaries="build folder $prebuilt"
  else
    # Unpacked into the output folder (out/ is ignored: the pack stays small
    # and travels alone); a pack of plain binaries is used where it lies.
    mkdir -p "$out/bin"
    for exe in mfsd mfsd_gpu_tests; do
      if [[ -e $prebuilt/$exe.xz ]]; then
        xz -d -c "$prebuilt/$exe.xz" >"$out/bin/$exe" && chmod +x "$out/bin/$exe" || status=1
      elif [[ -e $prebuilt/$exe ]]; then
        ln -sf "$prebuilt/$exe" "$out/bin/$exe"
      fi
    done
    [[ -d $prebuilt/lib ]] && export LD_LIBRARY_PATH="$prebuilt/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    mfsd="$out/bin/mfsd" tests="$out/bin/mfsd_gpu_tests"
    binaries="pack $prebuilt"
  fi
  note="prebuilt"
else
  # shellcheck source=common.sh
  source "$here/common.sh"
  mfsd_ensure_dependencies
  mfsd_build -DMFSD_CUDA=ON
  build_dir=$MFSD_BUILD mfsd="$MFSD_BUILD/mfsd" tests="$MFSD_BUILD/tests/mfsd_gpu_tests"
  binaries="built here in $MFSD_BUILD" note="built from source"
fi
for exe in "$mfsd" "$tests"; do
  [[ -x $exe ]] || { log "missing binary $exe"; status=1; }
done
phase_end setup "$status" 1 "$note"
[[ $status -ne 0 ]] && { report; exit 1; }

# probe: what the binaries are and see, and what would run.
phase_begin
"$mfsd" --version >"$out/mfsd_version.txt" 2>&1
status=$?
nvcc=$(command -v nvcc || { [[ -x /usr/local/cuda/bin/nvcc ]] && echo /usr/local/cuda/bin/nvcc; })
[[ -n $nvcc ]] && "$nvcc" --version >"$out/nvcc_version.txt" 2>&1
if [[ -n $build_dir && -f $build_dir/CMakeCache.txt ]]; then
  sed -n -E 's/^(CMAKE_CUDA_COMPILER_VERSION|CMAKE_CUDA_ARCHITECTURES|CMAKE_BUILD_TYPE|MFSD_NATIVE|MFSD_CUDA):[A-Z]*=/\1=/p' \
    "$build_dir/CMakeCache.txt" >"$out/build_info.txt"
  sed -n -E 's/^set\(CMAKE_CUDA_COMPILER_VERSION "(.*)"\)/nvcc \1/p' "$build_dir"/CMakeFiles/*/CMakeCUDACompiler.cmake \
    2>/dev/null | head -1 >>"$out/build_info.txt"
elif [[ -f ${prebuilt:-/nonexistent}/build_info.txt ]]; then
  cp "$prebuilt/build_info.txt" "$out/build_info.txt"
fi
"$tests" --gtest_list_tests >"$out/tests_planned.txt" 2>&1 || status=1
list_args=()
[[ -z $bench_size ]] && list_args=(--full)
python3 "$here/gpu_report.py" list-cases "${list_args[@]}" >"$out/throughput_planned.tsv" || status=1
cuda_line=$(grep -m1 '^cuda devices:' "$out/mfsd_version.txt")
devices=$(sed -n -E 's/^cuda devices: ([0-9]+).*/\1/p' "$out/mfsd_version.txt" | head -1)
if ! grep -q '^backends:.*cuda' "$out/mfsd_version.txt"; then
  log "$mfsd has no CUDA backend ($(grep -m1 '^backends:' "$out/mfsd_version.txt")): build with nvcc (MFSD_CUDA=ON)"
  [[ -z $dry_run ]] && status=1
elif [[ $gpu == yes && ${devices:-0} -eq 0 ]]; then
  gpu=no gpu_reason="mfsd sees no CUDA device (${cuda_line:-no 'cuda devices' line in mfsd --version})"
fi
phase_end probe "$status" 1 "${cuda_line:-}"
log "$(tr '\n' ' ' <"$out/mfsd_version.txt")"
[[ -s $out/nvidia_smi_query.csv ]] && log "device: $(head -1 "$out/nvidia_smi_query.csv")"
if [[ -n $dry_run ]]; then
  mapfile -t planned < <(python3 -c 'import sys; sys.path.insert(0, sys.argv[1]); import gpu_report as g
print("\n".join(g.planned_tests(sys.argv[2])))' "$here" "$out")
  log "would run ${#planned[@]} cross-backend tests (MFSD_REQUIRE_GPU=1): ${planned[*]}"
  log "would run $(wc -l <"$out/throughput_planned.tsv") throughput runs (backend cuda${bench_size:+, quick}):"
  awk -F'\t' '{ printf "[gpu_check]   %s, H/dp %s, %s\n", $1, $3, $4 }' "$out/throughput_planned.tsv" | tee -a "$out/summary.txt" >&2
  [[ $gpu == no ]] && log "no usable GPU here ($gpu_reason); a run without --dry-run would exit 2"
  report
  rc=$?
  [[ $status -ne 0 ]] && exit 1
  [[ ${#planned[@]} -eq 0 ]] && { log "the test binary lists no test"; exit 1; }
  exit $(( rc == 0 ? 0 : 1 ))
fi
[[ $status -ne 0 ]] && { report; exit 1; }
[[ $gpu == no ]] && no_gpu_exit

# tests: cross-backend agreement (the test binary reads configs/ from this checkout).
phase_begin
MFSD_REQUIRE_GPU=1 MFSD_SOURCE_DIR="$root" OMP_NUM_THREADS=$(nproc) \
  with_cap 240 "$tests" --gtest_output=xml:"$out/gpu_tests.xml" >"$out/gpu_tests.log" 2>&1
tests_status=$?
grep -E '^\[ *(OK|FAILED|SKIPPED) +\] [^ ]+ \([0-9]+ ms\)' "$out/gpu_tests.log" | tee -a "$out/summary.txt" >&2
phase_end tests "$tests_status" 1 "$([[ $tests_status -eq 124 ]] && echo 'stopped at 240 s')"

# throughput on the GPU (quick: two sizes per scene, one repeat). The runs'
# timing.json (round trips per step) are copied from out/bench/throughput/.
phase_begin
marker="$out/.throughput_start"
: >"$marker"
bench_cap=1200
[[ -n $bench_size ]] && bench_cap=240
MFSD_BINARY="$mfsd" with_cap "$bench_cap" \
  python3 "$root/bench/run.py" throughput --backend cuda ${bench_size} "${repeats[@]}" >"$out/throughput.log" 2>&1
bench_status=$?
latest=$(find "$root/bench/results" -maxdepth 1 -name 'throughput-*.json' -newer "$marker" 2>/dev/null | head -1)
if [[ -n $latest ]]; then
  cp "$latest" "$out/throughput.json"
  cp "${latest%.json}.md" "$out/throughput.md" 2>/dev/null
else
  [[ $bench_status -eq 0 ]] && bench_status=1
  log "the throughput suite wrote no results (tail of $out/throughput.log:)"
  tail -5 "$out/throughput.log" >&2
fi
mkdir -p "$out/throughput_timing"
for f in "$root"/out/bench/throughput/*/timing.json; do
  [[ -e $f && $f -nt $marker ]] && cp "$f" "$out/throughput_timing/$(basename "$(dirname "$f")").json"
done
# The bending column again with the sliced pair layout (issue 24 item 3),
# against the compressed rows above: out/throughput_sliced.md.
: >"$marker"
MFSD_BINARY="$mfsd" with_cap 120 python3 "$root/bench/run.py" throughput --backend cuda --quick --only "bending column" \
  --mfsd-args "--pair-layout sliced" --tag sliced >"$out/throughput_sliced.log" 2>&1
sliced=$(find "$root/bench/results" -maxdepth 1 -name 'throughput-*-sliced.json' -newer "$marker" 2>/dev/null | head -1)
if [[ -n $sliced ]]; then
  cp "$sliced" "$out/throughput_sliced.json"
  cp "${sliced%.json}.md" "$out/throughput_sliced.md" 2>/dev/null
  log "the bending column with --pair-layout sliced: $out/throughput_sliced.md"
else
  log "the sliced-layout throughput runs wrote no results (tail of $out/throughput_sliced.log:)"
  tail -5 "$out/throughput_sliced.log" >&2
fi
rm -f "$marker"
phase_end throughput "$bench_status" 1 "${latest:+${latest#"$root"/}}"

# divergence: where the backends part, when the tests fail (numpy needed).
if [[ $tests_status -ne 0 ]]; then
  phase_begin
  left=$(( budget - $(elapsed_in_budget) - 10 ))
  (( left < 60 )) && left=60
  with_cap "$left" python3 "$here/gpu_divergence.py" --binary "$mfsd" --out "$out/divergence_runs" \
    >"$out/divergence.txt" 2>&1
  div_status=$?
  rm -rf "$out/divergence_runs"
  phase_end divergence "$div_status" 1 "$([[ $div_status -eq 124 ]] && echo "stopped at $left s")"
fi

# Outside the budget: the rest of the ctest suite, the studies.
if [[ -n $full_suite ]]; then
  phase_begin
  if [[ -n $build_dir && -f $build_dir/CTestTestfile.cmake ]]; then
    MFSD_REQUIRE_GPU=1 ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" -LE validate \
      -E '^CrossBackend\.' >"$out/full_suite.log" 2>&1
    full_status=$?
    phase_end full_suite "$full_status" 0 "ctest -LE validate, MFSD_REQUIRE_GPU=1 ($out/full_suite.log)"
  else
    phase_end full_suite 1 0 "no build folder (a pack has only mfsd and mfsd_gpu_tests)"
  fi
fi
if [[ -n $studies ]]; then
  for study in "crack_branching --dp 0.06125" "kalthoff_winkler --dp 0.125" "four_point_bending --dp 0.5"; do
    name=${study%% *}
    phase_begin
    # shellcheck disable=SC2086
    MFSD_BINARY="$mfsd" python3 "$root/scripts/validation/$name.py" ${study#* } --backend cuda \
      --out "$out/${name}_seed" >"$out/${name}_seed.log" 2>&1
    phase_end "study_$name" $? 0 "at the seed's resolution"
  done
fi

report
rc=$?
total=$(elapsed_in_budget)
(( total > budget )) && log "WARNING: the phases in the budget took $total s, over the $budget s budget"
if [[ $rc -gt 2 ]]; then
  exit 1
fi
exit "$rc"
