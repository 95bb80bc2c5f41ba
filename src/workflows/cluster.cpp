#include "cluster.hpp"

#include <fmt/format.h>

#include <cstdlib>

#ifdef VORODEC_WITH_MPI
#include <mpi.h>
#endif

namespace vorodec::workflows {

namespace {

// Whether a launcher started this process as an MPI rank, and how many ranks it announced (0:
// not said): Open MPI's mpirun, or Slurm's srun through PMI-2 or PMIx.
bool launched(int& ranks) {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* v = std::getenv(name)) {
      ranks = std::atoi(v);
      return true;
    }
  ranks = 0;
  return std::getenv("PMIX_RANK") != nullptr;
}

}  // namespace

#ifdef VORODEC_WITH_MPI

Cluster::Cluster() {
  int ranks = 0;
  if (!launched(ranks)) return;
  MPI_Init(nullptr, nullptr);
  joined_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

Cluster::~Cluster() {
  if (joined_) MPI_Finalize();
}

std::vector<std::string> Cluster::gather(const std::string& mine) const {
  if (!joined_) return {mine};
  const int length = static_cast<int>(mine.size());
  std::vector<int> lengths(static_cast<std::size_t>(size_)), offsets(lengths.size());
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::string all;
  if (rank_ == 0) {
    for (std::size_t r = 1; r < lengths.size(); ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
    all.resize(static_cast<std::size_t>(offsets.back() + lengths.back()));
  }
  MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR,
              0, MPI_COMM_WORLD);
  std::vector<std::string> out;
  if (rank_ == 0)
    for (std::size_t r = 0; r < lengths.size(); ++r)
      out.push_back(
          all.substr(static_cast<std::size_t>(offsets[r]), static_cast<std::size_t>(lengths[r])));
  return out;
}

std::vector<std::string> Cluster::share(const std::string& mine) const {
  if (!joined_) return {mine};
  const int length = static_cast<int>(mine.size());
  std::vector<int> lengths(static_cast<std::size_t>(size_)), offsets(lengths.size());
  MPI_Allgather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (std::size_t r = 1; r < lengths.size(); ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
  std::string all(static_cast<std::size_t>(offsets.back() + lengths.back()), '\0');
  MPI_Allgatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(),
                 MPI_CHAR, MPI_COMM_WORLD);
  std::vector<std::string> out;
  for (std::size_t r = 0; r < lengths.size(); ++r)
    out.push_back(
        all.substr(static_cast<std::size_t>(offsets[r]), static_cast<std::size_t>(lengths[r])));
  return out;
}

void Cluster::abort(int code) const {
  if (joined_ && size_ > 1) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

#else

Cluster::Cluster() {
  int ranks = 0;
  unsupported_ = launched(ranks) && ranks > 1;
}

Cluster::~Cluster() = default;

std::vector<std::string> Cluster::gather(const std::string& mine) const {
  return {mine};
}

std::vector<std::string> Cluster::share(const std::string& mine) const {
  return {mine};
}

void Cluster::abort(int code) const {
  std::exit(code);
}

#endif

bool Cluster::refuse_without_mpi() const {
  if (unsupported_)
    fmt::print(stderr,
               "error: started as several MPI ranks, but this vorodec was built without MPI "
               "(cmake -DVORODEC_MPI=ON with libopenmpi-dev installed)\n");
  return unsupported_;
}

}  // namespace vorodec::workflows
