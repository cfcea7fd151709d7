#!/usr/bin/env python3
"""Writes the seeds of the `cluster` and `tangential` fuzz targets (fuzz/seeds/cluster/,
fuzz/seeds/tangential/) in the byte layouts documented on `check_cluster` and
`check_tangential` in fuzz/checks.rs. Run from anywhere: python3 fuzz/seeds/make_cluster_tangential.py
"""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def speed_byte(v):
    """The byte of a speed 1e-3 10^(4 b/255) m/s."""
    return round(255 * math.log10(v / 1e-3) / 4)


def over(entries):
    """Raw overrides: a count, then (selector, f64) entries."""
    out = bytes([len(entries)])
    for sel, x in entries:
        out += bytes([sel]) + struct.pack("<d", x)
    return out


def cluster(b0, b1, mu, rtol_byte, speed, dir_byte=128, damp=128, spin=0, balls=(), raw=()):
    head = bytes([b0, b1, mu, rtol_byte, speed_byte(speed), dir_byte, damp, spin])
    body = b"".join(bytes(b) for b in balls).ljust(40, b"\0")
    return head + body + (over(raw) if raw else b"")


def tangential(b0, b1, mu, rtol_byte, speed, incidence_deg, b6=128, spin_a=0, r_a=0.028575,
               r_b=0.028575, spin_b=0, turn=0, b12=0, raw=()):
    rb = lambda r: round(255 * (math.log10(r) + 3) / 2)
    head = bytes([b0, b1, mu, rtol_byte, speed_byte(speed), round(255 * incidence_deg / 89),
                  b6, spin_a, rb(r_a), rb(r_b), spin_b, turn, b12]).ljust(16, b"\0")
    return head + (over(raw) if raw else b"")


CLUSTER = {
    # Two pool balls head on, elastic Hertz, no friction, rtol 1e-8: they exchange velocities.
    "two_balls_head_on": cluster(0, 0, 0, 5, 1.0),
    # Newton's cradle of 5, elastic, 1 m/s.
    "cradle_5": cluster(3, 0, 0, 5, 1.0),
    # A cue ball into a 6-ball rack, Hunt-Crossley, mu 0.2, stick, 3 m/s, spins.
    "rack_7_hunt_crossley_spin": cluster(5 | 0x08 | 0x20, 1, 161, 5, 3.0, 140, 110, 60,
                                         [(0, 0, 0, 30 * i % 200, 0) for i in range(8)]),
    # A zig-zag of 4 with spins and sideways velocities, resin calibrated to e = 0.9.
    "zigzag_4_materials_restitution": cluster(2 | 0x10 | 0x20, 3 | (3 << 2), 60, 4, 2.0, 100,
                                              227, 80, [(5, 40, 20, 90, 0), (250, 200, 230, 10, 0),
                                                        (3, 90, 0, 200, 0), (0, 180, 60, 0, 0)]),
    # Unequal balls (materials by size byte) in a line with gaps, Kuwabara-Kono coefficient.
    "gaps_3_unequal_kuwabara_kono": cluster(1 | 0x18 | 0x40, 3 | (2 << 2), 0, 6, 0.5, 128,
                                            128, 0, [(0, 0, 0, 0, 10), (60, 0, 0, 0, 201),
                                                     (200, 0, 0, 0, 99)]),
    # The documented known failure: a tight 8-ball rack at 8 m/s (StepTooSmall).
    "rack_8_at_8_m_s": cluster(6 | 0x08 | 0x20, 1, 20, 5, 8.0),
    # Slow touch at 1 mm/s, stiff law, mu 1.
    "slow_stiff_mu_1": cluster(0 | 0x20, 7 << 5, 255, 7, 1e-3),
    # Bad input: a NaN velocity, an overlap of 1e-6, a negative mu, 23 balls.
    "nan_velocity": cluster(0x80, 0, 0, 5, 1.0, raw=[(4, float("nan"))]),
    "overlap": cluster(0x80 | 1, 0, 0, 5, 1.0, raw=[(12, 2 * 0.028575 - 1e-6)]),
    "negative_mu": cluster(0x80, 0, 0, 5, 1.0, raw=[(24, -0.1)]),
    "23_balls": cluster(7, 0, 0, 5, 1.0, spin=2),
}

TANGENTIAL = {
    # Chung and Ooi's Test 4: alumina, 2.5 mm, 3.9 m/s at 45 degrees, mu 0.092, rigid plane.
    "alumina_45deg_rigid_plane": tangential(1 << 5, 0, 123, 4, 3.9 * math.cos(math.pi / 4),
                                            45, r_a=0.0025),
    # Alumina at 20 degrees: the spring sticks and slides in turn.
    "alumina_20deg": tangential(1 << 5, 0, 123, 5, 3.9 * math.cos(math.radians(20)), 20,
                                r_a=0.0025),
    # Head on, Hunt-Crossley calibrated to e = 0.6 (Test 3), on a compliant steel plane.
    "hunt_crossley_e_0_6_steel_plane": tangential(1 | 4 | (1 << 5), 6 | 8, 0, 4, 3.9, 0,
                                                  b6=142, r_a=0.0025),
    # Kuwabara-Kono coefficient, oblique normal, spins, resin on glass.
    "kuwabara_kono_oblique_spin": tangential(2 | 4 | 8, 4 | (3 << 4), 166, 5, 1.0, 30, b6=180,
                                             spin_a=90),
    # Two resin pool balls, mu 0.2, 30 degrees, spins, Mindlin's stiffness (factor 1).
    "pair_resin_mindlin": tangential(3 | 8, 0, 166, 5, 1.0, 30, b6=128, spin_a=60, spin_b=200),
    # Unequal pair (aluminium on steel, 2 cm and 5 cm), factor 100, normal (1, 2, 3).
    "pair_unequal_stiff": tangential(3 | (2 << 5), 6 | (2 << 4), 120, 4, 0.3, 60, b6=255,
                                     r_a=0.02, r_b=0.05, turn=77),
    # The stuck limit: mu 1e6 at 5 degrees.
    "stuck_limit_mu_1e6": tangential(1 << 5, 0, 255, 5, 3.9 * math.cos(math.radians(5)), 5,
                                     r_a=0.0025),
    # Frictionless at 80 degrees with top spin, rubber on a compliant rubber plane.
    "frictionless_rubber_80deg": tangential(4 | 8 | (7 << 5), 7, 0, 4, 2.0, 80, spin_a=127),
    # Bad input: a zero normal, a NaN mu, a ball leaving the plane.
    "zero_normal": tangential(0x10, 0, 100, 4, 1.0, 10,
                              raw=[(15, 0.0), (16, 0.0), (17, 0.0)]),
    "nan_mu": tangential(0x10 | 3, 0, 100, 4, 1.0, 10, raw=[(0, float("nan"))]),
    "leaving": tangential(0x10, 0, 100, 4, 1.0, 10, raw=[(4, 1.0)]),
}

for target, seeds in [("cluster", CLUSTER), ("tangential", TANGENTIAL)]:
    for name, data in seeds.items():
        with open(os.path.join(HERE, target, name), "wb") as f:
            f.write(data)
