#!/usr/bin/env python3
"""Writes the stress levels (levels/stress/*.ron) of `rigidlab study stability`.

The .ron files are the source of truth and are committed; this script only
documents how the big ones were laid out and regenerates them:

    python3 levels/stress/generate.py

Each case's pass criteria (margins, which body is the "top", ...) live in
src/study/stability/cases.rs, keyed by file name. The `world` settings written
here are the *recorded* settings: the cheapest ones at which the case passes
(rapier's defaults where they suffice); the study also runs every case at
rapier's defaults and reports both.
"""

import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
G = 9.81


def num(x):
    """A float as RON reads it (always with a decimal point or exponent)."""
    s = repr(float(x))
    if "inf" in s or "nan" in s:
        raise ValueError(x)
    if "e" in s and "." not in s.split("e")[0]:
        a, b = s.split("e")
        s = a + ".0e" + b
    return s


def v2(p):
    return f"({num(p[0])}, {num(p[1])})"


def world(dt=1 / 60, substeps=4, iterations=1, duration=10.0, gravity=None, contact_hz=None):
    parts = [f"dt: {num(dt)}", f"substeps: {substeps}", f"solver_iterations: {iterations}",
             f"duration: {num(duration)}"]
    if contact_hz is not None:
        parts.append(f"contact_hz: {num(contact_hz)}")
    if gravity is not None:
        parts.insert(0, f"gravity: {v2(gravity)}")
    return "(" + ", ".join(parts) + ")"


def box(w, h):
    return f"Box(width: {num(w)}, height: {num(h)})"


def circle(r):
    return f"Circle(radius: {num(r)})"


def capsule(length, r):
    return f"Capsule(length: {num(length)}, radius: {num(r)})"


def polygon(points):
    return "Polygon(points: [" + ", ".join(v2(p) for p in points) + "])"


def segment(a, b):
    return f"Segment(a: {v2(a)}, b: {v2(b)})"


def body(name, shape=None, kind=None, position=None, angle=None, velocity=None, omega=None,
         mass=None, density=None, inertia=None, friction=None, restitution=None,
         lock_rotation=False):
    f = [f'name: "{name}"']
    if kind:
        f.append(f"kind: {kind}")
    if shape:
        f.append(f"shape: {shape}")
    if position is not None:
        f.append(f"position: {v2(position)}")
    if angle:
        f.append(f"angle: {num(angle)}")
    if velocity is not None:
        f.append(f"velocity: {v2(velocity)}")
    if omega:
        f.append(f"omega: {num(omega)}")
    if mass is not None:
        f.append(f"mass: {num(mass)}")
    if density is not None:
        f.append(f"density: {num(density)}")
    if inertia is not None:
        f.append(f"inertia: {num(inertia)}")
    if friction is not None:
        f.append(f"friction: {num(friction)}")
    if restitution is not None:
        f.append(f"restitution: {num(restitution)}")
    if lock_rotation:
        f.append("lock_rotation: true")
    return "(" + ", ".join(f) + ")"


def revolute(name, b1, b2, a1, a2):
    return (f'(name: "{name}", kind: revolute, body1: "{b1}", body2: "{b2}", '
            f"anchor1: {v2(a1)}, anchor2: {v2(a2)})")


def spring(name, b1, p2, k, rest):
    return (f'(name: "{name}", body1: "{b1}", point2: {v2(p2)}, stiffness: {num(k)}, '
            f"rest_length: {num(rest)})")


def level(file, header, title, source, statement, effects, world_, bodies, joints=(), springs=()):
    out = [f"// {line}" if line else "//" for line in header.strip("\n").split("\n")]
    out.append("Level(")
    out.append(f"  title: {quote(title)},")
    out.append(f"  source: (book: {quote(source[0])}, problem: {quote(source[1])}),")
    out.append(f"  statement: {quote(statement)},")
    out.append("  effects: [" + ", ".join(effects) + "],")
    out.append(f"  world: {world_},")
    out.append("  bodies: [")
    out += [f"    {b}," for b in bodies]
    out.append("  ],")
    if joints:
        out.append("  joints: [")
        out += [f"    {j}," for j in joints]
        out.append("  ],")
    if springs:
        out.append("  springs: [")
        out += [f"    {s}," for s in springs]
        out.append("  ],")
    out.append(")")
    with open(os.path.join(HERE, file), "w") as fh:
        fh.write("\n".join(out) + "\n")


def quote(s):
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def ground_box(name="ground", center=(0.0, -1.0), w=200.0, h=2.0, friction=None):
    return body(name, box(w, h), kind="fixed", position=center, friction=friction)


# ---------------------------------------------------------------- contacts


def vertical_stack():
    bodies = [ground_box()]
    for i in range(15):
        shift = -0.01 if i % 2 == 0 else 0.01
        bodies.append(body(f"box{i:02}", box(1, 1), position=(shift, 0.5 + i), density=1.0,
                           friction=0.3))
    level("vertical_stack.ron", """
Vertical stack of 15 unit boxes, alternately shifted by +-1 cm (Solver2D / Box2D v3 "Vertical Stack").
Criteria (src/study/stability/cases.rs): the top box moves < 5 cm, penetration, energy never gained.
Recorded: contacts at 60 Hz (world.contact_hz; at rapier's 30 Hz the stack sinks 7.2 cm).
""", "Vertical stack of 15 boxes", ("Solver2D / Box2D v3", "Contact/Vertical Stack"),
          "Fifteen 1 m boxes (density 1 kg/m^2, mu 0.3) stacked on the ground, every other one shifted 1 cm. The stack must stand still.",
          ["gravity", "contacts", "friction"], world(contact_hz=60), bodies)


def pyramid(base, origin=(0.0, 0.0), friction=0.6, prefix="box", density=1.0):
    out = []
    h = 0.5
    for i in range(base):
        y = origin[1] + (2 * i + 1) * h
        for j in range(i, base):
            x = origin[0] + (i + 1) * h + 2 * (j - i) * h - h * base
            out.append(body(f"{prefix}{i:02}_{j:02}", box(1, 1), position=(x, y), density=density,
                            friction=friction))
    return out


def pyramid_20():
    bodies = [ground_box()] + pyramid(20)
    level("pyramid_20.ron", """
Pyramid with a base of 20 unit boxes: 210 boxes (Solver2D / Box2D v3 "Pyramid", debug size).
Criteria: the top box moves < 5 cm, penetration, energy never gained.
""", "Pyramid of base 20", ("Solver2D / Box2D v3", "Contact/Pyramid (base 20)"),
          "210 boxes of 1 m (density 1 kg/m^2, mu 0.6) in a pyramid of base 20. It must stand still.",
          ["gravity", "contacts", "friction"], world(), bodies)


def card_house():
    # PEEL / Box2D v3 "Card House": cards 0.4 m x 2 mm, mu 0.7, leaning at +-25 degrees.
    card_h, card_t = 0.2, 0.001  # half extents
    a0, a1, a2 = math.radians(25), -math.radians(25), math.pi / 2
    bodies = [body("ground", box(80, 4), kind="fixed", position=(0, -2), friction=0.7)]
    nb, z0, y = 5, 0.0, card_h - 0.02
    k = 0
    level_no = 0
    while nb:
        z = z0
        for i in range(nb):
            if i != nb - 1:
                bodies.append(body(f"flat{level_no}_{i}", box(2 * card_t, 2 * card_h),
                                   position=(z + 0.25, y + card_h - 0.015), angle=a2,
                                   density=1.0, friction=0.7))
            bodies.append(body(f"left{level_no}_{i}", box(2 * card_t, 2 * card_h), position=(z, y),
                               angle=a1, density=1.0, friction=0.7))
            z += 0.175
            bodies.append(body(f"right{level_no}_{i}", box(2 * card_t, 2 * card_h),
                               position=(z, y), angle=a0, density=1.0, friction=0.7))
            z += 0.175
            k += 1
        y += card_h * 2 - 0.03
        z0 += 0.175
        nb -= 1
        level_no += 1
    level("card_house.ron", """
Card house of 5 storeys (PEEL, via Box2D v3 "Card House"): 40 cards 0.4 m x 2 mm leaning at +-25 deg, mu 0.7.
Held by friction only. Criteria: after the pairs lean together (1 s) the top pair moves < 1 cm,
penetration, energy never gained. Recorded: 8 substeps (at 4 the house collapses).
""", "Card house", ("Box2D v3 (from PEEL)", "Stacking/Card House"),
          "Forty playing cards (0.4 m by 2 mm, mu 0.7) leaning in pairs at 25 degrees with flat cards across, five storeys high. Friction alone holds it up.",
          ["gravity", "contacts", "friction"], world(substeps=8), bodies)


ARCH_PS1 = [(16.0, 0.0), (14.93803712795643, 5.133601056842984), (13.79871746027416, 10.24928069555078),
            (12.56252963284711, 15.34107019122473), (11.20040987372525, 20.39856541571217),
            (9.66521217819836, 25.40369899225096), (7.87179930638133, 30.3179337000085),
            (5.635199558196225, 35.03820717801641), (2.405937953536585, 39.09554102558315)]
ARCH_PS2 = [(24.0, 0.0), (22.33619528222415, 6.02299846205841), (20.54936888969905, 12.00964361211476),
            (18.60854610798073, 17.9470321677465), (16.46769273811807, 23.81367936585418),
            (14.05325025774858, 29.57079353071012), (11.23551045834022, 35.13775818285372),
            (7.752566060730571, 40.30450679009583), (3.016931552701656, 44.28891593799322)]


def arch():
    s = 0.25
    p1 = [(x * s, y * s) for x, y in ARCH_PS1]
    p2 = [(x * s, y * s) for x, y in ARCH_PS2]
    bodies = [body("ground", segment((-100, 0), (100, 0)), kind="fixed", friction=0.6)]
    # Voussoirs: the polygon points are world points, so each body sits at the origin.
    for i in range(8):
        bodies.append(body(f"right{i}", polygon([p1[i], p2[i], p2[i + 1], p1[i + 1]]), density=1.0,
                           friction=0.6))
    for i in range(8):
        bodies.append(body(f"left{i}", polygon([(-p2[i][0], p2[i][1]), (-p1[i][0], p1[i][1]),
                                                (-p1[i + 1][0], p1[i + 1][1]),
                                                (-p2[i + 1][0], p2[i + 1][1])]),
                           density=1.0, friction=0.6))
    bodies.append(body("keystone", polygon([p1[8], p2[8], (-p2[8][0], p2[8][1]), (-p1[8][0], p1[8][1])]),
                       density=1.0, friction=0.6))
    for i in range(4):
        bodies.append(body(f"load{i}", box(4, 1), position=(0, 0.5 + p2[8][1] + i), density=1.0,
                           friction=0.6))
    level("arch.ron", """
Arch of 17 voussoirs with 4 boxes on top, no joints: friction mu 0.6 holds it (Box2D v3 "Arch").
Criteria: the top box moves < 5 cm, penetration, energy never gained. Recorded: 16 substeps, and
contacts at 120 Hz (world.contact_hz; at rapier's 30 Hz the arch settles 31 cm).
""", "Arch held by friction", ("Box2D v3 / Solver2D", "Stacking/Arch"),
          "Seventeen voussoirs (mu 0.6) form a free-standing arch 11 m high carrying four 4 m x 1 m blocks. Nothing but contact and friction holds it.",
          ["gravity", "contacts", "friction"], world(substeps=16, contact_hz=120), bodies)


def mass_ratio_100():
    # Solver2D "High Mass Ratio 1": three pyramids of base 10 (2 m boxes, mu 0.5); the top box
    # of each has density 100, 200, 300 (the others 1), dropped from 2 m above its place.
    bodies = [body("ground", segment((-66, 0), (66, 0)), kind="fixed", friction=0.5)]
    e = 1.0
    for j in range(3):
        count = 10
        offset = -20 * e + 2 * (count + 1) * e * j
        y = e
        row = 0
        while count > 0:
            for i in range(count):
                coeff = i - 0.5 * count
                yy = y + 2 if count == 1 else y
                name = f"top{j}" if count == 1 else f"p{j}_{row}_{i}"
                bodies.append(body(name, box(2 * e, 2 * e), position=(2 * coeff * e + offset, yy),
                                   density=(j + 1) * 100.0 if count == 1 else 1.0, friction=0.5))
            count -= 1
            row += 1
            y += 2 * e
    level("mass_ratio_100.ron", """
High mass ratio 1 (Solver2D): three pyramids of base 10 (2 m boxes, mu 0.5) whose top box is 100, 200
and 300 times as heavy as the others, dropped from 2 m above its seat. Criteria: the heavy top boxes do not
sink (penetration < 1 cm), the tops stay put after landing (< 5 cm), energy never gained.
Recorded: 32 substeps, and contacts at 120 Hz (world.contact_hz) (at 30 Hz the tops sink 6.5 cm).
""", "High mass ratio 100:1 to 300:1 on pyramids", ("Solver2D", "Contact/High Mass Ratio 1"),
          "Three pyramids of 2 m boxes (density 1 kg/m^2, mu 0.5); the top box of each has density 100, 200, 300 kg/m^2 and is dropped from 2 m above its seat.",
          ["gravity", "contacts", "friction"], world(substeps=32, contact_hz=120), bodies)


def mass_ratio_400():
    # Solver2D "High Mass Ratio 2": a 20 m box (density 1) dropped onto two 1 m boxes: 400:1.
    bodies = [body("ground", segment((-66, 0), (66, 0)), kind="fixed", friction=0.6),
              body("small_left", box(1, 1), position=(-9, 0.5), density=1.0, friction=0.6),
              body("small_right", box(1, 1), position=(9, 0.5), density=1.0, friction=0.6),
              body("big", box(20, 20), position=(0, 26), density=1.0, friction=0.6)]
    level("mass_ratio_400.ron", """
High mass ratio 2 (Solver2D): a 20 m box dropped from 15 m onto two 1 m boxes of the same density (400:1).
Criteria: the big box comes to rest on the small ones (its centre at 11 m, sink < 2 cm), the small boxes
are not squeezed out, energy never gained. Recorded: 32 substeps, and contacts at 120 Hz (world.contact_hz).
""", "High mass ratio 400:1: big box on two small ones", ("Solver2D", "Contact/High Mass Ratio 2"),
          "A 20 m x 20 m box (density 1 kg/m^2) falls 15 m onto two 1 m boxes of the same density standing 18 m apart.",
          ["gravity", "contacts", "friction"], world(substeps=32, contact_hz=120), bodies)


def friction_ramp():
    # A fixed ramp tilted 0.25 rad (tan = 0.2553): mu 0.35 and 0.3 stick, 0.2, 0.1 and 0 slide.
    # Pairs take the larger mu of the two bodies (rigidlab's combine rule), so the ramp has none.
    th = -0.25
    c, s = math.cos(th), math.sin(th)
    length, thick = 200.0, 1.0
    bodies = [body("ramp", box(length, thick), kind="fixed", position=(0, 0), angle=th)]
    t = (c, s)        # down-slope tangent points to +x and down
    n = (-s, c)       # outward normal
    mus = [0.35, 0.3, 0.2, 0.1, 0.0]
    for k, mu in enumerate(mus):
        u = -90.0 + 3.0 * k          # position along the ramp from its centre
        off = thick / 2 + 0.5        # ramp half thickness + box half size
        p = (u * t[0] + off * n[0], u * t[1] + off * n[1])
        bodies.append(body(f"mu{int(round(mu * 100)):03}", box(1, 1), position=p, angle=th,
                           density=25.0, friction=mu if mu > 0 else None))
    # A stop at the foot of the ramp keeps the sliders on it in long runs (reached after 12 s).
    u_stop = 97.0
    off = thick / 2 + 2.0
    bodies.append(body("stop", box(1.0, 4.0), kind="fixed",
                       position=(u_stop * t[0] + off * n[0], u_stop * t[1] + off * n[1]), angle=th))
    level("friction_ramp.ron", """
Friction ramp (after Solver2D/Box2D "Friction Ramp" and newton-physics PR #2549): boxes at rest on a
ramp tilted 0.25 rad (tan = 0.2553) with mu = 0.35, 0.3 (stick) and 0.2, 0.1, 0 (slide).
Criteria: stickers creep < 1 cm; sliders travel 1/2 g (sin - mu cos) t^2 within 2 % by 10 s. A stop at
the ramp's foot catches the sliders (the frictionless one arrives after 12 s).
""", "Friction ramp: stick below tan(theta), slide above", ("Solver2D / Box2D v3", "Contact/Friction Ramp"),
          "Five 1 m boxes rest on a 200 m ramp tilted 0.25 rad. Their friction coefficients are 0.35, 0.3, 0.2, 0.1 and 0. Which ones slide, and how far in 10 s?",
          ["gravity", "contacts", "friction"], world(), bodies)


def overlap_recovery():
    # Solver2D "Overlap Recovery": pyramid of base 4, 1 m boxes overlapping by 25 %.
    base, overlap, extent = 4, 0.25, 0.5
    frac = 1 - overlap
    bodies = [body("ground", segment((-40, 0), (40, 0)), kind="fixed", friction=0.6)]
    y = extent
    for i in range(base):
        x = frac * extent * (i - base)
        for j in range(i, base):
            bodies.append(body(f"box{i}_{j}", box(1, 1), position=(x, y), density=1.0, friction=0.6))
            x += 2 * frac * extent
        y += 2 * frac * extent
    level("overlap_recovery.ron", """
Overlap recovery (Solver2D / Box2D v3): a pyramid of base 4 whose 1 m boxes start 25 % overlapped.
They must push apart without popping. Criteria: penetration < 1 cm after 2 s, the top box never above
its separated seat, energy below the initial energy plus the lift needed to separate the rows.
""", "Overlap recovery", ("Solver2D / Box2D v3", "Robustness/Overlap Recovery"),
          "Ten 1 m boxes (mu 0.6) stacked as a pyramid of base 4 start with 25 % overlap. They should separate gently.",
          ["gravity", "contacts", "friction"], world(), bodies)


def far_origin():
    # The vertical stack's cousin, a pyramid of base 6, 10 km from the origin (8 km, 6 km).
    ox, oy = 8000.0, 6000.0
    bodies = [body("ground", box(100, 2), kind="fixed", position=(ox, oy - 1), friction=0.6)]
    bodies += pyramid(6, origin=(ox, oy))
    level("far_origin.ron", """
Far from the origin (Solver2D "Far" samples, Box2D's "good to about 20 km"): a pyramid of base 6 built at
(8 km, 6 km), 10 km from the origin, where an f32 coordinate has a resolution of 0.5 to 1 mm.
Criteria: as the near-origin pyramid, the top box moves < 5 cm, penetration, energy never gained.
""", "A pyramid 10 km from the origin", ("Solver2D", "Far/Pyramid"),
          "Twenty-one 1 m boxes (mu 0.6) in a pyramid of base 6 standing at (8000, 6000) m. It must stand still.",
          ["gravity", "contacts", "friction"], world(), bodies)


def bullet_wall():
    bodies = [body("wall", box(0.02, 4), kind="fixed", position=(10, 2)),
              body("ground", segment((-20, 0), (40, 0)), kind="fixed"),
              body("bullet", circle(0.05), position=(0, 2), velocity=(300, 0), density=8000.0)]
    level("bullet_wall.ron", """
A bullet (5 cm radius) at 300 m/s against a fixed wall 2 cm thick (rapier#421, #984; Box2D "Bullet").
At 1/60 s it travels 5 m a step, 250 times the wall's thickness. Criteria: its centre never crosses the
wall's mid-plane. Recorded: the `ccd` effect (without it the ball flies through).
""", "Fast bullet against a thin wall", ("Box2D v3 / rapier issues", "Continuous/Bullet; rapier#421"),
          "A 10 cm steel ball flies at 300 m/s toward a 2 cm wall 10 m away. It must not tunnel through.",
          ["gravity", "contacts", "ccd"], world(), bodies)


def bouncing_ball_e1():
    bodies = [body("floor", segment((-5, 0), (5, 0)), kind="fixed"),
              body("ball", circle(0.1), position=(0, 1.1), mass=0.6, restitution=1.0,
                   lock_rotation=True)]
    level("bouncing_ball_e1.ron", """
A ball with e = 1 bouncing on the floor (rapier#97: it bounced higher every time). Energy must not grow.
Criteria: total energy never above the initial energy plus a stated margin; the apex never above 1.11 m;
penetration. Recorded: the `ccd` effect (without it the ball sinks 5 cm into the floor at each impact).
""", "Ball bouncing with e = 1", ("rapier issues", "rapier#97, #919, #974"),
          "A ball (r = 0.1 m) is dropped from 1 m onto a rigid floor with a coefficient of restitution of 1. It should bounce back to the same height, never higher.",
          ["gravity", "contacts", "restitution", "ccd"], world(), bodies)


def newtons_cradle():
    # Five balls of radius 0.25 m on 2 m pins, touching; the first one released from 60 degrees.
    r, L, n = 0.25, 2.0, 5
    bodies = []
    joints = []
    a = math.radians(60)
    for i in range(n):
        px = 2 * r * i
        bodies.append(body(f"pivot{i}", kind="fixed", position=(px, L)))
        if i == 0:
            pos = (px - L * math.sin(a), L - L * math.cos(a))
        else:
            pos = (px, 0.0)
        bodies.append(body(f"ball{i}", circle(r), position=pos, mass=1.0, inertia=1e-6,
                           restitution=1.0))
        joints.append(revolute(f"string{i}", f"pivot{i}", f"ball{i}", (0, 0),
                               (px - pos[0], L - pos[1])))
    level("newtons_cradle.ron", """
Newton's cradle (rapier#630: with e = 1 it gained energy under the TGS-soft solver): five 1 kg balls
(r = 0.25 m) on 2 m pins, touching; the first is released from 60 degrees. No friction.
Criteria: total energy never above the initial energy plus a stated margin; penetration; joint separation.
Recorded: dt 1/180 s with 2 substeps (at 1/60 s the impact drives one ball 3 cm into the next).
""", "Newton's cradle with e = 1", ("rapier issues", "rapier#630"),
          "Five 1 kg balls hang touching on 2 m strings. The first is pulled aside 60 degrees and released. With e = 1 the energy must not grow.",
          ["gravity", "contacts", "restitution", "joints"], world(dt=1 / 180, substeps=2), bodies, joints)


def mass_extremes():
    # Stack A: 1 kg / 1 g / 1 kg (a feather crushed between two boxes).
    # Stack B: 1 kg under a 1000 kg box. Boxes 1 m, mu 0.5.
    bodies = [ground_box(friction=0.5),
              body("a_base", box(1, 1), position=(-3, 0.5), mass=1.0, friction=0.5),
              body("a_light", box(1, 1), position=(-3, 1.5), mass=1e-3, friction=0.5),
              body("a_top", box(1, 1), position=(-3, 2.5), mass=1.0, friction=0.5),
              body("b_base", box(1, 1), position=(3, 0.5), mass=1.0, friction=0.5),
              body("b_heavy", box(1, 1), position=(3, 1.5), mass=1e3, friction=0.5)]
    level("mass_extremes.ron", """
Extreme masses: a 1 g box between two 1 kg boxes, and a 1000 kg box on a 1 kg box (ratios 1e-3 and 1e3).
Criteria: the tops move < 2 cm, penetration, energy never gained. Recorded: 32 substeps, and contacts
at 240 Hz (world.contact_hz; at rapier's 30 Hz the heavy box sinks through the light one).
""", "Bodies 1e-3 and 1e3 times the others' mass", ("rapier / avian issues", "avian#886, dart#3442"),
          "Two stacks of 1 m boxes: 1 kg, 1 g, 1 kg; and 1 kg under 1000 kg. Both must stand.",
          ["gravity", "contacts", "friction"], world(substeps=32, contact_hz=240), bodies)


# ---------------------------------------------------------------- joints


def chain_links(n, spacing, y, prefix="link", density=20.0, r=0.125):
    """Capsule links of length 1 m (cap centres +-0.5) laid along +x from a pivot at (0, y)."""
    bodies, joints = [], []
    prev = "pivot"
    for i in range(n):
        name = f"{prefix}{i:02}"
        bodies.append(body(name, capsule(1.0, r), position=((i + 0.5) * spacing, y), density=density))
        if i == 0:
            joints.append(revolute(f"j{i:02}", prev, name, (0, y), (-0.5, 0)))
        else:
            joints.append(revolute(f"j{i:02}", prev, name, (0.5, 0), (-0.5, 0)))
        prev = name
    return bodies, joints


def ball_and_chain():
    n, y, R = 40, 20.0, 7.5
    bodies, joints = chain_links(n, 1.0, y)
    bodies.insert(0, body("pivot", kind="fixed", position=(0, 0)))
    bodies.append(body("ball", circle(R), position=(n + R, y), density=20.0))
    joints.append(revolute("j_ball", f"link{n - 1:02}", "ball", (0.5, 0), (-R, 0)))
    level("ball_and_chain.ron", """
Ball and chain (Solver2D "Ball & Chain"): 40 capsule links (1 m, r 0.125, density 20) and a 7.5 m ball of
the same density, 591 times a link's mass, released horizontally. No damping, no contacts.
Criteria: joint separation < 2 cm, energy never above the initial energy plus 1 %.
Recorded: 64 substeps (at 4 the links open by 62 cm; 32 hold 10 s but not 1e5 steps).
""", "Ball and chain: 591:1 across a joint chain", ("Solver2D", "Joints/Ball & Chain"),
          "A chain of forty 1 m links (6 kg each) pinned at one end carries a 3.5 t ball at the other. It is released horizontally and swings.",
          ["gravity", "joints"], world(substeps=64), bodies, joints)


def stretched_chain():
    n, y = 40, 0.0
    bodies, joints = chain_links(n, 2.0, y)
    # The gaps are the test: say so, or validation rejects anchors that do not meet.
    joints = [j[:-1] + ", starts_apart: true)" for j in joints]
    bodies.insert(0, body("pivot", kind="fixed", position=(0, 0)))
    level("stretched_chain.ron", """
Stretched chain (Solver2D "Stretched Chain"): 40 links of 1 m created 2 m apart, so every joint starts
with a 1 m gap. The joints must close without exploding. No contacts.
Criteria: joint separation < 1 cm after 5 s, no body faster than 56 m/s, energy below the stated bound.
Recorded: 48 substeps close the joints (32 did with parry's 1.2%-light capsule inertia, 1.1 cm with the exact one); the energy and speed criteria fail at every setting (engine limit).
The run's energy-explosion guard lets it pass: the gain peaks at 5.6e3 x its reference in the first step
(links at rapier's 400 m/s clamp), is below 1e3 x within 0.3 s and below 1 x by 4.7 s: bounded, not sustained.
""", "Stretched chain recovers", ("Solver2D", "Joints/Stretched Chain"),
          "Forty 1 m links are created with their centres 2 m apart, pinned end to end: every pin starts 1 m open. The chain must pull itself together and hang.",
          ["gravity", "joints"], world(substeps=48), bodies, joints)


def bridge():
    n, y = 80, 20.0
    bodies = [body("left", kind="fixed", position=(0, y)), body("right", kind="fixed", position=(n, y))]
    joints = []
    prev = "left"
    for i in range(n):
        name = f"plank{i:02}"
        bodies.append(body(name, box(1.0, 0.25), position=(i + 0.5, y), density=20.0))
        joints.append(revolute(f"j{i:02}", prev, name, (0, 0) if i == 0 else (0.5, 0), (-0.5, 0)))
        prev = name
    joints.append(revolute(f"j{n:02}", prev, "right", (0.5, 0), (0, 0)))
    level("bridge_80.ron", """
Bridge of 80 planks (Solver2D "Bridge", half length): 80 planks of 1 m x 0.25 m (density 20) pinned end to end
between two fixed pins exactly 80 m apart, so the bridge can sag only by stretching its joints.
Criteria: joint separation < 2 cm, sag of the middle plank, energy never gained. Recorded: 16 substeps.
""", "Bridge of 80 planks", ("Solver2D", "Joints/Bridge"),
          "Eighty 1 m planks are pinned end to end between two pins 80 m apart. The chain is exactly as long as the span: any sag comes from joint error.",
          ["gravity", "joints"], world(substeps=16), bodies, joints)


def joint_grid():
    n = 30
    bodies, joints = [], []
    for k in range(n):
        for i in range(n):
            name = f"n{k:02}_{i:02}"
            fixed = (n // 2 - 3 <= k <= n // 2 + 3) and i == 0
            if fixed:
                bodies.append(body(name, circle(0.4), kind="fixed", position=(k, -i)))
            else:
                bodies.append(body(name, circle(0.4), position=(k, -i), density=1.0))
            if i > 0:
                joints.append(revolute(f"v{k:02}_{i:02}", f"n{k:02}_{i - 1:02}", name, (0, -0.5), (0, 0.5)))
            left_fixed = (n // 2 - 3 <= k - 1 <= n // 2 + 3) and i == 0
            if k > 0 and not (fixed and left_fixed):
                joints.append(revolute(f"h{k:02}_{i:02}", f"n{k - 1:02}_{i:02}", name, (0.5, 0), (-0.5, 0)))
    level("joint_grid_30.ron", """
Joint grid 30 x 30 (Solver2D / Box2D v3 "Joint Grid"): 900 discs (r 0.4, density 1) pinned to their
neighbours 1 m apart, 7 of the top row fixed; it falls and drapes. "This stresses the joint solver."
Criteria: joint separation < 2 cm, energy never gained, everything stays inside. Recorded: 16 substeps.
""", "Joint grid 30 x 30", ("Solver2D / Box2D v3", "Joints/Joint Grid"),
          "A 30 x 30 net of discs pinned to their neighbours hangs from seven fixed discs in the middle of its top row.",
          ["gravity", "joints"], world(substeps=16), bodies, joints)


# ---------------------------------------------------------------- free motion, springs


def spinning_disc():
    bodies = [body("disc", circle(0.5), position=(0, 0), omega=100.0, density=1.0)]
    level("spinning_disc.ron", """
Torque-free disc spinning at 100 rad/s in zero gravity: omega and energy must hold.
rapier clamps |omega| to (pi/4)/dt per step unless a body allows fast rotation (47.1 rad/s at dt = 1/60 s),
and rotates by the linearized angle atan(omega h) per substep. Recorded setting: dt = 1/128 s, the
largest power-of-two step whose cap (100.5 rad/s) lets 100 rad/s through.
Criteria: omega within 1e-4, energy within 1e-4, angle rate equal to the linearized theory atan(omega h)/h.
""", "Torque-free disc at 100 rad/s", ("rapier 0.35 changelog", "speed caps; torque-free spin"),
          "A disc of radius 0.5 m spins at 100 rad/s with nothing acting on it. Its angular velocity and kinetic energy must stay constant.",
          [], world(dt=1 / 128), bodies)


def stiff_spring():
    # Four 1 kg masses on ground-anchored springs with omega*dt = 0.5, 1.0, 1.5, 1.9 at dt = 1/60
    # (symplectic Euler is stable for omega*dt < 2). Each starts 0.1 m stretched, at rest.
    dt = 1 / 60
    bodies, springs = [], []
    for k, Om in enumerate([0.5, 1.0, 1.5, 1.9]):
        w = Om / dt
        y = -2.0 * k
        name = f"m{k}"
        bodies.append(body(name, circle(0.1), position=(1.1, y), mass=1.0, lock_rotation=True))
        springs.append(spring(f"s{k}", name, (0, y), w * w, 1.0))
    level("stiff_spring.ron", """
Stiff springs at k/m near the step's limit: four 1 kg masses on springs with omega*dt = 0.5, 1.0, 1.5, 1.9
(explicit symplectic Euler is stable below 2), released 0.1 m stretched, no gravity, no damping.
rigidlab evaluates spring forces before every substep, so n substeps integrate as symplectic Euler at
h = dt/n (held over 4 substeps they gained x2.5e4 in 10 s). Recorded setting: rapier's default 4 substeps
(omega*h = omega*dt/4, the cheapest that passes now); at substeps 1 each spring reaches its bound at omega*h = omega*dt.
Criteria: each spring's energy stays below E0 / (1 - omega*h/2), the exact bound for symplectic Euler.
""", "Stiff springs at the step's stability limit", ("numerical analysis", "symplectic Euler, omega h < 2"),
          "Four 1 kg masses on springs of stiffness 900, 3600, 8100 and 12996 N/m are released 0.1 m stretched. With dt = 1/60 s, omega*dt is 0.5 to 1.9.",
          ["springs"], world(), bodies, springs=springs)


def sand_pile():
    """10,000 grains poured into a bin: the sandbox's thousands-of-bodies scene (issue 45)."""
    r, pitch, cols, rows = 0.05, 0.12, 250, 40
    # Half a pitch of room each side for the rows' alternating shift of a quarter pitch.
    half = round(0.5 * (cols + 1) * pitch, 4)
    bodies = [ground_box(w=round(2.0 * half + 2.0, 4)),
              body("left_wall", box(1.0, 8.0), kind="fixed", position=(round(-half - 0.5, 4), 4.0)),
              body("right_wall", box(1.0, 8.0), kind="fixed", position=(round(half + 0.5, 4), 4.0))]
    for j in range(rows):
        # Rows shifted alternately by +-a quarter pitch, so each grain lands in the hollow
        # between two below; positions rounded to 0.1 mm to keep the file small.
        shift = 0.25 * pitch if j % 2 == 0 else -0.25 * pitch
        for i in range(cols):
            x = round(-0.5 * (cols - 1) * pitch + i * pitch + shift, 4)
            y = round(r + 0.02 + j * pitch, 4)
            # Density: the format's default, 1000 kg/m^2.
            bodies.append(body(f"g{j * cols + i}", circle(r), position=(x, y), friction=0.5))
    level("sand_pile.ron", f"""
Sand pile: {rows * cols} grains (discs of radius {r} m) dropped from a {cols} x {rows} grid into a bin
{2 * half:g} m wide, where they settle into a pile about {rows * cols * 2 * r / (2 * half):.0f} grains deep. The sandbox's
thousands-of-bodies scene (issue 45): `cargo bench --bench frame` and `--bench runner` time it.
Criteria (src/study/stability/cases.rs): energy never gained, penetration, every grain stays in the bin,
the pile comes to rest. Recorded: contacts at 60 Hz (world.contact_hz; at rapier's 30 Hz the grains at the
bottom of the pile sink 2.9 cm into each other).
""", f"Sand pile of {rows * cols} grains", ("rigidlab stress suite", "10,000 bodies (issue 45)"),
          f"{rows * cols} grains of sand, discs of radius {r} m (density 1000 kg/m^2, mu 0.5), fall into a bin {2 * half:g} m wide and settle. The pile must come to rest without exploding, gaining energy or leaking grains.",
          ["gravity", "contacts", "friction"], world(contact_hz=60.0), bodies)


def domino_field(lanes=50, per_lane=200, file="domino_field.ron", duration=12.0):
    # 12 s: the wave runs the 6.5 m of a lane at 0.63 m/s (measured: no closed form), 10.6 s.
    """Dominoes on stacked shelves, the first of each lane pushed: the sandbox's other
    thousands-of-bodies scene (issue 45), where `sleeping` keeps the dominoes not yet struck out
    of the solver. `lanes` x `per_lane` dominoes (tests/suite/study/domino_field.rs runs the
    level's first two lanes)."""
    # A domino 5 cm x 1 cm (height : thickness 5 : 1, a toy domino's proportions in 2D), spaced
    # 0.65 of its height; mu 0.4 (wood on wood). Shelves 2 cm thick, 12 cm apart: a fallen
    # domino (5 cm long, lying at most 5 cm high) never reaches the shelf above.
    h, t, d, mu = 0.05, 0.01, 0.0325, 0.4
    shelf_t, pitch = 0.02, 0.12
    # Room for the last domino to fall flat on its shelf: a height and a margin past it.
    lead, tail = 0.05, h + 0.05
    length = round(lead + (per_lane - 1) * d + t + tail, 4)
    x0 = round(-0.5 * length + lead + 0.5 * t, 4)
    # The push: the first domino of a lane turns about its front bottom corner at omega0, the
    # rigid motion of a tap (v_G = omega x (G - pivot)); 6 rad/s is 1.8x the 3.35 rad/s that
    # lifts its centre over the corner (m g (sqrt(h^2 + t^2)/2 - h/2) = I_pivot omega^2 / 2).
    w0 = 6.0
    push_v = (w0 * h / 2, w0 * t / 2)
    bodies = []
    for k in range(lanes):
        top = round(k * pitch, 4)
        bodies.append(body(f"shelf{k}", box(length, shelf_t), kind="fixed",
                           position=(0.0, round(top - shelf_t / 2, 4)), friction=mu))
        for i in range(per_lane):
            x = round(x0 + i * d, 4)
            first = i == 0
            bodies.append(body(f"d{k * per_lane + i}", box(t, h), position=(x, round(top + h / 2, 4)),
                               velocity=push_v if first else None, omega=-w0 if first else None,
                               friction=mu))
    n = lanes * per_lane
    level(file, f"""
Domino field: {n} dominoes (boxes {h} m x {t} m, spaced {d} m, mu {mu}) standing in {lanes} lanes of
{per_lane} on stacked shelves {pitch} m apart; the first domino of each lane is pushed (6 rad/s about its
front bottom corner) and the wave runs to the far end, at 0.63 m/s (10.6 s). The sandbox's other
thousands-of-bodies scene (issue 45), with `sleeping` declared: the dominoes not yet struck sleep from
0.5 s; the fallen ones stay awake with their row's front (rapier sleeps an island whole) until the row
is down. `cargo bench --bench frame` and `--bench runner` time it.
Criteria (src/study/stability/cases.rs): energy never gained, penetration, every domino stays on the
shelves, every domino ends toppled (tests/suite/study/domino_field.rs derives the angles).
""", f"Domino field of {n} dominoes", ("rigidlab stress suite", "10,000 bodies (issue 45)"),
          f"{n} dominoes, boxes {h * 100:g} cm tall and {t * 100:g} cm thick spaced {d * 100:g} cm apart (mu {mu}), stand in {lanes} rows on shelves. The first of each row is tipped over; the wave must run to the last domino of every row without the field exploding or gaining energy.",
          ["gravity", "contacts", "friction", "sleeping"], world(duration=duration), bodies)


def main():
    vertical_stack()
    pyramid_20()
    card_house()
    arch()
    mass_ratio_100()
    mass_ratio_400()
    friction_ramp()
    overlap_recovery()
    far_origin()
    bullet_wall()
    bouncing_ball_e1()
    newtons_cradle()
    mass_extremes()
    ball_and_chain()
    stretched_chain()
    bridge()
    joint_grid()
    spinning_disc()
    stiff_spring()
    sand_pile()
    domino_field()


if __name__ == "__main__":
    main()
