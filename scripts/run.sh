#!/usr/bin/env bash
# Sets up (Debian packages, Release build of the mfsd binary into build/) and
# runs a scene:
#   scripts/run.sh                       the built-in oscillating plate
#   scripts/run.sh configs/X.json [mfsd run options...]
# Only the binary is built (scripts/test.sh builds the rest). The CUDA
# backend is built in when nvcc is found and a GPU is visible, for that GPU's
# architecture; on a machine without a GPU a new build folder is set up
# without it (about a quarter of the build; it could not run here), and
# MFSD_CUDA=ON scripts/run.sh, or scripts/test.sh, adds it to the same folder.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
mfsd_ensure_dependencies
args=()
if [[ -n ${MFSD_CUDA:-} ]]; then
  args+=("-DMFSD_CUDA=$MFSD_CUDA")
elif [[ ! -f $MFSD_BUILD/CMakeCache.txt ]] && mfsd_has_nvcc && ! mfsd_gpu_visible; then
  mfsd_log "nvcc is here but no GPU: building the CPU backend only (MFSD_CUDA=ON $0 to add CUDA)"
  args+=(-DMFSD_CUDA=OFF)
fi
MFSD_TARGETS=mfsd mfsd_build "${args[@]}"
exec "$MFSD_BUILD/mfsd" run "$@"
