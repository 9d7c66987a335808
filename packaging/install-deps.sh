#!/usr/bin/env bash
# Installs every Debian 12 package HullInspect needs to build, test and run.
# Idempotent: does nothing when everything is already installed. Run as root
# (or with sudo).
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build ccache pkg-config git clang-format
  # CI's function budget measures functions with ctags (.ci/function-budget)
  universal-ctags
  # the fuzzed readers (tests/fuzz): clang with libFuzzer and the sanitizer runtimes
  clang libclang-rt-dev
  # core libraries
  libeigen3-dev libceres-dev libcgal-dev libopenmesh-dev libassimp-dev libopencv-dev
  libembree-dev libnanoflann-dev libpcl-dev libtbb-dev zlib1g-dev nlohmann-json3-dev
  # the step-iges plugin: STEP and IGES through OpenCASCADE
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev libocct-data-exchange-dev
  # GUI
  qtbase5-dev libqt5opengl5-dev libvtk9-dev libvtk9-qt-dev
  # tests: GoogleTest, a virtual X server for the GUI tests and the demo
  # without a display, Mesa's software OpenGL, fonts, numpy for the
  # independent contract checker (../shared/tools/check-bundle.py)
  libgtest-dev libgmock-dev xvfb xauth libgl1-mesa-dri fonts-dejavu-core python3-numpy
  # the report tests read the PDF back with an independent parser (pdfinfo),
  # and pdftoppm turns its pages into PNGs to look at
  poppler-utils
  # the Debian package: dpkg-shlibdeps (dpkg-dev), and the checks CI runs on
  # it (lintian, appstreamcli, desktop-file-validate)
  dpkg-dev lintian appstream desktop-file-utils
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
