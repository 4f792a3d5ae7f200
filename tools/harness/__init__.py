"""The one harness every study driver and benchmark uses.

- options:   `options(doc)` - argparse with the project's common options
- running:   `liggghts(...)`, `drum(...)`, `tool(...)` - LIGGGHTS serial or under
             mpirun, the project's binaries; a failed run raises RunFailed with
             its log's tail
- logs:      `Log(path)` - loop time, steps, atoms, per-rank bead counts
- timing:    `interleaved(...)` - timed rounds, variants interleaved
             (A B C A B C ...), with `median`, `spread`, `median_ratio`
- tables:    `read_csv` / `write_csv` (columns by name), `markdown(...)`,
             `whole(path)` - write through a temporary file, replace at the end
- charts:    `figure(...)` - matplotlib, headless
- facts:     `materials()` - inputs/materials.in, the one file of Table 3.1
             and the scene constants
- docs:      `generated_note(command)` - the line that opens every generated
             document

Derived physics is never computed here: ask a binary (`contact_law`,
`collide`, `drum_metrics`).
"""

from .core import (REPO, RunFailed, drum, drum_metric_table, drum_series, last_snapshot, liggghts, machine, materials, mpirun, options, post, render, say, snapshots,
                   tool, tool_path)
from .logs import Log
from .rounds import interleaved, median, median_ratio, spread
from .tables import generated_note, markdown, read_csv, read_csv_text, whole, write_csv, write_json, read_json
from .charts import figure, save

__all__ = [
    "REPO", "RunFailed", "drum", "drum_metric_table", "drum_series", "last_snapshot", "liggghts", "machine", "materials", "mpirun", "options", "post", "render", "say", "snapshots", "tool",
    "tool_path", "Log", "interleaved", "median", "median_ratio", "spread", "generated_note", "markdown",
    "read_csv", "read_csv_text", "whole", "write_csv", "write_json", "read_json", "figure", "save",
]
