#!/usr/bin/env bash
# Installs gridtopo's build and test dependencies from Debian 12 packages, only those that are missing.
# Idempotent; runs apt-get as root (or through sudo). Never installs the libmrpt-dev metapackage (ROS 1).
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  libmrpt-slam-dev libmrpt-gui-dev libwxgtk3.2-dev libopencv-dev libeigen3-dev
  libtclap-dev zlib1g-dev libpng-dev libssl-dev nlohmann-json3-dev
  # the loop closure's pose-graph solver (issue 23)
  libceres-dev
  googletest libgtest-dev
  xvfb xauth libgl1-mesa-dri libglx-mesa0
  # gridtopo-experiment: plots (gnuplot), and scripts/check_slurm.sh, which the suite runs (a one-node Slurm).
  gnuplot-nox python3 slurm-wlm munge
  # cpack -G DEB (scripts/check_install.sh, in the suite): dpkg-shlibdeps computes the runtime Depends
  dpkg-dev file
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
