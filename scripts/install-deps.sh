#!/usr/bin/env bash
# Installs beamfea's build dependencies from Debian's packages; skips what is present.
# Usage: scripts/install-deps.sh        (needs root, or sudo)
set -euo pipefail

packages=(
  g++ cmake ninja-build pkg-config
  libeigen3-dev libsuitesparse-dev libsundials-dev libvtk9-dev libspectra-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev
  liburdfdom-dev                # `beamfea urdf`: reading URDF robot descriptions (io/urdf_reader.cpp)
  libgtest-dev libbenchmark-dev
  libopenblas0-pthread          # CHOLMOD's supernodal factorisation is 6-14x faster than with reference BLAS
  openmpi-bin libopenmpi-dev    # `beamfea sweep` under mpirun
  libpetsc-real-dev             # the iterative solver: CG with algebraic multigrid (solvers/petsc_solver.cpp)
  libslepc-real-dev             # eigenvalues of models beyond one direct factorisation (modal, buckling)
  python3-matplotlib python3-numpy  # plots of the examples (Debian's /usr/bin/python3)
  pybind11-dev python3-pybind11 python3-dev python3-pytest  # the Python module (python/) and its tests
  python3-vtk9                  # tests read the .vtu files back with VTK's own reader
  python3-pandas                # optional for users: the tests of beamfea.sweep's DataFrame
  clang-14 libclang-rt-14-dev   # the libFuzzer targets (tests/fuzz, -DBEAMFEA_BUILD_FUZZERS=ON)
  libomp-14-dev                 # clang's OpenMP: a dependency's CMake config asks for OpenMP_CXX
)

missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# A concurrent apt run can make one install fail on a .deb: retry once.
for attempt in 1 2; do
  if $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"; then exit 0; fi
  echo "install-deps: apt-get failed (attempt $attempt), retrying" >&2
  sleep 5
done
exit 1
