#!/usr/bin/env python3
"""A platbench controller over the step protocol (docs/protocol.md), Python 3 standard library only.

A plain AABB mover in "collision" mode: each step it moves the character's box by the
displacement platbench's shared motion asks for (desired velocity * dt), first along x, then
along y, stopping flush against the level's solid boxes. It is grounded when its move down was
blocked. It models solid tiles only: levels with slopes, one-way platforms, ladders or moving
platforms are refused with a reason (platbench skips them and says so).

The shortest complete client, and a template for any language: read one JSON object per line
on stdin, answer with one JSON object per line on stdout (flushed), exit when stdin closes.
With `transport = "tcp"` in the controller file, the same lines travel over a TCP connection to
127.0.0.1 at the port in $PLATBENCH_PORT instead (as Godot's client must), and it exits when the
connection closes.
Lengths are in tiles, y up; a character's position is its feet (bottom centre of its box).
"""

import json
import os
import socket
import sys
import time

PROTOCOL = 1
EPS = 1e-9  # boxes closer than this along the other axis do not block (touching is not overlap)


IN, OUT = sys.stdin, sys.stdout
if os.environ.get("PLATBENCH_PORT"):
    _connection = socket.create_connection(("127.0.0.1", int(os.environ["PLATBENCH_PORT"])))
    _connection.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    IN = _connection.makefile("r", encoding="utf-8")
    OUT = _connection.makefile("w", encoding="utf-8")


def send(message):
    OUT.write(json.dumps(message) + "\n")
    OUT.flush()


def hello():
    return {
        "type": "hello",
        "protocol": PROTOCOL,
        "name": "python-aabb",
        "description": "x-then-y AABB moves against solid tiles (controllers/python/client.py)",
        "configs": [
            {
                "label": "aabb",
                "shape": "cuboid",
                "features": {"slopes": False, "one_way": False, "ladders": False,
                             "moving_platforms": False},
                "contact": {"gap": 0.0, "overlap_tolerance": 1e-6},
                "why": "the reference client: axis-separated box moves, flush contact",
            }
        ],
    }


def move_axis(box, d, axis, solids):
    """Moves `box` ([x0, y0, x1, y1]) by `d` along `axis` (0: x, 1: y) until a solid box stops
    it. Returns the distance moved and whether it was blocked."""
    if d == 0.0:
        return 0.0, False
    other = 1 - axis
    lo, hi = box[other], box[other + 2]
    allowed = d
    for s in solids:
        if s[other] >= hi - EPS or s[other + 2] <= lo + EPS:
            continue  # not beside the box along the other axis
        if d > 0 and s[axis] >= box[axis + 2] - EPS:
            allowed = min(allowed, s[axis] - box[axis + 2])
        elif d < 0 and s[axis + 2] <= box[axis] + EPS:
            allowed = max(allowed, s[axis + 2] - box[axis])
    return allowed, allowed != d


class Run:
    def __init__(self, message):
        self.solids = message["level"]["solid_boxes"]
        self.chars = [
            {"pos": list(c["spawn"]), "size": c["size"]} for c in message["characters"]
        ]

    def step(self, message):
        start = time.thread_time_ns()
        dt = message["dt"]
        out = []
        for char, request in zip(self.chars, message["characters"]):
            (x, y), (w, h) = char["pos"], char["size"]
            vx, vy = request["desired"]
            box = [x - w / 2, y, x + w / 2, y + h]
            dx, wall = move_axis(box, vx * dt, 0, self.solids)
            x += dx
            box = [x - w / 2, y, x + w / 2, y + h]
            dy, blocked = move_axis(box, vy * dt, 1, self.solids)
            y += dy
            grounded = blocked and vy <= 0
            char["pos"] = [x, y]
            out.append({
                "position": [x, y],
                "velocity": [dx / dt, dy / dt],
                "grounded": grounded,
                "ground_normal": [0.0, 1.0] if grounded else [0.0, 0.0],
                "wall": wall,
                "ceiling": blocked and vy > 0,
            })
        ns = time.thread_time_ns() - start
        return {"type": "state", "step": message["step"], "characters": out, "ns": ns}


def main():
    run = None
    for line in iter(IN.readline, ""):
        message = json.loads(line)
        kind = message["type"]
        if kind == "hello":
            send(hello())
        elif kind == "run":
            features = message["level"]["features"]
            missing = [name for name, present in sorted(features.items()) if present]
            if missing:
                send({"type": "refuse", "reason": "it models solid tiles only, not " + ", ".join(missing)})
            else:
                run = Run(message)
                send({"type": "ready"})
        elif kind == "step":
            send(run.step(message))
        elif kind == "end":
            return


if __name__ == "__main__":
    main()
