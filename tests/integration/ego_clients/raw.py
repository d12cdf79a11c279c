#!/usr/bin/env python3
"""A hostile TraCI client on a raw socket: sends one malformed message and reports what the
server answered (status of the first response) and whether it then closed the connection.

  raw.py PORT CASE SUMMARY_FILE     CASE: zero | huge | truncated | wrongtype
"""
import json
import socket
import struct
import sys
import time


def connect(port):
    for _ in range(600):
        try:
            return socket.create_connection(("127.0.0.1", port))
        except OSError:
            time.sleep(0.1)
    raise SystemExit("no server")


def read_exact(sock, n):
    data = b""
    while len(data) < n:
        chunk = sock.recv(n - len(data))
        if not chunk:
            return None
        data += chunk
    return data


def main():
    port, case, out = int(sys.argv[1]), sys.argv[2], sys.argv[3]
    get_speed = struct.pack("!BBBi", 1 + 1 + 1 + 4 + 3, 0xa4, 0x40, 3) + b"ego"
    messages = {
        "zero": struct.pack("!i", 0),
        "huge": struct.pack("!I", 0x80000000) + b"\x00" * 16,
        # The command says 12 bytes, the message holds 8 of them.
        "truncated": struct.pack("!i", 4 + 8) + get_speed[:8],
    }
    # setSpeed with an integer where a double belongs.
    content = struct.pack("!B", 0x40) + struct.pack("!i", 3) + b"ego" + struct.pack("!Bi", 0x09, 10)
    command = struct.pack("!BB", len(content) + 2, 0xc4) + content
    messages["wrongtype"] = struct.pack("!i", 4 + len(command)) + command

    sock = connect(port)
    sock.sendall(messages[case])
    summary = {"case": case}
    header = read_exact(sock, 4)
    if header:
        body = read_exact(sock, struct.unpack("!i", header)[0] - 4)
        summary["status"] = {"command": body[1], "result": body[2],
                             "text": body[7:7 + struct.unpack("!i", body[3:7])[0]].decode("latin1")}
    sock.settimeout(10)
    try:
        summary["closed"] = sock.recv(1) == b""
    except socket.timeout:
        summary["closed"] = False
    with open(out, "w") as f:
        json.dump(summary, f)


if __name__ == "__main__":
    main()
