#!/usr/bin/env bash
# Install the Debian packages jackpy needs (OpenGL/EGL via Mesa, Xvfb for window tests), idempotently.
set -euo pipefail
PKGS=(xvfb xauth libegl1 libgl1 libegl-mesa0 libgl1-mesa-dri libglx-mesa0 libgles2 libxrandr2 libxinerama1 libxcursor1 libxi6 libxkbcommon0 xdotool)
missing=()
for p in "${PKGS[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "installing system packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
