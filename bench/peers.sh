#!/usr/bin/env bash
# vorodec beside the open DEM peers (YADE, ESyS-Particle, LIGGGHTS) in one run, on the peers'
# workload: 2D uniaxial compression of a 50 x 100 mm specimen at axial strain 1e-6 per step,
# 5,000 and 20,000 bodies, 1 and 2 threads. Prints one table with contact updates per second
# (cu/s) and vorodec's ratio to each peer.
# Usage: bench/peers.sh [build dir] [peers dir]   (peers dir: a copy of the peers' scripts; the
# peer codes come from Debian: apt-get install yade esys-particle liggghts)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../build}" && pwd)
peers=${2:-}
work=$(mktemp -d)
results="$work/results.jsonl"

# vorodec: the default marble material with jkn, jks scaled by the block size (same E), blocks of
# the peers' count, density scaling to 5e-7 s, so strain 1e-6 per step = top platen at
# 1e-7 m / 5e-7 s = 0.2 m/s. vorodec runs up to about its peak (0.2 % strain); the peers run
# further, into a failed specimen: rates, not run lengths, are compared.
for spec in "5000 2000 2" "20000 1000 4"; do
  set -- $spec
  blocks=$1 steps=$2 stiffer=$3
  model="$work/vorodec_${blocks}.toml"
  /usr/bin/python3 - "$here/../models/ucs_marble.toml" "$blocks" "$stiffer" > "$model" <<'PY'
import re, sys
text, blocks, k = open(sys.argv[1]).read(), sys.argv[2], float(sys.argv[3])
scale = lambda m: "%s = %.6g" % (m.group(1), float(m.group(2)) * k)
text = re.sub(r"^(jk[ns]) = ([0-9.e]+)", scale, text, flags=re.M)
text = re.sub(r"^block_count = .*", "block_count = " + blocks, text, flags=re.M)
text = re.sub(r"^min_edge_length = .*", "min_edge_length = %.6g" % (2.5e-4 / k), text, flags=re.M)
text = re.sub(r"^\[contact\]\n[^\n]*\n", "", text, flags=re.M)
text = re.sub(r"^platen_velocity = .*", "platen_velocity = 0.2", text, flags=re.M)
text = re.sub(r"^ramp_time = .*", "ramp_time = 0", text, flags=re.M)
print(text)
PY
  for threads in 1 2; do
    name="vorodec_${blocks}_t$threads"
    "$build/vorodec" run "$model" --threads "$threads" --max-steps "$steps" --no-vtk \
      --out "$work/$name" > "$work/$name.log" 2>&1 || echo "$name: exit code $?" >&2
    /usr/bin/python3 - "$name" "$work/$name/summary.json" "$threads" >> "$results" <<'PY'
import json, sys
s = json.load(open(sys.argv[2]))
t = int(sys.argv[3])
rate = s["initial_contacts"] * s["steps"] / s["wall_time_s"]
print(json.dumps({"name": sys.argv[1], "bodies": s["blocks"] - 2, "contacts": s["initial_contacts"],
                  "steps": s["steps"], "wall_s": s["wall_time_s"], "threads": t,
                  "cu_per_s": rate, "cu_per_s_per_core": rate / t}))
PY
  done
done

if [ -n "$peers" ] && [ -d "$peers" ]; then
  cp -r "$peers" "$work/peers"
  mkdir -p "$work/peers/logs"
  what=""
  command -v yade > /dev/null && what="$what yade"
  command -v esysparticle > /dev/null && what="$what esys"
  command -v liggghts > /dev/null && what="$what liggghts"
  if [ -n "$what" ]; then
    (cd "$work/peers" && RESULTS="$results" ./run_all.sh $what) 2> "$work/peers.log" || true
  else
    echo "peers: none of yade, esysparticle, liggghts is installed; vorodec only" >&2
  fi
fi

/usr/bin/python3 - "$results" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
def rate(r):  # contact updates per second, as each code reports it
    return r.get("cu_per_s") or r.get("contact_updates_per_s") or r.get("contact-updates/s")
def par(r):  # threads, MPI ranks or ESyS workers
    return r.get("threads") or r.get("mpi_ranks") or r.get("workers") or r.get("par") or 1
def bodies(r):  # vorodec's blocks or the peers' particles
    return r.get("bodies", r.get("particles", 0))
def size(r):
    return 5000 if bodies(r) < 10000 else 20000
# vorodec's 1-thread rate per core at each size, the numerator of every ratio
ours = {size(r): rate(r) for r in rows if r["name"].startswith("vorodec") and par(r) == 1}
print("| run | bodies | steps | wall s | cu/s | cu/s per core | vorodec 1 thread / this, per core |")
print("|---|---|---|---|---|---|---|")
for r in rows:
    cu, p = rate(r), par(r)
    per_core = cu / p if cu else None
    ratio = ours.get(size(r)) / per_core if per_core and size(r) in ours else None
    print("| %s | %s | %s | %s | %s | %s | %s |" % (r["name"], bodies(r),
          r.get("steps", "?"), r.get("wall_s", "?"), "%.3g" % cu if cu else "?",
          "%.3g" % per_core if per_core else "?", "%.2g" % ratio if ratio else "?"))
PY
echo "raw results: $results"
