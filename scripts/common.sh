# Shared set-up for scripts/run.sh, scripts/test.sh and bench/: installs the
# Debian packages mfsd needs (as root) or prints the exact apt command, then
# configures and builds Release into build/. Source it; do not run it.

MFSD_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
MFSD_BUILD=${MFSD_BUILD:-$MFSD_ROOT/build}

mfsd_log() { printf '[mfsd] %s\n' "$*" >&2; }

# Debian packages: compiler, CMake, OpenMP (libgomp comes with g++), JSON,
# command-line parsing, GoogleTest, Google Benchmark; Thrust from Debian only
# when no CUDA toolkit (whose CCCL provides it) is installed.
mfsd_required_packages() {
  local pkgs="g++ cmake make nlohmann-json3-dev libcxxopts-dev libgtest-dev libbenchmark-dev"
  if ! command -v nvcc >/dev/null 2>&1 && [[ ! -x /usr/local/cuda/bin/nvcc ]]; then
    pkgs="$pkgs libthrust-dev"
  fi
  # The distributed engine's MPI (issue 25), when asked (scripts/test.sh --mpi).
  [[ ${MFSD_WITH_MPI:-0} == 1 ]] && pkgs="$pkgs libopenmpi-dev openmpi-bin"
  echo "$pkgs"
}

# The Python module's build and test packages (issue 28; scripts/test.sh
# --python), from PyPI for the python3 on PATH: nanobind, NumPy, pytest, and matplotlib for the examples' figures.
mfsd_ensure_python_packages() {
  [[ ${MFSD_WITH_PYTHON:-0} == 1 ]] || return 0
  python3 -c "import nanobind, numpy, pytest, matplotlib" 2>/dev/null && return 0
  mfsd_log "installing Python packages for $(command -v python3): nanobind numpy pytest matplotlib"
  python3 -m pip install -q nanobind numpy pytest matplotlib || {
    mfsd_log "could not install them; run: python3 -m pip install nanobind numpy pytest matplotlib"
    exit 1
  }
}

mfsd_ensure_dependencies() {
  mfsd_ensure_python_packages
  local missing=()
  for p in $(mfsd_required_packages); do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [[ ${#missing[@]} -eq 0 ]] && return 0
  if [[ $(id -u) -eq 0 ]]; then
    mfsd_log "installing Debian packages: ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >/dev/null
    apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  else
    mfsd_log "missing Debian packages: ${missing[*]}"
    mfsd_log "install them with:  sudo apt-get update && sudo apt-get install -y ${missing[*]}"
    exit 1
  fi
}

# mfsd_build [extra cmake args...]: configure (once) and build Release into $MFSD_BUILD.
mfsd_build() {
  if [[ -x /usr/local/cuda/bin/nvcc ]] && ! command -v nvcc >/dev/null 2>&1; then
    export PATH=/usr/local/cuda/bin:$PATH
  fi
  local jobs
  jobs=$(nproc 2>/dev/null || echo 2)
  cmake -S "$MFSD_ROOT" -B "$MFSD_BUILD" -DCMAKE_BUILD_TYPE=Release "$@" >"$MFSD_BUILD.configure.log" 2>&1 || {
    cat "$MFSD_BUILD.configure.log" >&2
    mfsd_log "CMake configuration failed (log above)"
    exit 1
  }
  mfsd_log "building in $MFSD_BUILD ($(grep -o 'CUDA backend [A-Z]*' "$MFSD_BUILD.configure.log" || echo 'CUDA backend ?'))"
  cmake --build "$MFSD_BUILD" -j "$jobs" >"$MFSD_BUILD.build.log" 2>&1 || {
    grep -E -B2 -A6 'error' "$MFSD_BUILD.build.log" | head -80 >&2
    mfsd_log "build failed; full log: $MFSD_BUILD.build.log"
    exit 1
  }
}
