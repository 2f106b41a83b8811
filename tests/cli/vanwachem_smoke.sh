#!/usr/bin/env bash
# The van Wachem et al. (2001) case (cases/vanwachem2001/dem.toml) in CI size: the case file as it is, with a
# smaller bed (6,000 of its 17,562 spheres, placed on the lattice's lowest 60 mm, not settled) for 0.02 s on one
# core. probes.csv must carry the relative pressure at 45 mm and the bed height with finite values: the bed height
# inside the placed bed's 60 mm (87% of its 6,936 lattice sites filled: a mean solids fraction of 0.27, so the
# probe's threshold is set to 0.15 here; the case's 0.3 is half a settled bed's), the relative pressure positive
# (the gas carries part of the bed's weight above the tap).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

opts=(--threads 1 --end-time 0.02 --set particles.count=6000 --set particles.fill_height=0.06
      --set settle.enabled=false --set 'settle.cache=""' --set output.fields=false --set output.particles=false
      --set output.tracers=false --set output.checkpoint_interval=0 --set 'probe[3].solids_fraction=0.15')
run_ok "vanwachem: 0.02 s of a small bed" run "$ROOT/cases/vanwachem2001/dem.toml" --out "$WORK/vw" "${opts[@]}"
check "vanwachem: probes.csv columns and values" /usr/bin/python3 - "$WORK/vw/probes.csv" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 21, len(rows)  # every 1e-3 s from 0 to 0.02 s
for col in ("rel45_dp_Pa", "bed_bed_height_m", "tap45_p_Pa", "plane45_eps"):
    assert col in rows[0], (col, list(rows[0]))
    assert all(math.isfinite(float(r[col])) for r in rows), col
h = [float(r["bed_bed_height_m"]) for r in rows]
assert all(0.03 < v < 0.07 for v in h), (min(h), max(h))
assert all(float(r["rel45_dp_Pa"]) > 0.0 for r in rows[1:]), [r["rel45_dp_Pa"] for r in rows]
print(f"bed height {min(h):.4f}-{max(h):.4f} m, relative pressure at 45 mm {rows[-1]['rel45_dp_Pa']} Pa at 0.02 s")
PY
finish
