#!/usr/bin/env bash
# Installs Kappa's build and test dependencies from Debian packages.
# Idempotent: asks dpkg which packages are missing and installs only those, so a
# second run does nothing and returns in well under a second.
set -euo pipefail

packages=(
  cmake g++ ninja-build pkg-config git python3
  libopenexr-dev libpng-dev libtinyobjloader-dev libtbb-dev
  libgtest-dev libcli11-dev nlohmann-json3-dev
  libembree-dev libbenchmark-dev
  # glTF: tinygltf's header (its implementation is compiled in renderer/scene/gltf/)
  libtinygltf-dev
  # textures, environment images and the PNG preview, behind a module loaded on first use
  libopenimageio-dev
  python3-numpy python3-openimageio python3-matplotlib
  locales
  # /usr/bin/time: the hostile corpus bounds the peak memory of its big-file cases
  time
  # clang and its runtime (libFuzzer, sanitizers) for tools/fuzz.sh
  clang libclang-rt-14-dev
  # kappa-mpi: one frame on many ranks (Open MPI 4.1; build/kappa does not link it)
  libopenmpi-dev openmpi-bin
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "setup: installing ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
