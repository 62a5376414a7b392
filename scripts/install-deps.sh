#!/usr/bin/env bash
# Installs the Debian 12 packages raycache needs to build, test and run.
# Idempotent: does nothing when everything is present. Uses sudo when not root.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git ccache
  libembree-dev libtbb-dev libassimp-dev nlohmann-json3-dev libcli11-dev
  libstb-dev libopenexr-dev
  libgtest-dev libgmock-dev
  libegl-dev libgl1-mesa-dri libegl-mesa0 libepoxy-dev
  libglfw3-dev libimgui-dev xvfb xauth
  clang libclang-rt-14-dev
  libopenmpi-dev openmpi-bin
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
