#!/usr/bin/env bash
# Sets up (Debian packages, Release build into build/) and runs the tests:
#   scripts/test.sh            unit, regression and CLI tests (label validate excluded)
#   scripts/test.sh --all      also the long validation runs (ctest label validate)
#   scripts/test.sh --gpu      also require the GPU tests to run (MFSD_REQUIRE_GPU=1)
#   scripts/test.sh --mpi      also the MPI loopback tests on 1, 2, 4 ranks (installs OpenMPI; issue 25)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
exclude="validate"
cmake_args=()
for arg in "$@"; do
  case "$arg" in
    --all) exclude="" ;;
    --gpu) export MFSD_REQUIRE_GPU=1 ;;
    --mpi) export MFSD_WITH_MPI=1; cmake_args+=(-DMFSD_MPI=ON) ;;
    *) mfsd_log "unknown option $arg (expected --all, --gpu or --mpi)"; exit 2 ;;
  esac
done
mfsd_ensure_dependencies
start=$(date +%s)
mfsd_build "${cmake_args[@]}"
mfsd_log "build took $(( $(date +%s) - start )) s"
args=(--test-dir "$MFSD_BUILD" --output-on-failure -j "$(nproc 2>/dev/null || echo 2)")
[[ -n $exclude ]] && args+=(-LE "$exclude")
ctest "${args[@]}"
mfsd_log "tests passed in $(( $(date +%s) - start )) s"
