#!/usr/bin/env bash
# Installs the Debian 12 packages PeriAdapt builds against (run as root).
set -euo pipefail
pkgs=(build-essential cmake pkg-config libyaml-cpp-dev libcli11-dev libfmt-dev nlohmann-json3-dev
      libmuparser-dev libcairo2-dev libpng-dev libeigen3-dev libgtest-dev libbenchmark-dev python3
      python3-meshio zlib1g-dev libcgal-dev libgmsh-dev libopenmpi-dev openmpi-bin
      libtrilinos-zoltan-dev)
missing=()
for p in "${pkgs[@]}"; do dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p"); done
if ((${#missing[@]})); then
  export DEBIAN_FRONTEND=noninteractive
  as_root=()
  if [[ $(id -u) -ne 0 ]]; then
    if command -v sudo > /dev/null; then
      as_root=(sudo -E)
    else
      echo "install-deps.sh: missing Debian packages (${missing[*]}); run as root or install sudo" >&2
      exit 1
    fi
  fi
  "${as_root[@]}" apt-get update -qq
  "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
