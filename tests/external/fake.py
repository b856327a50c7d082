#!/usr/bin/env python3
"""A controller that misbehaves on purpose, at step 2, as its first argument says: crash, hang,
garbage, order, nan, huge, slow, or well (it does not); or deaf: it stops reading its input once
it has answered `hello`. Before that it answers as the protocol says (standing still at the
spawn). A second argument names a file it writes its process id to."""

import json
import os
import sys
import time

MODE = sys.argv[1]
if len(sys.argv) > 2:
    with open(sys.argv[2], "w") as f:
        f.write(str(os.getpid()))


def send(message):
    sys.stdout.write(json.dumps(message) + "\n")
    sys.stdout.flush()


chars = []
for line in iter(sys.stdin.readline, ""):
    m = json.loads(line)
    if m["type"] == "hello":
        send({"type": "hello", "protocol": 1, "name": "fake-" + MODE, "configs": [{"label": "default"}]})
        if MODE == "deaf":
            while True:
                time.sleep(1000)
    elif m["type"] == "run":
        chars = [c["spawn"] for c in m["characters"]]
        send({"type": "ready"})
    elif m["type"] == "step":
        k = m["step"]
        state = [{"position": p, "velocity": [0.0, 0.0], "grounded": False} for p in chars]
        reply = {"type": "state", "step": k, "characters": state, "ns": 1000}
        if k == 2:
            if MODE == "crash":
                sys.stderr.write("fake: crashing on purpose\n")
                sys.stderr.flush()
                sys.exit(3)
            if MODE == "hang":
                while True:
                    time.sleep(1000)
            if MODE == "garbage":
                sys.stdout.write("this is not JSON\n")
                sys.stdout.flush()
                continue
            if MODE == "order":
                reply["step"] = k + 1
            if MODE == "nan":
                state[0]["position"] = [float("nan"), 1.0]
            if MODE == "huge":
                state[0]["position"] = [1e300, 1.0]
            if MODE == "slow":
                time.sleep(1.0)
        send(reply)
    elif m["type"] == "end":
        break
