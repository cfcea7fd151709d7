"""Cluster on the cloth (docs/cluster.md, "The cloth"): every ball rests on a bed pressed by
its Hertz contact and preloaded by its weight, with Coulomb friction at its lowest point.
Expected values from Newton's laws and Coulomb's bound, written out here:

- without friction anywhere, two equal balls head on exchange velocities (momentum and
  energy), and each ball's cloth impulse is its weight's, m g T over the run's time T (all
  forces between them are horizontal, so nothing else pushes along z);
- along x only the cloth's friction acts from outside: sum m v_x' = m v_0 + sum F_x, and
  each |F| <= mu_c P (Coulomb) with P that ball's cloth impulse.
"""

from __future__ import annotations

import pickle

import numpy as np
import pytest

import billiard_contact as bc

M, R, E, NU, G = 0.17, 0.028575, 5.4e9, 0.34, 9.81
BALL = bc.Ball(mass=M, radius=R, alpha=0.4)
SLATE = {"youngs_modulus": 5.0e10, "poisson_ratio": 0.25}


def on_cloth(mu=0.0, mu_c=0.0, **kw):
    return bc.Cluster(balls=[BALL, BALL], mu=mu, youngs_modulus=E, poisson_ratio=NU,
                      cloth=dict(SLATE, mu=mu_c), **kw)


def head_on(v=1.0):
    p = np.array([[0.0, 0.0, R], [2.0 * R, 0.0, R]])
    vel = np.array([[v, 0.0, 0.0], [0.0, 0.0, 0.0]])
    return p, vel, np.zeros((2, 3))


def test_frictionless_cloth_carries_the_weights_only():
    out = on_cloth().resolve(*head_on(), rtol=1e-10)
    assert np.abs(out["velocities"][0]).max() < 1e-8
    assert np.allclose(out["velocities"][1], [1.0, 0.0, 0.0], atol=1e-8)
    weight = M * G * out["time"]
    assert sorted(c["ball"] for c in out["cloth_contacts"]) == [0, 1]
    for c in out["cloth_contacts"]:
        assert c["impulse"] == pytest.approx(weight, rel=1e-9)
        assert np.all(c["friction_impulse"] == 0.0)


def test_cloth_friction_within_coulomb_and_the_x_momentum_balance():
    mu_c = 0.2
    out = on_cloth(mu_c=mu_c).resolve(*head_on(), rtol=1e-10)
    p_out = M * out["velocities"][:, 0].sum()
    friction = sum(c["friction_impulse"][0] for c in out["cloth_contacts"])
    assert p_out == pytest.approx(M * 1.0 + friction, abs=1e-12)
    for c in out["cloth_contacts"]:
        assert np.linalg.norm(c["friction_impulse"]) <= mu_c * c["impulse"] * (1 + 1e-9)
        assert c["friction_impulse"][0] <= 0.0


def test_pickles_to_an_equal_model_with_the_same_answers():
    c = on_cloth(mu=0.06, mu_c=0.2)
    back = pickle.loads(pickle.dumps(c))
    assert back == c and repr(back) == repr(c)
    assert "cloth={'youngs_modulus': 50000000000.0" in repr(c)
    a, b = c.resolve(*head_on()), back.resolve(*head_on())
    assert np.array_equal(a["velocities"], b["velocities"])
    assert a["cloth_contacts"][0]["impulse"] == b["cloth_contacts"][0]["impulse"]
    # Without a cloth the result has no cloth contacts.
    free = bc.Cluster(balls=[BALL, BALL], mu=0.06, youngs_modulus=E, poisson_ratio=NU)
    p, v, w = head_on()
    assert "cloth_contacts" not in free.resolve(p, v, w)


@pytest.mark.parametrize("cloth, words", [
    ({"youngs_modulus": 5e10}, ["cloth.poisson_ratio", "missing"]),
    (dict(SLATE, muu=0.2), ["cloth.muu", "unknown key"]),
    ({"youngs_modulus": -1.0, "poisson_ratio": 0.25}, ["cloth.youngs_modulus"]),
])
def test_bad_cloths_are_refused_naming_the_key(cloth, words):
    with pytest.raises(ValueError) as e:
        bc.Cluster(balls=[BALL, BALL], mu=0.1, youngs_modulus=E, poisson_ratio=NU, cloth=cloth)
    for w in words:
        assert w in str(e.value)


def test_refusals_at_resolve_and_with_mindlin():
    with pytest.raises(ValueError, match="cloth"):
        bc.Cluster(balls=[BALL, BALL], mu=0.1, youngs_modulus=E, poisson_ratio=NU,
                   tangential="mindlin", cloth=SLATE)
    p, v, w = head_on()
    p[1, 2] += 1e-3
    with pytest.raises(ValueError, match=r"balls\[1\].*resting on the cloth"):
        on_cloth().resolve(p, v, w)
    with pytest.raises(ValueError, match=r"cloth.mu = -1"):
        on_cloth(mu_c=-1.0).resolve(*head_on())


def pressed_in():
    """A ball rolling at 1 cm/s towards one pressed into the cloth at 1 cm/s, 60 um apart."""
    p = np.array([[0.0, 0.0, R], [2.0 * R + 60e-6, 0.0, R]])
    v = np.array([[0.01, 0.0, 0.0], [0.0, 0.0, -0.01]])
    return p, v, np.zeros((2, 3))


def held_on_slate(out):
    """What a slate bed and gravity hold at the end of `out` for resin balls, written out:
    delta = R - z + delta_s the compression (z = R where a ball rests, at k delta_s^(3/2) =
    m g), V(delta) = (2/5) k max(delta, 0)^(5/2) - m g delta, k = (4/3) E* sqrt(R) with 1/E*
    the sum of (1 - nu^2)/E of ball and bed; held = sum V(delta_out) - V(delta_s)."""
    e_star = 1.0 / ((1 - NU**2) / E + (1 - 0.25**2) / 5.0e10)
    k = 4.0 / 3.0 * e_star * np.sqrt(R)
    ds = (M * G / k) ** (2.0 / 3.0)

    def store(d):
        return 0.4 * k * max(d, 0.0) ** 2.5 - M * G * d

    return sum(store(R - z + ds) - store(ds) for z in out["positions"][:, 2])


def lost_less_heat(out, k_in):
    """K_in - K_out - heat (J) of `out`."""
    k_out = 0.5 * M * float(np.sum(out["velocities"] ** 2)) + 0.2 * M * R * R * float(
        np.sum(out["spins"] ** 2))
    return k_in - k_out - sum(c["heat"] for c in out["contacts"] + out["cloth_contacts"])


def test_a_ball_pressed_into_the_cloth_balances_with_what_the_cloth_holds():
    """A ball pressed into the elastic cloth at 1 cm/s hops while the other rolls up to it
    (elastic, frictionless). The cloth's store written out (`held_on_slate`) is the one
    reported, and K_in = K_out + heat + held."""
    out = on_cloth().resolve(*pressed_in(), rtol=1e-10)
    held = held_on_slate(out)
    assert out["cloth_held"] == pytest.approx(held, rel=1e-12, abs=1e-18)
    k_in = 0.5 * M * (0.01**2 + 0.01**2)
    assert lost_less_heat(out, k_in) - out["cloth_held"] == pytest.approx(0.0, abs=1e-7 * k_in)
    # The ball hopped: it landed on the cloth again (a cloth contact per landing).
    assert sum(c["ball"] == 1 for c in out["cloth_contacts"]) >= 2


def test_a_damped_cloth_returns_its_restitution_and_balances():
    """A ball dropped at 1 m/s onto a bed calibrated to restitution 0.5 at that speed (no
    gravity, no friction: the drop is the ball's alone) leaves at 0.5 m/s, the calibration's
    promise; with gravity and friction a ball pressed in at 1 cm/s beside a rolling one
    closes K_in = K_out + heat + held (the damping's work in the cloth contacts' heat, the
    store written out as above). The dict round-trips through repr and pickle."""
    damped = {"damping": "hunt-crossley", "restitution": 0.5, "at_speed": 1.0}
    drop = bc.Cluster(balls=[BALL, BALL], mu=0.0, youngs_modulus=E, poisson_ratio=NU,
                      cloth=dict(SLATE, mu=0.0, gravity=0.0, **damped))
    p = np.array([[0.0, 0.0, R], [2.0 * R, 0.0, R]])
    v = np.array([[1e-3, 0.0, -1.0], [0.0, 0.0, 0.0]])
    out = drop.resolve(p, v, np.zeros((2, 3)), rtol=1e-10)
    assert out["velocities"][0][2] == pytest.approx(0.5, abs=1e-6)
    back = pickle.loads(pickle.dumps(drop))
    assert back == drop and repr(back) == repr(drop)
    assert "'damping': 'hunt-crossley', 'restitution': 0.5, 'at_speed': 1.0" in repr(drop)

    c = bc.Cluster(balls=[BALL, BALL], mu=0.06, youngs_modulus=E, poisson_ratio=NU,
                   cloth=dict(SLATE, mu=0.2, damping="kuwabara-kono", coefficient=2e-5))
    out = c.resolve(*pressed_in(), rtol=1e-10)
    k_in = 0.5 * M * (0.01**2 + 0.01**2)
    assert lost_less_heat(out, k_in) - held_on_slate(out) == pytest.approx(0.0, abs=1e-7 * k_in)
    # The damping took energy from the pressed ball's vertical motion.
    assert sum(c["heat"] for c in out["cloth_contacts"] if c["ball"] == 1) > 0.0


@pytest.mark.parametrize("keys, words", [
    ({"damping": "viscous"}, ["cloth.damping", "hunt-crossley"]),
    ({"damping": "hunt-crossley", "restitution": 0.5}, ["cloth.restitution", "cloth.at_speed"]),
    ({"coefficient": 0.1}, ["cloth.coefficient", "damping"]),
    ({"damping": "hunt-crossley"}, ["cloth.damping", "coefficient"]),
])
def test_bad_cloth_dampings_are_refused_naming_the_key(keys, words):
    with pytest.raises(ValueError) as e:
        bc.Cluster(balls=[BALL, BALL], mu=0.1, youngs_modulus=E, poisson_ratio=NU,
                   cloth=dict(SLATE, **keys))
    for w in words:
        assert w in str(e.value)
    # A restitution out of range is refused when the cloth is built, naming it.
    c = bc.Cluster(balls=[BALL, BALL], mu=0.1, youngs_modulus=E, poisson_ratio=NU,
                   cloth=dict(SLATE, damping="hunt-crossley", restitution=1.5, at_speed=1.0))
    with pytest.raises(ValueError, match=r"cloth.restitution = 1.5"):
        c.resolve(*head_on())
