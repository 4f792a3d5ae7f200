"""Options, the scene's constants, and launching LIGGGHTS and the project's tools."""

import argparse
import itertools
import os
import platform
import re
import shutil
import subprocess
import time
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]

# Binaries: an environment variable overrides (e.g. DRUM_METRICS=build/tools/drum/drum_metrics);
# otherwise PATH (setup.sh installs them to /usr/local/bin).
_ENV = {"liggghts": "LIGGGHTS", "drum_metrics": "DRUM_METRICS", "collide": "COLLIDE",
        "contact_law": "CONTACT_LAW", "drum_mesh": "DRUM_MESH"}


_copies = itertools.count()  # private input copies (threads may run several at once)


def _forget_copies():
    """Removes the input copies of drivers no longer alive (a killed driver leaves its copy)."""
    for f in (REPO / "post" / ".inputs").glob("*_*_*.*"):
        pid = f.stem.rsplit("_", 2)[-2]
        if pid.isdigit() and not Path(f"/proc/{pid}").exists():
            f.unlink(missing_ok=True)


class RunFailed(RuntimeError):
    """A LIGGGHTS run or a tool that exited non-zero; the message ends with its output's tail."""


def post(*parts):
    """A path under post/ (the scratch area of runs, not committed), its parent created."""
    p = REPO.joinpath("post", *map(str, parts))
    p.parent.mkdir(parents=True, exist_ok=True)
    return p


def tool_path(name):
    path = os.environ.get(_ENV.get(name, name.upper()), "") or shutil.which(name)
    if not path:
        raise RunFailed(f"{name} not found: run `bash setup.sh` (installs it) or set {_ENV.get(name, name.upper())}")
    return path


def tool(name, *args, check=True, cwd=None):
    """Runs a project binary (from the repository root, or `cwd`); returns its standard output."""
    try:
        r = subprocess.run([tool_path(name), *map(str, args)], cwd=cwd or REPO, capture_output=True, text=True)
    except OSError as e:  # e.g. a binary being relinked
        raise RunFailed(f"{name} could not be started: {e}") from e
    if check and r.returncode != 0:
        raise RunFailed(f"{name} {' '.join(map(str, args))} failed:\n{_tail(r.stdout + r.stderr)}")
    return r.stdout


def mpirun(np):
    """The launcher prefix for `np` ranks: Open MPI refuses root without a flag, and
    more ranks than cores need --oversubscribe. One rank runs without mpirun."""
    if np <= 1:
        return []
    cmd = ["mpirun", "-np", str(np)]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    if np > (os.cpu_count() or 1):
        cmd.append("--oversubscribe")
    return cmd


def liggghts(script, variables=None, log=None, np=1, check=True, launcher=()):
    """Runs `liggghts -in script -var NAME VALUE ...` from the repository root, output to `log`
    (default post/<script stem>.log), each rank under `launcher` if given (e.g. valgrind).
    Returns the Log. Raises RunFailed with the log's tail."""
    from .logs import Log
    log = Path(log) if log else post(Path(script).stem + ".log")
    log.parent.mkdir(parents=True, exist_ok=True)
    # LIGGGHTS reads its input as it goes (and `jump SELF` rewinds it): a script rewritten in place
    # during a run would be read on from a stale offset, rerunning or skipping commands. Each run
    # reads a private copy (its includes are read before the run starts).
    if not (REPO / script).is_file():
        raise RunFailed(f"{script}: no such input script")
    _forget_copies()
    private = post(".inputs", f"{Path(script).stem}_{os.getpid()}_{next(_copies)}{Path(script).suffix}")
    shutil.copyfile(REPO / script, private)
    cmd = mpirun(np) + [*launcher, tool_path("liggghts"), "-in", str(private)]
    for k, v in (variables or {}).items():
        cmd += ["-var", k, str(v)]
    try:
        with open(log, "w") as out:
            r = subprocess.run(cmd, cwd=REPO, stdout=out, stderr=subprocess.STDOUT)
    finally:
        private.unlink(missing_ok=True)
    if check and r.returncode != 0:
        shown = " ".join(str(script) if c == str(private) else c for c in cmd)  # the script, not its copy
        raise RunFailed(f"{shown} failed (log {log}):\n{_tail(log.read_text(errors='replace'))}")
    return Log(log, returncode=r.returncode)


def drum(log, np=2, check=True, **variables):
    """One inputs/drum.in run; `variables` are its -var overrides (name=..., rpm=..., ...)."""
    return liggghts("inputs/drum.in", variables, log=log, np=np, check=check)


def snapshots(prefix):
    """The bead files PREFIX_<step>.vtp of a run as [(step, path)], in step order."""
    prefix = Path(prefix)
    return sorted((int(m.group(1)), f) for f in prefix.parent.glob(prefix.name + "_*.vtp")
                  if (m := re.fullmatch(re.escape(prefix.name) + r"_(\d+)\.vtp", f.name)))


def last_snapshot(prefix):
    """PREFIX_<step>.vtp with the highest step."""
    files = snapshots(prefix)
    if not files:
        raise RunFailed(f"no snapshots {prefix}_<step>.vtp")
    return files[-1][1]


def machine():
    """What results were measured on: cores, architecture, CPU model, LIGGGHTS package version."""
    cpu = next((line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
                if line.startswith("model name")), platform.processor() or "?")
    r = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "liggghts"], capture_output=True, text=True)
    return {"cores": os.cpu_count(), "arch": platform.machine(), "cpu": cpu,
            "liggghts": r.stdout if r.returncode == 0 and r.stdout else "?"}


def render(prefix, out, *options, attempts=8):
    """A ParaView picture of a run's last snapshot (`xvfb-run -a pvbatch tools/drum/render.py`).
    pvbatch opens several X connections, and on a loaded machine one is now and then refused
    ("bad X server connection": 1 render in 6 to 1 in 2, also against an Xvfb up for minutes); two
    xvfb-run started at once can also pick the same display: a failure is retried, the last one raised."""
    for attempt in range(attempts):
        try:
            return tool("xvfb-run", "-a", "pvbatch", "tools/drum/render.py", prefix, "--out", out, *options)
        except RunFailed:
            if attempt == attempts - 1:
                raise
            time.sleep(1.0)


def drum_series(prefix, dt, rpm, out=None, skip=None, until=None, average=None, batch_seconds=None, cache=None):
    """`drum_metrics series` on a run's snapshots (options left out when None); returns its
    printed summary. It writes OUT_metrics.csv, OUT_average.csv and OUT_metrics.png (OUT:
    `out`, or the prefix)."""
    args = ["series", "--prefix", prefix, "--dt", dt, "--rpm", rpm]
    for option, value in (("--out", out), ("--skip", skip), ("--until", until), ("--average", average),
                          ("--batch-seconds", batch_seconds), ("--cache", cache)):
        if value is not None:
            args += [option, value]
    return tool("drum_metrics", *args)


def drum_metric_table():
    """The drum metrics as `drum_metrics metrics` lists them (key, column, se_column, unit, label,
    description): scripts show metrics from this table instead of listing them again."""
    import csv
    import io
    return list(csv.DictReader(io.StringIO(tool("drum_metrics", "metrics"))))  # text: the unit "1" stays "1"


def materials(path=None):
    """inputs/materials.in as {name: value}: its `variable NAME equal VALUE` lines."""
    path = Path(path) if path else REPO / "inputs" / "materials.in"
    values = {}
    for n, line in enumerate(path.read_text().splitlines(), 1):
        words = line.split("#", 1)[0].split()
        if not words:
            continue
        if len(words) != 4 or words[0] != "variable" or words[2] != "equal":
            raise ValueError(f"{path}:{n}: expected `variable NAME equal VALUE`, got: {line.strip()}")
        values[words[1]] = float(words[3])
    return values


def options(doc, **defaults):
    """argparse from a driver's docstring (first paragraph: description; the rest: epilog), with
    the common options a driver asks for: np, out, rounds, restart (pass their defaults)."""
    first, _, rest = (doc or "").strip().partition("\n\n")
    p = argparse.ArgumentParser(description=" ".join(first.split()), epilog=rest,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    common = {
        "np": (int, "MPI ranks"),
        "out": (Path, "where the results go"),
        "rounds": (int, "timed rounds, variants interleaved within each round"),
        "restart": (Path, "a settled drum state (restart file) to start from"),
    }
    for name, default in defaults.items():
        kind, text = common[name]
        p.add_argument("--" + name, type=kind, default=default, required=default is None,
                       help=f"{text} (default: {default})" if default is not None else text)
    return p


def say(who, text):
    """Progress line of a driver, flushed at once (long runs go to nohup logs)."""
    print(f"{who}: {text}", flush=True)


def _tail(text, lines=8):
    return "\n".join(text.rstrip().splitlines()[-lines:])


if __name__ == "__main__":
    sys.exit("harness is a library: import it from tools/ or benchmarks/ drivers")
