#!/usr/bin/env bash
# Installs the Debian 12 packages luz needs to build and test, only those missing.
#   scripts/setup.sh          everything: the tests, viewer, Python, MPI, figures, web page
#   scripts/setup.sh --demo   what `luz` alone needs (scripts/demo.sh)
set -euo pipefail
packages=(cmake ninja-build g++ pkg-config nlohmann-json3-dev libcli11-dev libpng-dev
          zlib1g-dev libopenexr-dev libtbb-dev libtinyobjloader-dev)
[ "${1:-}" = "--demo" ] || packages+=(
          openexr  # exrheader: ExrCodec.ExrheaderAcceptsWhatLuzWrites
          libgtest-dev libgmock-dev libbenchmark-dev
          libembree-dev  # Embree 3: bench/bvh_vs_embree only
          libsdl2-dev libimgui-dev libgl-dev xvfb xauth  # the viewer (luz view) and its tests
          python3-dev python3-numpy pybind11-dev  # the Python module (import luz), then its tests:
          python3-pytest python3-nbclient python3-nbformat python3-ipykernel python3-matplotlib
          python3-tqdm python3-ipywidgets jupyter-nbconvert  # the notebook: examples/lecture.ipynb
          openmpi-bin libopenmpi-dev  # mpirun -np N luz render (luz-mpi) and its tests
          chromium  # luz figures (python3-matplotlib, python3-numpy above) and its page test
          emscripten node-acorn)  # luz web (luz.html, web/) and its tests in chromium
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "luz setup: installing ${missing[*]}" >&2
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi
