"""Numbers in error messages are written as a person reads them: the shortest form that
reads back to the same double, in scientific notation outside 1e-4 <= |v| < 1e16. Rust's
plain `{}` of 5e-324 is "0." followed by 323 zeros and a 5, of 1e308 a 1 and 308 zeros;
neither may reach the user."""

from __future__ import annotations

import pytest

import billiard_contact as bc

BASE = dict(mass=0.17, radius=0.028575, mu=0.06, restitution=1.0)


@pytest.mark.parametrize(
    "key,value,text",
    [
        ("mass", 5e-324, "mass = 5e-324"),
        ("mass", 1e-310, "mass = 1e-310"),
        ("mass", 1e308, "mass = 1e308"),
        ("radius", 1e300, "radius = 1e300"),
        ("radius", 5e-324, "radius = 5e-324"),
        ("alpha", 1e300, "alpha = 1e300"),
    ],
)
def test_extreme_values_are_named_in_short_form(key, value, text):
    kwargs = dict(BASE)
    kwargs[key] = value
    with pytest.raises(ValueError) as err:
        bc.BallBall(**kwargs)
    message = str(err.value)
    assert text in message, message
    assert "0" * 20 not in message, message
    assert len(message) < 300, message
