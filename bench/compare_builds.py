#!/usr/bin/env python3
"""A/B timing of brume builds: `brume bench` runs alternating between builds, per-pass medians and ratios.

    bench/compare_builds.py [options] NAME=BRUME[@SPV_DIR] NAME=BRUME[@SPV_DIR] ...

Each round runs every build once, so that a busy or drifting machine affects all alike, in an order
rotated by one build each round (A B C, B C A, C A B, ...): on the reference machine the run that
opens a round was measured up to a third slower in some hours, which a fixed order charges to one
build. Use a multiple of the build count as --rounds. The first build is the baseline. A build is a
`brume` binary (copy build/app/brume aside before a change: its SPIR-V is embedded), optionally with a BRUME_SPV_DIR of
shaders that replace the embedded ones (docs/performance.md, "How to measure"). Prints each round's
wall medians, then per pass: the baseline's median over rounds, each other build's median, their
ratio, and the ratio in every round (a ratio that swings across 1 from round to round is noise).
With --realtime the runs use `chrt -f 10` (root only): the other processes on the cores then wait.
Exit status 2 with one sentence when a build is missing or a run fails.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile


def fail(message):
    print(f"compare_builds: {message}", file=sys.stderr)
    sys.exit(2)


class OneSentenceParser(argparse.ArgumentParser):
    """argparse's errors as this script's: one sentence on stderr, exit status 2."""

    def error(self, message):
        fail(message[0].upper() + message[1:].rstrip(".") + " (see --help).")


def parse_build(text):
    name, sep, rest = text.partition("=")
    if not sep or not name or not rest:
        fail(f"'{text}' is not NAME=BRUME or NAME=BRUME@SPV_DIR.")
    binary, _, spv = rest.partition("@")
    if not (os.path.isfile(binary) and os.access(binary, os.X_OK)):
        fail(f"build '{name}': {binary} is not an executable file.")
    if spv and not os.path.isdir(spv):
        fail(f"build '{name}': the SPIR-V folder {spv} does not exist.")
    return name, binary, spv


def main():
    p = OneSentenceParser(description="\n\n".join(__doc__.split("\n\n")[2:]), formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("builds", nargs="+", metavar="NAME=BRUME[@SPV_DIR]",
                   help="a build: its name in the table, its brume binary, optionally a BRUME_SPV_DIR; the first is the baseline")
    p.add_argument("--scene", default="assets/scenes/default.json", help="scene file (default: %(default)s)")
    p.add_argument("--quality", default="high", choices=["low", "medium", "high", "ultra"],
                   help="froxel quality preset (default: %(default)s)")
    p.add_argument("--width", type=int, default=1280, help="pixels (default: %(default)s)")
    p.add_argument("--height", type=int, default=720, help="pixels (default: %(default)s)")
    p.add_argument("--frames", type=int, default=3, help="timed renders per run (default: %(default)s)")
    p.add_argument("--rounds", type=int, default=4, help="runs per build (default: %(default)s)")
    p.add_argument("--orbit", type=float, default=0.0, help="camera turn per render, deg (default: at rest)")
    p.add_argument("--realtime", action="store_true", help="run each bench under chrt -f 10 (root)")
    a = p.parse_args()
    if len(a.builds) < 2:
        fail("give two builds or more: the first is the baseline.")
    if a.rounds < 1 or a.frames < 1:
        fail("--rounds and --frames must be 1 or more.")
    if not os.path.isfile(a.scene):
        fail(f"the scene {a.scene} does not exist.")
    builds = [parse_build(b) for b in a.builds]
    names = [b[0] for b in builds]
    if len(set(names)) != len(names):
        fail("two builds have the same name.")
    runs = {name: [] for name in names}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.rounds):
            for name, binary, spv in builds[r % len(builds):] + builds[:r % len(builds)]:
                out = os.path.join(tmp, f"{name}_{r}.json")
                cmd = [binary, "bench", a.scene, "--width", str(a.width), "--height", str(a.height), "--quality",
                       a.quality, "--frames", str(a.frames), "--warmup", "1", "--orbit", str(a.orbit), "--json", out]
                if a.realtime:
                    cmd = ["chrt", "-f", "10"] + cmd
                env = dict(os.environ)
                env.pop("BRUME_SPV_DIR", None)
                if spv:
                    env["BRUME_SPV_DIR"] = spv
                done = subprocess.run(cmd, env=env, capture_output=True, text=True)
                if done.returncode != 0:
                    last = (done.stderr.strip().splitlines() or ["(no message)"])[-1]
                    fail(f"build '{name}' failed in round {r + 1}: {last}")
                with open(out) as f:
                    runs[name].append(json.load(f))
            print(f"round {r + 1}/{a.rounds}, load {os.getloadavg()[0]:.1f}: wall ms " +
                  ", ".join(f"{n} {runs[n][-1]['wall_ms']:.1f}" for n in names), flush=True)
    base = names[0]
    passes = []
    for n in names:
        for run in runs[n]:
            passes += [k for k in run["pass_ms"] if k not in passes]
    rows = [("wall", lambda run: run["wall_ms"])] + [(k, lambda run, k=k: run["pass_ms"].get(k, 0.0)) for k in passes]
    width = max(len(k) for k, _ in rows)
    header = f"{'':{width}} {base + ' ms':>12}"
    for n in names[1:]:
        header += f" | {n + ' ms':>12} {'ratio':>6}  per round"
    print(f"\n{a.scene}, {a.width}x{a.height}, {a.quality}, {a.frames} frames, {a.rounds} rounds" +
          (f", orbit {a.orbit:g} deg" if a.orbit else "") + "; medians over rounds")
    print(header)
    for label, get in rows:
        ref = [get(run) for run in runs[base]]
        line = f"{label:{width}} {statistics.median(ref):12.2f}"
        for n in names[1:]:
            vals = [get(run) for run in runs[n]]
            m, mr = statistics.median(vals), statistics.median(ref)
            ratio = f"{m / mr:6.3f}" if mr > 0 else f"{'-':>6}"
            per = " ".join(f"{v / b:.2f}" if b > 0 else "-" for v, b in zip(vals, ref))
            line += f" | {m:12.2f} {ratio}  {per}"
        print(line)


if __name__ == "__main__":
    main()
