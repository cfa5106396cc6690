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
  local pkgs="g++ cmake ninja-build make nlohmann-json3-dev libcxxopts-dev libgtest-dev libbenchmark-dev"
  if ! mfsd_has_nvcc; then
    pkgs="$pkgs libthrust-dev"
  fi
  # The distributed engine's MPI (issue 25), when asked (scripts/test.sh --mpi).
  [[ ${MFSD_WITH_MPI:-0} == 1 ]] && pkgs="$pkgs libopenmpi-dev openmpi-bin"
  # The Python module (issue 28): Debian's python3 headers and venv, for
  # when the python3 on PATH is Debian's (its packages then go into a venv).
  if [[ ${MFSD_WITH_PYTHON:-0} == 1 && $(command -v python3) == /usr/bin/python3 ]]; then
    pkgs="$pkgs python3-dev python3-venv"
  fi
  echo "$pkgs"
}

# The Python module's build and test packages (issue 28; scripts/test.sh
# --python): nanobind, NumPy, pytest, and matplotlib for the examples'
# figures. The python3 on PATH when it has them; else a virtual environment
# in $MFSD_VENV (build/venv, with the system's packages visible), where pip
# installs them: Debian 12's python3 refuses pip into the system
# ("externally managed"). Exports MFSD_PYTHON_EXE, the interpreter to use.
MFSD_VENV=${MFSD_VENV:-$MFSD_BUILD/venv}
mfsd_python_modules="nanobind numpy pytest matplotlib"
mfsd_has_python_modules() { "$1" -c "import ${mfsd_python_modules// /, }" 2>/dev/null; }
mfsd_ensure_python_packages() {
  [[ ${MFSD_WITH_PYTHON:-0} == 1 ]] || return 0
  local system
  system=$(command -v python3) || { mfsd_log "python3 is not installed (Debian: python3 python3-venv)"; exit 1; }
  if mfsd_has_python_modules "$system"; then
    export MFSD_PYTHON_EXE=$system
    return 0
  fi
  if ! mfsd_has_python_modules "$MFSD_VENV/bin/python3"; then
    # (Debian's python3 needs python3-venv: mfsd_required_packages asks for it.)
    if [[ ! -x $MFSD_VENV/bin/python3 ]]; then
      "$system" -m venv --system-site-packages "$MFSD_VENV" || {
        rm -rf "$MFSD_VENV"
        mfsd_log "could not make a virtual environment in $MFSD_VENV (Debian: apt-get install python3-venv)"
        exit 1
      }
    fi
    mfsd_log "installing Python packages into $MFSD_VENV: $mfsd_python_modules"
    "$MFSD_VENV/bin/python3" -m pip install -q $mfsd_python_modules || {
      mfsd_log "could not install them; run: $MFSD_VENV/bin/python3 -m pip install $mfsd_python_modules"
      exit 1
    }
  fi
  export MFSD_PYTHON_EXE=$MFSD_VENV/bin/python3
}

mfsd_ensure_dependencies() {
  mfsd_ensure_debian_packages
  mfsd_ensure_python_packages
}

mfsd_ensure_debian_packages() {
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

# Whether nvcc is installed, and whether a CUDA device is visible.
mfsd_has_nvcc() { command -v nvcc >/dev/null 2>&1 || [[ -x /usr/local/cuda/bin/nvcc ]]; }
mfsd_gpu_visible() { command -v nvidia-smi >/dev/null 2>&1 && nvidia-smi -L 2>/dev/null | grep -q '^GPU'; }

# mfsd_build [extra cmake args...]: configure (once) and build Release into
# $MFSD_BUILD: every target, or the ones named in MFSD_TARGETS (e.g. "mfsd").
mfsd_build() {
  if [[ -x /usr/local/cuda/bin/nvcc ]] && ! command -v nvcc >/dev/null 2>&1; then
    export PATH=/usr/local/cuda/bin:$PATH
  fi
  local jobs
  jobs=$(nproc 2>/dev/null || echo 2)
  # Ninja for a new build folder: it rebuilds an object only when its own
  # command changes (Make's generator rebuilds every object of a target when
  # any source of it gets a flag, e.g. the CUDA backend added later).
  local generator=()
  [[ ! -f $MFSD_BUILD/CMakeCache.txt ]] && command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
  cmake -S "$MFSD_ROOT" -B "$MFSD_BUILD" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "$@" >"$MFSD_BUILD.configure.log" 2>&1 || {
    cat "$MFSD_BUILD.configure.log" >&2
    mfsd_log "CMake configuration failed (log above)"
    exit 1
  }
  mfsd_log "building in $MFSD_BUILD ($(grep -o 'CUDA backend [A-Z]*' "$MFSD_BUILD.configure.log" || echo 'CUDA backend ?'))"
  local targets=()
  for t in ${MFSD_TARGETS:-}; do targets+=(--target "$t"); done
  cmake --build "$MFSD_BUILD" -j "$jobs" "${targets[@]}" >"$MFSD_BUILD.build.log" 2>&1 || {
    grep -E -B2 -A6 'error' "$MFSD_BUILD.build.log" | head -80 >&2
    mfsd_log "build failed; full log: $MFSD_BUILD.build.log"
    exit 1
  }
}
