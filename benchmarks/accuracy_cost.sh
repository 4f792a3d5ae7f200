#!/usr/bin/env bash
# Accuracy against cost, dt = tc/5 ... tc/81 (the thesis' 1.23 us):
#   cost   CPU seconds per simulated second of the drum: the settled slab of
#          model_cost.sh continued for --span simulated seconds at each dt,
#          LIGGGHTS loop time x ranks / span; --runs rounds, the dts
#          interleaved within each round (tc/5 tc/10 ... tc/5 tc/10 ...), median.
#          exactRestitution only changes the coefficients computed at init:
#          its cost per step is the nominal one at the same dt.
#   error  1. two-body head-on collision (collide, 128 start phases):
#          restitution and contact-duration error against the requested en
#          and tc, nominal coefficients (= stock hooke/stiffness given them:
#          identical forces, see model_cost) and `exactRestitution on`;
#          2. drum metrics: the slab continued for --window simulated seconds
#          from the same state at each dt (snapshots every 5 ms), Hc, Hd and
#          the angle of repose averaged over the window; drift = difference
#          to the finest nominal dt. Same start, so the drift is the timestep's
#          effect plus the chaotic divergence of the trajectories (the
#          standard error of the window averages says how large that is).
#
#   benchmarks/accuracy_cost.sh --restart FILE [--ratios 5,10,20,40,81] [--exact-ratios 5,10,20]
#                               [--span 0.01] [--runs 5] [--window 0.2] [--np 2] [--out benchmarks/results]
set -euo pipefail
restart=""; ratios=5,10,20,40,81; exact_ratios=5,10,20; span=0.01; runs=5; window=0.2; np=2
out=benchmarks/results
while [ $# -gt 0 ]; do
  case "$1" in
    --restart) restart=$2; shift 2 ;;
    --ratios) ratios=$2; shift 2 ;;
    --exact-ratios) exact_ratios=$2; shift 2 ;;
    --span) span=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --window) window=$2; shift 2 ;;
    --np) np=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "accuracy_cost: unknown option $1 (see the header of $0)" >&2; exit 2 ;;
  esac
done
[ -n "$restart" ] || { echo "accuracy_cost: --restart FILE (a settled drum, e.g. from model_cost.sh) is needed" >&2; exit 2; }
source "$(dirname "$0")/../tools/drum_common.sh"
collide=${COLLIDE:-collide}
mpirun_for "$np"
mkdir -p "$out" post/accuracy
dtof() { awk -v r="$1" 'BEGIN {printf "%.10g", 1e-4 / r}'; }

# 1. two-body errors: one LIGGGHTS run per dt holds all 128 phases
for mode in off on; do
  "$collide" sweep-dt --geometry pair --en 0.56 --et 0.46 --ratios "$ratios" --phases 128 \
    --exact-restitution "$mode" --csv "post/accuracy/twobody_exact_$mode.csv" > /dev/null
done

# 2. cost: rounds of short runs, the dts interleaved
: > post/accuracy/timings.txt
for i in $(seq 1 "$runs"); do
  for r in ${ratios//,/ }; do
    echo "accuracy_cost: timing round $i, tc/$r ..."
    log=post/accuracy/time_$r.log
    drum_run "$log" -var start restart -var restart "$restart" -var dt "$(dtof "$r")" \
      -var time "$span" -var dumpdt 1 -var name "accuracy/time_$r"
    echo "$r $(loop_time "$log")" >> post/accuracy/timings.txt
  done
done
beads=$(sed -n 's/^drum: done, \([0-9]*\) beads kept.*/\1/p' "post/accuracy/time_${ratios%%,*}.log")

# 3. drum metrics over the window at each dt, nominal and exact
echo "tc_over_dt,exact,snapshots,head,head_err,shoulder,shoulder_err,centre_of_mass,centre_of_mass_err,repose_angle,repose_angle_err" \
  > post/accuracy/window.csv
for spec in $(for r in ${ratios//,/ }; do echo "$r:off"; done; for r in ${exact_ratios//,/ }; do echo "$r:on"; done); do
  r=${spec%%:*}; ex=${spec##*:}
  tag=window_${r}_$ex
  echo "accuracy_cost: drum window ${window} s at tc/$r, exactRestitution $ex ..."
  rm -f post/accuracy/${tag}_*.vtp
  drum_run "post/accuracy/$tag.log" -var start restart -var restart "$restart" -var dt "$(dtof "$r")" \
    -var exact "$ex" -var time "$window" -var dumpdt 0.005 -var name "accuracy/$tag"
  "$metrics" series --prefix "post/accuracy/$tag" --dt "$(dtof "$r")" --rpm 21 > /dev/null
  # window averages: every snapshot after the shared start state
  awk -F, -v r="$r" -v ex="$ex" 'NR > 2 {
      for (k = 0; k < 4; k++) { v = $(k == 0 ? 3 : k == 1 ? 4 : k == 2 ? 5 : 8)
                                if (v != "nan") { n[k]++; s[k] += v; q[k] += v * v } } }
    END { printf "%s,%s,%d", r, ex, n[2]
          for (k = 0; k < 4; k++) { m = s[k] / n[k]; var = (q[k] / n[k] - m * m) * n[k] / (n[k] - 1); if (var < 0) var = 0
                                    printf ",%.6g,%.3g", m, sqrt(var / n[k]) }
          printf "\n" }' "post/accuracy/${tag}_metrics.csv" >> post/accuracy/window.csv
done

# 4. one table: cost, two-body errors, drum drifts against the finest nominal dt
finest=$(echo "${ratios//,/ }" | tr ' ' '\n' | sort -g | tail -1)
python3 - "$out" "$finest" "$np" "$span" "$beads" <<'PY'
import csv, statistics, sys
out, finest, np_, span, beads = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), int(sys.argv[5])
t = {}
for line in open("post/accuracy/timings.txt"):
    r, s = line.split()
    t.setdefault(float(r), []).append(float(s))
two = {m: {float(r["tc_over_dt"]): r for r in csv.DictReader(open("post/accuracy/twobody_exact_%s.csv" % m))}
       for m in ("off", "on")}
win = {(float(r["tc_over_dt"]), r["exact"]): r for r in csv.DictReader(open("post/accuracy/window.csv"))}
ref = win[(finest, "off")]
keys = (("centre_of_mass", "Hc_mm", 1e3), ("shoulder", "Hd_mm", 1e3), ("repose_angle", "angle_deg", 1.0))
with open(out + "/accuracy_cost.csv", "w") as f:
    f.write("tc_over_dt,exact,dt,cpu_s_per_simulated_s,particle_steps_per_s,restitution_err,duration_err_steps,"
            + ",".join("%s,%s_err,%s_drift" % (n, n, n) for _, n, _ in keys) + "\n")
    for (r, ex), w in sorted(win.items(), key=lambda kv: (kv[0][1], kv[0][0])):
        loop = statistics.median(t[r])
        dt = 1e-4 / r
        row = two["on" if ex == "on" else "off"][r]
        f.write("%g,%s,%.6g,%.6g,%.6g,%s,%s" % (r, ex, dt, loop * np_ / span, beads * (span / dt) / loop,
                                                row["restitution_rel_err"], row["duration_err_steps"]))
        for k, _, scale in keys:
            f.write(",%.6g,%.3g,%.4g" % (float(w[k]) * scale, float(w[k + "_err"]) * scale,
                                          (float(w[k]) - float(ref[k])) * scale))
        f.write("\n")
PY
cat "$out/accuracy_cost.csv"
