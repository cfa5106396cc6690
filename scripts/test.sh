#!/usr/bin/env bash
# Sets up (Debian packages, Release build into build/) and runs the tests:
#   scripts/test.sh            unit, regression and CLI tests (label validate excluded)
#   scripts/test.sh --all      also the long validation runs (ctest label validate)
#   scripts/test.sh --gpu      also require the GPU tests to run (MFSD_REQUIRE_GPU=1)
#   scripts/test.sh --mpi      also the MPI loopback tests on 1, 2, 4 ranks (installs OpenMPI; issue 25)
#   scripts/test.sh --python   also the Python module and its tests (installs nanobind, NumPy, pytest; issue 28)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
exclude="validate"
cmake_args=()
for arg in "$@"; do
  case "$arg" in
    --all) exclude="" ;;
    --gpu) export MFSD_REQUIRE_GPU=1 ;;
    --mpi) export MFSD_WITH_MPI=1; cmake_args+=(-DMFSD_MPI=ON) ;;
    --python) export MFSD_WITH_PYTHON=1; cmake_args+=(-DMFSD_PYTHON=ON) ;;
    *) mfsd_log "unknown option $arg (expected --all, --gpu, --mpi or --python)"; exit 2 ;;
  esac
done
mfsd_ensure_dependencies
# The python3 with the module's packages (a virtual environment where the
# system's refuses pip; scripts/common.sh).
[[ ${MFSD_WITH_PYTHON:-0} == 1 ]] && cmake_args+=("-DPython_EXECUTABLE=$MFSD_PYTHON_EXE")
# Every backend nvcc can build (a build folder that scripts/run.sh set up
# without CUDA gains it here; the g++ objects are reused).
cmake_args+=("-DMFSD_CUDA=${MFSD_CUDA:-AUTO}")
start=$(date +%s)
mfsd_build "${cmake_args[@]}"
mfsd_log "build took $(( $(date +%s) - start )) s"
# ctest starts the costliest tests first when it knows their costs: a fresh
# build folder gets the costs of a full run (tests/ctest_cost_data.txt, from
# build/Testing/Temporary/CTestCostData.txt), so that the long RKPM and MPI
# runs do not start last and leave a core idle at the end.
costs=$MFSD_BUILD/Testing/Temporary/CTestCostData.txt
[[ -f $costs ]] || { mkdir -p "$(dirname "$costs")" && cp "$MFSD_ROOT/tests/ctest_cost_data.txt" "$costs"; }
args=(--test-dir "$MFSD_BUILD" --output-on-failure -j "$(nproc 2>/dev/null || echo 2)")
[[ -n $exclude ]] && args+=(-LE "$exclude")
ctest "${args[@]}"
mfsd_log "tests passed in $(( $(date +%s) - start )) s"
