#include "parallel/mpi_comm.hpp"

#ifdef FLUIDBED_HAVE_MPI

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace fluidbed {

struct MpiComm::Impl {
  MPI_Comm comm = MPI_COMM_NULL;
  bool own_mpi = false;
  int rank = 0;
  int size = 1;
};

namespace {

void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw_simulation_error(std::string("MPI: ") + what + " failed");
}

// The entries of `region` outside `own`, in storage order (axis 0 fastest): what one rank sends another for the
// other's ghosts, enumerated alike on both sides.
template <int Dim, class F>
void for_each_outside(const IndexBox<Dim>& region, const IndexBox<Dim>& own, F&& f) {
  for_each(region, [&](const Index<Dim>& c) {
    if (!own.contains(c)) f(c);
  });
}

template <int Dim>
void exchange(MPI_Comm comm, int me, int ranks, Field<Dim>& f) {
  if (ranks == 1) return;
  // Every rank's box of this field (the same kind of field, the same ghost width, on every rank).
  std::array<int, 2 * Dim> mine{};
  for (int a = 0; a < Dim; ++a) {
    mine[static_cast<std::size_t>(a)] = f.box().lo[a];
    mine[static_cast<std::size_t>(Dim + a)] = f.box().hi[a];
  }
  std::vector<int> all(static_cast<std::size_t>(2 * Dim * ranks));
  check(MPI_Allgather(mine.data(), 2 * Dim, MPI_INT, all.data(), 2 * Dim, MPI_INT, comm), "allgather of boxes");
  auto box_of = [&](int q) {
    IndexBox<Dim> b;
    for (int a = 0; a < Dim; ++a) {
      b.lo[a] = all[static_cast<std::size_t>(2 * Dim * q + a)];
      b.hi[a] = all[static_cast<std::size_t>(2 * Dim * q + Dim + a)];
    }
    return b;
  };
  const int g = f.ghost();
  std::vector<std::vector<double>> in(static_cast<std::size_t>(ranks)), out(static_cast<std::size_t>(ranks));
  std::vector<MPI_Request> requests;
  for (int q = 0; q < ranks; ++q) {
    if (q == me) continue;
    const IndexBox<Dim> bq = box_of(q);
    std::size_t n_in = 0;
    for_each_outside<Dim>(intersect(f.allocated(), bq), f.box(), [&](const Index<Dim>&) { ++n_in; });
    std::vector<double>& send = out[static_cast<std::size_t>(q)];
    for_each_outside<Dim>(intersect(bq.grown(g), f.box()), bq, [&](const Index<Dim>& c) { send.push_back(f[c]); });
    if (n_in > 0) {
      in[static_cast<std::size_t>(q)].resize(n_in);
      requests.emplace_back();
      check(MPI_Irecv(in[static_cast<std::size_t>(q)].data(), static_cast<int>(n_in), MPI_DOUBLE, q, 0, comm,
                      &requests.back()),
            "receive of a halo");
    }
    if (!send.empty()) {
      requests.emplace_back();
      check(MPI_Isend(send.data(), static_cast<int>(send.size()), MPI_DOUBLE, q, 0, comm, &requests.back()),
            "send of a halo");
    }
  }
  check(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE), "halo exchange");
  for (int q = 0; q < ranks; ++q) {
    if (q == me || in[static_cast<std::size_t>(q)].empty()) continue;
    std::size_t k = 0;
    const std::vector<double>& got = in[static_cast<std::size_t>(q)];
    for_each_outside<Dim>(intersect(f.allocated(), box_of(q)), f.box(), [&](const Index<Dim>& c) { f[c] = got[k++]; });
  }
}

}  // namespace

MpiComm::MpiComm() : impl_(std::make_unique<Impl>()) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "initialisation");
    impl_->own_mpi = true;
  }
  check(MPI_Comm_dup(MPI_COMM_WORLD, &impl_->comm), "duplicate of the world communicator");
  MPI_Comm_rank(impl_->comm, &impl_->rank);
  MPI_Comm_size(impl_->comm, &impl_->size);
}

MpiComm::~MpiComm() {
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (finalised) return;
  MPI_Comm_free(&impl_->comm);
  if (impl_->own_mpi) MPI_Finalize();
}

int MpiComm::rank() const { return impl_->rank; }
int MpiComm::size() const { return impl_->size; }

double MpiComm::sum(double local) const { return sum(ExactSum(local)); }

double MpiComm::sum(const ExactSum& local) const {
  // Integer sums of the limbs: associative, so the reduction tree of MPI cannot change the result.
  const std::array<std::int64_t, ExactSum::kWords> mine = local.words();
  std::array<std::int64_t, ExactSum::kWords> total{};
  check(MPI_Allreduce(mine.data(), total.data(), ExactSum::kWords, MPI_INT64_T, MPI_SUM, impl_->comm), "exact sum");
  return ExactSum::from_words(total).value();
}

double MpiComm::max(double local) const {
  double out = local;
  check(MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MAX, impl_->comm), "maximum");
  return out;
}

double MpiComm::min(double local) const {
  double out = local;
  check(MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MIN, impl_->comm), "minimum");
  return out;
}

void MpiComm::sum(std::span<double> values) const {
  const std::size_t n = values.size();
  std::vector<std::int64_t> mine(n * ExactSum::kWords), total(mine.size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto w = ExactSum(values[i]).words();
    std::copy(w.begin(), w.end(), mine.begin() + static_cast<std::ptrdiff_t>(i * ExactSum::kWords));
  }
  check(MPI_Allreduce(mine.data(), total.data(), static_cast<int>(mine.size()), MPI_INT64_T, MPI_SUM, impl_->comm),
        "element-wise exact sum");
  for (std::size_t i = 0; i < n; ++i) {
    values[i] = ExactSum::from_words(std::span<const std::int64_t, ExactSum::kWords>(
                                         total.data() + i * ExactSum::kWords, ExactSum::kWords))
                    .value();
  }
}

void MpiComm::exchange_halo(Field<2>& f) const { exchange<2>(impl_->comm, impl_->rank, impl_->size, f); }
void MpiComm::exchange_halo(Field<3>& f) const { exchange<3>(impl_->comm, impl_->rank, impl_->size, f); }

}  // namespace fluidbed

#endif  // FLUIDBED_HAVE_MPI
