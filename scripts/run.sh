#!/usr/bin/env bash
# Sets up (Debian packages, Release build into build/) and runs a scene:
#   scripts/run.sh                       the built-in oscillating plate
#   scripts/run.sh configs/X.json [mfsd run options...]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
mfsd_ensure_dependencies
mfsd_build
exec "$MFSD_BUILD/mfsd" run "$@"
