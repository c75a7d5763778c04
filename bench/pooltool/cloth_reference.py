"""Reference values from pooltool 0.3.3 for ccdsim's cloth motion laws and cue strike.

Writes JSON to stdout: for a fixed grid of balls (velocity, angular velocity, motion state)
and times, pooltool's `evolve_ball_motion` (the ball and its state after t seconds, through
every transition) and its transition times; for a grid of shots, pooltool's `cue_strike`.
ccdsim's test `cloth_vs_pooltool` (crates/ccdsim/tests/suite/) compares its own laws with
these numbers. Run by scripts/pooltool-reference, which installs pooltool into a virtualenv
of its own.
"""

import json
import sys

import numpy as np
import pooltool.constants as const
import pooltool.ptmath as ptmath
from pooltool.objects.ball.params import BallParams
from pooltool.objects.cue.datatypes import CueSpecs
from pooltool.physics.evolve import evolve_ball_motion
from pooltool.physics.resolve.stick_ball.instantaneous_point import cue_strike

STATES = {
    const.stationary: "stationary",
    const.spinning: "spinning",
    const.sliding: "sliding",
    const.rolling: "rolling",
}


def ball_cases(R):
    """Balls in every state: sliding with top, draw and side spin, rolling, spinning."""
    cases = []
    for vx, vy in [(2.0, 0.0), (0.3, -1.1), (-0.05, 0.02)]:
        for wx, wy, wz in [(0.0, 0.0, 0.0), (15.0, -60.0, 4.0), (-30.0, 25.0, -40.0)]:
            cases.append(((vx, vy), (wx, wy, wz), const.sliding))
        # Rolling: ω_xy = ẑ×v/R, with and without vertical spin.
        for wz in [0.0, 3.0, -50.0]:
            cases.append(((vx, vy), (-vy / R, vx / R, wz), const.rolling))
    for wz in [7.5, -0.2]:
        cases.append(((0.0, 0.0), (0.0, 0.0, wz), const.spinning))
    cases.append(((0.0, 0.0), (0.0, 0.0, 0.0), const.stationary))
    return cases


def main():
    p = BallParams.default()
    R, m, g = p.R, p.m, p.g
    out = {
        "pooltool": "0.3.3",
        "params": {
            "radius": R,
            "mass": m,
            "sliding_friction": p.u_s,
            "rolling_friction": p.u_r,
            "spinning_friction": p.u_sp,
            "gravity": g,
        },
        "evolve": [],
        "strikes": [],
    }
    for (v, w, s) in ball_cases(R):
        rvw = np.array([[0.5, 1.0, R], [v[0], v[1], 0.0], list(w)], dtype=np.float64)
        times = {
            "slide": float(ptmath.get_slide_time(rvw, R, p.u_s, g)),
            "roll": float(ptmath.get_roll_time(rvw, p.u_r, g)),
            "spin": float(ptmath.get_spin_time(rvw, R, p.u_sp, g)),
        }
        for t in [0.0, 0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 60.0]:
            after, state = evolve_ball_motion(s, rvw.copy(), R, m, p.u_s, p.u_sp, p.u_r, g, t)
            out["evolve"].append(
                {
                    "pos": [0.5, 1.0],
                    "vel": list(v),
                    "spin": list(w),
                    "state": STATES[s],
                    "t": t,
                    "times": times,
                    "after": {
                        "pos": [float(after[0, 0]), float(after[0, 1])],
                        "vel": [float(after[1, 0]), float(after[1, 1])],
                        "spin": [float(x) for x in after[2]],
                        "state": STATES[state],
                    },
                }
            )
    M = CueSpecs.default().M
    for V0 in [0.5, 2.0, 6.0]:
        for phi in [0.0, 37.5, 270.0]:
            for theta in [0.0, 5.0, 30.0]:
                for a, b in [(0.0, 0.0), (0.3, 0.0), (0.0, -0.5), (-0.4, 0.6)]:
                    v, w = cue_strike(m, M, R, V0, phi, theta, a, b, throttle_english=True)
                    out["strikes"].append(
                        {
                            "V0": V0,
                            "phi": phi,
                            "theta": theta,
                            "a": a,
                            "b": b,
                            "cue_mass": M,
                            "vel": [float(v[0]), float(v[1]), float(v[2])],
                            "spin": [float(x) for x in w],
                        }
                    )
    json.dump(out, sys.stdout, indent=1)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
