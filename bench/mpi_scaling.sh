#!/usr/bin/env bash
# The MPI overhead on one machine (docs/SCALING.md): demo:whitted at 3200×2400 rendered by
# 1 process × 2 threads and by 2 processes × 1 thread (mpirun), side by side, alternating,
# REPS times each; prints the median wall times, their ratio, the bytes rank 0 received per
# tile and the messages, and checks the two images are the same bytes. Also 1 process under
# mpirun, unbound (--bind-to none: the plumbing alone), and, with --aa adaptive, the corner
# broadcast.
#
#     bench/mpi_scaling.sh [LUZ] [REPS]      # LUZ defaults to build/release/luz, REPS to 5
set -euo pipefail
luz="$(realpath "${1:-build/release/luz}")"
reps="${2:-5}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mpirun=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpirun+=(--allow-run-as-root)
scene=(demo:whitted --width 3200 --height 2400 -q)

# run NAME AA THREADS COMMAND…: appends the wall seconds of one run to $tmp/NAME.times
run() {
  local name="$1" aa="$2" threads="$3"
  shift 3
  local t0 t1
  t0=$(date +%s.%N)
  "$@" render "${scene[@]}" --aa "$aa" --threads "$threads" -o "$tmp/$name.png" \
    --stats "$tmp/$name.json"
  t1=$(date +%s.%N)
  echo "$t1 - $t0" | bc >>"$tmp/$name.times"
}
median() { sort -g "$1" | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

for aa in none adaptive; do
  for ((i = 0; i < reps; i++)); do
    run "p1t2_$aa" "$aa" 2 "$luz"
    run "p2t1_$aa" "$aa" 1 "${mpirun[@]}" -np 2 "$luz"
    run "mpi1t2_$aa" "$aa" 2 "${mpirun[@]}" --bind-to none -np 1 "$luz"
  done
  cmp "$tmp/p1t2_$aa.png" "$tmp/p2t1_$aa.png" || { echo "images differ ($aa)" >&2; exit 1; }
done

printf '%-9s %-22s %8s %8s %10s %10s %12s\n' aa run wall_s render_s vs_1x2 tiles_in bytes_per_tile
for aa in none adaptive; do
  base=$(median "$tmp/p1t2_$aa.times")
  for name in p1t2 p2t1 mpi1t2; do
    m=$(median "$tmp/${name}_$aa.times")
    /usr/bin/python3 - "$tmp/${name}_$aa.json" "$name" "$aa" "$m" "$base" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); name, aa, m, base = sys.argv[2], sys.argv[3], float(sys.argv[4]), float(sys.argv[5])
label = {"p1t2": "1 process x 2 threads", "p2t1": "2 processes x 1 thread",
         "mpi1t2": "mpirun -np 1 (unbound) x 2"}[name]
mpi = s.get("mpi", {})
tiles = mpi.get("tiles_received", 0)
per = mpi.get("tile_bytes_received", 0) / tiles if tiles else 0
print(f"{aa:9s} {label:22s} {m:8.2f} {s['seconds']:8.2f} {m / base:10.3f} {tiles:10d} {per:12.0f}")
if name == "p2t1":
    print(f"{'':9s} {'':22s} primary_rays_by_process={s['primary_rays_by_process']} "
          f"messages={mpi.get('messages_received_and_sent')} broadcast_bytes={mpi.get('broadcast_bytes')}")
PY
  done
done
