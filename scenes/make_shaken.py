#!/usr/bin/env python3
"""Writes scenes/shaken-motion.csv: the ground-motion record of scenes/shaken.toml.

The foundation's acceleration (fractions of g along the scene's X, Y, Z) at 200 samples a
second for 2.5 s: sinusoids of 1.5 Hz along X (0.7 g), 1 Hz along Z (0.3 g) and 2.5 Hz along Y
(0.1 g), each under an envelope rising over the first 0.5 s and falling over the last 0.5 s, so
that the record starts and ends at rest. Not a real earthquake: a record whose effect on a block
held with a factor of safety of 1.29 is several slips that turn it, then a stop.

Standard library only; the same file every time. Run from the repository root:
    python3 scenes/make_shaken.py
"""

import math
import os

RATE = 200  # samples per second
LENGTH = 2.5  # s
RAMP = 0.5  # s


def main():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "shaken-motion.csv")
    lines = ["t_s,ax_g,ay_g,az_g"]
    for k in range(int(RATE * LENGTH) + 1):
        t = k / RATE
        envelope = min(1.0, t / RAMP, (LENGTH - t) / RAMP)
        ax = -0.7 * math.sin(2 * math.pi * 1.5 * t) * envelope
        ay = 0.1 * math.sin(2 * math.pi * 2.5 * t) * envelope
        az = 0.3 * math.sin(2 * math.pi * 1.0 * t) * envelope
        lines.append(f"{t:.3f},{ax:.6f},{ay:.6f},{az:.6f}")
    with open(path, "w", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
