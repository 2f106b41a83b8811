#pragma once
// Comm over MPI processes (OpenMPI): reductions that give the same bits on any number of ranks, and the halo
// exchange of fields whose owned boxes are disjoint blocks of one domain (decomposition.hpp). Built when MPI is
// found (FLUIDBED_HAVE_MPI); a run without a launcher is one rank of it.
//
// The exchange fills a field's ghost entries that lie in another rank's box with that rank's values; the ghosts
// beyond the domain's sides are left to the boundary conditions, as on one rank. Periodic images across ranks are
// not exchanged by this version: periodic_halo.hpp fills them on one rank only.
#include <memory>
#include <span>

#include "parallel/comm.hpp"

namespace fluidbed {

class MpiComm final : public Comm {
 public:
  /// Initialises MPI (funnelled threads) unless the program already did, and finalises it at destruction if it
  /// initialised it. The communicator is a duplicate of MPI_COMM_WORLD.
  MpiComm();
  ~MpiComm() override;
  MpiComm(const MpiComm&) = delete;
  MpiComm& operator=(const MpiComm&) = delete;

  int rank() const override;
  int size() const override;
  /// The ranks' values summed exactly and rounded once, so independent of the ranks' order; a sum that must not
  /// depend on how its terms are split among ranks passes each rank's ExactSum instead.
  double sum(double local) const override;
  double max(double local) const override;
  double min(double local) const override;
  void sum(std::span<double> values) const override;
  void max(std::span<double> values) const override;
  void sum(std::span<std::int64_t> values) const override;
  double sum(const ExactSum& local) const override;
  void exchange_halo(Field<2>& f) const override;
  void exchange_halo(Field<3>& f) const override;
  void exchange_halo_among(Field<2>& f, std::span<const IndexBox<2>> boxes, HaloCells cells) const override;
  void exchange_halo_among(Field<3>& f, std::span<const IndexBox<3>> boxes, HaloCells cells) const override;
  std::vector<Bytes> allgather(const Bytes& local) const override;
  std::vector<Bytes> gather(const Bytes& local, int root) const override;
  void broadcast(Bytes& data, int root) const override;
  std::vector<Bytes> exchange(const std::vector<Bytes>& send) const override;
  std::vector<Bytes> exchange_among(std::span<const int> ranks, const std::vector<Bytes>& send) const override;
  void exchange_with(std::span<const int> ranks, const std::vector<std::vector<double>>& send,
                     std::vector<std::vector<double>>& recv) const override;
  void barrier() const override;
  bool all_arrive_within(double timeout_s) const override;
  [[noreturn]] void abort(int code) const override;
  double seconds_communicating() const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fluidbed
