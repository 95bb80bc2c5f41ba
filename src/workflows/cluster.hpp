#pragma once
// The processes sharing one batch: the MPI ranks when launched by mpirun or srun (and built with
// VORODEC_MPI), otherwise this process alone. The only place that knows about MPI.
#include <string>
#include <vector>

namespace vorodec::workflows {

class Cluster {
 public:
  Cluster();  // joins MPI when the environment says a launcher started us
  ~Cluster();
  Cluster(const Cluster&) = delete;
  Cluster& operator=(const Cluster&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // Launched by mpirun/srun with several ranks, but built without MPI (every rank would run
  // every case): says so on stderr, with how to build with MPI, and returns true.
  bool refuse_without_mpi() const;
  // Rank 0 receives every rank's text, in rank order; the other ranks receive nothing.
  std::vector<std::string> gather(const std::string& mine) const;
  // Every rank receives every rank's text, in rank order.
  std::vector<std::string> share(const std::string& mine) const;
  // Stops every rank (a rank that returns alone would leave the others waiting in gather).
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1;
  bool joined_ = false, unsupported_ = false;
};

}  // namespace vorodec::workflows
