"""Reference values from pooltool 0.4.4's frictional ball-ball model for ccdsim's option.

ccdsim's default ball-ball model is pooltool 0.3.3's (frictionless, elastic); its frictional
option follows the model pooltool 0.4 added, `frictional_inelastic`. pooltool 0.4 does not
install on this machine kind (it pins development builds of panda3d that PyPI does not
carry), so this script runs that model's resolver straight from pooltool 0.4.4's source
distribution: argv[1] is the path of its `pooltool` folder. The functions
`_resolve_ball_ball` (physics/resolve/ball_ball/frictional_inelastic) and `surface_velocity`
(ptmath/utils.py) are compiled from those files as published, without numba's decorators,
and run with the vector helpers of the installed pooltool 0.3.3, which has the others it
calls (`angle`, `coordinate_rotation`, `unit_vector`, `norm3d`, `cross`).

Writes JSON to stdout: for a grid of collisions (where the balls meet, their velocities and
spins, e_b, and the ball-ball friction u_b), the velocities and spins pooltool gives them.
ccdsim's test `frictional_vs_pooltool` (crates/ccdsim/tests/suite/) compares its own model
with these numbers. Run by scripts/pooltool-reference.
"""

import ast
import json
import math
import sys

import numpy as np
import pooltool.constants as const
import pooltool.ptmath as ptmath
from pooltool.objects.ball.params import BallParams


def peer_function(path, name):
    """The function `name` of the file `path` of pooltool 0.4.4's source, undecorated."""
    tree = ast.parse(open(path).read())
    fn = next(
        node
        for node in tree.body
        if isinstance(node, ast.FunctionDef) and node.name == name
    )
    fn.decorator_list = []
    module = ast.Module(body=[fn], type_ignores=[])
    from numpy.typing import NDArray

    space = {"np": np, "ptmath": ptmath, "const": const, "cross": ptmath.cross, "NDArray": NDArray}
    exec(compile(module, path, "exec"), space)
    return space[name]


def peer_resolver(root):
    """`_resolve_ball_ball` of pooltool 0.4.4 (`root` is its source's `pooltool` folder),
    with 0.4.4's `surface_velocity` beside the helpers 0.3.3 already has."""
    ptmath.surface_velocity = peer_function(f"{root}/ptmath/utils.py", "surface_velocity")
    return peer_function(
        f"{root}/physics/resolve/ball_ball/frictional_inelastic/__init__.py",
        "_resolve_ball_ball",
    )


def peer_slip_speed(rvw1, rvw2, R):
    """The slip speed pooltool 0.4.4's Alciatore friction reads (its `calculate_friction`):
    the surface velocities at the points facing +x and -x, less the centres' x velocities."""
    x = np.array([1.0, 0.0, 0.0])
    c1 = rvw1[1] + np.cross(rvw1[2], R * x) - np.array([rvw1[1][0], 0.0, 0.0])
    c2 = rvw2[1] + np.cross(rvw2[2], -R * x) - np.array([rvw2[1][0], 0.0, 0.0])
    return float(np.linalg.norm(c1 - c2))


def main():
    resolve = peer_resolver(sys.argv[1])
    R = BallParams.default().R
    # Alciatore's curve as pooltool 0.4.4's AlciatoreBallBallFriction defaults have it.
    a, b, c = 9.951e-3, 0.108, 1.088
    velocities = [
        ((2.0, 0.0), (0.0, 0.0)),
        ((1.2, 0.4), (0.0, 0.0)),
        ((0.7, -0.3), (-0.5, 0.2)),
        ((3.0, 1.0), (0.4, -0.6)),
    ]
    spins = [
        ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
        ((0.0, 70.0, 0.0), (0.0, 0.0, 0.0)),
        ((-20.0, -40.0, 35.0), (0.0, 0.0, 0.0)),
        ((5.0, 10.0, -80.0), (12.0, -30.0, 20.0)),
    ]
    cases = []
    for angle in [0.0, 17.0, 35.0, 62.0, 150.0, 233.0]:
        t = math.radians(angle)
        for v1, v2 in velocities:
            for w1, w2 in spins:
                # Only balls that approach along the line of centres collide.
                n = (math.cos(t), math.sin(t))
                if (v1[0] - v2[0]) * n[0] + (v1[1] - v2[1]) * n[1] <= 0.0:
                    continue
                frictions = [("constant", 0.05), ("constant", 0.6)]
                if angle == 0.0:
                    frictions.append(("alciatore", None))
                for kind, u in frictions:
                    for e_b in [0.95, 1.0]:
                        r1 = np.array([0.5, 0.7, R])
                        r2 = r1 + 2.0 * R * np.array([n[0], n[1], 0.0])
                        rvw1 = np.array([r1, [v1[0], v1[1], 0.0], w1], dtype=float)
                        rvw2 = np.array([r2, [v2[0], v2[1], 0.0], w2], dtype=float)
                        u_b = u
                        if kind == "alciatore":
                            u_b = a + b * math.exp(-c * peer_slip_speed(rvw1, rvw2, R))
                        o1, o2 = resolve(rvw1.copy(), rvw2.copy(), R, u_b, e_b)
                        cases.append(
                            {
                                "pos": [list(r1[:2]), list(r2[:2])],
                                "vel": [list(v1), list(v2)],
                                "spin": [list(w1), list(w2)],
                                "restitution": e_b,
                                "friction": kind,
                                "u_b": u_b if kind == "constant" else None,
                                "after_vel": [list(o1[1][:2]), list(o2[1][:2])],
                                "after_spin": [list(o1[2]), list(o2[2])],
                            }
                        )
    json.dump(
        {
            "pooltool": "0.4.4 (frictional_inelastic from its source distribution)",
            "radius": R,
            "alciatore": [a, b, c],
            "cases": cases,
        },
        sys.stdout,
        indent=1,
    )
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
