#!/usr/bin/env bash
# Time to first result, as a new user meets it (issue 47): a fresh clone of
# this repository's HEAD, then `scripts/run.sh` (Debian packages, the build
# of the mfsd binary, the default plate) and, with --test, `scripts/test.sh
# ARGS` in the same clone (the rest of the build and the suite). Prints the
# wall time of each and the slowest compile steps (build/.ninja_log).
#   bench/build_time.sh [--test "ARGS"] [--keep DIR]
# e.g. bench/build_time.sh --test "--mpi --python"   (what .ci/run runs)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
test_args="" run_tests=0 dir=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --test) run_tests=1; test_args=$2; shift 2 ;;
    --keep) dir=$2; shift 2 ;;
    *) echo "usage: bench/build_time.sh [--test \"ARGS\"] [--keep DIR]" >&2; exit 2 ;;
  esac
done
if [[ -z $dir ]]; then
  dir=$(mktemp -d /tmp/mfsd_build_time.XXXXXX)
  trap 'rm -rf "$dir"' EXIT
fi
git clone -q "$root" "$dir/mfsd"
cd "$dir/mfsd"
echo "commit $(git rev-parse --short HEAD), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
t0=$(date +%s.%N)
scripts/run.sh -q >/dev/null
t1=$(date +%s.%N)
[[ -f out/oscillating_plate_2d/energies.csv ]] || { echo "run.sh left no plate output" >&2; exit 1; }
printf 'scripts/run.sh (build of mfsd, the plate): %.0f s (%s)\n' "$(echo "$t1 - $t0" | bc)" \
  "$(grep -o 'CUDA backend [A-Z]*' build.configure.log)"
slowest() {
  awk '{printf "%7.1f s  %s\n", ($2 - $1) / 1000, $4}' build/.ninja_log | sort -rn | head -"$1"
  awk '{t = ($2 - $1) / 1000; s += t; if ($4 ~ /_cuda_/) c += t; else if ($4 ~ /_cpu_/) g += t;
        else if ($4 ~ /tests\//) x += t}
       END {printf "compile and link time summed: %.0f s (CUDA instantiations %.0f, CPU instantiations %.0f, tests %.0f)\n",
            s, c, g, x}' build/.ninja_log
}
slowest 5
if [[ $run_tests == 1 ]]; then
  # shellcheck disable=SC2086
  scripts/test.sh $test_args >"$dir/test.log" 2>&1 || { tail -40 "$dir/test.log"; exit 1; }
  t2=$(date +%s.%N)
  printf 'scripts/test.sh %s after it (the rest of the build, the suite): %.0f s; %s\n' "$test_args" \
    "$(echo "$t2 - $t1" | bc)" "$(grep -o 'build took [0-9]* s' "$dir/test.log")"
  grep -E 'tests passed|tests failed' "$dir/test.log" | tail -1
  slowest 12
fi
