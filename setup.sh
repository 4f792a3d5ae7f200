#!/usr/bin/env bash
# Installs the Debian packages this project needs, builds it, and installs
# the `liggghts` launcher (with the viscoelastic models) into /usr/local/bin,
# ahead of the stock /usr/bin/liggghts on PATH.
set -euo pipefail
cd "$(dirname "$0")"
sudo=""
[ "$(id -u)" -ne 0 ] && sudo=sudo
$sudo apt-get update
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends \
  build-essential cmake liggghts libliggghts-dev openmpi-bin libopenmpi-dev shellcheck \
  libeigen3-dev libboost-dev libcli11-dev libgtest-dev libbenchmark-dev valgrind \
  python3 python3-matplotlib python3-numpy python3-scipy \
  paraview paraview-dev python3-paraview xvfb xauth
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
$sudo cmake --install build
$sudo ldconfig
