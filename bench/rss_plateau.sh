# Sourced by bench/memory.sh and bench/memory_3d.sh. rss_plateau PID OUT [FRAMES]: follows the fluidbed run PID
# (started under /usr/bin/time, so the program is its child) until it ends and prints the largest VmRSS of the
# program, in kB, sampled every 10 ms while OUT/checkpoints is empty (before the final checkpoint begins) and, with
# FRAMES = 1, once the first particle frame (.vtu) is on disk. Called in $( ), it cannot wait for PID: the caller
# does, for the run's exit status.
rss_plateau() {
  local pid=$1 out=$2 frames=${3:-0} plateau=0 rss child=""
  while kill -0 "$pid" 2>/dev/null; do
    [ -n "$child" ] || child=$(pgrep -P "$pid" -n || true)
    if [ -n "$child" ] && [ -z "$(ls "$out/checkpoints" 2>/dev/null)" ] &&
       { [ "$frames" != 1 ] || [ -n "$(ls "$out/particles" 2>/dev/null | grep 'vtu$' || true)" ]; }; then
      rss=$(awk '/^VmRSS/{print $2}' "/proc/$child/status" 2>/dev/null || echo 0)
      [ "${rss:-0}" -gt "$plateau" ] && plateau=$rss
    fi
    sleep 0.01
  done
  echo "$plateau"
}
