#!/usr/bin/env python3
"""Writes the levels that calibrate and test the run budget (src/runner/budget.rs).

    python3 tools/budget_levels.py            # the adversarial levels, into tests/budget/
    python3 tools/budget_levels.py --calib D  # also the calibration levels, into D

The adversarial levels are test inputs of tests/suite/runner/budget.rs and rows of the table in
docs/cli.md: 1000 discs at one point, 1000 split substeps, and an impulse_momentum check over
1e8 steps (refused: never run); 10^4 questions (1.4 MB) is written with --calib only. The calibration levels are what
the unit costs in src/runner/budget.rs were measured on (tools/budget_calibrate.sh).
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "budget")


def level(title, effects, world, bodies, extra=""):
    return (f"// Written by tools/budget_levels.py: {title}.\n"
            f"Level(\n  title: \"{title}\",\n  effects: [{', '.join(effects)}],\n"
            f"  world: {world},\n  bodies: [\n" + "".join(f"    {b},\n" for b in bodies)
            + "  ],\n" + extra + ")\n")


def ball(name="ball", x=0.0, y=10.0, r=0.1):
    return f"(name: \"{name}\", shape: Circle(radius: {r}), mass: 0.5, position: ({x}, {y}))"


def questions(n, duration):
    qs = "".join(
        f"    (id: \"q{i}\", ask: \"Height at the end\", unit: \"m\", expected: 10.0, tolerance: 1e9,"
        f" quantity: Y(\"ball\"), at: Time({duration}), why: \"budget test\"),\n"
        for i in range(n))
    return "  questions: [\n" + qs + "  ],\n"


def discs_at_one_point(n, duration=1.0, substeps=4):
    bodies = [f"(name: \"ground\", kind: fixed, shape: Box(width: 40.0, height: 1.0), position: (0.0, -0.5))"]
    bodies += [f"(name: \"d{i}\", shape: Circle(radius: 0.1), mass: 0.1, position: (0.0, 1.0))" for i in range(n)]
    return level(f"{n} discs at one point", ["gravity", "contacts"],
                 f"(dt: 0.016666666666666666, substeps: {substeps}, duration: {duration})", bodies)


def spring(substeps, duration=1.0):
    bodies = ["(name: \"block\", shape: Box(width: 0.1, height: 0.1), mass: 0.5, position: (0.6, 0.0), lock_rotation: true)"]
    extra = ("  springs: [\n    (name: \"spring\", body1: \"block\", point2: (0.0, 0.0), stiffness: 50.0,"
             " rest_length: 0.5),\n  ],\n")
    return level(f"A spring at {substeps} split substeps", ["springs"],
                 f"(dt: 0.016666666666666666, substeps: {substeps}, duration: {duration})", bodies, extra)


def impulse_momentum(steps, dt=0.01):
    extra = ("  checks: [\n    (kind: impulse_momentum, body: \"ball\", tolerance: 1e-3, why: \"budget test\"),\n"
             "  ],\n")
    return level(f"An impulse_momentum check over {steps:.0e} steps (1e8 at --dt 1e-5)", ["gravity"],
                 f"(dt: {dt}, substeps: 1, duration: {steps * dt:g}.0)", [ball()], extra)


def free_bodies(n, substeps, iterations, duration):
    bodies = [f"(name: \"b{i}\", shape: Circle(radius: 0.1), mass: 0.5, position: ({i}.0, 0.0))" for i in range(n)]
    return level(f"{n} free bodies", ["gravity"],
                 f"(dt: 0.016666666666666666, substeps: {substeps}, solver_iterations: {iterations}, duration: {duration})",
                 bodies)


def chain(n, substeps, iterations, duration):
    bodies = ["(name: \"pivot\", kind: fixed, position: (0.0, 0.0))"]
    bodies += [f"(name: \"l{i}\", shape: Capsule(length: 1.0, radius: 0.1), mass: 1.0, position: ({i}.5, 0.0))"
               for i in range(n)]
    joints = [f"(name: \"j0\", kind: revolute, body1: \"pivot\", body2: \"l0\", anchor1: (0.0, 0.0), anchor2: (-0.5, 0.0))"]
    joints += [f"(name: \"j{i}\", kind: revolute, body1: \"l{i-1}\", body2: \"l{i}\", anchor1: (0.5, 0.0), anchor2: (-0.5, 0.0))"
               for i in range(1, n)]
    extra = "  joints: [\n" + "".join(f"    {j},\n" for j in joints) + "  ],\n"
    return level(f"A chain of {n} links", ["gravity", "joints"],
                 f"(dt: 0.016666666666666666, substeps: {substeps}, solver_iterations: {iterations}, duration: {duration})",
                 bodies, extra)


def write(folder, name, text):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "w") as f:
        f.write(text)


def main():
    write(OUT, "discs_1000_one_point.ron", discs_at_one_point(1000))
    write(OUT, "spring_1000_substeps.ron", spring(1000, duration=2.0))
    # 1e5 steps as written (a level may hold at most 1e7); `--dt 1e-5` makes them 1e8.
    write(OUT, "impulse_momentum_1e8.ron", impulse_momentum(100_000))
    if len(sys.argv) == 3 and sys.argv[1] == "--calib":
        d = sys.argv[2]
        # 1.4 MB: tests/suite/runner/budget.rs generates its own copy.
        write(d, "questions_10k.ron",
              level("10^4 questions", ["gravity"], "(dt: 0.016666666666666666, substeps: 1, duration: 10.0)",
                    [ball()], questions(10_000, 10.0)))
        write(d, "empty.ron", level("one ball", ["gravity"], "(dt: 0.016666666666666666, substeps: 1, duration: 0.1)", [ball()]))
        write(d, "free_1000_s4_i1.ron", free_bodies(1000, 4, 1, 20.0))
        write(d, "free_1000_s16_i4.ron", free_bodies(1000, 16, 4, 10.0))
        write(d, "chain_200_s8_i1.ron", chain(200, 8, 1, 20.0))
        write(d, "chain_200_s8_i8.ron", chain(200, 8, 8, 20.0))
        write(d, "spring_s100.ron", spring(100, duration=20.0))
        write(d, "spring_s1000.ron", spring(1000, duration=2.0))
        write(d, "discs_300_s1.ron", discs_at_one_point(300, duration=1.0, substeps=1))
        write(d, "discs_300_s8.ron", discs_at_one_point(300, duration=1.0, substeps=8))
        write(d, "questions_1k.ron", level("10^3 questions", ["gravity"], "(dt: 0.016666666666666666, substeps: 1, duration: 20.0)", [ball()], questions(1000, 20.0)))
        write(d, "im_1e6.ron", impulse_momentum(1_000_000, dt=0.001))
        write(d, "im_0.ron", level("no check", ["gravity"], "(dt: 0.001, substeps: 1, duration: 1000.0)", [ball()]))


if __name__ == "__main__":
    main()
