#pragma once
// What the solvers ask of the processes they run on: global reductions and the exchange of ghost layers between
// sub-domains. The serial implementation owns the whole domain, so a halo exchange has no neighbour to talk to
// (the physical boundary conditions fill every ghost cell) and a reduction is the value itself; the MPI
// implementation (mpi_comm.hpp) replaces it without touching the solvers, which already call it at the points where
// ranks meet. A sum that must not depend on the number of ranks is accumulated exactly (ExactSum) on each rank and
// reduced exactly: sum(const ExactSum&).
#include <span>

#include "core/field.hpp"
#include "parallel/exact_sum.hpp"

namespace fluidbed {

class Comm {
 public:
  virtual ~Comm() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// Sum, maximum and minimum over all ranks (the same answer on every rank, in a fixed order of ranks).
  virtual double sum(double local) const = 0;
  virtual double max(double local) const = 0;
  virtual double min(double local) const = 0;
  /// Element-wise sum over ranks, in place.
  virtual void sum(std::span<double> values) const = 0;
  /// The exact sum over ranks of every rank's exact partial sum, rounded once: the same bits for any number of
  /// ranks and any split of the terms among them.
  virtual double sum(const ExactSum& local) const = 0;
  /// Fill the ghost cells of f that lie inside the domain from the ranks that own them.
  virtual void exchange_halo(Field<2>& f) const = 0;
  virtual void exchange_halo(Field<3>& f) const = 0;
};

/// One process: no neighbour, a reduction is the value itself (not final: a test may count the exchanges).
class SerialComm : public Comm {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  double sum(double local) const override { return local; }
  double max(double local) const override { return local; }
  double min(double local) const override { return local; }
  void sum(std::span<double>) const override {}
  double sum(const ExactSum& local) const override { return local.value(); }
  void exchange_halo(Field<2>&) const override {}
  void exchange_halo(Field<3>&) const override {}
};

/// The communicator of a run on one process.
inline const Comm& serial_comm() {
  static const SerialComm comm;
  return comm;
}

}  // namespace fluidbed
