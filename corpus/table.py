#!/usr/bin/env python3
"""Rewrite the "now" columns of docs/maps.md's per-map table from one judge run.

Usage (from the repository root):

    python3 corpus/judge.py target/release/platbench MAPS > JUDGED
    python3 corpus/table.py JUDGED docs/maps.md

Each row of the table is found by its map and game (from corpus/intent/*.toml); its "now"
verdict and "what differs now" are rewritten from the judge's line for that map. The "before"
column is left as it is (it comes from the release binary of an older commit).
"""
import glob
import os
import re
import sys
import tomllib


def prose(verdict, details):
    """A judge line's details as the table says them, and the short verdict."""
    parts, kinds = [], []
    for d in details:
        m = re.match(r"layer '(.+)': game (\S+), read (\S+) ", d)
        if m:
            kinds.append("layers")
            parts.append(f"`{m.group(1)}` is {m.group(2).replace('_', '-')} in the game, read {m.group(3)}")
        elif d.startswith("layer ") and "not listed by inspect" in d:
            kinds.append("layers")
            parts.append(d)
        elif d.startswith("sides: the game leaves them open"):
            kinds.append("sides")
            parts.append("the game leaves the sides open, platbench walls them")
        elif d.startswith("sides: the game stops the player"):
            kinds.append("sides")
            parts.append("the game stops the player at the sides, platbench leaves them open")
        elif d.startswith("spawn:"):
            kinds.append("spawn")
            parts.append("the map marks the spawn, none read")
        elif d.startswith("not judged:"):
            parts.append(d)
        else:
            parts.append(d)
    kinds = list(dict.fromkeys(kinds))
    if verdict == "RIGHT":
        short = "right"
    elif verdict == "ERROR":
        short = "refused"
    else:
        short = "wrong: " + ", ".join(kinds)
    return short, "; ".join(parts)


def split_details(rest):
    """The judge's `; `-separated details, keeping `not judged: a, b` whole."""
    out = []
    for piece in rest.split("; "):
        if piece:
            out.append(piece)
    return out


def main():
    judged, doc = sys.argv[1], sys.argv[2]
    lines = {}
    for line in open(judged, encoding="utf-8"):
        m = re.match(r"(RIGHT|WRONG|ERROR|MISSING)\s+(Tiled|LDtk)\s+(\S+): ?(.*)$", line.rstrip("\n"))
        if m:
            lines[m.group(3)] = (m.group(1), m.group(4))
    keys = {}
    for path in sorted(glob.glob("corpus/intent/*.toml")):
        with open(path, "rb") as f:
            spec = tomllib.load(f)
        key = f"`{spec['map']}`"
        if "level" in spec:
            key += f", level `{spec['level']}`"
        key += f" ({spec['game']})"
        keys[key] = os.path.basename(path)[: -len(".toml")]
    out, done = [], 0
    for row in open(doc, encoding="utf-8").read().split("\n"):
        cells = row.split(" | ")
        if row.startswith("| ") and len(cells) == 6 and cells[1] in keys:
            verdict, rest = lines[keys[cells[1]]]
            if verdict == "ERROR":
                short, text = "refused", "refused: " + rest.removeprefix("error: ").split(": ", 1)[-1]
            else:
                short, text = prose(verdict, split_details(rest))
            cells[4] = short
            cells[5] = text + " |" if text else " |"
            row = " | ".join(cells)
            done += 1
        out.append(row)
    if done != len(keys):
        sys.exit(f"rewrote {done} rows, expected {len(keys)}")
    open(doc, "w", encoding="utf-8").write("\n".join(out))
    print(f"rewrote {done} rows")


if __name__ == "__main__":
    main()
