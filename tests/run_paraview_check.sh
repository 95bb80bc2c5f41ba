#!/usr/bin/env bash
# Opens a .pvd series in ParaView's pvbatch under Xvfb (tests/paraview_check.py): every time step is
# loaded, the last one is coloured by a cell array and saved as a PNG.
#
#   tests/run_paraview_check.sh results/run/vtk/blocks.pvd [out.png] [cell_array]
#   tests/run_paraview_check.sh results/run/vtk/damage.pvd [out.png] damage_density   (.vti series)
#
# Debian's python3-paraview conflicts with python3-vtk9 (needed by libvtk9-dev), so it is not
# installed: its .deb is fetched with `apt-get download` (matching the installed paraview version)
# and unpacked with `dpkg -x` into a cache dir, then put on PYTHONPATH for pvbatch.
# Cache: $VORODEC_PARAVIEW_CACHE, else ${XDG_CACHE_HOME:-$HOME/.cache}/vorodec/paraview.
#
# Exit codes: 0 pass, 1 failure, 2 usage, 77 ParaView not available (ctest SKIP_RETURN_CODE 77).
set -uo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

skip() {
  echo "ParaView not available: $*" >&2
  exit 77
}

if [ $# -lt 1 ] || [ $# -gt 3 ]; then
  echo "usage: $0 file.pvd [out.png] [cell_array]" >&2
  exit 2
fi
pvd="$1"
if [ ! -f "$pvd" ]; then
  echo "run_paraview_check: no such file: $pvd" >&2
  exit 1
fi
png="${2:-${pvd%.pvd}_last.png}"
array=("${@:3}")

command -v Xvfb >/dev/null 2>&1 || skip "Xvfb not found (Debian package xvfb; see scripts/install-deps.sh)"
command -v pvbatch >/dev/null 2>&1 || skip "pvbatch not found (Debian package paraview; see scripts/install-deps.sh)"

pv_version="$(dpkg-query -W -f='${Version}' paraview 2>/dev/null)" ||
  skip "pvbatch is not from Debian's paraview package, cannot pick a matching python3-paraview"

# python3-paraview: use it if installed, else a private unpack of the matching .deb.
pythonpath=""
if ! dpkg-query -W -f='${Status}' python3-paraview 2>/dev/null | grep -q "install ok installed"; then
  cache="${VORODEC_PARAVIEW_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/vorodec/paraview}"
  root="$cache/python3-paraview_${pv_version}"
  pythonpath="$root/usr/lib/python3/dist-packages"
  if [ ! -f "$root/.complete" ]; then
    command -v apt-get >/dev/null 2>&1 || skip "apt-get not found, cannot fetch python3-paraview"
    mkdir -p "$cache" || skip "cannot create cache dir $cache"
    (
      flock 9 || exit 1
      [ -f "$root/.complete" ] && exit 0
      dl="$(mktemp -d "$cache/download.XXXXXX")" || exit 1
      trap 'rm -rf "$dl"' EXIT
      cd "$dl" || exit 1
      echo "run_paraview_check: fetching python3-paraview=$pv_version into $cache" >&2
      if ! apt-get download -q "python3-paraview=$pv_version" >apt.log 2>&1; then
        # A machine whose package lists were cleaned needs them once; only root may refresh them.
        if [ "$(id -u)" -eq 0 ]; then
          apt-get update -qq >>apt.log 2>&1 && apt-get download -q "python3-paraview=$pv_version" >>apt.log 2>&1
        fi
      fi
      debs=(python3-paraview_*.deb)
      deb="${debs[0]}"
      if [ ! -f "$deb" ]; then
        sed 's/^/  apt: /' apt.log >&2
        exit 1
      fi
      rm -rf "$root" && mkdir -p "$root" && dpkg -x "$deb" "$root" &&
        [ -f "$pythonpath/paraview/simple.py" ] && touch "$root/.complete"
    ) 9>"$cache/.lock"
    [ -f "$root/.complete" ] ||
      skip "cannot obtain python3-paraview=$pv_version (apt-get download failed: no network or no package lists?)"
  fi
fi

mkdir -p "$(dirname "$png")"
rm -f "$png"
log="$(mktemp)"
start=$(date +%s.%N)
# Our own Xvfb with -displayfd: the server binds the first free display itself, so it cannot race
# another server for a number (xvfb-run -a picks a number from lock files and does not wait for its
# server to exit, which under load gave "bad X server connection"). It is stopped and reaped before
# the script ends.
xvfb_pid=""
stop_xvfb() {
  if [ -n "$xvfb_pid" ]; then
    kill "$xvfb_pid" 2>/dev/null
    wait "$xvfb_pid" 2>/dev/null
    xvfb_pid=""
  fi
}
trap 'stop_xvfb; rm -f "$log" "$log.display" "$log.xvfb"' EXIT
for attempt in 1 2 3; do
  : >"$log.display"
  Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp 3>"$log.display" >"$log.xvfb" 2>&1 &
  xvfb_pid=$!
  display=""
  for _ in $(seq 1 100); do
    display="$(tr -dc '0-9' <"$log.display")"
    [ -n "$display" ] && break
    kill -0 "$xvfb_pid" 2>/dev/null || break
    sleep 0.1
  done
  if [ -z "$display" ]; then
    echo "run_paraview_check: Xvfb did not start (attempt $attempt):" >&2
    sed 's/^/  Xvfb: /' "$log.xvfb" >&2
    stop_xvfb
    rc=1
    continue
  fi
  PYTHONPATH="${pythonpath}${PYTHONPATH:+:$PYTHONPATH}" DISPLAY=":$display" \
    pvbatch "$here/paraview_check.py" "$pvd" "$png" "${array[@]}" >"$log" 2>&1
  rc=$?
  stop_xvfb
  grep -q "bad X server connection" "$log" || break
  echo "run_paraview_check: X server :$display not reachable (attempt $attempt), retrying" >&2
  sed 's/^/  Xvfb: /' "$log.xvfb" >&2
done
end=$(date +%s.%N)
cat "$log"
# pvbatch has been known to exit 0 after a Python error: also require the script's own OK line.
if [ $rc -ne 0 ] || ! grep -q "^paraview_check: OK" "$log" || [ ! -s "$png" ]; then
  echo "run_paraview_check: FAILED (pvbatch exit $rc)" >&2
  exit 1
fi
awk -v a="$start" -v b="$end" -v png="$png" 'BEGIN { printf "run_paraview_check: passed in %.1f s, image %s\n", b - a, png }'
