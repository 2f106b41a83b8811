#!/usr/bin/env bash
# Every kind of bad input ends with exit code 2 and one line naming the file, line and key (issue 6).
source "$(dirname "$0")/lib.sh"

# A small valid DEM case the bad ones are derived from.
# Dotted keys only, so a test can replace or add any key with one line.
cat > "$WORK/ok.toml" <<'TOML'
case.name = "ok"
case.end_time = 0.002
particles.count = 50
settle.enabled = false
gas.enabled = false
output.interval = 0.001
output.checkpoint_interval = 0.0
TOML
bad() {  # bad NAME REGEX 'key = value'...: ok.toml with those keys replaced or added
  local name=$1 regex=$2
  shift 2
  cp "$WORK/ok.toml" "$WORK/$name.toml"
  local kv key
  for kv in "$@"; do
    key=${kv%% =*}
    if grep -q "^$key =" "$WORK/$name.toml"; then
      grep -v "^$key =" "$WORK/$name.toml" > "$WORK/$name.tmp"
      mv "$WORK/$name.tmp" "$WORK/$name.toml"
    fi
    printf '%s\n' "$kv" >> "$WORK/$name.toml"
  done
  expect 2 "$regex" "$name" "$FLUIDBED" check "$WORK/$name.toml"
}

expect 0 "OK" "valid case" "$FLUIDBED" check "$WORK/ok.toml"
expect 2 "nonexistent.toml: cannot read" "missing case file" "$FLUIDBED" check "$WORK/nonexistent.toml"
mkdir -p "$WORK/dir.toml"
expect 2 "dir.toml: cannot read" "unreadable case file (a folder)" "$FLUIDBED" check "$WORK/dir.toml"
printf '[case]\nname = "x"\nend_time = = 1\n' > "$WORK/syntax.toml"
expect 2 "syntax.toml:3:[0-9]+: TOML syntax error" "TOML syntax error" "$FLUIDBED" check "$WORK/syntax.toml"
printf '[case]\nend_time = 1.0\n' > "$WORK/noname.toml"
expect 2 "missing required value case.name" "missing required value" "$FLUIDBED" check "$WORK/noname.toml"
bad unknown_key "unknown key 'dem.tme_step'; did you mean 'dem.time_step'" "dem.tme_step = 1e-4"
bad wrong_type "wrong_type.toml:[0-9]+:[0-9]+: dem.time_step: expected a number" 'dem.time_step = "fast"'
bad zero_diameter "species\[0\].diameter: 0 is out of range: must be > 0" "species = [{diameter = 0.0}]"
bad negative_density "species\[0\].density: -2700 is out of range" "species = [{density = -2700.0}]"
bad zero_stiffness "contact.stiffness: 0 is out of range: must be > 0" "contact.stiffness = 0"
bad restitution_zero "contact.restitution: 0 is out of range: must be > 0, <= 1" "contact.restitution = 0.0"
bad restitution_above_one "contact.restitution: 1.2 is out of range" "contact.restitution = 1.2"
bad negative_friction "contact.friction: -0.1 is out of range: must be >= 0" "contact.friction = -0.1"
bad unstable_dt "dem.time_step: 0.001 s is above the stability limit.*largest stable time step is 0.00023" "dem.time_step = 1e-3"
bad too_many_particles "particles.count: 1000000 particles do not fit" "particles.count = 1000000"
bad bad_model 'case.model: "lbm" is not one of "dem", "tfm"' 'case.model = "lbm"'
bad fractions "fractions add up to" "species = [{fraction = 0.5}, {fraction = 0.3}]"
bad wall_restitution "contact.wall_restitution: 1.5 is out of range" "contact.wall_restitution = 1.5"
bad gravity_size "domain.gravity: expected 2 or 3 values, got 4" "domain.gravity = [0.0, -9.81, 0.0, 0.0]"
bad gravity_z_in_2d "domain.gravity: z = 0.5 m/s\^2 in a 2D case" "domain.gravity = [0.0, -9.81, 0.5]"
bad gravity_old_name_size "gravity_old_name_size.toml:[0-9]+:[0-9]+ \(dem.gravity\): domain.gravity: expected 2 or 3 values" "dem.gravity = [0.0, -9.81, 0.0, 0.0]"
bad depth_in_2d "domain.depth: a 2D case \(case.dimension = 2\) has no depth" "domain.depth = 0.1"
bad no_depth_in_3d "missing required value domain.depth" "case.dimension = 3"
bad fill_height "particles.fill_height: 2 m is above the domain height" "particles.fill_height = 2.0"
bad particle_file_missing "particles.source = \"file\" needs particles.file" 'particles.source = "file"'
# Gas, grid and jets: read and checked even when gas.enabled = false.
bad gas_viscosity_zero "gas_viscosity_zero.toml:[0-9]+:[0-9]+: gas.viscosity: 0 is out of range: must be > 0" "gas.viscosity = 0.0"
bad gas_viscosity_negative "gas.viscosity: -1e-05 is out of range: must be > 0" "gas.viscosity = -1e-5"
bad cell_width_zero "grid.cell_width: 0 is out of range: must be > 0" "grid.cell_width = 0.0"
bad cell_height_negative "grid.cell_height: -0.02 is out of range: must be > 0" "grid.cell_height = -0.02"
bad cell_width_not_dividing "grid.cell_width: 0.07 m does not divide the domain width 0.6 m into whole cells" "grid.cell_width = 0.07"
bad cell_height_not_dividing "grid.cell_height: 0.03 m does not divide the domain height 1 m into whole cells" "grid.cell_height = 0.03"
bad jet_outside "inlet.jet\[0\].centre: the jet \[0.69, 0.71\] m is not inside the bottom \[0, 0.6\] m" "inlet.jet = [{centre = 0.7}]"
bad jet_narrow "inlet.jet\[0\].width: 0.01 m is narrower than a gas cell \(0.02 m\)" "inlet.jet = [{width = 0.01}]"
bad jet_ends_before_start "inlet.jet\[0\].end: the jet closes before it opens" "inlet.jet = [{start = 0.3, end = 0.1}]"
bad second_jet_outside "inlet.jet\[1\].centre: the jet" "inlet.jet = [{centre = 0.3}, {centre = 0.595}]"
bad inlet_unknown_key "unknown key 'inlet.velocty'; did you mean 'inlet.velocity'" "inlet.velocty = 1.8"
bad jet_unknown_key "unknown key 'inlet.jet\[0\].speed'" "inlet.jet = [{centre = 0.3, speed = 3.0}]"
bad jet_wrong_type "jet_wrong_type.toml:[0-9]+:[0-9]+: inlet.jet\[0\].velocity: expected a number in m/s, got a string" \
  'inlet.jet = [{velocity = "fast"}]'
bad jet_not_tables "inlet.jet: expected an array of tables" "inlet.jet = [1.0, 2.0]"
expect 2 "--set dem.time_step=abc.*expected a number|dem.time_step: expected a number" "--set with a wrong type" \
  "$FLUIDBED" check "$WORK/ok.toml" --set dem.time_step=abc
expect 2 "--set nosuchkey: expected SECTION.KEY=VALUE" "--set without =" "$FLUIDBED" check "$WORK/ok.toml" --set nosuchkey
expect 2 "unknown key 'contact.stifness'; did you mean 'contact.stiffness'" "--set unknown key" \
  "$FLUIDBED" check "$WORK/ok.toml" --set contact.stifness=100
expect 2 "threads" "--threads 0" "$FLUIDBED" run "$WORK/ok.toml" --threads 0
# --set through arrays of tables and values (issue 11, item 1): exit 2 with one line, never a crash, never a new entry.
set_bad() {  # set_bad NAME REGEX ASSIGNMENT: --set on the paper's case (one species, one jet)
  local literal
  literal=$(sed 's/[][().*^$+?{}|\\]/\\&/g' <<<"$3")
  expect 2 "^fluidbed: --set $literal: $2" "$1" "$FLUIDBED" check "$ROOT/cases/gera1998/dem.toml" --set "$3"
  local lines
  lines=$("$FLUIDBED" check "$ROOT/cases/gera1998/dem.toml" --set "$3" 2>&1 | wc -l)
  expect 0 "" "$1: one line" test "$lines" -eq 1
}
set_bad set_array_key "'species' is an array of tables: name one entry, as in species\[0\].diameter" species.diameter=0.003
set_bad set_jet_key "'inlet.jet' is an array of tables: name one entry" inlet.jet.velocity=20
set_bad set_under_value "'case.name' is a string, not a section" case.name.x=1
set_bad set_index_on_table "'case' is a table, not an array" 'case[0].name=1'
set_bad set_huge_index "'species' has 1 entry \(species\[0\]\); --set changes existing entries only" 'species[100000].diameter=0.003'
set_bad set_new_species "'species' has 1 entry" 'species[1].diameter=0.003'
set_bad set_section_value "'case' is a section" case=1
expect 0 "OK" "--set a whole species array" "$FLUIDBED" check "$ROOT/cases/gera1998/dem.toml" \
  --set 'species=[{diameter = 0.004}, {diameter = 0.004, density = 2500.0}]'

# Defaults from the bed (issue 11, item 11): a 1 mm bed without dem.time_step gets t_c / 20 rounded down to the
# 1-1.25-2-2.5-4-5-8 series (t_c = 9.34e-5 s: 4e-6 s), printed; U_mf defaults to the bed's Ergun value, printed.
expect 0 "note: dem.time_step not given: 4e-06 s = t_c / 23.4, from t_c / 20" "derived time step (1 mm)" \
  "$FLUIDBED" check "$WORK/ok.toml" --set 'species=[{diameter = 0.001}]'
expect 0 "stiffness for a 1% mean static overlap +k = " "stiffness for a target overlap" "$FLUIDBED" check "$WORK/ok.toml"
expect 0 "note: bubble.u_mf not given: 1.909 m/s, the Ergun U_mf" "U_mf default" \
  "$FLUIDBED" check "$WORK/ok.toml" --set gas.enabled=true
expect 0 "bubble.u_mf\) +1.800 m/s" "the paper's case keeps U_mf = 1.8" "$FLUIDBED" check "$ROOT/cases/gera1998/dem.toml"
# check covers every species (item 12) and refuses what run refuses, gas on or off.
expect 0 "species 1 +d = 0.002 m.*contact duration 0-1" "check: every species and pair" \
  bash -c "'$FLUIDBED' check '$WORK/ok.toml' --set 'species=[{diameter = 0.004}, {diameter = 0.002}]' | tr '\n' ' '"
bad grid_one_cell "grid.cell_width: 0.6 m leaves 1 cell across the domain width 0.6 m; the grid needs .*at least 2" \
  "grid.cell_width = 0.6" "grid.cell_height = 0.02"
expect 2 "grid.cell_width: 0.6 m leaves 1 cell" "run refuses the same grid" \
  "$FLUIDBED" run "$WORK/grid_one_cell.toml" --quiet --out "$WORK/grid1"
# One domain and gravity for every model; the full viscous stress (item 13).
expect 0 "gravity \(0, -5\) m/s\^2" "a TFM case sets gravity" "$FLUIDBED" check "$ROOT/cases/gera1998/tfm.toml" \
  --set 'domain.gravity=[0.0, -5.0]'
expect 0 "OK" "gas.viscous_stress = full" "$FLUIDBED" check "$ROOT/cases/gera1998/dem.toml" --set gas.viscous_stress=full
expect 2 "gas.viscous_stress: the two-fluid model's gas has no viscous stress" "TFM refuses a gas viscous stress" \
  "$FLUIDBED" check "$ROOT/cases/gera1998/tfm.toml" --set gas.viscous_stress=full
# Units that look wrong say what is wrong and the likely slip (item 14).
bad diameter_in_mm "species\[0\].diameter: a particle of 4 m is larger than the domain \(0.6 x 1 m\).*4 mm is 0.004 m" \
  "species = [{diameter = 4.0}]"
bad density_in_g_cm3 "species\[0\].density: 2.7 kg/m\^3 is the density of a gas, not of a solid.*2.7 g/cm\^3 is 2700 kg/m\^3" \
  "species = [{density = 2.7}]"
bad particle_above_cell "species\[0\].diameter: a particle of 0.03 m is larger than a gas cell" \
  "gas.enabled = true" "particles.count = 10" "species = [{diameter = 0.03}]"
bad gas_density_in_g_cm3 "gas.density: 0.001205 kg/m\^3 is thinner than any gas.*is 1.205 kg/m\^3" "gas.density = 0.001205"
bad gas_viscosity_in_micro "gas.viscosity: 18 Pa s is above the viscosity of any gas.*18 uPa s is 1.8e-05 Pa s" \
  "gas.viscosity = 18.0"
expect 2 "tfm.particle_density: 2.7 kg/m\^3 is the density of a gas" "TFM density in g/cm^3" \
  "$FLUIDBED" check "$ROOT/cases/gera1998/tfm.toml" --set tfm.particle_density=2.7
expect 0 "note: gas.viscosity = 0.018 Pa s is the viscosity of a liquid" "a liquid's viscosity is a note" \
  "$FLUIDBED" check "$WORK/ok.toml" --set gas.viscosity=0.018

# A particle CSV with a bad row names the file, the row and the column.
printf 'id,x,y,vx,vy,omega,species\n0,0.1,0.1,0,0,0,0\n1,0.2,abc,0,0,0,0\n' > "$WORK/bad.csv"
bad bad_particle_csv "bad.csv: row 3, column (3|y)" 'particles.source = "file"' "particles.file = \"$WORK/bad.csv\""
# An id given twice: the DEM solver refuses it when a run starts, so `check` does too (issue 11, item 12).
printf 'id,x,y,vx,vy,omega,species\n4,0.1,0.1,0,0,0,0\n5,0.2,0.1,0,0,0,0\n4,0.3,0.1,0,0,0,0\n' > "$WORK/twice.csv"
# A settled bed cached for another bed (here: 3 particles, no record of how it was settled): run settles anew
# instead of reusing it, and check says so (tests/cli/settle_cache.sh runs it).
cp "$WORK/twice.csv" "$WORK/cache3.csv" && sed -i 's/^4,0.3/6,0.3/' "$WORK/cache3.csv"
cp "$WORK/ok.toml" "$WORK/cache3.toml" && sed -i '/^settle\./d' "$WORK/cache3.toml"
printf 'settle.enabled = true\nsettle.cache = "%s"\n' "$WORK/cache3.csv" >> "$WORK/cache3.toml"
expect 0 "note: settle.cache .*cache3.csv will not be reused \(no record\)" "a stale settle cache is a note" \
  "$FLUIDBED" check "$WORK/cache3.toml"
bad particle_id_twice "twice.csv: row 4, column 1: duplicate id 4" 'particles.source = "file"' \
  "particles.file = \"$WORK/twice.csv\""

# Issue 27: a law's required property is asked for (item 3); a particle deeper than the box blames the depth
# (item 10); a slab thinner than its spheres stops the run at its first voidage below zero (item 1).
bad hertz_without_modulus 'species\[0\].youngs_modulus: contact.normal = "hertz" takes the contact stiffness.*at 7e10 Pa' \
  'contact.normal = "hertz"'
bad particle_deeper_than_box "domain.depth: 0.002 m is shallower than a particle of species\[0\].diameter = 0.004 m" \
  "case.dimension = 3" "domain.depth = 0.002" "grid.cell_depth = 0.002"
cat > "$WORK/thin_slab.toml" <<'TOML'
case.name = "thin-slab"
case.end_time = 0.001
domain.width = 0.04
domain.height = 0.1
species = [{diameter = 0.002}]
particles.count = 150
particles.fill_height = 0.03
settle.enabled = false
grid.cell_width = 0.01
grid.cell_height = 0.01
inlet.velocity = 0.5
inlet.jet = []
coupling.depth = 0.0002
output.checkpoint_interval = 0.0
TOML
expect 0 "warning: coupling.depth = 0.0002 m is too thin for the largest particles" "check warns of a slab thinner than its spheres" \
  "$FLUIDBED" check "$WORK/thin_slab.toml"
expect 3 "at t = 0 s the voidage is -[0-9.]+ \(below zero\) in [0-9]+ of 40 gas cells.*coupling.depth = 0.0002 m" \
  "a voidage below zero stops the run" "$FLUIDBED" run "$WORK/thin_slab.toml" --quiet --out "$WORK/thin_slab"

# Item 4: a size range far in a tail of its law is refused naming the species and its keys (before: NaN reached the
# user as `dem.skin: -nan`, or every particle sat at d_min).
bad normal_far_tail "species\[0\]\.d_min: the cut-offs species\[0\]\.d_min = 0.006 m and species\[0\]\.d_max = 0.007 m lie" \
  'species = [{size_distribution = "normal", mean = 0.004, std = 0.0001, d_min = 0.006, d_max = 0.007}]'
bad lognormal_far_tail "species\[0\]\.d_min: .*species\[0\]\.median = 0.001 m and species\[0\]\.sigma = 0.1" \
  'species = [{size_distribution = "log-normal", median = 0.001, sigma = 0.1, d_min = 0.0025, d_max = 0.003}]'
# Issue 28 item 5: keys of earlier versions name their replacement; DEM alone in a small box needs no [grid].
bad old_top_wall 'domain.top_wall: domain.top_wall is now domain.particle_top: "wall" for top_wall = true' \
  "domain.top_wall = true"
expect 2 "tfm.inlet_noise: tfm.inlet_noise is now inlet.noise" "an old TFM key names its new one" \
  "$FLUIDBED" check "$ROOT/cases/gera1998/tfm.toml" --set tfm.inlet_noise=0.1
grep -v '^particles.count' "$WORK/ok.toml" > "$WORK/small_box.toml"
printf 'domain.width = 0.03\ndomain.height = 0.05\nparticles.count = 20\n' >> "$WORK/small_box.toml"
expect 0 "" "a gas-off case in a 0.03 m box without [grid] runs" "$FLUIDBED" run "$WORK/small_box.toml" --quiet \
  --out "$WORK/small_box"

# Output folder that cannot be written.
touch "$WORK/not-a-folder"
expect 2 "cannot" "unwritable output folder" "$FLUIDBED" run "$WORK/ok.toml" --quiet --out "$WORK/not-a-folder/out"

# Restart files: not HDF5, and a checkpoint of another case.
echo "garbage" > "$WORK/garbage.h5"
expect 2 "garbage.h5" "unreadable restart file" "$FLUIDBED" run "$WORK/ok.toml" --quiet --out "$WORK/r1" --restart "$WORK/garbage.h5"
expect 0 "" "a run that writes a checkpoint" "$FLUIDBED" run "$WORK/ok.toml" --quiet --out "$WORK/r2"
sed 's/case.name = "ok"/case.name = "other"/' "$WORK/ok.toml" > "$WORK/other.toml"
expect 2 "checkpoint is of case 'ok'" "mismatched restart file" \
  "$FLUIDBED" run "$WORK/other.toml" --quiet --out "$WORK/r3" --restart "$WORK/r2/checkpoints/final.h5"
expect 2 "restart file not found" "missing restart file" "$FLUIDBED" run "$WORK/ok.toml" --quiet --out "$WORK/r4" --restart "$WORK/none.h5"

finish
