#!/usr/bin/env bash
# The README's two Quick start commands:
#   packaging/quickstart.sh demo   install, build, and run the main job: the GUI on the
#                                  embedded demo survey, or without a display the headless
#                                  pipeline writing its report and remeshed model
#   packaging/quickstart.sh test   install, build, and pass the tests
# Builds into ./build (override with HI_BUILD_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-}"
case "$mode" in demo|test) ;; *) echo "usage: $0 demo|test" >&2; exit 2 ;; esac
shift || true

packaging/install-deps.sh
build="${HI_BUILD_DIR:-build}"
jobs="$(nproc)"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DHI_WERROR=ON
cmake --build "$build" -j "$jobs"

if [ "$mode" = test ]; then
  exec ctest --test-dir "$build" --output-on-failure -j "$jobs" "$@"
fi
out="${HI_DEMO_OUT:-demo-output}"
if [ -x "$build/bin/hullinspect" ] && { [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; }; then
  exec "$build/bin/hullinspect" --demo "$@"
fi
# No display: hullinspect's headless main job (the whole pipeline on the demo,
# then the report with figures drawn offscreen; no X server needed).
echo "quickstart: no display: running the headless main job on the demo survey into $out/"
exec "$build/bin/hullinspect" --demo --out "$out"
