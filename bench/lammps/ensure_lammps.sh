# Sourced by the benchmarks that run LAMMPS beside fluidbed (bench/peer_lammps.sh, peer_lammps_3d.sh, memory_3d.sh).
# ensure_lammps: the peer is a Debian package like the rest of the tool chain; install it when `lmp` is missing,
# and stop the script (exit 2) when it still is.
ensure_lammps() {
  if ! command -v lmp >/dev/null; then
    local sudo=""
    [ "$(id -u)" = 0 ] || sudo=sudo
    echo "installing the Debian package lammps" >&2
    $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends lammps >&2 || true
  fi
  command -v lmp >/dev/null || { echo "LAMMPS (lmp, Debian package lammps) is not installed and could not be installed" >&2; exit 2; }
}
