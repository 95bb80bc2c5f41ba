#!/usr/bin/env bash
# Installs vorodec's Debian 12 dependencies. Idempotent: packages already present are skipped.
set -euo pipefail

packages=(
  build-essential cmake pkg-config ccache
  libcgal-dev libeigen3-dev libsuitesparse-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev libtomlplusplus-dev libcli11-dev
  # Checkpoints: cereal binary archives (header-only), zlib's CRC-32.
  libcereal-dev zlib1g-dev
  # JSON: summary.json and every JSON the project writes or reads (header-only).
  nlohmann-json3-dev
  # Calibration: NLopt's derivative-free optimisers (BOBYQA).
  libnlopt-cxx-dev
  libvtk9-dev python3-vtk9 python3-matplotlib python3-numpy
  # The Python module (python/): pybind11 and the headers of Debian's /usr/bin/python3.
  pybind11-dev python3-dev
  # MPI for `vorodec batch` across machines (mpirun; optional at build time, used by the tests).
  libopenmpi-dev openmpi-bin
  xvfb
  # pvbatch for tests/run_paraview_check.sh (~37 packages, removes nothing). Its python3-paraview
  # conflicts with python3-vtk9 (needed by libvtk9-dev): never install it, the check unpacks its
  # .deb privately.
  paraview
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
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
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
