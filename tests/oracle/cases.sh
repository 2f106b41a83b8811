# The runs of the regression oracle, shared by regenerate.sh and tests/cli/oracle.sh.
ORACLE_DEM_END=0.2
ORACLE_TFM_END=0.5
ORACLE_DEM3D_END=0.05
ORACLE_TFM3D_END=0.1
ORACLE_CASES=(dem tfm tfm-constant-viscosity tfm-inviscid dem3d tfm3d-slab)

# oracle_run FLUIDBED ROOT NAME OUT: one short run into OUT of cases/gera1998/NAME.toml, or of the 3D entries
# tests/oracle/dem3d.toml and cases/tfm3d/slab.toml (a fresh settle for the DEM cases, so that the settling is part
# of what is frozen).
oracle_run() {
  local fluidbed=$1 root=$2 name=$3 out=$4 end=$ORACLE_TFM_END
  local file="$root/cases/gera1998/$name.toml"
  local extra=()
  case $name in
    dem) end=$ORACLE_DEM_END ;;
    dem3d) end=$ORACLE_DEM3D_END file="$root/tests/oracle/dem3d.toml" ;;
    tfm3d-slab) end=$ORACLE_TFM3D_END file="$root/cases/tfm3d/slab.toml" ;;
  esac
  if [[ $name == dem* ]]; then extra=(--set "settle.cache=\"$out.settled.csv\""); fi
  "$fluidbed" run "$file" --out "$out" --end-time "$end" --threads 2 --quiet --overwrite \
    --set output.particles=false --set output.fields=false "${extra[@]}"
}

# oracle_strip CSV: the file without the wall_s column (the only value that depends on the machine's speed).
oracle_strip() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "wall_s") skip = i }
           { line = ""; for (i = 1; i <= NF; ++i) if (i != skip) line = line (line == "" ? "" : ",") $i; print line }' "$1"
}
