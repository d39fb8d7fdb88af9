"""Benchmark of design studies: load times (xacro vs the template cache) and a 1,000-design four-bar
sweep on 1 and 2 workers; prints the rows docs/sweeps.md quotes.

    PYTHONPATH=. python tools/sweep_bench.py [--designs 1000] [--samples 100]
"""

from __future__ import annotations

import argparse
import os
import platform
import time

from mechkit.bench.sweep_speed import load_times, sweep_speed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=1000)
    parser.add_argument("--samples", type=int, default=100)
    parser.add_argument("--runs", type=int, default=7)
    args = parser.parse_args()
    print(
        f"# {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {platform.processor() or platform.machine()}, "
        f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}"
    )
    print(
        "\n| mechanism | load via xacro (ms) | load via cache (ms) | URDF via xacro (ms) | URDF via cache (ms) "
        "| one-off expansion (ms) |"
    )
    print("|---|---|---|---|---|---|")
    for r in load_times(runs=args.runs):
        print(
            f"| {r.name} | {r.xacro_ms:.1f} | {r.cache_ms:.1f} | {r.render_xacro_ms:.1f} | {r.render_cache_ms:.2f} "
            f"| {r.expand_ms:.0f} |"
        )
    s = sweep_speed(args.designs, args.samples)
    print(
        f"\nfour-bar sweep: {s.designs} designs x {s.samples} samples; 1 worker {s.seconds[1]:.1f} s, "
        f"2 workers {s.seconds[2]:.1f} s; parallel efficiency {100 * s.efficiency:.0f} %; statuses {s.statuses}; "
        f"load average after {os.getloadavg()[0]:.1f}"
    )


if __name__ == "__main__":
    main()
