#!/usr/bin/env bash
# Installs every Debian package pathlab needs. Idempotent: packages already
# present are skipped, and nothing is done when all are there.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libtbb-dev libopenexr-dev libpng-dev libtinyobjloader-dev
  libcli11-dev nlohmann-json3-dev libtomlplusplus-dev libsqlite3-dev libboost-dev
  libgtest-dev libbenchmark-dev
  # pbrt-v4 scenes: Loop subdivision through OpenSubdiv; assimp only for the PLY
  # benchmark that measures it beside pathlab's own reader (docs/pbrt-format.md).
  libassimp-dev libosd-dev zlib1g-dev
  # FFTW 3: the error spectrum's periodograms (`pathlab compare --error-spectrum`).
  libfftw3-dev
  # The wolf scene, when it must be fetched from Debian's 0ad-data package.
  libarchive-tools
  # The report: figures with matplotlib; its test drives Chromium from Node.
  python3-matplotlib python3-numpy chromium nodejs
  # Test data: the Cornell boxes Embree's tutorials and tinyobjloader ship,
  # which the scene tests read (they skip where these are missing).
  embree-tools python3-tinyobjloader
  # Public PLY models (ASCII, binary, quads, points only) for the PLY tests.
  assimp-testmodels
  # The Python module (docs/python.md): pybind11 and Python's headers to build
  # it, pytest for its tests, pandas for study tables as DataFrames.
  pybind11-dev python3-dev python3-pytest python3-pandas python3-setuptools
  # `pathlab view`, the browser lab: its HTTP server and the tests' client.
  libcpp-httplib-dev
  # Studies across the ranks of a cluster (docs/cluster.md): Open MPI, its
  # headers for pathlab and its mpirun for the tests.
  libopenmpi-dev openmpi-bin
  # Spectral mode (docs/spectral.md): the CIE 1931 2° colour-matching functions
  # and the CIE standard illuminants as colord ships them, converted at build time.
  colord-data
)
# npm ships inside some nodejs builds; Debian's own package only where it does not.
if ! command -v npm >/dev/null 2>&1; then PACKAGES+=(npm); fi
# Optional extras for `make bench` (Embree's tutorial path tracer comes with
# embree-tools, above).
if [[ "${PATHLAB_SETUP_EXTRAS:-}" == *bench* ]]; then PACKAGES+=(hyperfine); fi
# `make fuzz`: clang with libFuzzer and its sanitizer runtimes.
if [[ "${PATHLAB_SETUP_EXTRAS:-}" == *fuzz* ]]; then
  PACKAGES+=(clang-14 libclang-rt-14-dev libfuzzer-14-dev)
fi
# `make sanitize`: gcc's AddressSanitizer, UBSan and ThreadSanitizer runtimes.
if [[ "${PATHLAB_SETUP_EXTRAS:-}" == *sanitize* ]]; then PACKAGES+=(libasan8 libubsan1 libtsan2); fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "setup: installing ${missing[*]}" >&2
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
