#!/usr/bin/env python3
"""Runs a command while this process holds many UDP sockets on random
ephemeral ports, as a busy machine's programs do with their outgoing sockets
(DNS lookups, DDS participants' send sockets, media streams).

It reproduces the flaky-test issue on demand: DDS domains above 101 have their
ports inside Linux's ephemeral range, so a held port can be a domain's
discovery port and the participants never meet; domains 0..101 are immune.

  tests/stress/ephemeral_port_pressure.py --sockets 14000 -- build/tests/some_test

Exits with the command's exit code. Only loopback-free bind(port 0) calls are
made: nothing is sent anywhere.
"""
import argparse
import resource
import socket
import subprocess
import sys


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sockets", type=int, default=14000,
                        help="how many ephemeral UDP ports to hold (default 14000)")
    parser.add_argument("--report-domain", type=int, action="append", default=[],
                        help="print whether this DDS domain's discovery port is held")
    parser.add_argument("command", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not command:
        parser.error("no command given")
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    wanted = args.sockets + 256
    if soft < wanted:
        resource.setrlimit(resource.RLIMIT_NOFILE, (min(wanted, hard), hard))
    held = []
    try:
        for _ in range(args.sockets):
            s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            s.bind(("0.0.0.0", 0))
            s.set_inheritable(False)
            held.append(s)
    except OSError as error:
        print(f"ephemeral_port_pressure: stopped at {len(held)} sockets: {error}", file=sys.stderr)
    ports = {s.getsockname()[1] for s in held}
    print(f"ephemeral_port_pressure: holding {len(ports)} UDP ports", flush=True)
    for domain in args.report_domain:
        port = 7400 + 250 * domain
        state = "HELD" if port in ports else "free"
        print(f"ephemeral_port_pressure: domain {domain} discovery port {port}: {state}", flush=True)
    code = subprocess.call(command)
    for s in held:
        s.close()
    return code


if __name__ == "__main__":
    sys.exit(main())
