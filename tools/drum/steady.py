#!/usr/bin/python3
"""The thesis study to steady state: each speed of the chain runs until its time averages reach target standard errors, and is committed with its end state as soon as it is done.

The chain (section 3.4.2): the slowest speed starts from the grid (or --start-state), each
faster one from the committed end state of the one before. A speed runs in segments of --segment simulated seconds
(restart-chained, so an interrupted speed resumes from its last segment; once settled, a segment
ends where --min-batches revolutions, then one more, fit after the steady start: the earliest the
verdict can be 'done'); after each segment
`drum_metrics steady` decides: the metrics have settled (MSER) and the averages after the steady
start, by batch means over whole drum revolutions, have standard errors within --target (default
Hc 0.3 mm, angle 0.3 deg) with at least --min-batches batches. A speed that reaches --cap
simulated seconds stops there, flagged. With --rule obm the error bars are tools/drum/estimator.py's
instead (overlapping batch means, batch length from the series): the speed is done where each
target metric has 10 effective degrees of freedom or more over the whole steady window and its
standard error times t(0.975, 10) (its 95 % half-width at 10 dof) is within --target, and its
row holds the estimator's means, standard errors, half-widths (<key>_hw95_<unit>) and degrees of
freedom (<key>_dof) for every metric. Then, for the speed: the time series and averages
(`drum_metrics series`), a ParaView picture, the end state (compressed restart), the settings and
the cost go to docs/drum/NAME/<rpm>rpm/, its row to docs/drum/NAME.csv, the study's report
(tools/drum/report.py) to docs/drum/NAME.md and .png, and with --commit the driver commits them.
Rerunning the command continues from what is committed (and from the segments in post/NAME/ of a
speed in progress); a committed speed with other settings stops it. A checkpoint or segment of
the same trajectory (period, -var settings, segment and settle) is resumed when only the stop rule
changed (targets, cap, rule): the new rule decides from there. With --extend, so is a committed
speed: decided again under this rule from its committed series and, where the rule asks for more,
run on from its committed end state (its series and state extended, as if it had run longer in the
first place). The speeds after it, and other studies started from one of its committed states,
stay valid: run.json lists the earlier end states (`earlier_states_sha256`), points of the same
steady flow.

A speed can outlast a working day (7 rpm: five revolutions are 43 s simulated, hours of the
machine). Every --checkpoint-minutes of wall time (and with --checkpoint-now, at once) the speed
in progress is checkpointed to docs/drum/NAME/<rpm>rpm/partial/: its last segment's end state, the
per-snapshot metrics so far (drum_metrics' cache: the snapshots themselves stay in post/) and its
progress, committed with --commit. A rerun on a fresh clone, without post/, goes on from there.

  tools/drum/steady.py --name study_thesis --period 0.024 --var dt 2e-5 --var exact on --commit
  tools/drum/steady.py --name tiny --speeds 21,28 --var fill 0.05 --segment 0.02 --cap 0.06 --settle 0.02
"""

import gzip
import hashlib
import math
import shlex
import shutil
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness  # noqa: E402
import chain  # noqa: E402
import report  # noqa: E402
import study  # noqa: E402
import estimator  # noqa: E402

WHO = "steady"
DEFAULT_TARGETS = {"Hc": 3e-4, "angle": 0.3}  # [m], [deg]: the default targets
CONFIDENCE = 0.95  # --rule obm's intervals
# docs/drum/NAME.csv: one row per speed (the metrics' value and standard-error columns follow)
TABLE = ["rpm", "conventions", "wall", "period_m", "beads", "dt_s", "settle_s", "average_s", "revolutions",
         "batches", "done", "cpu_hours"]


def revolution(rpm):
    """One drum revolution [s]: the batch length of the time averages."""
    return 60.0 / rpm


def parse_targets(pairs):
    """["Hc=0.0003", ...] -> {"Hc": 0.0003, ...}; none -> the defaults."""
    targets = {}
    for p in pairs or []:
        key, _, value = p.partition("=")
        try:
            targets[key] = float(value)
        except ValueError:
            raise chain.PlanError(f"--target {p}: expected KEY=VALUE, e.g. Hc=0.0003") from None
        if targets[key] <= 0:
            raise chain.PlanError(f"--target {p}: must be > 0")
    return targets or dict(DEFAULT_TARGETS)


# What a speed's trajectory depends on; the rest of the settings (targets, cap, rule) only decide
# where it stops, so a checkpoint stays usable when they change.
TRAJECTORY = ("period", "variables", "segment", "settle", "fresh_start")


def trajectory(settings):
    return {k: settings.get(k) for k in TRAJECTORY}


def settings_of(args):
    """What makes two runs of a speed comparable: a committed speed with other settings is not
    this study's."""
    settings = {"period": args.period, "variables": args.variables, "segment": args.segment, "cap": args.cap,
                "settle": args.settle, "targets": args.targets, "min_batches": args.min_batches}
    if args.confidence > 0:  # absent otherwise: studies committed before the option stay comparable
        settings["confidence"] = args.confidence
    if args.rule != "revolutions":  # likewise
        settings["rule"] = args.rule
    if args.fresh_start:
        settings["fresh_start"] = True
    if args.all_dof:
        settings["all_dof"] = True
    return settings


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def states_of(record):
    """The end states a committed speed has had: its state now and, where it was extended, the
    earlier ones (a successor started from any of them follows the same steady flow)."""
    return {record["state_sha256"], *record.get("earlier_states_sha256", [])}


def plan(speeds, committed, settings, force=False, first_state=None, extend=False):
    """Which speeds to run. `committed`: {rpm: its run.json or None}. A speed counts as done if
    committed with these settings and started from a state its predecessor has had (`states_of`;
    for the first speed `first_state`, the hash of --start-state or a set of such hashes, None for
    the grid), so redoing one speed redoes every faster one. A speed committed with other
    settings stops the study (PlanError naming it) unless `force`, or, with `extend`, where only
    the stop rule differs (`TRAJECTORY` the same), is to be extended ("extend"): decided again
    under this rule and run on from its end state. A speed extended since is done for the
    settings it was committed under before (`earlier_settings`: it holds all their series and
    more). Returns [(rpm, True | False | "extend")]."""
    out = []
    previous = first_state if isinstance(first_state, (set, frozenset)) else {first_state}
    for rpm in speeds:
        c = committed.get(rpm)
        same_flow = c is not None and c["start_state_sha256"] in previous
        ours = c is not None and (c["settings"] == settings or settings in c.get("earlier_settings", []))
        extensible = extend and same_flow and trajectory(c["settings"]) == trajectory(settings)
        if c is not None and not ours and not force and not extensible:
            changed = sorted(k for k in set(c["settings"]) | set(settings)
                             if c["settings"].get(k) != settings.get(k))
            hint = (" (or --extend: only its stop rule differs)" if same_flow and not extend
                    and trajectory(c["settings"]) == trajectory(settings) else "")
            raise chain.PlanError(f"{rpm} rpm is committed with other settings ({', '.join(changed)}); "
                                  f"use another --name, or --force to redo it{hint}")
        done = same_flow and (ours or ("extend" if extensible else False))
        out.append((rpm, done))
        previous = states_of(c) if done else {"pending"}
    return out


def counted(row, t_end, rpm, snapshot):
    """(snapshots per batch, snapshots from the steady start to `t_end`) as `drum_metrics steady`
    counts them: batches of round(revolution / snapshot) snapshots back from the end of the
    series; None before the series has settled (no steady start yet). `row`: the last
    `drum_metrics steady` row."""
    start = float(row["steady_from_s"])
    if row["settled"] not in (1.0, "1", "true", True) or not math.isfinite(start):
        return None
    return max(1, round(revolution(rpm) / snapshot)), round((t_end - start) / snapshot) + 1


def next_length(row, t_end, rpm, segment, min_batches, snapshot):
    """Simulated seconds of the next segment: `segment`, or less where the minimum of batches can
    be met sooner: once settled, the segment ends where min_batches batches (`counted`) fit, then
    one more (the earliest a verdict can be 'done'), and is at least one snapshot."""
    if (count := counted(row, t_end, rpm, snapshot)) is None:
        return segment
    batch, have = count
    want = max(min_batches, have // batch + 1)
    return min(segment, max(want * batch - have, 1) * snapshot)


def still_needed(row, t_end, rpm, min_batches, snapshot):
    """Simulated seconds still needed, at least, for min_batches whole batches after the steady
    start (`counted`; the error targets may need more); nan before the series has settled."""
    if (count := counted(row, t_end, rpm, snapshot)) is None:
        return float("nan")
    batch, have = count
    return max(min_batches * batch - have, 0) * snapshot


def progress_note(still, loops, dt, rule="revolutions"):
    """What a segment's line says of the time left: the simulated seconds still needed at least and
    their wall time at this speed's rate so far (its segments' LIGGGHTS loop times)."""
    what, met = (("for the minimum of batches", "enough batches; the error targets decide") if rule == "revolutions"
                 else ("for the half-widths", "the half-widths meet their targets; the effective degrees of "
                                              "freedom decide"))
    if not math.isfinite(still):
        return "not settled yet"
    if still <= 0:
        return met
    steps = sum(lp["steps"] for lp in loops)
    if not steps:
        return f"at least {still:.3g} s simulated more"
    per_second = sum(lp["loop_s"] for lp in loops) / (steps * dt)
    return (f"at least {still:.3g} s simulated more {what}, about "
            f"{still * per_second / 60:.0f} min at this speed's {per_second / 60:.1f} min per simulated second")


def verdict(row, simulated, cap):
    """After a segment: 'done' (settled, enough batches, errors within target), 'capped' (the
    cap is reached first) or 'continue'."""
    if row["done"] in (1.0, "1", "true", True):
        return "done"
    return "capped" if simulated >= cap - 1e-9 else "continue"


def obm_columns(row, snapshots, steady_from, snapshot, metrics):
    """--rule obm: a finished speed's row takes, for every metric (`harness.drum_metric_table()`),
    the estimator's mean, standard error, 95 % half-width (<key>_hw95_<unit as its column spells
    it>) and effective dof over the whole steady window, in place of the batch means. A speed
    capped before it settled has no steady window: its row keeps the batch means."""
    if not math.isfinite(steady_from):
        return row
    intervals = estimator.window_intervals(snapshots, steady_from, snapshot, {m["key"]: m["column"] for m in metrics},
                                           CONFIDENCE)
    row["batches"] = float("nan")
    for m in metrics:
        iv = intervals[m["key"]]
        row[m["column"]], row[m["se_column"]] = iv.mean, iv.se
        unit = m["column"].rsplit("_", 1)[1]  # (m/s: mps)
        row[f"{m['key']}_hw95_{unit}"], row[f"{m['key']}_dof"] = iv.half_width, iv.dof
    return row


def at_min_dof(iv):
    """The 95 % half-width the interval would have at MIN_DOF degrees of freedom: its standard error
    times t(0.975, MIN_DOF). Held to a target, it bounds the standard error, so the power a target
    was chosen for (estimator.half_width_for_power, at MIN_DOF) holds at any dof above it; the
    half-width itself would allow a larger error at more dof (80 % at 10, 74 % at many)."""
    return iv.se * float(estimator.stats.t.ppf(0.5 + CONFIDENCE / 2.0, estimator.MIN_DOF))


def obm_verdict(intervals, targets, simulated, cap):
    """--rule obm, after a segment: 'done' where every metric of `intervals` (the targets', with
    --all-dof every metric's) has MIN_DOF effective degrees of freedom or more and each target
    metric's half-width at MIN_DOF (at_min_dof) is within its target, else 'capped' or 'continue'."""
    if intervals and all(iv.dof >= estimator.MIN_DOF and (k not in targets or at_min_dof(iv) <= targets[k])
                         for k, iv in intervals.items()):
        return "done"
    return "capped" if simulated >= cap - 1e-9 else "continue"


def obm_still_needed(intervals, targets, averaged):
    """Simulated seconds still needed, about: for the half-widths to reach their targets (they fall
    as the square root of the time averaged), and for MIN_DOF degrees of freedom at each metric's
    batch length (obm_dof: 1.5 (n/b - 1)); nan before the series has settled."""
    ratios = [(at_min_dof(iv) / targets[k]) ** 2 for k, iv in intervals.items() if k in targets]
    if not ratios or not averaged > 0 or not all(math.isfinite(r) for r in ratios):
        return float("nan")
    dof = [iv.batch_seconds * (1.0 + estimator.MIN_DOF / 1.5) - averaged for iv in intervals.values()
           if iv.dof < estimator.MIN_DOF and math.isfinite(iv.batch_seconds)]
    return max([averaged * (max(ratios) - 1.0), 0.0, *dof])


def pack(src, dst):
    """gzip `src` to `dst` (whole or not at all), with a fixed header time and no file name (the
    temporary file's would differ each time): the same state packs to the same bytes, so git
    stores it once."""
    with harness.whole(dst) as tmp, open(src, "rb") as f, open(tmp, "wb") as raw, \
            gzip.GzipFile(filename="", fileobj=raw, mode="wb", compresslevel=9, mtime=0) as z:
        shutil.copyfileobj(f, z)


def unpack(src, dst):
    """gunzip `src` to `dst` (whole or not at all)."""
    with harness.whole(dst) as tmp, gzip.open(src, "rb") as f, open(tmp, "wb") as out:
        shutil.copyfileobj(f, out)


def trim_cache(src, dst, last_step):
    """drum_metrics' metrics cache `src` (first column: the step) without the snapshots after
    `last_step` (those of a segment that was not recorded), written to `dst`."""
    lines = Path(src).read_text().splitlines(keepends=True)
    kept = lines[:1] + [line for line in lines[1:] if line.strip() and int(line.split(",", 1)[0]) <= last_step]
    with harness.whole(dst) as tmp:
        tmp.write_text("".join(kept))


def commit(message, *paths, tries=10):
    """Commits these paths only (whatever else is staged stays staged); retries while another git
    process holds the index, so a study can run beside other work in the same repository."""
    for k in range(tries):
        add = subprocess.run(["git", "add", *map(str, paths)], cwd=harness.REPO, capture_output=True, text=True)
        if add.returncode == 0 and subprocess.run(["git", "diff", "--cached", "--quiet", "--", *map(str, paths)],
                                                  cwd=harness.REPO).returncode == 0:
            return  # already committed as it is (a checkpoint asked for right after the driver's own)
        r = add if add.returncode else subprocess.run(
            ["git", "commit", "-q", "-m", message, "--", *map(str, paths)], cwd=harness.REPO,
            capture_output=True, text=True)
        if r.returncode == 0:
            return
        if "index.lock" not in r.stderr or k == tries - 1:
            raise subprocess.CalledProcessError(r.returncode, r.args, r.stdout, r.stderr)
        time.sleep(5)


class Study:
    def __init__(self, args):
        self.args = args
        self.work = harness.REPO / "post" / args.name
        self.docs = Path(args.docs).resolve() / args.name
        self.settings = settings_of(args)
        self.dt = float(args.variables.get("dt") or study.drum_default("dt"))
        self.dumpdt = float(args.variables.get("dumpdt") or study.drum_default("dumpdt"))

    def first_state(self):
        """--start-state unpacked into post/ (or None: the grid) and its hash (of the file as given)."""
        given = self.args.start_state
        if not given:
            return None, None
        given = Path(given).resolve()
        if given.suffix != ".gz":
            return given, sha256(given)
        plain = self.work / ("start_" + given.stem)
        plain.parent.mkdir(parents=True, exist_ok=True)
        if not plain.exists() or plain.stat().st_mtime < given.stat().st_mtime:
            unpack(given, plain)
        return plain, sha256(given)

    def first_states(self, first_sha):
        """The hashes a first speed may have started from: --start-state's, and where it is a
        study's committed end state that was extended since, its earlier ones (`states_of`)."""
        if not self.args.start_state:
            return {first_sha}
        record = Path(self.args.start_state).resolve().parent / "run.json"
        if record.exists() and (r := harness.read_json(record)).get("state_sha256") == first_sha:
            return states_of(r)
        return {first_sha}

    def committed(self, rpm):
        p = self.docs / f"{rpm}rpm" / "run.json"
        return harness.read_json(p) if p.exists() else None

    def prefix(self, rpm):
        return self.work / f"{rpm}rpm"

    def forget(self, rpm):
        """Removes the speed's files from post/: segments, snapshots, metrics cache, progress."""
        for f in self.work.glob(f"{rpm}rpm[_.]*"):
            f.unlink()

    def start_of(self, previous, first, first_sha):
        """Where a speed starts and that state's hash: the committed end state of the speed before
        it (unpacked into post/), or for the first speed the --start-state (None: the grid)."""
        if previous is None:
            return first, first_sha
        return self.state(previous), self.committed(previous)["state_sha256"]

    def checkpoint_now(self, steps, first, first_sha):
        """--checkpoint-now: each speed in progress whose record in post/ belongs to this study
        (these settings, started from its predecessor's committed state)."""
        previous, previous_done = None, True
        for rpm, done in steps:
            progress = self.work / f"{rpm}rpm_progress.json"
            if done is not True and previous_done and progress.exists():
                if done == "extend":
                    start, start_sha = self.extension_start(rpm), self.committed(rpm)["start_state_sha256"]
                else:
                    start, start_sha = self.start_of(previous, first, first_sha)
                record = harness.read_json(progress)
                if (record["state"] and trajectory(record["settings"]) == trajectory(self.settings)
                        and record["start"] == str(start)
                        and record.get("start_sha256", start_sha) == start_sha):
                    try:
                        self.checkpoint(rpm, {**record, "start_sha256": start_sha})
                    except FileNotFoundError:  # a running study moved on to its next segment meanwhile
                        self.checkpoint(rpm, {**harness.read_json(progress), "start_sha256": start_sha})
            previous, previous_done = rpm, done is not False

    def cache(self, rpm):
        """drum_metrics' per-snapshot metrics of the speed so far (all its segments)."""
        return self.work / f"{rpm}rpm_metrics_cache.csv"

    def partial(self, rpm):
        """The committed checkpoint of a speed in progress."""
        return self.docs / f"{rpm}rpm" / "partial"

    def checkpoint(self, rpm, done):
        """The speed's last recorded segment into partial/ (committed with --commit): the state
        under its segment's name, then the metrics cache, and last the progress record naming
        them, so an interruption leaves the previous checkpoint whole. A speed that has reached
        its verdict is not checkpointed: it is finished where its snapshots are."""
        if done.get("outcome", "continue") != "continue":
            harness.say(WHO, f"{rpm} rpm has reached its verdict ({done['outcome']}): rerun the study here to "
                             "finish it (its picture needs the snapshots in post/)")
            return
        part = self.partial(rpm)
        part.mkdir(parents=True, exist_ok=True)
        name = f"state_seg{done['segments']}.restart.gz"
        pack(done["state"], part / name)
        if not self.cache(rpm).exists():
            self.check(rpm)  # measures the snapshots into the cache
        trim_cache(self.cache(rpm), part / "metrics_cache.csv", done["last_step"])
        harness.write_json(part / "progress.json", {**done, "state": name})
        for old in part.glob("state_seg*.restart.gz"):
            if old.name != name:
                old.unlink()
        if self.args.commit:
            commit(f"Drum study {self.args.name}: {rpm} rpm checkpoint ({done['simulated_s']:g} s simulated, "
                   f"{done['segments']} segments)", part)
        harness.say(WHO, f"{rpm} rpm: checkpoint of segment {done['segments']} in {part}"
                         f"{' (committed)' if self.args.commit else ''}")

    def restore(self, rpm, start, start_sha, local):
        """The committed checkpoint of this speed, if it belongs to this start and these settings
        and is further on than the segments in post/: unpacked into post/ (returns its progress),
        else `local`."""
        part = self.partial(rpm)
        if not (part / "progress.json").exists():
            return local
        saved = harness.read_json(part / "progress.json")
        if trajectory(saved["settings"]) != trajectory(self.settings) or saved.get("start_sha256") != start_sha:
            harness.say(WHO, f"{rpm} rpm: the checkpoint in {part} is of other settings or another start state: "
                             "not used")
            return local
        if local and local["segments"] >= saved["segments"]:
            return local
        self.forget(rpm)
        state = self.work / f"{rpm}rpm_seg{saved['segments']}.restart"
        unpack(part / saved["state"], state)
        trim_cache(part / "metrics_cache.csv", self.cache(rpm), saved["last_step"])
        done = {**saved, "settings": self.settings, "start": str(start), "state": str(state)}
        harness.write_json(self.work / f"{rpm}rpm_progress.json", done)
        harness.say(WHO, f"{rpm} rpm: resuming from the checkpoint in {part} (segment {saved['segments']}, "
                         f"{saved['simulated_s']:g} s simulated)")
        return done

    def state(self, rpm):
        """The committed end state of a speed, unpacked into post/ (LIGGGHTS reads plain files)."""
        packed = self.docs / f"{rpm}rpm" / "state.restart.gz"
        plain = self.work / f"{rpm}rpm_committed.restart"
        plain.parent.mkdir(parents=True, exist_ok=True)  # a fresh clone has no post/<name> yet
        if not plain.exists() or plain.stat().st_mtime < packed.stat().st_mtime:
            unpack(packed, plain)
        return plain

    def segment(self, rpm, k, start, seconds):
        a = self.args
        variables = {**a.variables, "rpm": rpm, "period": a.period, "time": f"{seconds:.10g}",
                     "name": f"{a.name}/{rpm}rpm"}
        variables.update({"start": "restart", "restart": start} if start else {"start": "grid"})
        if a.fresh_start and start and k == 1 and rpm == a.speeds[0]:
            variables["history"] = "fresh"  # the start state's contact histories are other models'
        harness.say(WHO, f"{rpm} rpm, segment {k}: {seconds:g} s from {start.name if start else 'the grid'} ...")
        log = harness.drum(self.work / f"{rpm}rpm_seg{k}.log", np=a.np, **variables)
        # one run of the segment's steps, or the record (time, CPU, loops) would not match the series
        # as drum.in counts them: round(time/dt) in LIGGGHTS rounds halves up
        asked = math.floor(float(f"{seconds:.10g}") / self.dt + 0.5)
        ran = [steps for steps, _ in log.runs]
        if ran != [asked]:
            raise harness.RunFailed(f"{log.path}: runs of {ran} steps, "
                                    f"the segment asked for one of {asked}")
        return log

    def check(self, rpm):
        args = ["steady", "--prefix", self.prefix(rpm), "--dt", self.dt, "--rpm", rpm, "--cache", self.cache(rpm),
                "--batch-seconds", f"{revolution(rpm):.10g}", "--min-batches", self.args.min_batches]
        if self.args.confidence > 0:
            args += ["--confidence", f"{self.args.confidence:g}"]
        for key, value in self.args.targets.items():
            args += ["--target", f"{key}={value:g}"]
        return harness.read_csv_text(harness.tool("drum_metrics", *args))[0]

    def intervals(self, rpm, row):
        """--rule obm: each target metric's 95 % interval (tools/drum/estimator.py), with --all-dof
        every metric's, over the snapshots from the steady start (`drum_metrics steady`'s) to the
        last; {} before the series has settled."""
        start = float(row["steady_from_s"])
        if row["settled"] not in (1.0, "1", "true", True) or not math.isfinite(start):
            return {}
        columns = {m["key"]: m["column"] for m in harness.drum_metric_table()}
        keys = [*self.args.targets, *(k for k in columns if self.args.all_dof and k not in self.args.targets)]
        return estimator.window_intervals(harness.read_csv(self.cache(rpm)), start, self.dumpdt,
                                          {k: columns[k] for k in keys}, CONFIDENCE)

    def decide(self, rpm, simulated):
        """(verdict, the drum_metrics steady row, --rule obm's intervals or None) of the speed's series
        as it is."""
        row = self.check(rpm)
        if self.args.rule != "obm":
            return verdict(row, simulated, self.args.cap), row, None
        intervals = self.intervals(rpm, row)
        return obm_verdict(intervals, self.args.targets, simulated, self.args.cap), row, intervals

    def extension_start(self, rpm):
        """What a speed's extension records as its start (`run_speed`'s `start`): its committed end
        state (the extension runs on from its own end state, not from its predecessor's)."""
        return self.docs / f"{rpm}rpm" / "state.restart.gz"

    def from_committed(self, rpm, base, start, start_sha):
        """A committed speed to be extended (`base`: its run.json) as a progress record in post/:
        its end state as its last segment's, its series as the metrics cache (each snapshot's step
        from its time; the values to the series' 10 digits) and its counts, decided under this
        rule; `extends_sha256` names the end state it grows from (a record of another extension
        is not resumed)."""
        out = self.docs / f"{rpm}rpm"
        if sha256(out / "state.restart.gz") != base["state_sha256"]:
            raise chain.PlanError(f"{out / 'state.restart.gz'} is not the end state its run.json records: an "
                                  "interrupted write? Restore both from git before extending the speed")
        self.forget(rpm)
        self.work.mkdir(parents=True, exist_ok=True)
        state = self.work / f"{rpm}rpm_seg{base['segments']}.restart"
        unpack(out / "state.restart.gz", state)
        header, *lines = [line for line in (out / "series_metrics.csv").read_text().splitlines() if line.strip()]
        steps = [round(float(line.split(",", 1)[0]) / self.dt) for line in lines]
        with harness.whole(self.cache(rpm)) as tmp:
            tmp.write_text("".join(f"{k},{line}\n" for k, line in zip(["step", *steps], [header, *lines])))
        outcome, _, _ = self.decide(rpm, base["simulated_s"])
        done = {"settings": self.settings, "start": str(start), "start_sha256": start_sha,
                "extends_sha256": base["state_sha256"], "segments": base["segments"],
                "simulated_s": base["simulated_s"], "cpu_s": base["cpu_s"], "beads": base["beads"],
                "loops": list(base.get("loops", [])), "last_step": max(steps), "state": str(state), "outcome": outcome}
        harness.write_json(self.work / f"{rpm}rpm_progress.json", done)
        harness.say(WHO, f"{rpm} rpm: the committed speed ({base['segments']} segments, {base['simulated_s']:g} s "
                         f"simulated, {base['outcome']}) decided again under this rule: {outcome}")
        return done

    def run_speed(self, rpm, start, start_sha, base=None):
        """Segments until the verdict; returns (verdict, progress record, end-state restart).
        After each segment its end state is copied to <rpm>rpm_seg<k>.restart and only then
        recorded in <rpm>rpm_progress.json: an interruption at any point resumes from a whole
        state, and snapshots written after it (by an interrupted segment) are removed. Without
        segments in post/ (a fresh clone) a committed checkpoint is the place to resume. `base`:
        the run.json of a committed speed to extend (`from_committed`), unless an extension of it
        in post/ or in a checkpoint is further on."""
        a = self.args
        self.work.mkdir(parents=True, exist_ok=True)
        progress = self.work / f"{rpm}rpm_progress.json"
        done = harness.read_json(progress) if progress.exists() else None
        if done and (trajectory(done["settings"]) != trajectory(self.settings) or done["start"] != str(start)
                     or done.get("start_sha256", start_sha) != start_sha):
            harness.say(WHO, f"{rpm} rpm: the segments in {self.work} are of other settings or another start "
                             "state: not resumed")
            done = None
        if base is not None and done and done.get("extends_sha256") != base["state_sha256"]:
            done = None  # another extension's, or a record from before the speed was committed
        done = self.restore(rpm, start, start_sha, done)
        if base is not None and (not done or done["segments"] < base["segments"]
                                 or done.get("extends_sha256") != base["state_sha256"]):
            done = self.from_committed(rpm, base, start, start_sha)
        if not done:
            self.forget(rpm)
            done = {"settings": self.settings, "start": str(start), "start_sha256": start_sha, "segments": 0,
                    "simulated_s": 0.0, "cpu_s": 0.0, "beads": 0, "last_step": -1, "state": None}
        done.setdefault("start_sha256", start_sha)
        for step, f in harness.snapshots(self.prefix(rpm)):
            if done["last_step"] >= 0 and step > done["last_step"]:
                f.unlink()
        if done["last_step"] >= 0 and self.cache(rpm).exists():
            trim_cache(self.cache(rpm), self.cache(rpm), done["last_step"])
        outcome = done.get("outcome", "continue")  # a verdict reached before an interruption stands ...
        row = None
        if outcome != "continue" and done.get("settings") != self.settings:
            # ... unless the stop rule changed since: decided again from the series as it is
            outcome, row, _ = self.decide(rpm, done["simulated_s"])
            done["outcome"] = outcome
            harness.say(WHO, f"{rpm} rpm: its verdict decided again under the changed stop rule: {outcome}")
        done["settings"] = self.settings
        while outcome == "continue":
            k = done["segments"] + 1
            grid = done["state"] is None and start is None
            seconds = a.segment + (a.settle if grid else 0.0)
            if done["segments"] > 0 and a.rule == "revolutions":
                # no longer than the next verdict needs (see next_length)
                snaps = harness.snapshots(self.prefix(rpm))
                if snaps:
                    seconds = next_length(row or self.check(rpm), snaps[-1][0] * self.dt, rpm, a.segment,
                                          a.min_batches, self.dumpdt)
            log = self.segment(rpm, k, None if grid else Path(done["state"] or start), seconds)
            state = self.work / f"{rpm}rpm_seg{k}.restart"
            shutil.copyfile(self.work / f"{rpm}rpm.restart", state)
            previous = done["state"]
            done.update(segments=k, simulated_s=done["simulated_s"] + seconds, cpu_s=done["cpu_s"] + log.cpu_seconds,
                        beads=log.atoms, last_step=harness.snapshots(self.prefix(rpm))[-1][0], state=str(state))
            # each segment's loop as LIGGGHTS timed it: the rate a speed runs at, kept with its results
            done.setdefault("loops", []).append({"steps": log.steps, "loop_s": log.loop_time,
                                                 "neighbor_builds": log.neighbor_builds})
            # The segment's snapshots go into the metrics cache before it counts as recorded: the
            # next segment rewrites the snapshot at its first step (the restart's), whose drum
            # forces differ by the restart's one-step perturbation; the cache keeps this one.
            outcome, row, intervals = self.decide(rpm, done["simulated_s"])
            done["outcome"] = outcome
            harness.write_json(progress, done)
            if previous:
                Path(previous).unlink(missing_ok=True)
            if outcome == "continue" and time.monotonic() - self.last_checkpoint >= 60 * a.checkpoint_minutes:
                self.checkpoint(rpm, done)
                self.last_checkpoint = time.monotonic()
            left = ""
            if intervals is None:
                errors = f"{row['batches']} batches, " + ", ".join(f"{c} {row[c]:.3g}" for c in row if "_se_" in c)
                still = still_needed(row, done["last_step"] * self.dt, rpm, a.min_batches, self.dumpdt)
            else:
                errors = ", ".join([f"{k} 95 % half-width {iv.half_width:.3g} ({iv.dof:.1f} dof)"
                                    for k, iv in intervals.items() if k in a.targets] +
                                   [f"{k} {iv.dof:.1f} dof" for k, iv in intervals.items()
                                    if k not in a.targets and iv.dof < estimator.MIN_DOF]) or "no interval yet"
                still = obm_still_needed(intervals, a.targets, done["last_step"] * self.dt - row["steady_from_s"])
            if outcome == "continue":
                left = f" ({progress_note(still, done['loops'], self.dt, a.rule)})"
            harness.say(WHO, f"{rpm} rpm: {done['simulated_s']:g} s simulated, settled {row['settled']}, "
                             f"{errors}: {outcome}{left}")
        return outcome, done, Path(done["state"])

    def finish(self, rpm, outcome, done, restart, start_sha, base=None):
        """Series, averages, picture and state of a finished speed into docs/, and its row. An
        extended speed (`base`: its run.json before) that ran no new segment keeps its files: its
        row and record are those of the new rule."""
        a = self.args
        out = self.docs / f"{rpm}rpm"
        out.mkdir(parents=True, exist_ok=True)
        if base is None or done["segments"] > base["segments"]:
            harness.drum_series(self.prefix(rpm), self.dt, rpm, out=out / "series",
                                batch_seconds=f"{revolution(rpm):.10g}", cache=self.cache(rpm))
            harness.render(self.prefix(rpm), out / "picture.png")
            pack(restart, out / "state.restart.gz")
        average = harness.read_csv(out / "series_average.csv")[0]
        steady_from = average["steady_from_s"]
        t_end = done["last_step"] * self.dt  # the last snapshot's
        # times are whole steps of dt: rounded to 1 ns so that a difference of two of them reads 0, not -7e-15
        averaged = round(t_end - steady_from, 9) if not math.isnan(steady_from) else float("nan")
        row = {"rpm": rpm, "conventions": a.variables.get("conventions", "thesis"),
               "wall": a.variables.get("wall") or study.drum_default("wall"), "period_m": float(a.period), "beads": done["beads"],
               "dt_s": self.dt, "settle_s": round(steady_from - (t_end - done["simulated_s"]), 9), "average_s": averaged,
               "revolutions": averaged / revolution(rpm), "batches": average.get("batches", float("nan")),
               "done": outcome == "done", "cpu_hours": done["cpu_s"] / 3600}
        for m in harness.drum_metric_table():
            row[m["column"]], row[m["se_column"]] = average[m["column"]], average[m["se_column"]]
        if a.rule == "obm":
            obm_columns(row, harness.read_csv(self.cache(rpm)), steady_from, self.dumpdt, harness.drum_metric_table())
        table = self.docs.with_suffix(".csv")
        rows = [r for r in (harness.read_csv(table) if table.exists() else []) if r["rpm"] != rpm]
        rows = sorted(rows + [row], key=lambda r: r["rpm"])
        harness.write_csv(table, rows, TABLE + [k for k in row if k not in TABLE])
        # run.json last: it marks the speed done (the plan reads it)
        record = {"rpm": rpm, "settings": self.settings, "outcome": outcome, "segments": done["segments"],
                  "simulated_s": done["simulated_s"], "cpu_s": done["cpu_s"], "beads": done["beads"],
                  "loops": done.get("loops", []), "start_state_sha256": start_sha,
                  "state_sha256": sha256(out / "state.restart.gz"),
                  "command": self.command, "date": time.strftime("%Y-%m-%d"), "machine": harness.machine()}
        if base is not None:
            if done["segments"] == base["segments"]:  # decided again, nothing run: where it ran stays
                record.update(date=base.get("date"), machine=base.get("machine"),
                              decided_again=time.strftime("%Y-%m-%d"))
            if earlier := sorted(states_of(base) - {record["state_sha256"]}):
                record["earlier_states_sha256"] = earlier  # where its successors may have started
            settings = [x for x in base.get("earlier_settings", []) + [base["settings"]] if x != self.settings]
            record["earlier_settings"] = [x for k, x in enumerate(settings) if x not in settings[:k]]
        harness.write_json(out / "run.json", record)
        shutil.rmtree(self.partial(rpm), ignore_errors=True)  # done: the checkpoint's removal is committed below
        written = report.write(a.name, self.docs.parent) + self.refreshed()  # with this speed in them
        if a.commit:
            commit(f"Drum study {a.name}: {rpm} rpm ({outcome}, {done['simulated_s']:g} s simulated)", out, table,
                   *written)
        harness.say(WHO, f"{rpm} rpm {outcome}: wrote {out}"
                         f"{' and committed' if a.commit else ''}")

    def under_way(self, rpm):
        """What is recorded of a speed in progress, for the plan: its segments in post/ or its
        committed checkpoint, whichever is further on ('' if neither)."""
        records = [harness.read_json(f) for f in (self.work / f"{rpm}rpm_progress.json",
                                                  self.partial(rpm) / "progress.json") if f.exists()]
        if not records:
            return ""
        r = max(records, key=lambda x: x["segments"])
        return f" (under way: {r['simulated_s']:g} s simulated)"

    def refreshed(self):
        """--refresh: runs each command; returns the files of those that succeeded."""
        files = []
        for command, path in self.args.refresh:  # files generated from the table (e.g. the README's results)
            r = subprocess.run(shlex.split(command), cwd=harness.REPO, capture_output=True, text=True)
            if r.returncode:
                harness.say(WHO, f"--refresh {command}: exit {r.returncode}, {path} not refreshed: "
                                 f"{(r.stdout + r.stderr).strip()[-500:]}")
            else:
                files.append(harness.REPO / path)
        return files

    def main(self):
        a = self.args
        self.command = "tools/drum/steady.py " + shlex.join(sys.argv[1:])
        self.last_checkpoint = time.monotonic()
        first, first_sha = self.first_state()
        steps = plan(a.speeds, {r: self.committed(r) for r in a.speeds}, self.settings, a.force,
                     self.first_states(first_sha), a.extend)
        if a.dry_run:
            harness.say(WHO, f"study {a.name}:")
        for rpm, done in steps:
            harness.say(WHO, f"plan: {rpm} rpm: {'to extend' if done == 'extend' else 'committed' if done else 'to run'}"
                             f"{self.under_way(rpm) if done is not True else ''}")
        if a.dry_run:
            return 0
        if a.checkpoint_now:
            self.checkpoint_now(steps, first, first_sha)
            return 0
        if a.commit:  # results an interrupted run wrote but did not commit
            paths = [self.docs.with_suffix(".csv")] + [self.docs / f"{r}rpm" for r, _ in steps]
            paths = [p for p in paths if p.exists()]
            status = subprocess.run(["git", "status", "--porcelain", "--", *map(str, paths)], cwd=harness.REPO,
                                    capture_output=True, text=True).stdout if paths else ""
            if status.strip():  # the report too: an interruption before finish() wrote it would leave it stale
                commit(f"Drum study {a.name}: results written before an interruption", *paths,
                       *report.write(a.name, self.docs.parent), *self.refreshed())
        previous = None
        for rpm, done in steps:
            if done is not True:
                began = time.monotonic()
                if done == "extend":
                    base = self.committed(rpm)
                    start, start_sha = self.extension_start(rpm), base["start_state_sha256"]
                else:
                    base = None
                    start, start_sha = self.start_of(previous, first, first_sha)
                outcome, record, restart = self.run_speed(rpm, start, start_sha, base)
                self.finish(rpm, outcome, record, restart, start_sha, base)
                harness.say(WHO, f"{rpm} rpm took {(time.monotonic() - began) / 60:.1f} min")
            previous = rpm
        return 0


def arguments(argv=None):
    p = harness.options(__doc__, np=2)
    p.add_argument("--name", default="study_thesis", help="docs/drum/NAME/ and post/NAME/ (default: %(default)s)")
    p.add_argument("--speeds", default="7,14,21,28,35,42,49,56,63", help="rpm, ascending (default: %(default)s)")
    p.add_argument("--period", default="0.024", help="axial period [m] (default: %(default)s, the thesis scene)")
    p.add_argument("--start-state", metavar="RESTART[.gz]",
                   help="the first speed starts from this state instead of the grid (e.g. the shipped "
                        "inputs/drum_L24_21rpm.restart.gz)")
    p.add_argument("--segment", type=float, default=1.0, help="simulated seconds per segment (default: %(default)s)")
    p.add_argument("--settle", type=float, default=2.0,
                   help="extra seconds of the first segment of a grid start (default: %(default)s)")
    p.add_argument("--cap", type=float, default=30.0, help="simulated seconds at most per speed (default: %(default)s)")
    p.add_argument("--target", action="append", metavar="KEY=SE",
                   help="standard error (--rule revolutions) or 95 %% half-width (--rule obm) to reach, per metric "
                        "key of `drum_metrics metrics` (repeatable; "
                        "default: Hc=0.0003 angle=0.3)")
    p.add_argument("--min-batches", type=int, default=5, help="batches (revolutions) at least (default: %(default)s)")
    p.add_argument("--confidence", type=float, default=0.0,
                   help="0: the standard errors as estimated must meet the targets; e.g. 0.95: their 95 %% upper "
                        "confidence bound must (chi-square over the batches' degrees of freedom: 4.42 times the "
                        "estimate from 3 batches), which lets calm speeds stop at --min-batches 3 and keeps noisy "
                        "ones going (default: %(default)s)")
    p.add_argument("--rule", choices=("revolutions", "obm"), default="revolutions",
                   help="revolutions: batch means of whole revolutions (--min-batches, --confidence) must meet the "
                        "targets as standard errors; obm: tools/drum/estimator.py's intervals (overlapping batch "
                        "means, batch length from the series) over the steady window, at 10 effective degrees of "
                        "freedom at least, their standard errors times t(0.975, 10) within the targets "
                        "(default: %(default)s)")
    p.add_argument("--fresh-start", action="store_true",
                   help="the first segment from --start-state drops its contact histories (drum.in -var history "
                        "fresh): for contact models other than the state's, e.g. tangential pournin from a history state")
    p.add_argument("--var", nargs=2, action="append", metavar=("NAME", "VALUE"), default=[],
                   help="a drum.in -var for every run (repeatable), e.g. --var dt 2e-5 --var exact on")
    p.add_argument("--docs", default=str(harness.REPO / "docs" / "drum"),
                   help="where finished speeds go: DOCS/NAME/<rpm>rpm/ and DOCS/NAME.csv (default: docs/drum)")
    p.add_argument("--commit", action="store_true", help="git commit each speed as soon as it is done")
    p.add_argument("--force", action="store_true", help="redo speeds committed with other settings")
    p.add_argument("--extend", action="store_true",
                   help="a speed committed under another stop rule (targets, cap, rule, --all-dof; the same period, "
                        "-var settings, segment and settle) is decided again under this one and, where it asks for "
                        "more, runs on from its committed end state; the speeds after it stay committed")
    p.add_argument("--all-dof", action="store_true",
                   help="--rule obm: every metric's interval, not only the targets', must have 10 effective degrees "
                        "of freedom for a speed to be done")
    p.add_argument("--checkpoint-minutes", type=float, default=120.0,
                   help="checkpoint the speed in progress to docs/ after a segment once this many minutes of wall "
                        "time have passed since the last (default: %(default)s; 0: after every segment)")
    p.add_argument("--checkpoint-now", action="store_true",
                   help="checkpoint the speeds in progress from post/ (their last recorded segment) and stop")
    p.add_argument("--refresh", nargs=2, action="append", default=[], metavar=("COMMAND", "FILE"),
                   help="after each finished speed, run COMMAND (from the repository's root) and commit FILE, which "
                        "it regenerates from the study's table, with the speed (repeatable), e.g. "
                        "--refresh tools/readme_results.py README.md; a failure is reported, not fatal")
    p.add_argument("--dry-run", action="store_true", help="print the plan, run nothing")
    args = p.parse_args(argv)
    try:
        args.speeds = chain.parse_speeds(args.speeds)
        args.variables = chain.parse_vars(args.var)
        args.targets = parse_targets(args.target)
        if not 0.0 <= args.confidence < 1.0:
            raise chain.PlanError(f"--confidence {args.confidence}: must be in [0, 1)")
        if args.confidence > 0 and args.min_batches < 2:
            raise chain.PlanError(f"--min-batches {args.min_batches}: the SE bound needs 2 batches at least")
        if args.all_dof and args.rule != "obm":
            raise chain.PlanError("--all-dof: needs --rule obm")
        if args.segment <= 0 or args.cap < args.segment or args.settle < 0:
            raise chain.PlanError(f"--segment {args.segment} --cap {args.cap} --settle {args.settle}: "
                                  "need 0 < segment <= cap, settle >= 0")
    except chain.PlanError as e:
        p.error(str(e))
    return args


def main(argv=None):
    args = arguments(argv)
    try:
        return Study(args).main()
    except (harness.RunFailed, chain.PlanError, OSError, subprocess.CalledProcessError) as e:
        harness.say(WHO, f"ERROR: {e}")
        return 1


if __name__ == "__main__":
    sys.exit(main())
