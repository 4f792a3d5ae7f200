#!/bin/bash
# The thesis-scale drum runs still to do, in order, on 2 cores. Each step is a resumable
# tools/drum/steady.py study that commits as it goes and continues from what is committed, so
# rerunning this script goes on where it stopped (a step already committed takes seconds).
#
#   bash setup.sh   # once per checkout: the campaign runs the installed binaries
#   mkdir -p post && nohup setsid tools/drum/campaign.sh >> post/campaign.out 2>&1 &
#   tools/drum/campaign.sh --checkpoint-now    # before stopping the machine: checkpoint and stop
#   tools/drum/campaign.sh --plan              # where each step stands: speeds committed, to run, to extend
#
# Do not start it while one of its studies runs on its own (steady.py has no lock); two
# campaigns at once are refused. It runs a copy of the installed binaries (post/campaign-bin), so
# `bash setup.sh` and the tests may run beside it; a rebuilt model reaches it when it is restarted.
#
# The steps, in order (each is explained where it runs, below):
#  1. The thesis' chain, 7-63 rpm (Table 3.1, tc/5 with exactRestitution, primitive cylinder), and
#     a second history of 21 rpm from 28 rpm's end state.
#  2. The slip test (Fig. 3.5-3.6): ramps of one rpm per 1.5 s from a carried 21 rpm bed, with the
#     thesis' table and with YADE 1.12's conventions, two histories each (tools/drum/slip.py).
#  3. The chain again from the grid with the bound rule, to 35 rpm (study_bound).
#  4. The timestep ladder at 21 rpm, each run to the power rule (a 0.1 mm / 0.1 deg difference
#     found with 80 % power): the nominal law at the thesis' tc/81 (the reference) and tc/20,
#     exactRestitution at its guard's coarsest step and tc/10, the nominal law at tc/10
#     (benchmarks/drum_timestep.py).
#  5. study_thesis extended until each of its averages has 10 effective degrees of freedom
#     (steady.py --extend; the README's results regenerated with it), then 42 rpm at tc/40 and
#     tc/20 (capped at 8 s): with 4 they complete the timestep comparison.
#  6. The release study (tools/drum/release.py, docs/drum/release.md): a 12 mm period check, three
#     21 rpm start states, ramps at the thesis' 1.76 s per rpm at bead-drum mu 0.5, 0.65, 0.8 and
#     0.95, holds just below and above the release at mu 0.5 and 0.95, YADE's other conventions
#     one at a time at mu 0.5, the surface-velocity mesh at mu 0.5 and 0.95 from the same three
#     start states.
#  7. The rest of the ladder (the nominal law at tc/40, exactCollision at tc/5 and tc/10) and the
#     slip ramp 27 -> 35 rpm at tc/20.
#  8. study_yade's speeds 21-63 under the estimator's rule, each set against the thesis' table
#     (docs/drum/conventions_<rpm>rpm.md) and the thesis' trend (docs/drum/thesis_trend.md).
#  9. The drum's wall at 21 rpm (the rotating mesh, the surface-velocity mesh) against the
#     primitive cylinder; study_bound on to 63 rpm against study_thesis; YADE's 7 and 14 rpm.
set -euo pipefail
cd "$(dirname "$0")/../.."
mkdir -p post
exec 9> post/campaign.lock
if [[ "${1:-}" != "--checkpoint-now" && "${1:-}" != "--plan" ]] && ! flock -n 9; then
  echo "campaign: another campaign is running (post/campaign.lock)"; exit 1
fi
py=/usr/bin/python3
now=()
if [[ "${1:-}" == "--checkpoint-now" ]]; then now=(--checkpoint-now); fi
if [[ "${1:-}" == "--plan" ]]; then now=(--dry-run); fi  # each study's plan: runs and commits nothing
# The campaign runs its own copy of the installed binaries, taken when it starts: `bash setup.sh`
# (a rebuild, a test run from a clone) rewrites the installed library in place, which would crash
# a run that has it mapped. So a campaign can go on while the project is rebuilt and tested.
# (--checkpoint-now and --plan run no simulation and leave a running campaign's copy alone.)
if [[ ${#now[@]} -eq 0 ]]; then
  own=post/campaign-bin
  installed=$(dirname "$(command -v liggghts || echo /nonexistent/liggghts)")
  if [[ ! -e "$installed/../lib/libliggghts_viscoelastic.so" ]]; then
    echo "campaign: the project's liggghts and model library are not installed ($installed/../lib): run 'bash setup.sh' first"
    exit 1
  fi
  rm -rf "$own.new" && mkdir -p "$own.new/bin" "$own.new/lib"
  cp "$installed/../lib/libliggghts_viscoelastic.so" "$own.new/lib/"
  for t in liggghts drum_metrics drum_mesh contact_law collide; do
    cp "$installed/$t" "$own.new/bin/"
    export "${t^^}=$PWD/$own/bin/$t"  # the variable tools/harness reads for it: its name in capitals
  done
  rm -rf "$own" && mv "$own.new" "$own"
  echo "campaign: runs $LIGGGHTS ($(sha256sum "$own/lib/libliggghts_viscoelastic.so" | cut -c1-12))"
fi
steady() { "$py" tools/drum/steady.py --var wall cylinder --var skin 0.3 --commit "$@" "${now[@]}"; }
# commit what an analysis wrote (only these files: a campaign shares the repository)
save() {
  local message=$1 files=() f k
  shift
  for f in "$@"; do if [[ -e "$f" ]]; then files+=("$f"); fi; done
  [[ ${#files[@]} -gt 0 ]] || return 0
  # another git process (a checkpoint or other work in the repository) may hold the index: retry,
  # and in the end go on without the commit rather than end the campaign (the files stay written)
  for k in 1 2 3 4 5 6 7 8 9 10; do
    if git add -- "${files[@]}" &&
      { git diff --cached --quiet -- "${files[@]}" || git commit -q -m "$message" -- "${files[@]}"; }; then
      return 0
    fi
    sleep 5
  done
  echo "campaign: NOT COMMITTED after $k tries (commit them by hand): ${files[*]}"
}
# a step whose start state an earlier step has not written yet (only with --checkpoint-now or --plan)
ready() { [[ -e "$1" ]] || { echo "campaign: $1 not written yet"; false; }; }
thesis=(--var dt 2e-5 --var exact on)
yade=(--var dt 1e-5 --var exact off --var conventions yade)
slip_speeds=22,23,24,25,26,27,28,29,30,31,32,33,34,35
yade_slip_speeds=22,23,24,25,26,27,28

steady --name study_thesis "${thesis[@]}" --segment 2 --cap 60
# A second history of 21 rpm: from 28 rpm's end state (the same carried bed, arrived at from
# above), against the chain's 21 rpm with tools/drum/histories.py.
steady --name history_21rpm_from28 --speeds 21 --start-state docs/drum/study_thesis/28rpm/state.restart.gz \
  "${thesis[@]}" --segment 2 --cap 40
if [[ ${#now[@]} -eq 0 ]]; then
  "$py" tools/drum/histories.py docs/drum/study_thesis.csv docs/drum/history_21rpm_from28.csv --rpm 21 \
    --out docs/drum/histories_21rpm.md || echo "campaign: the two histories of 21 rpm disagree, or the comparison failed (above)"
  save "Drum: two histories of 21 rpm at thesis scale" docs/drum/histories_21rpm.md
fi
# The slip test (Fig. 3.5-3.6): the speed raised from 21 rpm one rpm at a time, 1.5 s per speed
# (21 -> 28 in 10.5 s: the thesis' ramp took 1e7 steps, about 12 s), from the chain's carried
# 21 rpm bed with the thesis' table (bead-drum mu 0.95), on to 35 rpm, where the chain's bed no
# longer turns with the drum; then with YADE 1.12's conventions (mu 0.5, facet meff m/2, no
# attraction; run with the nominal law at tc/10, as exactRestitution then refused the facet mass) from 21 rpm under
# them: study_yade's 21 rpm state after 8 s (settled: its four 2 s means of Hc within 0.11 mm),
# kept as docs/drum/slip_yade/start_state.restart.gz, so the ramp need not wait for that speed's
# averages; study_yade then goes on from the same state to 21 rpm's averages (slip.py's first
# YADE row). Under YADE's conventions the bed lets go during 26-27 rpm, so that ramp stops at 28 rpm,
# the thesis' ramp's end, which answers the 27 -> 28 rpm step. tools/drum/slip.py reads both
# at once. A release speed is one event of one history: so, once study_yade has 21 rpm's steady
# end state (later in the same steady flow than the first ramp's start), the same YADE ramp
# again from there (slip_yade_replica), a second history of the release. Each slip speed is
# one segment: --checkpoint-now keeps nothing of one under way (at most 1.5 s simulated is
# redone). The slip question comes first: it is the study's answer.
steady --name slip_thesis --speeds "$slip_speeds" --start-state docs/drum/study_thesis/21rpm/state.restart.gz \
  "${thesis[@]}" --segment 1.5 --cap 1.5
steady --name slip_yade --speeds "$yade_slip_speeds" --start-state docs/drum/slip_yade/start_state.restart.gz \
  "${yade[@]}" --segment 1.5 --cap 1.5
# both conventions; rerun once study_yade has 21 rpm's steady averages (the YADE ramp's first
# point) and once the YADE ramp's second history has run
slip_all() {
  local yade_start=- replica=()
  if [[ -e docs/drum/study_yade/21rpm/state.restart.gz ]]; then yade_start=study_yade:21; fi
  if [[ -e docs/drum/slip_yade_replica/22rpm/run.json ]]; then
    replica=(--study slip_yade_replica "YADE 1.12 conventions, second history (from 21 rpm's steady end state)"
             --start "$yade_start")
  fi
  if [[ -e docs/drum/slip_thesis_replica/22rpm/run.json ]]; then
    replica+=(--study slip_thesis_replica "thesis table, second history (from 21 rpm arrived at from 28 rpm)"
              --start history_21rpm_from28:21)
  fi
  "$py" tools/drum/slip.py \
    --study slip_thesis "thesis table (bead-drum mu 0.95)" --start study_thesis:21 \
    --study slip_yade "YADE 1.12 conventions (bead-drum mu 0.5, facet meff m/2, no attraction)" --start "$yade_start" \
    "${replica[@]}" --out docs/drum/slip_test || echo "campaign: the slip test's analysis failed (above)"
  save "Drum: the slip test at thesis scale" docs/drum/slip_test.md docs/drum/slip_test.csv docs/drum/slip_test.png
}
if [[ ${#now[@]} -eq 0 ]]; then slip_all; fi
steady --name study_yade --speeds 21 --start-state docs/drum/study_thesis/21rpm/state.restart.gz \
  "${yade[@]}" --segment 2 --cap 40
if ready docs/drum/study_yade/21rpm/state.restart.gz; then
  steady --name slip_yade_replica --speeds "$yade_slip_speeds" --start-state docs/drum/study_yade/21rpm/state.restart.gz \
    "${yade[@]}" --segment 1.5 --cap 1.5
fi
if [[ ${#now[@]} -eq 0 ]]; then slip_all; fi
# the two YADE histories let go about a rpm apart (26-27 and 28 rpm): so the thesis' table's ramp
# again too, from its other 21 rpm history (history_21rpm_from28's steady end state), to 35 rpm
if ready docs/drum/history_21rpm_from28/21rpm/state.restart.gz; then
  steady --name slip_thesis_replica --speeds "$slip_speeds" \
    --start-state docs/drum/history_21rpm_from28/21rpm/state.restart.gz "${thesis[@]}" --segment 1.5 --cap 1.5
fi
if [[ ${#now[@]} -eq 0 ]]; then slip_all; fi
# The thesis' chain again from the grid with the stop rule recommended for new studies
# (--min-batches 3 --confidence 0.95), first to 35 rpm: the time to the target as the driver
# achieves it (the report's figure for it so far is a replay on study_thesis). 7-28 rpm take more
# than an hour each, so 35 rpm, the fifth of nine, decides whether the median is within an hour.
bound=(--name study_bound "${thesis[@]}" --min-batches 3 --confidence 0.95 --segment 2 --cap 60)
steady "${bound[@]}" --speeds 7,14,21,28,35
# one 21 rpm study from the chain's 21 rpm state, steady with 5 revolutions at least and the
# standard errors' 95 % bound within the targets, set against the chain's own 21 rpm (tc/5 with
# exactRestitution) by histories.py KIND (a difference: the change's effect)
against_chain() {  # NAME KIND OUT MESSAGE, then steady.py's options for the study
  local name=$1 kind=$2 out=$3 message=$4
  shift 4
  steady --name "$name" --speeds 21 --start-state docs/drum/study_thesis/21rpm/state.restart.gz \
    "$@" --min-batches 5 --confidence 0.95
  if [[ ${#now[@]} -eq 0 ]]; then
    "$py" tools/drum/histories.py docs/drum/study_thesis.csv "docs/drum/$name.csv" --rpm 21 "--$kind" --out "$out" \
      || echo "campaign: $name differs from the chain's 21 rpm, or the comparison failed ($out)"
    save "$message" "$out"
  fi
}
# one timestep with the nominal law (skin: the neighbour skin in bead diameters; a thinner one
# changes only round-off, never which contacts are computed, and has fewer pairs to check where
# beads move little per step: benchmarks/README.md, "Neighbour skin at the thesis' tc/81")
# Each ends where, at 10 dof at least, its 95 % half-widths at 10 dof (tools/drum/estimator.py) are
# within Hc 0.0535 mm and angle 0.0535 deg: two runs at that detect a difference of 0.1 mm / 0.1 deg
# between them with 80 % power or more (estimator.half_width_for_power). The stop rule changed after
# tc/81 had run 0.75 s; its segments are kept (steady.py resumes a trajectory under a new rule).
power_rule=(--rule obm --target Hc=5.35e-5 --target angle=0.0535)
timestep() {
  local step=$1 label=$2 segment=$3 skin=$4
  against_chain "dt_$label" timesteps "docs/drum/timestep_21rpm_$label.md" \
    "Drum: 21 rpm at tc/5 against $label at thesis scale" \
    --var dt "$step" --var exact off --var skin "$skin" --segment "$segment" --cap "${cap:-20}" "${power_rule[@]}"
}
# the thesis' tc/81 first: the reference every other timestep is read against, and the longest
# run (161 min of 2 cores per simulated second), so it starts before the rest. Capped at 10 s: Hc
# met its half-width at 9.25 s (0.039 mm, 10.1 dof); the angle's 1 s block means wander over
# 34.37-34.63 deg, so its half-width stayed at 0.060-0.069 deg from 7.5 to 9.25 s, and the rule's
# 0.0535 deg would take 4.6 s or more (12 h and up); benchmarks/drum_timestep.py states the power
# reached against it. (Lowering a cap keeps the committed segments: only the stop rule changes.)
cap=10 timestep 1.23e-6 tc81 0.25 0.1
timestep 5e-6 tc20 0.5 0.3
# The rest of the timestep ladder at 21 rpm (benchmarks/drum_timestep.py reads them against tc/81):
# exactRestitution at the coarsest step its guard admits (0.247 tc: 2.45e-5 s) and at tc/10, the
# plain law at tc/10 and tc/40 (study_thesis' own 21 rpm is exactRestitution's tc/5). (exactCollision
# needs `tangential pournin`, whose contact history a restart of these `history` states cannot
# carry: not run yet.)
ladder() {  # NAME DT EXACT SEGMENT SKIN [RPM]
  local rpm=${6:-21}
  steady --name "$1" --speeds "$rpm" --start-state "docs/drum/study_thesis/${rpm}rpm/state.restart.gz" \
    --var dt "$2" --var exact "$3" --var skin "$5" --segment "$4" --cap "${cap:-20}" "${power_rule[@]}"
}
ladder dt_exr_tc4 2.45e-5 on 2 0.3
ladder dt_exr_tc10 1e-5 on 1 0.3
ladder dt_tc10 1e-5 off 1 0.3
# study_thesis' averages to 10 effective degrees of freedom each: 23 of its 90 had fewer, all at
# 35-63 rpm, where the slowest metrics (the bed's turn, the wall's roll) need steady windows up to
# about 35 s (docs/drum/error_bars.md). Each speed is decided again under the estimator's rule with
# every metric held to 10 dof and, where that asks for more, runs on from its committed end state
# (--extend: the speeds after it, and the studies started from its states, stay valid; the chain's
# first line above still finds it committed). About 50 s simulated at tc/5: 10-12 hours. The
# table's rows then carry the estimator's own columns (tools/drum/rederive.py's page describes
# the table before the extension). The README's results, read from this table, are regenerated and
# committed with each speed (its check in the test suite would fail on a stale block).
steady --name study_thesis "${thesis[@]}" --segment 2 --cap 40 --rule obm --all-dof --extend \
  --refresh tools/readme_results.py README.md
# 42 rpm (the bed released, rolling on the wall): the plain law at tc/40 as the reference, tc/20, and
# study_thesis' exactRestitution tc/5. Its Hc swings 4 times more than at 21 rpm: the power rule's
# 0.0535 mm would take about 90 s simulated, so each stops at 8 s (benchmarks/drum_timestep.py
# states the power reached). Before the release study: with the 21 rpm ladder they complete the
# timestep comparison.
cap=8 ladder dt42_tc40 2.5e-6 off 0.5 0.2 42
cap=8 ladder dt42_tc20 5e-6 off 0.5 0.3 42
# The release study: where the bed lets go against the bead-drum friction (tools/drum/release.py,
# docs/drum/release.csv). First the 12 mm period (half the beads), along the thesis' chain from the
# grid (7 -> 14 -> 21 rpm: a grid start at 21 rpm can settle on rolling beads) to a carried 21 rpm
# (rel_L12_a), then the thesis' table ramped at 1.5 s per rpm as slip_thesis was; if it lets go
# within the 24 mm histories' interval the scan runs on 12 mm, else on 24 mm. Three start states
# two revolutions apart at 21 rpm (a: the chain's end state, b, c), then per mu (0.5, 0.65, 0.8,
# 0.95) a ramp from each at the thesis' 1.76 s per rpm (21 -> 28 rpm over 1e7 steps of 1.23 us),
# 22 rpm up to about 3 rpm past the release the slip test found.
release_ramp() {  # NAME START_STATE MU SPEEDS SECONDS PERIOD [steady.py options: later -var win]
  local name=$1 start=$2 mu=$3 speeds=$4 seconds=$5 period=$6
  shift 6
  steady --name "$name" --speeds "$speeds" --period "$period" --start-state "$start" "${thesis[@]}" --var bd_mu "$mu" \
    --segment "$seconds" --cap "$seconds" "$@"
}
steady --name rel_L12_a --speeds 7,14,21 --period 0.012 "${thesis[@]}" --segment 2 --cap 30 --rule obm
if ready docs/drum/rel_L12_a/21rpm/state.restart.gz; then
  release_ramp rel_L12_check docs/drum/rel_L12_a/21rpm/state.restart.gz 0.95 "$slip_speeds" 1.5 0.012
fi
if [[ ${#now[@]} -eq 0 ]]; then
  "$py" tools/drum/release.py || echo "campaign: the release table failed (above)"
  save "Drum: where the bed lets go, ramp by ramp" docs/drum/release.csv docs/drum/release.png docs/drum/release.md
fi
if scan=$("$py" tools/drum/release.py --scan-period); then
  if [[ "$scan" == 0.012 ]]; then first=rel_L12_a; else first=study_thesis; fi
  declare -A from=([a]="docs/drum/$first/21rpm/state.restart.gz" [b]=docs/drum/rel_b/21rpm/state.restart.gz
                   [c]=docs/drum/rel_c/21rpm/state.restart.gz)
  steady --name rel_b --speeds 21 --period "$scan" --start-state "${from[a]}" "${thesis[@]}" --segment 2.86 --cap 5.72
  if ready "${from[b]}"; then
    steady --name rel_c --speeds 21 --period "$scan" --start-state "${from[b]}" "${thesis[@]}" --segment 2.86 --cap 5.72
  fi
  for tag in 50 65 80 95; do
    case $tag in
      50) speeds=22,23,24,25,26,27,28,29,30,31 ;;
      65) speeds=22,23,24,25,26,27,28,29,30,31,32 ;;
      80) speeds=22,23,24,25,26,27,28,29,30,31,32,33 ;;
      95) speeds=22,23,24,25,26,27,28,29,30,31,32,33,34,35 ;;
    esac
    for h in a b c; do
      if ready "${from[$h]}"; then release_ramp "rel_mu${tag}_$h" "${from[$h]}" "0.$tag" "$speeds" 1.76 "$scan"; fi
    done
    if [[ ${#now[@]} -eq 0 ]]; then
      "$py" tools/drum/release.py || echo "campaign: the release table failed (above)"
      save "Drum: where the bed lets go, bead-drum mu up to 0.$tag" docs/drum/release.csv docs/drum/release.png docs/drum/release.md
    fi
  done
  # Holds (tools/drum/release.py, module note): does a bed held steady at one speed let go where the
  # ramps do? At mu 0.5 and 0.95, the fastest speed all three ramps ran through carried, from the
  # first ramp's state there, then the slowest none reached carried, from that hold's end state;
  # the power rule, at most 12 s each.
  for tag in 50 95; do
    if hold=$("$py" tools/drum/release.py --hold "0.$tag"); then
      read -r below above start <<< "$hold"
      steady --name "rel_mu${tag}_hold" --speeds "$below,$above" --period "$scan" --start-state "$start" \
        "${thesis[@]}" --var bd_mu "0.$tag" --segment 2 --cap 12 --rule obm
    fi
  done
  if [[ ${#now[@]} -eq 0 ]]; then
    "$py" tools/drum/release.py || echo "campaign: the release table failed (above)"
    save "Drum: where a bed held steady lets go" docs/drum/release.csv docs/drum/release.png docs/drum/release.md docs/drum/release_holds.csv
  fi
  # YADE's other conventions one at a time at mu 0.5 (one history, a's; beside rel_mu50_a..c): no
  # attraction, en 0.51, the tangential law the thesis prints (pournin: its contact histories start
  # afresh), and the facet mass m/2 (exactRestitution solves for the halved law, so at the scan's
  # own step and law). Then the wall as YADE saw it: the static mesh with a surface velocity
  # (a bead's tangential spring restarts at every facet) at mu 0.5 and 0.95.
  s50=22,23,24,25,26,27,28,29,30,31
  if ready "${from[a]}"; then
    release_ramp rel_mu50_cut_a "${from[a]}" 0.5 "$s50" 1.76 "$scan" --var attraction off
    release_ramp rel_mu50_en51_a "${from[a]}" 0.5 "$s50" 1.76 "$scan" --var bd_en 0.51
    release_ramp rel_mu50_pournin_a "${from[a]}" 0.5 "$s50" 1.76 "$scan" --var tangential pournin --fresh-start
    release_ramp rel_mu50_half_a "${from[a]}" 0.5 "$s50" 1.76 "$scan" --var facetmass half
    release_ramp rel_mu50_surface_a "${from[a]}" 0.5 "$s50" 1.76 "$scan" --var wall surface
    release_ramp rel_mu95_surface_a "${from[a]}" 0.95 22,23,24,25,26,27,28,29,30,31,32,33,34,35 1.76 "$scan" \
      --var wall surface
  fi
  # the surface mesh from the other two start states too: its release against the cylinder's with
  # the same three histories, not one ramp against three
  for h in b c; do
    if ready "${from[$h]}"; then
      release_ramp "rel_mu50_surface_$h" "${from[$h]}" 0.5 "$s50" 1.76 "$scan" --var wall surface
      release_ramp "rel_mu95_surface_$h" "${from[$h]}" 0.95 22,23,24,25,26,27,28,29,30,31,32,33,34,35 1.76 "$scan" \
        --var wall surface
    fi
  done
  if [[ ${#now[@]} -eq 0 ]]; then
    "$py" tools/drum/release.py || echo "campaign: the release table failed (above)"
    save "Drum: where the bed lets go, YADE's conventions one at a time" docs/drum/release.csv docs/drum/release.png docs/drum/release.md \
      docs/drum/release_holds.csv
  fi
fi
ladder dt_tc40 2.5e-6 off 0.5 0.2
# exactCollision on the drum (tangential pournin, which it needs: its contact histories start afresh
# from study_thesis' history state), at tc/5 and tc/10
for exc in "dt_exc_tc5 2e-5 2" "dt_exc_tc10 1e-5 1"; do
  read -r name step segment <<< "$exc"
  steady --name "$name" --speeds 21 --start-state docs/drum/study_thesis/21rpm/state.restart.gz --fresh-start \
    --var dt "$step" --var exact off --var collision on --var tangential pournin --segment "$segment" --cap 20 \
    "${power_rule[@]}"
done
# Does the speed at which the bed lets go move with the timestep? The thesis-table ramp again from
# 26 rpm's end state of slip_thesis (tc/5, exactRestitution), 27 -> 35 rpm at tc/20 with the plain
# law, 1.5 s per rpm as there (tools/drum/slip.py reads both).
steady --name slip_tc20 --speeds 27,28,29,30,31,32,33,34,35 --start-state docs/drum/slip_thesis/26rpm/state.restart.gz \
  --var dt 5e-6 --var exact off --segment 1.5 --cap 1.5
# study_yade's speeds under the estimator's stop rule (its 21 rpm, committed under the earlier rule,
# decided again and run on if that asks for more: --extend), so that its error bars are the same
# kind as the extended study_thesis' beside it
if ready docs/drum/study_yade/21rpm/state.restart.gz; then
  steady --name study_yade --speeds 21,28,35,42,49,56,63 --start-state docs/drum/study_thesis/21rpm/state.restart.gz \
    "${yade[@]}" --segment 2 --cap 40 --rule obm --extend
fi
if [[ ${#now[@]} -eq 0 ]]; then
  # each steady YADE speed against the thesis' table at the same speed (a difference: the set's, with
  # its timestep and restitution: histories.py lists the settings that differ)
  for rpm in 21 28 35; do
    if grep -q "^$rpm," docs/drum/study_yade.csv; then
      "$py" tools/drum/histories.py docs/drum/study_thesis.csv docs/drum/study_yade.csv --rpm "$rpm" --conventions \
        --out "docs/drum/conventions_${rpm}rpm.md" || true  # exits 1 where they differ: the answer, in the file
    fi
  done
  save "Drum: YADE's conventions against the thesis' table, steady speeds" docs/drum/conventions_{21,28,35}rpm.md
  "$py" tools/drum/thesis_trend.py || echo "campaign: the thesis' trend page failed (above)"
  save "Drum: the thesis' trend beside both steady studies" docs/drum/thesis_trend.md
fi
# The drum's wall at 21 rpm, steady, from the chain's 21 rpm state under the thesis' table with
# the same rule as 5: the rotating mesh (`wall moving`: facets that keep a contact's history) and
# the static mesh with a surface velocity (`wall surface`: a bead's tangential spring restarts at
# every facet it crosses), each against the chain's primitive cylinder (histories.py --settings:
# docs/drum/walls_21rpm_<wall>.md). The slip question is one of friction at the drum, where the
# wall's representation could matter; about 4 hours each (the mesh costs 1.27 times the cylinder).
# the drum's wall against the chain's primitive cylinder (a later --var wall overrides steady()'s)
wall() {
  against_chain "walls_$1" settings "docs/drum/walls_21rpm_$1.md" \
    "Drum: 21 rpm steady on the $1 wall against the primitive cylinder" \
    "${thesis[@]}" --var wall "$1" --segment 2 --cap 40
}
wall moving
wall surface
# Last (as far as compute allows), study_bound on to 63 rpm: from 14 rpm on a second history of
# each speed (each starts from a state study_thesis did not pass through), set against
# study_thesis with tools/drum/histories.py (docs/drum/histories_bound/).
steady "${bound[@]}"
if [[ ${#now[@]} -eq 0 ]]; then
  mkdir -p docs/drum/histories_bound
  both=()  # 7 rpm is one history in both (the same start and series)
  for rpm in 14 21 28 35 42 49 56 63; do
    if grep -q "^$rpm," docs/drum/study_bound.csv; then both+=("$rpm"); fi
  done
  # each speed's check, then all rows at once against chance, in one file
  if [[ ${#both[@]} -gt 0 ]]; then
    list=$(IFS=,; echo "${both[*]}")
    "$py" tools/drum/histories.py docs/drum/study_thesis.csv docs/drum/study_bound.csv --rpm "$list" \
      --out docs/drum/histories_bound/README.md > /dev/null \
      || echo "campaign: two histories of a speed disagree, or the comparison failed (docs/drum/histories_bound/README.md)"
  fi
  save "Drum: study_thesis against study_bound, speed by speed" docs/drum/histories_bound
fi
# Fig. 3.2-3.4 under YADE's rules, its two slowest speeds: the chain from the grid as the thesis' own
# (7 -> 14 rpm; study_yade runs 21 rpm on from the thesis' 21 rpm state)
steady --name study_yade_low --speeds 7,14 "${yade[@]}" --segment 2 --cap 60 --rule obm
if [[ ${#now[@]} -eq 0 ]]; then
  "$py" tools/drum/thesis_trend.py || echo "campaign: the thesis' trend page failed (above)"
  save "Drum: the thesis' trend beside both steady studies" docs/drum/thesis_trend.md
fi
