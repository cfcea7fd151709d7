"""Cluster(..., tangential="mindlin"): Mindlin's tangential spring at every contact
(docs/cluster.md, "Tangential compliance in clusters").

The expected two-ball answer is the two-sphere compliant kernel's
(`resolve_sphere_sphere_compliant_damped`, an integration of its own with its own events),
printed by tests/cluster_mindlin.rs (`two_balls_of_one_material_match_the_pair_kernel`,
pair rtol = atol = 1e-12) for the same balls, material, mu and incoming state.
"""

from __future__ import annotations

import copy
import pickle

import numpy as np
import pytest

import billiard_contact as bc

E, NU = 5.4e9, 0.34
A = bc.Ball(mass=0.17, radius=0.028575, alpha=0.4)
B = bc.Ball(mass=0.16, radius=0.0275, alpha=0.4)

# Ball B's centre at r_A + r_B from A's along n; A at the origin.
N = np.array([1.0, 0.2, -0.1]) / np.linalg.norm([1.0, 0.2, -0.1])
POSITIONS = np.array([[0.0, 0.0, 0.0], N * (0.028575 + 0.0275)])
VELOCITIES = np.array([[1.5, 0.3, 0.0], [-0.2, 0.0, 0.1]])
SPINS = np.array([[0.0, 0.0, 40.0], [10.0, -5.0, 0.0]])

# The pair kernel's answer (see the module's docstring).
PAIR_V = np.array([
    [-0.09759298675366135, -0.2364273386794336, 0.1148518187258817],
    [1.4974425484257652, 0.5699540473468983, -0.022030057396249303],
])
PAIR_W = np.array([
    [-2.6188248679188764, 3.834226855523757, 21.480205031858848],
    [7.108728067697037, -0.7668828392226071, -20.44648500147455],
])


def mindlin(mu=0.2, **kw):
    return bc.Cluster(balls=[A, B], mu=mu, youngs_modulus=E, poisson_ratio=NU,
                      tangential="mindlin", **kw)


def test_two_balls_match_the_pair_kernel():
    out = mindlin().resolve(POSITIONS, VELOCITIES, SPINS, rtol=1e-11)
    speed = np.linalg.norm(VELOCITIES[0] - VELOCITIES[1])
    scale = max(speed, 0.028575 * np.linalg.norm(SPINS[0]), 0.0275 * np.linalg.norm(SPINS[1]))
    assert np.abs(out["velocities"] - PAIR_V).max() < 1e-8 * scale
    radii = np.array([[0.028575], [0.0275]])
    assert np.abs(radii * (out["spins"] - PAIR_W)).max() < 1e-8 * scale
    # Momentum, exactly as the pair's forces act.
    m = np.array([[0.17], [0.16]])
    p_in, p_out = (m * VELOCITIES).sum(axis=0), (m * out["velocities"]).sum(axis=0)
    assert np.abs(p_out - p_in).max() < 1e-12 * 0.17 * scale
    # The spring's friction differs from the rigid stick rule's.
    rigid = bc.Cluster(balls=[A, B], mu=0.2, youngs_modulus=E, poisson_ratio=NU)
    other = rigid.resolve(POSITIONS, VELOCITIES, SPINS, rtol=1e-11)
    assert np.abs(other["spins"] - out["spins"]).max() > 1e-3


def test_mindlin_needs_the_material_and_names_it():
    with pytest.raises(ValueError, match="youngs_modulus, poisson_ratio"):
        bc.Cluster(balls=[A, B], mu=0.2, stiffness=4.5e8, tangential="mindlin")
    with pytest.raises(ValueError, match="tangential"):
        bc.Cluster(balls=[A, B], mu=0.2, youngs_modulus=E, poisson_ratio=NU,
                   tangential="soft")


def test_pickles_with_its_tangential_law():
    c = mindlin()
    for d in (pickle.loads(pickle.dumps(c)), copy.copy(c), copy.deepcopy(c)):
        assert d == c
        assert "tangential='mindlin'" in repr(d) or 'tangential="mindlin"' in repr(d)
        a = d.resolve(POSITIONS, VELOCITIES, SPINS)
        b = c.resolve(POSITIONS, VELOCITIES, SPINS)
        assert np.array_equal(a["velocities"], b["velocities"])
    assert c != bc.Cluster(balls=[A, B], mu=0.2, youngs_modulus=E, poisson_ratio=NU)
