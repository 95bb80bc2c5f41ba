#!/bin/sh
# The batch run by `mpirun -np 2` writes the same results.csv as on one machine (all but the wall
# time column). Usage: run_mpi_batch.sh <vorodec> <batch file> <scratch folder>
set -eu
vorodec=$1 batch=$2 scratch=$3
rm -rf "$scratch"
# Open MPI refuses root unless told; CI runs as root in a container.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Shared memory between ranks without ptrace-based single copy (blocked in containers); no
# network transports; Open MPI's own allocations are no leaks of ours (sanitizer builds).
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_rmaps_base_oversubscribe=1 ASAN_OPTIONS=detect_leaks=0
# Exit code 5: the batch ran, some case stopped early (batch_small's step_limit cases).
status=0
"$vorodec" batch "$batch" --no-vtk --out "$scratch/one" > "$scratch.one.log" 2>&1 || status=$?
[ "$status" -eq 0 ] || [ "$status" -eq 5 ] || { cat "$scratch.one.log"; exit 1; }
status=0
mpirun -np 2 --oversubscribe "$vorodec" batch "$batch" --no-vtk --out "$scratch/mpi" \
  > "$scratch.mpi.log" 2>&1 || status=$?
[ "$status" -eq 0 ] || [ "$status" -eq 5 ] || { cat "$scratch.mpi.log"; exit 1; }
grep -q "rank 1: case" "$scratch.mpi.log" || { echo "rank 1 ran no case"; cat "$scratch.mpi.log"; exit 1; }
without_wall_time() { sed 's/,[^,]*$//' "$1"; }
without_wall_time "$scratch/one/results.csv" > "$scratch.one.csv"
without_wall_time "$scratch/mpi/results.csv" > "$scratch.mpi.csv"
[ "$(wc -l < "$scratch.one.csv")" -gt 1 ] || { echo "empty results.csv"; exit 1; }
diff "$scratch.one.csv" "$scratch.mpi.csv"
echo "mpirun -np 2: results.csv identical ($(($(wc -l < "$scratch.one.csv") - 1)) cases)"
