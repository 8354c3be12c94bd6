#!/usr/bin/env bash
# Installs everything the project builds and tests with, from Debian's packages.
# Both README commands and .ci/run call this; it is safe to run again.
set -euo pipefail

packages=(
    build-essential cmake pkg-config
    libeigen3-dev libccd-dev
    googletest libgtest-dev libgmock-dev libbenchmark-dev
    libcli11-dev nlohmann-json3-dev
    libcairo2-dev libfontconfig-dev
    libreadline-dev
    libglfw3-dev libimgui-dev libgl-dev
    xvfb xauth libgl1-mesa-dri
)

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done

if ((${#missing[@]})); then
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}"
fi
