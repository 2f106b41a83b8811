#!/usr/bin/env bash
# The two-fluid model across ranks (issue 30, item 4; docs/parallel.md): a case gives the same bytes on 1, 2, 3 and 4
# ranks in every output a run writes (monitor.csv without wall_s, bubble*.csv, field .vti frames, tracers, the .pvd
# series): the paper's TFM case to 0.2 s, the 3D column to 0.05 s, a 3D bed periodic in x and z; the other two
# rheologies with other limiters, drag laws and a pulsed inlet on 3 ranks; 2 ranks x 2 threads; probes after every
# step and time averages on 2 ranks; a checkpoint written
# on 3 ranks continues on 2 and on 1 to the uninterrupted run's bits. The runs take gas.pressure_solver =
# "cg-multigrid", the backend whose answer does not depend on the ranks. CI runs as root on 2 cores, hence Open MPI's
# root permission and oversubscription.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
check "mpiexec is installed (make deps)" command -v mpiexec
mg=(--set gas.pressure_solver='"cg-multigrid"')

mpi_ok() {  # mpi_ok NAME RANKS fluidbed-run-arguments...
  local name=$1 n=$2
  shift 2
  expect 0 "" "$name" mpiexec -n "$n" --oversubscribe "$FLUIDBED" run "$@" --quiet
}

ranks_agree() {  # ranks_agree NAME CASE EXTRA...: one process, then 2, 3 and 4 ranks, all the same bytes
  local name=$1 case_file=$2
  shift 2
  run_ok "$name: one process" run "$case_file" --out "$WORK/$name-1" --threads 1 "${mg[@]}" "$@"
  local n
  for n in 2 3 4; do
    mpi_ok "$name: $n ranks" "$n" "$case_file" --out "$WORK/$name-$n" --threads 1 "${mg[@]}" "$@"
    same_results "$name: $n ranks vs one process" "$WORK/$name-1" "$WORK/$name-$n"
  done
}

ranks_agree paper "$ROOT/cases/gera1998/tfm.toml" --end-time 0.2 --set output.checkpoint_interval=0.0
check "paper: the jet bubble was tracked" test "$(wc -l < "$WORK/paper-1/bubble.csv")" -gt 5
ranks_agree column "$ROOT/cases/tfm3d/column.toml" --end-time 0.05 --set output.interval=0.025 \
  --set output.checkpoint_interval=0.0

# Periodic in x and z, the jet in the corner at the periodic planes.
ranks_agree periodic "$ROOT/tests/cli/periodic_tfm.toml" --end-time 0.03

# The other rheologies, limiters, drag laws and an inlet schedule, and two threads a rank (hybrid MPI x OpenMP):
# one process against 3 ranks, and against 2 ranks x 2 threads.
variant() {  # variant NAME CASE EXTRA...
  local name=$1 case_file=$2
  shift 2
  run_ok "$name: one process" run "$case_file" --out "$WORK/$name-1" --threads 1 "${mg[@]}" "$@"
  mpi_ok "$name: 3 ranks" 3 "$case_file" --out "$WORK/$name-3" --threads 1 "${mg[@]}" "$@"
  same_results "$name: 3 ranks vs one process" "$WORK/$name-1" "$WORK/$name-3"
}
variant viscous "$ROOT/cases/gera1998/tfm-constant-viscosity.toml" --end-time 0.1 --set tfm.limiter='"van_leer"' \
  --set coupling.drag_law='"gidaspow"' --set output.checkpoint_interval=0.0
variant inviscid "$ROOT/cases/gera1998/tfm-inviscid.toml" --end-time 0.1 --set tfm.limiter='"minmod"' \
  --set coupling.drag_law='"di-felice"' --set inlet.schedule='"sine"' --set inlet.amplitude=0.3 \
  --set inlet.frequency=10 --set output.checkpoint_interval=0.0
variant bingham "$ROOT/cases/gera1998/tfm-bingham.toml" --end-time 0.1 --set tfm.limiter='"upwind"' \
  --set coupling.drag_law='"beetstra"' --set output.checkpoint_interval=0.0
expect 0 "" "paper: 2 ranks x 2 threads" env OMP_NUM_THREADS=2 mpiexec -n 2 --oversubscribe "$FLUIDBED" run \
  "$ROOT/cases/gera1998/tfm.toml" --out "$WORK/paper-2x2" --threads 2 --end-time 0.2 "${mg[@]}" \
  --set output.checkpoint_interval=0.0 --quiet
same_results "paper: 2 ranks x 2 threads vs one process" "$WORK/paper-1" "$WORK/paper-2x2"

# Probes after every step and time averages (rank 0's observers, on the fields gathered from the blocks).
cat "$ROOT/cases/gera1998/tfm.toml" "$ROOT/tests/cli/paper_probes.toml" > "$WORK/obs.toml"
cat >> "$WORK/obs.toml" <<'TOML'

[averages]
t_start = 0.02
t_end = 0.08
interval = 0.005
TOML
run_ok "observers: one process" run "$WORK/obs.toml" --out "$WORK/obs-1" --threads 1 --end-time 0.1 "${mg[@]}" \
  --set output.checkpoint_interval=0.0
mpi_ok "observers: 2 ranks" 2 "$WORK/obs.toml" --out "$WORK/obs-2" --threads 1 --end-time 0.1 "${mg[@]}" \
  --set output.checkpoint_interval=0.0
for f in probes.csv averages.csv averages.vti; do
  check "observers: $f exists" test -s "$WORK/obs-1/$f"
  check "observers: $f identical on 2 ranks" cmp "$WORK/obs-1/$f" "$WORK/obs-2/$f"
done

# Restart across rank counts: 3 ranks to 0.1 s, then 2 ranks and 1 rank from its checkpoint to 0.2 s.
mpi_ok "restart: 3 ranks to 0.1 s" 3 "$ROOT/cases/gera1998/tfm.toml" --out "$WORK/split" --end-time 0.1 --threads 1 \
  "${mg[@]}" --set output.checkpoint_interval=0.0
cp -r "$WORK/split" "$WORK/split1"
mpi_ok "restart: continued on 2 ranks to 0.2 s" 2 "$ROOT/cases/gera1998/tfm.toml" --out "$WORK/split" --end-time 0.2 \
  --threads 1 "${mg[@]}" --set output.checkpoint_interval=0.0 --restart "$WORK/split/checkpoints/final.h5"
same_results "3 ranks then 2" "$WORK/paper-1" "$WORK/split"
run_ok "restart: continued on 1 process to 0.2 s" run "$ROOT/cases/gera1998/tfm.toml" --out "$WORK/split1" \
  --end-time 0.2 --threads 1 "${mg[@]}" --set output.checkpoint_interval=0.0 --restart "$WORK/split1/checkpoints/final.h5"
same_results "3 ranks then 1" "$WORK/paper-1" "$WORK/split1"
finish
