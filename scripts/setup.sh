#!/usr/bin/env bash
# Installs every Debian package the project needs to build, test and run.
# Idempotent and quiet: apt-get runs only when something is missing.
set -euo pipefail

packages=(
  cmake ninja-build g++ python3
  libtbb-dev libglm-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  clang libclang-rt-14-dev
  pkg-config libepoxy-dev libegl-dev libegl-mesa0 libgl1-mesa-dri
  libassimp-dev assimp-testmodels libopenimageio-dev
  glslang-tools
  python3-matplotlib
  libabsl-dev libsparsehash-dev
  pybind11-dev python3-dev python3-numpy python3-pytest
  python3-setuptools python3-pip python3-venv
  libglfw3-dev libimgui-dev xvfb xauth
  libopenvdb-dev libopencsg-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools glslang-dev spirv-tools
)

missing=()
for p in "${packages[@]}"; do
  [[ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)" == *"install ok installed"* ]] || missing+=("$p")
done
if [[ ${#missing[@]} -gt 0 ]]; then
  sudo_cmd=()
  [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
