#!/usr/bin/env bash
# Install lsdem's build and run dependencies from Debian's packages (needs root or sudo).
# Skips apt entirely when everything is already there, so repeated runs are fast.
set -euo pipefail

packages=(
    build-essential cmake ccache pkg-config
    libopenvdb-dev libopenvdb-tools libboost-iostreams-dev libimath-dev libblosc-dev
    libtbb-dev libeigen3-dev libassimp-dev libcgal-dev libgmp-dev libmpfr-dev
    libpng-dev zlib1g-dev libtomlplusplus-dev libssl-dev libcli11-dev nlohmann-json3-dev
    libgtest-dev libgmock-dev libbenchmark-dev
    python3 python3-matplotlib
    pybind11-dev python3-dev python3-numpy python3-pytest
    libopenmpi-dev openmpi-bin
)

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi

echo "lsdem: installing Debian packages: ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "lsdem: need root or sudo to install packages" >&2; exit 1; }
    sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
