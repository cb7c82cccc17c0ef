#!/usr/bin/env bash
# Installs every Debian 12 package lagfsi needs to build, test and plot.
# Idempotent: when everything is present it only checks (a second or two).
set -euo pipefail
PKGS=(
  build-essential cmake g++ git pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libeigen3-dev
  libsuitesparse-dev
  libvtk9-dev
  nlohmann-json3-dev
  libgtest-dev googletest
  libomp-dev
  petsc-dev openmpi-bin
  python3 python3-matplotlib python3-numpy python3-pil
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PKGS[@]} packages present"
  exit 0
fi
echo "setup: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
