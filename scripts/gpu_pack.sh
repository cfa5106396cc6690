#!/usr/bin/env bash
# Builds the CUDA binaries that scripts/gpu_check.sh needs for one GPU
# architecture and packs them small enough to travel to a GPU machine that has
# none of our Debian packages:
#   scripts/gpu_pack.sh [ARCH] [DIR]      (default ARCH 90 = H100/H200, DIR .gpu)
# Release build in build-gpu-sm<ARCH>/ (MFSD_GPU_BUILD to choose another
# folder) with the portable CPU flags (MFSD_NATIVE=OFF: the other machine's CPU
# may lack this one's instructions); mfsd and mfsd_gpu_tests stripped and
# xz-compressed, the OpenMP runtime beside them (DIR/lib), and DIR/build_info.txt
# (nvcc, architecture, flags, mfsd --version) for the report. The pack must stay
# under 64 MiB (what a device machine's copy of the working tree may carry);
# about 17 MiB. MFSD_PACK_ONLY=1 packs the build folder as it is (no configure,
# no build). Then, on the GPU machine:
#   bash scripts/gpu_check.sh --prebuilt DIR --out "$OUT/gpu_check"
# which unpacks into its output folder (DIR keeps only the .xz files).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
arch=${1:-90}
dest=${2:-$MFSD_ROOT/.gpu}
limit=$((64 * 1024 * 1024))
export MFSD_BUILD=${MFSD_GPU_BUILD:-$MFSD_ROOT/build-gpu-sm$arch}
[[ -x /usr/local/cuda/bin/nvcc ]] && export PATH=/usr/local/cuda/bin:$PATH
if [[ ${MFSD_PACK_ONLY:-} != 1 ]]; then
  mfsd_ensure_dependencies
  cmake -S "$MFSD_ROOT" -B "$MFSD_BUILD" -DCMAKE_BUILD_TYPE=Release -DMFSD_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES="$arch" \
    -DMFSD_NATIVE=OFF -DMFSD_BENCH=OFF >"$MFSD_BUILD.configure.log" 2>&1 ||
    { cat "$MFSD_BUILD.configure.log" >&2; exit 1; }
  mfsd_log "building mfsd and mfsd_gpu_tests for sm_$arch in $MFSD_BUILD"
  cmake --build "$MFSD_BUILD" -j "$(nproc)" --target mfsd mfsd_gpu_tests >"$MFSD_BUILD.build.log" 2>&1 ||
    { grep -E -B2 -A6 'error' "$MFSD_BUILD.build.log" | head -60 >&2; exit 1; }
fi
for exe in "$MFSD_BUILD/mfsd" "$MFSD_BUILD/tests/mfsd_gpu_tests"; do
  [[ -x $exe ]] || { mfsd_log "missing $exe"; exit 1; }
done
"$MFSD_BUILD/mfsd" --version | grep -q '^backends:.*cuda' ||
  { mfsd_log "$MFSD_BUILD/mfsd has no CUDA backend (is nvcc installed?)"; exit 1; }
rm -rf "$dest" && mkdir -p "$dest/lib"
for exe in "$MFSD_BUILD/mfsd" "$MFSD_BUILD/tests/mfsd_gpu_tests"; do
  strip -o "$dest/$(basename "$exe")" "$exe"
  xz -T0 -6 -f "$dest/$(basename "$exe")"
done
gomp=$(g++ -print-file-name=libgomp.so.1)
cp -L "$gomp" "$dest/lib/"
cache() { sed -n -E "s/^$1:[A-Z]*=//p" "$MFSD_BUILD/CMakeCache.txt" | head -1; }
nvcc_version=$(sed -n -E 's/^set\(CMAKE_CUDA_COMPILER_VERSION "(.*)"\)/\1/p' "$MFSD_BUILD"/CMakeFiles/*/CMakeCUDACompiler.cmake \
  2>/dev/null | head -1)
{
  echo "packed $(date -u +%FT%TZ) by scripts/gpu_pack.sh from $(basename "$MFSD_BUILD")"
  echo "nvcc ${nvcc_version:-?}, CUDA architectures $(cache CMAKE_CUDA_ARCHITECTURES), $(cache CMAKE_BUILD_TYPE)," \
    "MFSD_NATIVE=$(cache MFSD_NATIVE), g++ $(g++ -dumpfullversion)"
  "$MFSD_BUILD/mfsd" --version | head -1
} >"$dest/build_info.txt"
size=$(du -sb "$dest" | cut -f1)
mfsd_log "packed into $dest: $((size / 1024 / 1024)) MiB ($(ls "$dest" | tr '\n' ' '))"
if (( size > limit )); then
  mfsd_log "the pack is over 64 MiB: it would not travel to a device machine"
  exit 1
fi
