#!/usr/bin/env python3
"""Writes the seed corpus of the TraCI fuzz targets: messages as SUMO's Python client sends
them (one file per conversation, messages back to back, each with its 4-byte length)."""
import os
import struct

INVALID = -1073741824.0


def cmd(cid, content):
    if len(content) + 2 <= 255:
        return struct.pack("!BB", len(content) + 2, cid) + content
    return struct.pack("!BiB", 0, len(content) + 6, cid) + content


def msg(*commands):
    body = b"".join(commands)
    return struct.pack("!i", len(body) + 4) + body


def s(text):
    return struct.pack("!i", len(text)) + text.encode()


def get(cid, var, obj, extra=b""):
    return cmd(cid, struct.pack("!B", var) + s(obj) + extra)


def typed_s(text):
    return b"\x0c" + s(text)


def typed_d(v):
    return struct.pack("!Bd", 0x0B, v)


step = cmd(0x02, struct.pack("!d", 0.0))
seeds = {
    "version": msg(cmd(0x00, b"")) + msg(cmd(0x03, struct.pack("!i", 1))),
    "python_loop": msg(cmd(0x00, b""))
    + msg(cmd(0xd4, struct.pack("!dd", INVALID, INVALID) + s("ego") + bytes([3, 0x40, 0x52, 0x56])))
    + msg(cmd(0x84, struct.pack("!dd", INVALID, INVALID) + s("ego") + struct.pack("!Bd", 0xa4, 100.0) + bytes([2, 0x40, 0x42])))
    + msg(step) + msg(get(0xc4, 0x40, "ego", typed_d(12.0))) + msg(step)
    + msg(get(0xa4, 0x7e, "ego", typed_s("orch.hand_over"))) + msg(cmd(0x7f, b"")),
    "commands": msg(get(0xc4, 0x13, "ego", struct.pack("!BiBbBd", 0x0F, 2, 0x08, 1, 0x0B, 3.0)))
    + msg(get(0xc4, 0x14, "ego", struct.pack("!BiBdBd", 0x0F, 2, 0x0B, 5.0, 0x0B, 2.0)))
    + msg(get(0xc4, 0xb4, "ego", struct.pack("!Bi", 0x0F, 7) + typed_s("E0") + struct.pack("!BiBdBdBdBbBd", 0x09, 1, 0x0B, 10.0, 0x0B, -8.0, 0x0B, 90.0, 0x08, 2, 0x0B, 100.0)))
    + msg(get(0xc4, 0x5b, "ego", struct.pack("!Bi", 0x09, 2)), get(0xc4, 0xb3, "ego", struct.pack("!Bi", 0x09, 0))),
    "gets": msg(get(0xab, 0x66, ""), get(0xab, 0x7b, ""), get(0xa4, 0x00, ""), get(0xa4, 0x68, "ego", typed_d(100.0)),
                get(0xae, 0x42, "actor2"), get(0xa3, 0x44, "E0_0")),
    "step_to_time": msg(cmd(0x02, struct.pack("!d", 1.0)), get(0xab, 0x66, "")),
}
here = os.path.dirname(os.path.abspath(__file__))
for name, data in seeds.items():
    with open(os.path.join(here, "corpus", name), "wb") as f:
        f.write(data)
