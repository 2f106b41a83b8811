// The parallel layer's headers compile on their own (the MPI work fills this folder: ranks, halos, reductions,
// particle exchange), and the parts of Comm that every implementation shares.
#include "parallel/comm.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/launcher.hpp"
#include "parallel/mpi_comm.hpp"
#include "parallel/periodic_halo.hpp"

#include <limits>
#include <stdexcept>

namespace fluidbed {

const std::byte* Unpacker::take(std::size_t n) {
  if (n > b_.size() - at_) throw std::runtime_error("Unpacker: a message ended early (internal error)");
  const std::byte* p = b_.data() + at_;
  at_ += n;
  return p;
}

std::optional<std::string> Comm::first_failure(const std::optional<std::string>& local, double key) const {
  // Whether any rank failed; then the smallest key of the failing ranks and the lowest failing rank with it, whose
  // message goes to all.
  if (max(local ? 1.0 : 0.0) == 0.0) return std::nullopt;
  constexpr double kNone = std::numeric_limits<double>::infinity();
  const double best = -max(local ? -key : -kNone);
  const bool mine = local && key == best;
  const int who = static_cast<int>(-max(mine ? -static_cast<double>(rank()) : -static_cast<double>(size())));
  Bytes msg;
  if (rank() == who) {
    const std::string& s = *local;
    msg.assign(reinterpret_cast<const std::byte*>(s.data()), reinterpret_cast<const std::byte*>(s.data()) + s.size());
  }
  broadcast(msg, who);
  return std::string(reinterpret_cast<const char*>(msg.data()), msg.size());
}

Bytes Comm::allgather_concat(const Bytes& local) const {
  Bytes out;
  for (const Bytes& b : allgather(local)) out.insert(out.end(), b.begin(), b.end());
  return out;
}

}  // namespace fluidbed
