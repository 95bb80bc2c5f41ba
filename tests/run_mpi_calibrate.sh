#!/bin/sh
# A calibration under `mpirun -np 2` takes the same path to the same parameters as on one machine,
# with both ranks running evaluations' runs. Usage: run_mpi_calibrate.sh <vorodec> <file> <scratch>
set -eu
vorodec=$1 calibration=$2 scratch=$3
rm -rf "$scratch"
# As in run_mpi_batch.sh: root in a container, shared memory only, no leak reports from Open MPI.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_rmaps_base_oversubscribe=1 ASAN_OPTIONS=detect_leaks=0
"$vorodec" calibrate "$calibration" --out "$scratch/one" > "$scratch.one.log" 2>&1 ||
  { cat "$scratch.one.log"; exit 1; }
mpirun -np 2 --oversubscribe "$vorodec" calibrate "$calibration" --out "$scratch/mpi" \
  > "$scratch.mpi.log" 2>&1 || { cat "$scratch.mpi.log"; exit 1; }
grep -q "rank 1: case" "$scratch.mpi.log" || { echo "rank 1 ran no run"; cat "$scratch.mpi.log"; exit 1; }
# history.csv without the time columns (elapsed, longest run).
without_times() { cut -d, -f1-3,6- "$1"; }
without_times "$scratch/one/history.csv" > "$scratch.one.csv"
without_times "$scratch/mpi/history.csv" > "$scratch.mpi.csv"
diff "$scratch.one.csv" "$scratch.mpi.csv"
diff "$scratch/one/calibrated_e2e_small.toml" "$scratch/mpi/calibrated_e2e_small.toml" |
  grep -v "^[<>] # Calibrated by\|^---\|^1c1" && exit 1
echo "mpirun -np 2: the same $(($(wc -l < "$scratch.one.csv") - 1)) evaluations and calibrated model"
