#!/usr/bin/env bash
# Installs every build, run and test dependency of isoquad from Debian 12 packages.
# Safe to run again: apt-get skips what is already installed.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libeigen3-dev
  libgdal-dev gdal-bin libgeos-dev
  libproj-dev proj-bin proj-data
  libgeographiclib-dev
  libmuparser-dev libcli11-dev libsleef-dev
  libcairo2-dev
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  libnetcdf-dev
  python3-gdal python3-numpy python3-meshio python3-scipy python3-netcdf4 gmsh time
  python3-qgis qgis-providers
)
stamp=/var/lib/apt/periodic/update-success-stamp
if [ ! -d /var/lib/apt/lists/partial ] || [ -z "$(ls -A /var/lib/apt/lists 2>/dev/null | grep -v -e partial -e lock)" ]; then
  $SUDO apt-get update -q
fi
if ! $SUDO apt-get install -y -q --no-install-recommends "${PACKAGES[@]}"; then
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${PACKAGES[@]}"
fi
