"""The bundled HART-II rigs with the measured blade motion (config/rigs/hart_ii_*_measured.yaml)
carry the measured condition and blade motion of tests/validation/hart_ii_case.py (from
tests/data/hart_ii/opencopter_hart_ii_params.json5): the numbers written into the YAML files must
not drift from that source (degrees, rounded to 1e-6)."""

import numpy as np
import pytest

import hart_ii_case as h
from nps.app.config import load_rig


@pytest.mark.parametrize("name", ["BL", "MN", "MV"])
def test_measured_blade_motion_configs_match_the_case_data(name, repo_root):
    case = h.CASES[name]
    rig = load_rig(repo_root / f"config/rigs/hart_ii_{name.lower()}_measured.yaml")
    condition, rotor = rig["condition"], rig["rotor_config"]
    assert (condition["omega_rad_s"], condition["thrust_N"], condition["roll_moment_Nm"], condition["pitch_moment_Nm"],
            condition["shaft_angle_deg"]) == (case.omega, case.thrust, case.roll, case.pitch, case.shaft_deg)
    assert condition["atmosphere"]["density_kg_m3"] == case.rho and condition["atmosphere"]["speed_of_sound_mps"] == case.c0
    hhc = [(3, case.theta3_deg, case.psi3_deg)] if case.theta3_deg else []
    assert [(e["n"], e["amplitude_deg"], e["phase_deg"]) for e in rotor.get("higher_harmonic_pitch", [])] == hhc
    for key, series in (("elastic_twist_harmonics", case.elastic_twist), ("prescribed_flap", h.tip_flap_harmonics(case))):
        written = np.array([(e["n"], e["cos_deg"], e["sin_deg"]) for e in rotor[key]])
        expected = np.array([(n, np.degrees(c), np.degrees(s)) for n, c, s in series])
        assert written.shape == expected.shape, key
        np.testing.assert_allclose(written, expected, rtol=0.0, atol=1e-6, err_msg=key)
