#!/usr/bin/env bash
# Installs what RegoDEM needs to build, test and benchmark on Debian 12, from Debian's
# own packages only. Run as root (or with sudo available). `regodem plot` needs
# /usr/bin/python3 with python3-matplotlib and python3-numpy; the snapshot tests use
# python3-vtk9. The Python module (python/, docs/python.md) builds with pybind11 for
# /usr/bin/python3 and is tested with pytest; pandas is optional to it and tested here.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends \
  g++ cmake ninja-build pkg-config \
  libyaml-cpp-dev libcli11-dev libfmt-dev libspdlog-dev libeigen3-dev nlohmann-json3-dev \
  libgtest-dev libgmock-dev libbenchmark-dev \
  zlib1g-dev python3-vtk9 python3-matplotlib python3-numpy \
  python3-dev pybind11-dev python3-pytest python3-pandas \
  libopenmpi-dev openmpi-bin
