#!/usr/bin/env bash
# The determinism contract across ranks (issue 29, docs/parallel.md): a case run with `mpirun -n N` for N = 2, 3, 4
# gives the same bytes as the same case on one process, in every output a run writes (monitor.csv without wall_s,
# bubble*.csv, particle CSVs and .vtu, field .vti, tracers, the .pvd series); with two threads per rank too; a
# checkpoint written on 3 ranks continues on 2 and on 1 to the uninterrupted run's bits. Cases: the paper's 2D
# CFD-DEM bed, a 3D bed with a disc jet (settled in vacuum by the run on its ranks), a periodic CFD-DEM box, a
# periodic DEM bed with an outflow side and a feed, a Hertz-Mindlin mixture with rolling springs, and a bed whose
# blocks are dealt again as it moves (rebalancing). CI runs as root on 2 cores, hence Open MPI's root permission
# and oversubscription.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# Open MPI's shared-memory transport wants room in /dev/shm; the vader single-copy mechanism is not needed.
export OMPI_MCA_btl_vader_single_copy_mechanism=none
check "mpiexec is installed (make deps)" command -v mpiexec

mpi_ok() {  # mpi_ok NAME RANKS fluidbed-run-arguments...: a run on RANKS ranks that must exit 0
  local name=$1 n=$2
  shift 2
  expect 0 "" "$name" mpiexec -n "$n" --oversubscribe "$FLUIDBED" run "$@" --quiet
}

# ranks_agree NAME CASE EXTRA...: the case on one process, then on 2, 3 and 4 ranks, all the same bytes.
ranks_agree() {
  local name=$1 case_file=$2
  shift 2
  run_ok "$name: one process" run "$case_file" --out "$WORK/$name-1" --threads 1 "$@"
  local n
  for n in 2 3 4; do
    mpi_ok "$name: $n ranks" "$n" "$case_file" --out "$WORK/$name-$n" --threads 1 "$@"
    same_results "$name: $n ranks vs one process" "$WORK/$name-1" "$WORK/$name-$n"
  done
}

# The paper's bed (22,000 particles, the jet) to 0.05 s from one settled bed: settled once, by the first run.
ranks_agree paper "$ROOT/cases/gera1998/dem.toml" --end-time 0.05 --set settle.cache="\"$WORK/paper-bed.csv\"" \
  --set output.interval=0.025 --set output.particles_csv=true --set output.checkpoint_interval=0.0
check "paper: the decomposition is logged" grep -q "decomposition: .* blocks" "$WORK/paper-4/log.txt"

# 3D: 600 spheres settled in vacuum by each run on its own ranks, then fluidised with a disc jet (the regression
# oracle's 3D bed), with particle CSVs.
# With probes of the particles' tops (gathered from every rank at each row) beside a field probe, at the frames'
# times: a probe row must equal the percentile of the frame's particles (numpy's default, Hyndman-Fan 7).
probes3d=(--set 'probe=[{kind="particle_top",name="top",percentile=90},{kind="particle_top",name="max",percentile=100},{kind="bed_height",name="bed"}]'
          --set probes.interval=0.005)
ranks_agree bed3d "$ROOT/tests/oracle/dem3d.toml" --set output.particles_csv=true "${probes3d[@]}"
check "bed3d: the settled beds are the same bytes" cmp "$WORK/bed3d-1/settled.csv" "$WORK/bed3d-3/settled.csv"
check "bed3d: particle_top rows are the frames' percentiles" /usr/bin/python3 - "$WORK/bed3d-1" <<'PY'
import csv, re, sys
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy
run = sys.argv[1]
rows = {round(float(r["time_s"]), 9): r for r in csv.DictReader(open(run + "/probes.csv"))}
frames = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', open(run + "/particles.pvd").read())
assert len(frames) >= 5, frames
for t, f in frames:
    rd = vtk.vtkXMLUnstructuredGridReader()
    rd.SetFileName(run + "/" + f)
    rd.Update()
    o = rd.GetOutput()
    top = vtk_to_numpy(o.GetPoints().GetData())[:, 1] + 0.5 * vtk_to_numpy(o.GetPointData().GetArray("diameter"))
    r = rows[round(float(t), 9)]
    for col, p in (("top_top_m", 90), ("max_top_m", 100)):
        assert abs(float(r[col]) - np.percentile(top, p)) <= 1e-15, (t, col, r[col], np.percentile(top, p))
print(f"{len(frames)} frames: particle_top = numpy's percentile of the tops")
PY

# Two threads per rank (hybrid MPI x OpenMP).
mpi_ok "bed3d: 2 ranks x 2 threads" 2 "$ROOT/tests/oracle/dem3d.toml" --out "$WORK/bed3d-hybrid" --threads 2 \
  --set output.particles_csv=true "${probes3d[@]}"
same_results "bed3d: 2 ranks x 2 threads vs one process" "$WORK/bed3d-1" "$WORK/bed3d-hybrid"

# A CFD-DEM box periodic in x, gravity tilted so that particles and gas cross the periodic side (and the ranks).
cat >"$WORK/pgas.toml" <<'TOML'
case.name = "pgas"
case.end_time = 0.04
case.seed = 5
domain.width = 0.08
domain.height = 0.1
domain.gravity = [2.0, -9.81]
domain.periodic = ["x"]
particles.count = 150
particles.fill_height = 0.04
particles.layers = 2
settle.enabled = false
grid.cell_width = 0.01
inlet.velocity = 2.5
inlet.jet = []
output.interval = 0.02
output.particles_csv = true
output.monitor_interval = 0.005
output.checkpoint_interval = 0.0
output.tracers = false
TOML
ranks_agree periodic "$WORK/pgas.toml"

# DEM alone, periodic in x, an outflow bottom and a feed near the top: particles cross the periodic side, leave
# and arrive with new ids, on every rank count alike.
cat >"$WORK/feed.toml" <<'TOML'
case.name = "feed"
case.end_time = 0.15
case.seed = 3
domain.width = 0.08
domain.height = 0.15
domain.gravity = [3.0, -9.81]
domain.periodic = ["x"]
domain.particle_outflow = ["bottom"]
domain.particle_top = "wall"
particles.count = 150
particles.fill_height = 0.05
particles.layers = 2
settle.enabled = false
gas.enabled = false
grid.cell_width = 0.01
insertion.rate = 500.0
insertion.region_min = [0.0, 0.11]
insertion.region_max = [0.08, 0.14]
insertion.velocity = [0.0, -0.5]
output.interval = 0.05
output.particles_csv = true
output.monitor_interval = 0.005
output.checkpoint_interval = 0.0
TOML
ranks_agree feed "$WORK/feed.toml"
check "feed: particles left and arrived" awk -F, 'NR == 1 { for (k = 1; k <= NF; ++k) { if ($k == "particles_lost") l = k;
  if ($k == "particles_inserted") i = k } } END { exit !($l > 0 && $i > 0) }' "$WORK/feed-4/monitor.csv"

# A Hertz-Mindlin mixture with elastic-plastic rolling springs (pair and wall springs travel with the particles).
write_cfd_case "$WORK/mix.toml" mix \
  'species = [{diameter = 0.004, youngs_modulus = 1e7}, {diameter = 0.003, density = 1500.0, youngs_modulus = 1e7}]' \
  'contact.normal = "hertz"' 'contact.damping = "tsuji"' 'contact.tangential = "mindlin"' 'contact.rolling = "epsd"' \
  'contact.rolling_friction = 0.1' 'contact.wall_youngs_modulus = 1e7'
ranks_agree mix "$WORK/mix.toml" --end-time 0.03 --set dem.time_step=5e-5

# Rebalancing: a DEM bed tipped sideways by tilted gravity, blocks dealt again whenever the busiest rank carries
# 2% more than the mean; the results do not move.
cat >"$WORK/tilt.toml" <<'TOML'
case.name = "tilt"
case.end_time = 0.15
case.seed = 9
domain.width = 0.1
domain.height = 0.1
domain.gravity = [-6.0, -8.0]
particles.count = 250
particles.fill_height = 0.06
settle.enabled = false
gas.enabled = false
grid.cell_width = 0.01
parallel.rebalance_threshold = 1.02
output.interval = 0.05
output.particles_csv = true
output.monitor_interval = 0.005
output.checkpoint_interval = 0.0
TOML
ranks_agree rebalance "$WORK/tilt.toml"
check "rebalance: the blocks were dealt again on 4 ranks" \
  bash -c "grep -Eq 'blocks dealt again [1-9][0-9]* times' '$WORK/rebalance-4/log.txt'"

# Restart across rank counts: a checkpoint written on 3 ranks at 0.025 s continues on 2 and on 1 rank to the
# bits of the uninterrupted one-process run (bed3d-1, which ran with the same case and no checkpoint between),
# its probes.csv included.
mpi_ok "restart: 3 ranks to 0.025 s" 3 "$ROOT/tests/oracle/dem3d.toml" --out "$WORK/split" --end-time 0.025 \
  --set output.particles_csv=true "${probes3d[@]}"
cp -r "$WORK/split" "$WORK/split-2"
mpi_ok "restart: continued on 2 ranks" 2 "$ROOT/tests/oracle/dem3d.toml" --out "$WORK/split-2" \
  --set output.particles_csv=true "${probes3d[@]}" --restart latest
same_results "restart: 3 ranks then 2 vs one process" "$WORK/bed3d-1" "$WORK/split-2"
cp -r "$WORK/split" "$WORK/split-1"
run_ok "restart: continued on one process" run "$ROOT/tests/oracle/dem3d.toml" --out "$WORK/split-1" \
  --set output.particles_csv=true "${probes3d[@]}" --restart latest
same_results "restart: 3 ranks then 1 vs one process" "$WORK/bed3d-1" "$WORK/split-1"
finish
