#!/usr/bin/env bash
# Builds the CUDA binaries that scripts/gpu_check.sh needs for one GPU
# architecture and packs them small enough to travel to a GPU machine that has
# none of our Debian packages:
#   scripts/gpu_pack.sh [ARCH] [DIR]      (default ARCH 90 = H100/H200, DIR .gpu)
# Release build in build-gpu-sm<ARCH>/ with the portable CPU flags
# (MFSD_NATIVE=OFF: the other machine's CPU may lack this one's instructions);
# mfsd and mfsd_gpu_tests stripped and xz-compressed, with the OpenMP runtime
# beside them (DIR/lib). Then, on the GPU machine:
#   scripts/gpu_check.sh --prebuilt DIR
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
arch=${1:-90}
dest=${2:-$MFSD_ROOT/.gpu}
mfsd_ensure_dependencies
export MFSD_BUILD=${MFSD_GPU_BUILD:-$MFSD_ROOT/build-gpu-sm$arch}
[[ -x /usr/local/cuda/bin/nvcc ]] && export PATH=/usr/local/cuda/bin:$PATH
cmake -S "$MFSD_ROOT" -B "$MFSD_BUILD" -DCMAKE_BUILD_TYPE=Release -DMFSD_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES="$arch" \
  -DMFSD_NATIVE=OFF -DMFSD_BENCH=OFF >"$MFSD_BUILD.configure.log" 2>&1 ||
  { cat "$MFSD_BUILD.configure.log" >&2; exit 1; }
mfsd_log "building mfsd and mfsd_gpu_tests for sm_$arch in $MFSD_BUILD"
cmake --build "$MFSD_BUILD" -j "$(nproc)" --target mfsd mfsd_gpu_tests >"$MFSD_BUILD.build.log" 2>&1 ||
  { grep -E -B2 -A6 'error' "$MFSD_BUILD.build.log" | head -60 >&2; exit 1; }
rm -rf "$dest" && mkdir -p "$dest/lib"
for exe in "$MFSD_BUILD/mfsd" "$MFSD_BUILD/tests/mfsd_gpu_tests"; do
  strip -o "$dest/$(basename "$exe")" "$exe"
  xz -T0 -6 -f "$dest/$(basename "$exe")"
done
gomp=$(g++ -print-file-name=libgomp.so.1)
cp -L "$gomp" "$dest/lib/"
mfsd_log "packed into $dest: $(du -sh "$dest" | cut -f1) ($(ls "$dest" | tr '\n' ' '))"
