"""A contact-law scene through `run_toml`: the command's JSON, with the realised impulse,
duration and the `contact_law` object (docs/contact-law.md)."""

from __future__ import annotations

import billiard_contact as bc
from conftest import SCENES, cli_json

LAW = """
[balls]
mass = 0.17
radius = 0.028575
youngs_modulus = 5.4e9
poisson_ratio = 0.34
[contact]
mu = 0.06
[contact.law]
model = "hertz"
damping = "{damping}"
restitution = 0.95
at_speed = 1.0
[incoming.cm]
u = [0.5, 0.0, 0.0]
"""


def test_calibrated_laws_rebound_at_their_restitution():
    for damping in ["hunt-crossley", "kuwabara-kono"]:
        got = bc.run_toml(LAW.format(damping=damping), method="dop853", rtol=1e-12)
        law = got["contact_law"]
        assert got["profile"] == "contact-law"
        assert abs(law["restitution"] - 0.95) < 1e-9
        # head on at U(0) = 0.5 m/s: P = (1 + e) m U(0), and U_out = -e U(0)
        assert abs(got["impulse"] - 1.95 * 0.17 * 0.5) < 1e-9
        assert abs(got["cm_out"]["u"][0] + 0.95 * 0.5) < 1e-9
        assert law["coefficient"] > 0 and law["peak_force"] > 0
        assert 3e-4 < got["duration"] < 5e-4  # about the elastic 402 us


def test_law_scene_equals_cli_json(cli):
    scene = next(s for s in SCENES if s.stem == "hertz_law_hunt_crossley")
    assert bc.run(str(scene)) == cli_json(cli, "run", str(scene), "--json")
