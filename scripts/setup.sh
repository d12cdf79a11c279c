#!/usr/bin/env bash
# Installs everything the orchestrator needs to build and test on Debian 12 (bookworm).
# Runs apt-get as root (directly, or through sudo when not root). Safe to run repeatedly:
# when every package is already installed it does nothing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  sumo sumo-tools                       # SUMO 1.15: libsumocpp, libtracicpp, netconvert, traci
  nlohmann-json3-dev libeigen3-dev libcli11-dev libspdlog-dev libfmt-dev
  libboost-dev libboost-filesystem-dev libboost-system-dev
  libyaml-cpp-dev libpugixml-dev libssl-dev
  libproj-dev                           # PROJ: OpenSCENARIO GeoPosition through the road's geoReference
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  python3 xvfb xauth
  slurm-wlm munge                       # the nightly batch's Slurm test runs a single-node cluster
  clang libclang-rt-14-dev               # libFuzzer target of the ego TraCI server (tests/fuzz)
  libjs-chart.js                        # Chart.js, compiled into report.html (orchestrator/report)
  chromium chromium-driver              # the reports' browser tests (tests/browser, label browser)
  ffmpeg                                # run --video
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

as_root=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  as_root=(sudo)
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update
"${as_root[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
