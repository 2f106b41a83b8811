#!/usr/bin/env bash
# The same case with 1 and 2 OpenMP threads gives byte-identical particles and fields (issue 6): no
# order-dependent reductions anywhere in the coupled step.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

write_cfd_case "$WORK/cfd.toml" cfd
run_ok "cfd: --threads 1" run "$WORK/cfd.toml" --out "$WORK/t1" --threads 1
run_ok "cfd: --threads 2" run "$WORK/cfd.toml" --out "$WORK/t2" --threads 2
check "cfd: the logs name 1 and 2 threads" \
  bash -c "grep -q '; 1 thread;' '$WORK/t1/log.txt' && grep -q '; 2 threads;' '$WORK/t2/log.txt'"
same_results "cfd 1 vs 2 threads" "$WORK/t1" "$WORK/t2"
# More threads than cores must not change anything either (oversubscription changes the scheduling).
run_ok "cfd: --threads 3" run "$WORK/cfd.toml" --out "$WORK/t3" --threads 3
same_results "cfd 1 vs 3 threads" "$WORK/t1" "$WORK/t3"

# The two-fluid model's threaded cell and face loops (closures, limiter face values, momentum predictors).
tfm=("$ROOT/cases/gera1998/tfm.toml" --end-time 0.1 --quiet --overwrite)
for t in 1 2 3; do run_ok "tfm: --threads $t" run "${tfm[@]}" --out "$WORK/tfm$t" --threads "$t"; done
same_results "tfm 1 vs 2 threads" "$WORK/tfm1" "$WORK/tfm2"
same_results "tfm 1 vs 3 threads" "$WORK/tfm1" "$WORK/tfm3"

finish
