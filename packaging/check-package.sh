#!/usr/bin/env bash
# Builds the Debian package from a build folder, installs it on this machine
# with apt-get and checks it as a user would meet it:
#   packaging/check-package.sh [BUILD_DIR]        (default: build)
# - hullinspect-cli --version and plugins (both plugins loaded from /usr/lib)
# - the headless demo from /usr/bin/hullinspect with no display: the report
#   and the remeshed model written; a glTF export of it
# - the desktop entry (desktop-file-validate) and the AppStream metadata
#   (appstreamcli validate)
# - lintian's findings printed; exits non-zero on a lintian error.
# Run as root or with sudo (it installs the package). CI runs it (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
start=$(date +%s)
step() { echo "== check-package [$(( $(date +%s) - start ))s] $*"; }

step "cpack"
rm -f "$build"/hullinspect_*.deb
(cd "$build" && cpack -G DEB >/dev/null)
deb=$(ls "$build"/hullinspect_*_amd64.deb)
echo "$deb: $(du -h "$deb" | cut -f1)"
dpkg-deb --info "$deb" | sed -n '/Package:/,$p'

step "apt-get install ./$deb"
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "./$deb" >/dev/null
dpkg -s hullinspect | grep -E '^(Status|Version):'

step "installed programs"
test "$(command -v hullinspect-cli)" = /usr/bin/hullinspect-cli
hullinspect-cli --version
hullinspect --version
plugins=$(hullinspect-cli plugins)
echo "$plugins"
for p in step-iges gltf; do
  grep -q "^  $p .*/usr/lib/hullinspect/plugins/$p.so" <<<"$plugins" || { echo "plugin $p not loaded" >&2; exit 1; }
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
step "headless demo: /usr/bin/hullinspect --demo --out $out/demo (no display)"
env -u DISPLAY -u WAYLAND_DISPLAY /usr/bin/hullinspect --demo --out "$out/demo" >"$out/demo.log" 2>&1 ||
  { tail -20 "$out/demo.log"; exit 1; }
tail -3 "$out/demo.log"
for f in report.pdf report.html mapping/model.ply; do
  test -s "$out/demo/$f" || { echo "the headless demo wrote no $f" >&2; exit 1; }
done
hullinspect-cli export "$out/demo" --out "$out/hull.glb"

step "desktop entry and AppStream metadata"
desktop-file-validate /usr/share/applications/org.hullinspect.HullInspect.desktop
appstreamcli validate --no-net /usr/share/metainfo/org.hullinspect.HullInspect.metainfo.xml
test -s /usr/share/icons/hicolor/48x48/apps/hullinspect.png
grep -q "application/x-hullinspect-project" /usr/share/mime/globs2

step "lintian"
# --fail-on error: the findings are printed, an error fails the step.
lintian --fail-on error --display-info --tag-display-limit 0 "$deb" | tee "$out/lintian.txt"
echo "lintian: $(grep -c '^E:' "$out/lintian.txt" || true) errors, $(grep -c '^W:' "$out/lintian.txt" || true) warnings, $(grep -c '^I:' "$out/lintian.txt" || true) info"
step "done"
