#!/usr/bin/env bash
# Talus setup: the two commands of the README.
#
#   ./setup.sh            install the Debian packages Talus needs (as root; skipped when they are
#                         all there), prepare OpenFOAM's development sources, configure, build,
#                         and run the main demo (cases/01_demo_cfd_dem.py: CFD-DEM under mpirun, the DEM
#                         and 2 OpenFOAM ranks). Safe to run again: it only does what is missing.
#   ./setup.sh test       run the whole test suite (ctest, then pytest) and print one summary line.
#
# Options (before or after the command):
#   --build-dir DIR       build folder (default: ./build)
#   --no-install          do not touch system packages (a non-root user with the packages present)
#   --cmake-args "..."    extra CMake arguments, e.g. "-DTALUS_WITH_FEM=OFF"
# Environment: TALUS_OPENFOAM_SRC (default /opt/talus/openfoam-v1912), JOBS (default: nproc).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build="$here/build"
install_packages=1
cmake_args=()
command=build
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) build=$(realpath -m "$2"); shift 2 ;;
    --no-install) install_packages=0; shift ;;
    --cmake-args) read -r -a extra <<<"$2"; cmake_args+=("${extra[@]}"); shift 2 ;;
    build|test) command=$1; shift ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    *) echo "setup.sh: unknown argument '$1' (see ./setup.sh --help)" >&2; exit 2 ;;
  esac
done
python=/usr/bin/python3   # Debian's interpreter: it sees the python3-* packages
jobs=${JOBS:-$(nproc)}
openfoam_src=${TALUS_OPENFOAM_SRC:-/opt/talus/openfoam-v1912}

# Every Debian package the components use; cases and benchmarks also use the peers yade and
# liggghts, installed here so a fresh machine can run them (xvfb: Yade's examples import its Qt
# GUI, which needs a display even under -x).
packages=(
  g++ make cmake git pkg-config ca-certificates
  libgtest-dev googletest
  libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev libsuitesparse-dev libtbb-dev libhypre-dev
  libopenmpi-dev openmpi-bin libhdf5-openmpi-dev coinor-libclp-dev libtrilinos-zoltan-dev
  pybind11-dev python3-dev python3-numpy python3-scipy python3-matplotlib python3-pytest python3-h5py python3-mpi4py
  openfoam flex libfl-dev bzip2 zlib1g-dev
  python3-dolfinx python3-escript gmsh python3-gmsh
  yade liggghts xvfb xauth
)

step() { printf '\n== %s\n' "$*"; }
elapsed() { printf '%ds' $(( $(date +%s) - $1 )); }

install_dependencies() {
  local missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -eq 0 ]; then
    echo "all ${#packages[@]} Debian packages are installed"
    return
  fi
  if [ "$(id -u)" -ne 0 ]; then
    echo "setup.sh: missing Debian packages: ${missing[*]}" >&2
    echo "run ./setup.sh as root to install them, or install them yourself and use --no-install" >&2
    exit 1
  fi
  echo "installing ${#missing[@]} packages: ${missing[*]}"
  apt-get update -q
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
}

run_build() {
  local t0
  if [ $install_packages -eq 1 ]; then
    t0=$(date +%s); step "Debian packages"; install_dependencies; echo "($(elapsed "$t0"))"
    t0=$(date +%s); step "OpenFOAM v1912 development sources ($openfoam_src)"
    bash "$here/foam-solvers/prepare-openfoam-sources.sh" "$openfoam_src"; echo "($(elapsed "$t0"))"
  fi
  t0=$(date +%s); step "configure ($build)"
  cmake -S "$here" -B "$build" -DPython3_EXECUTABLE=$python -DTALUS_OPENFOAM_SRC="$openfoam_src" \
        "${cmake_args[@]}"
  echo "($(elapsed "$t0"))"
  t0=$(date +%s); step "build ($jobs jobs)"
  cmake --build "$build" -j "$jobs"; echo "($(elapsed "$t0"))"
  "$build/bin/talus" info
  t0=$(date +%s); step "main demo: beads settling in a liquid, CFD-DEM under mpirun (cases/01_demo_cfd_dem.py)"
  (cd "$here" && "$build/bin/talus" run -j 1 cases/01_demo_cfd_dem.py --results "$here/results")
  echo "($(elapsed "$t0"))"
}

run_tests() {
  if [ ! -x "$build/bin/talus" ]; then
    echo "setup.sh test: no build in $build; run ./setup.sh first" >&2
    exit 2
  fi
  local log; log=$(mktemp -d)
  step "C++ tests (ctest)"
  set +e
  ctest --test-dir "$build" -j "$jobs" --output-on-failure | tee "$log/ctest"
  local ctest_rc=${PIPESTATUS[0]}
  step "Python tests (pytest)"
  TALUS_BUILD_DIR="$build" $python -m pytest "$here/tests" -q -p no:cacheprovider | tee "$log/pytest"
  local pytest_rc=${PIPESTATUS[0]}
  # One summary line over both runners: "N passed, N failed[, N skipped]".
  local c_total c_failed p_passed p_failed p_skipped
  c_total=$(sed -n 's/.*tests failed out of \([0-9]*\).*/\1/p' "$log/ctest" | tail -1)
  c_failed=$(sed -n 's/.* \([0-9]*\) tests failed out of.*/\1/p' "$log/ctest" | tail -1)
  p_passed=$(grep -Eo '[0-9]+ passed' "$log/pytest" | tail -1 | cut -d' ' -f1)
  p_failed=$(grep -Eo '[0-9]+ (failed|error)' "$log/pytest" | awk '{s+=$1} END {print s+0}')
  p_skipped=$(grep -Eo '[0-9]+ skipped' "$log/pytest" | tail -1 | cut -d' ' -f1)
  local passed=$(( ${c_total:-0} - ${c_failed:-0} + ${p_passed:-0} ))
  local failed=$(( ${c_failed:-0} + ${p_failed:-0} ))
  [ "$ctest_rc" -ne 0 ] && [ "${c_failed:-0}" -eq 0 ] && failed=$(( failed + 1 ))
  [ "$pytest_rc" -ne 0 ] && [ "${p_failed:-0}" -eq 0 ] && failed=$(( failed + 1 ))
  rm -rf "$log"
  set -e
  echo
  echo "talus: $passed passed, $failed failed, ${p_skipped:-0} skipped"
  [ "$failed" -eq 0 ]
}

case $command in
  build) run_build ;;
  test) run_tests ;;
esac
