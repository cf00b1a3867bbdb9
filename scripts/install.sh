#!/usr/bin/env bash
# Installs everything the project needs on a fresh Debian (bookworm) machine, then builds.
# Idempotent: a second run skips what is already there and only rebuilds what changed.
#   apt packages -> .venv (torch, stable-baselines3, gymnasium, pytest, ray, training/) -> build/
set -euo pipefail
cd "$(dirname "$0")/.."

APT_PACKAGES=(build-essential cmake ninja-build pkg-config python3 python3-venv python3-pip
  libeigen3-dev libfcl-dev libassimp-dev libsuitesparse-dev libcgal-dev
  nlohmann-json3-dev catch2 libcli11-dev libpugixml-dev zlib1g-dev libpng-dev)

missing=()
for p in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "[install] apt packages: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# Python side in a project-local virtual environment. The stamp holds a hash of
# pyproject.toml, so the (large) torch install runs again only when it changes.
PYTHON=${PYTHON:-python3}
stamp=.venv/.installed-$(sha256sum training/pyproject.toml | cut -c1-16)
if [ ! -f "$stamp" ]; then
  echo "[install] python virtual environment (.venv)"
  [ -x .venv/bin/python ] || "$PYTHON" -m venv .venv
  .venv/bin/pip install -q --upgrade pip
  .venv/bin/pip install -q -e "training[dev,cluster]"
  rm -f .venv/.installed-* && touch "$stamp"
fi

echo "[install] build (build/, Release)"
[ -f build/build.ninja ] || cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)"
