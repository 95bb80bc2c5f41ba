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

command -v xvfb-run >/dev/null 2>&1 || skip "xvfb-run not found (Debian package xvfb; see scripts/install-deps.sh)"
command -v xauth >/dev/null 2>&1 || skip "xauth not found (Debian package xauth; see scripts/install-deps.sh)"
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
trap 'rm -f "$log"' EXIT
start=$(date +%s.%N)
# xvfb-run -a can race another X server for a display number under load ("bad X server
# connection"); that is the machine, not the series: retry a few times.
for attempt in 1 2 3; do
  PYTHONPATH="${pythonpath}${PYTHONPATH:+:$PYTHONPATH}" \
    xvfb-run -a -s "-screen 0 1280x1024x24" \
    pvbatch "$here/paraview_check.py" "$pvd" "$png" "${array[@]}" >"$log" 2>&1
  rc=$?
  grep -q "bad X server connection" "$log" || break
  echo "run_paraview_check: X server not reachable (attempt $attempt), retrying" >&2
  sleep 2
done
end=$(date +%s.%N)
cat "$log"
# pvbatch has been known to exit 0 after a Python error: also require the script's own OK line.
if [ $rc -ne 0 ] || ! grep -q "^paraview_check: OK" "$log" || [ ! -s "$png" ]; then
  echo "run_paraview_check: FAILED (pvbatch exit $rc)" >&2
  exit 1
fi
awk -v a="$start" -v b="$end" -v png="$png" 'BEGIN { printf "run_paraview_check: passed in %.1f s, image %s\n", b - a, png }'
