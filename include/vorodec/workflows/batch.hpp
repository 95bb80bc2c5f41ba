#pragma once
// `vorodec batch`: runs every case of a batch file, each as a `vorodec run` child process in its
// own folder, as many at a time as there are cores; under mpirun/srun the cases are dealt
// round-robin to the MPI ranks. Rank 0 (or the one process) writes results.csv, one row per case.
#include <filesystem>

namespace vorodec::workflows {

struct BatchOptions {
  std::filesystem::path batch_file;
  std::filesystem::path out;  // results folder; empty: the batch file's `output`
  int jobs = 0;               // cases at a time per process; 0: all cores (1 per MPI rank)
  long max_steps = 0;         // > 0: passed to every case as --max-steps
  bool write_vtk = true;
  std::filesystem::path executable = "/proc/self/exe";  // the `vorodec` that runs the cases
};

// Exit code: 0 every case exited 0; 5 some case did not (its row says how); 2 bad batch input.
int run_batch(const BatchOptions& options);

}  // namespace vorodec::workflows
