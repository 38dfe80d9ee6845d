#!/usr/bin/env python3
"""Prints docs/accuracy.md's per-level table from a study's summary.md.

    python3 tools/accuracy_doc_table.py docs/figures/accuracy/summary.md

The table joins two of summary.md's tables, row by row on the level's name: "Cheapest setting
that meets each level's tolerance" (the setting, its cost, rapier's defaults) and "Declared
effects against all effects" (all / declared). Nothing is recomputed, so the page cannot say
what the study did not.
"""

import sys


def table(lines, heading):
    """The rows (lists of cells) of the first table after `heading`."""
    start = lines.index(heading)
    rows = []
    for line in lines[start + 1:]:
        if line.startswith("## "):
            break
        if line.startswith("|") and not line.startswith("|---"):
            rows.append([c.strip() for c in line.strip().strip("|").split("|")])
    return rows[1:]  # without the header


def main(path):
    lines = open(path, encoding="utf-8").read().splitlines()
    cheapest = table(lines, "## Cheapest setting that meets each level's tolerance")
    effects = {r[0]: r[4] for r in table(
        lines, "## Declared effects against all effects (cost at the level's settings)")}
    print("| level | class | cheapest setting meeting the tolerance | its cost, µs per simulated s"
          " | rapier defaults: cost, meets? | all effects / declared |")
    print("|---|---|---|---|---|---|")
    for r in cheapest:
        level, cls, _own, setting, its, defaults = r[:6]
        cost = its.split(",")[0].strip()
        d = [c.strip() for c in defaults.split(",")]
        d_cost, d_meets = (d[0], d[2]) if len(d) >= 3 else (defaults, "-")
        print(f"| {level} | {cls} | {setting} | {cost} | {d_cost}, {d_meets} "
              f"| {effects.get(level, '-')} |")
    print(f"\n{len(cheapest)} levels", file=sys.stderr)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: accuracy_doc_table.py SUMMARY.md")
    main(sys.argv[1])
