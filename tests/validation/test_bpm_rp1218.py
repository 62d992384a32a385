"""BPM mechanisms and boundary-layer correlations against NASA RP-1218's own prediction curves.

Reference: Brooks, Pope & Marcolini, NASA RP-1218 (1989), curves digitised from the report's
figures (tests/data/bpm/README.md). Every spectrum case is the report's NACA 0012 model, span
L = 45.72 cm, observer at r_e = 1.22 m, Θ_e = Φ_e = 90°, ν = 1.4529e-5 m²/s, c0 = 340.46 m/s; the
model is evaluated at the digitised frequencies (1/3-octave band centres) and compared in dB.

Tolerances and measured maximum errors (|NPS − figure|, dB):

- TBL-TE suction/pressure side and separation, LBL-VS, tip: 1 dB over every digitised point;
  measured max 0.92 dB (figure 45a separation), typically 0.3-0.6 dB.
- bluntness (figure 98d, h = 2.5 mm, Ψ = 14°, 69.5 m/s, 60.96 cm): 1 dB from the lowest band up
  to the band above the spectral peak (measured 0.90 dB); on the steep high-frequency roll-off
  (last two bands) the report's curve lies 2.5-2.6 dB above eq. (76) (its slope −155.5 dB per
  decade makes a small shift of the peak Strouhal number a large level difference; BPM.jl and
  AcousticAnalogies.jl show the same deviation): bounded at 3 dB there.
- boundary-layer thicknesses (figures 6-8): 10 % relative (measured max 8.9 %, figure 8 suction
  side δ*_s near the 7.5° branch point; ≤ 4.2 % on figure 6).
"""

from pathlib import Path

import numpy as np
import pytest

from nps.noise.broadband import bpm

DATA = Path(__file__).resolve().parents[1] / "data" / "bpm" / "rp1218"
MEDIUM = bpm.Medium(speed_of_sound_mps=340.46, kinematic_viscosity_m2_s=1.4529e-5)
MIC = bpm.Directivity(distance_m=1.22, high=1.0, low=1.0)  # Θ_e = Φ_e = 90°: D̄_h = D̄_l = 1 (B1, B2)
SPAN_M = 0.4572


def _curve(name):
    return np.loadtxt(DATA / f"19890016302-{name}.csv", delimiter=",")


def _spectrum_error_db(name, component, chord_m, speed_mps, alpha_deg, tripped, h_m=0.0, psi_deg=0.0):
    data = _curve(name)
    sections = bpm.Sections(chord_m, SPAN_M, speed_mps, np.radians(alpha_deg), h_m, np.radians(psi_deg), tripped)
    msp = bpm.section_msp(data[:, 0] * 1e3, sections, MIC, MEDIUM)[component]
    return 10.0 * np.log10(msp / bpm.P_REF_PA**2) - data[:, 1]


# (figure file, component, chord m, speed m/s, α* deg, tripped): RP-1218 figure captions
SPECTRA = [
    ("figure11-a-TBL-TE-suction", "tbl_te_suction", 0.3048, 71.3, 0.0, True),
    ("figure11-d-TBL-TE-suction", "tbl_te_suction", 0.3048, 31.7, 0.0, True),
    ("figure12-U71.3-TBL-TE-suction", "tbl_te_suction", 0.3048, 71.3, 1.5, True),
    ("figure12-U71.3-TBL-TE-pressure", "tbl_te_pressure", 0.3048, 71.3, 1.5, True),
    ("figure12-U71.3-separation", "separation", 0.3048, 71.3, 1.5, True),
    ("figure26-a-TBL-TE-suction", "tbl_te_suction", 0.1016, 71.3, 0.0, True),
    ("figure26-d-TBL-TE-suction", "tbl_te_suction", 0.1016, 31.7, 0.0, True),
    ("figure28-a-TBL-TE-suction", "tbl_te_suction", 0.1016, 71.3, 6.7, True),
    ("figure28-a-TBL-TE-pressure", "tbl_te_pressure", 0.1016, 71.3, 6.7, True),
    ("figure28-a-separation", "separation", 0.1016, 71.3, 6.7, True),
    ("figure28-d-TBL-TE-suction", "tbl_te_suction", 0.1016, 31.7, 6.7, True),
    ("figure28-d-TBL-TE-pressure", "tbl_te_pressure", 0.1016, 31.7, 6.7, True),
    ("figure28-d-separation", "separation", 0.1016, 31.7, 6.7, True),
    ("figure38-d-TBL-TE-suction", "tbl_te_suction", 0.0254, 31.7, 0.0, True),
    ("figure39-d-TBL-TE-suction", "tbl_te_suction", 0.0254, 31.7, 4.8, True),
    ("figure39-d-TBL-TE-pressure", "tbl_te_pressure", 0.0254, 31.7, 4.8, True),
    ("figure39-d-separation", "separation", 0.0254, 31.7, 4.8, True),
    ("figure45-a-TBL-TE-suction", "tbl_te_suction", 0.3048, 71.3, 1.5, False),
    ("figure45-a-TBL-TE-pressure", "tbl_te_pressure", 0.3048, 71.3, 1.5, False),
    ("figure45-a-separation", "separation", 0.3048, 71.3, 1.5, False),
    ("figure45-a-LBL-VS", "lbl_vs", 0.3048, 71.3, 1.5, False),
    ("figure54-a-LBL-VS", "lbl_vs", 0.1524, 71.3, 2.7, False),
    ("figure60-d-LBL-VS", "lbl_vs", 0.1016, 31.7, 3.3, False),
    ("figure65-d-LBL-VS", "lbl_vs", 0.0508, 31.7, 0.0, False),
    ("figure69-a-separation", "separation", 0.0508, 71.3, 15.4, False),  # stalled form, eq. (28)
]


@pytest.mark.parametrize("case", SPECTRA, ids=[c[0] for c in SPECTRA])
def test_mechanism_spectrum_within_1_db(case):
    name, component, chord, speed, alpha, tripped = case
    err = _spectrum_error_db(name, component, chord, speed, alpha, tripped)
    assert np.max(np.abs(err)) < 1.0, np.round(err, 2)


def test_stalled_section_has_no_tbl_te_side_noise():
    """Figure 69a (α* = 15.4° > 12.5°): RP-1218 sets SPL_p = SPL_s = −∞ in stall (eq. 28)."""
    sections = bpm.Sections(0.0508, SPAN_M, 71.3, np.radians(15.4), 0.0, 0.0, False)
    out = bpm.section_msp(np.array([500.0, 5000.0]), sections, MIC, MEDIUM)
    assert np.all(out["tbl_te_pressure"] == 0.0) and np.all(out["tbl_te_suction"] == 0.0)
    assert np.all(out["separation"] > 0.0)


def test_bluntness_figure98d():
    err = _spectrum_error_db("figure98-d-bluntness", "bluntness", 0.6096, 69.5, 0.0, True, h_m=2.5e-3, psi_deg=14.0)
    assert np.max(np.abs(err[:-2])) < 1.0, np.round(err, 2)
    assert np.max(np.abs(err[-2:])) < 3.0, np.round(err, 2)


def test_tip_vortex_figure91():
    """Figure 91: rounded tip, 15.24 cm chord, 71.3 m/s, α'_TIP = 0.71 × 10.8° (measured max 0.54 dB)."""
    data = _curve("figure91-tip")
    msp = bpm.tip_vortex_msp(data[:, 0] * 1e3, 0.1524, 71.3, np.radians(0.71 * 10.8), MIC, MEDIUM, "round")
    err = 10.0 * np.log10(msp / bpm.P_REF_PA**2) - data[:, 1]
    assert np.max(np.abs(err)) < 1.0, np.round(err, 2)


BOUNDARY_LAYER = [
    ("figure06-bl_thickness-tripped", lambda x: bpm.bl_thickness_zero_alpha(x * 1e6, True)),
    ("figure06-bl_thickness-untripped", lambda x: bpm.bl_thickness_zero_alpha(x * 1e6, False)),
    ("figure06-disp_thickness-tripped", lambda x: bpm.displacement_thickness_zero_alpha(x * 1e6, True)),
    ("figure06-disp_thickness-untripped", lambda x: bpm.displacement_thickness_zero_alpha(x * 1e6, False)),
    ("figure07-bl_thickness-pressure_side", lambda a: bpm.pressure_side_ratios(a)[0]),
    ("figure07-pressure_side", lambda a: bpm.pressure_side_ratios(a)[1]),
    ("figure07-bl_thickness-suction_side", lambda a: bpm.suction_side_ratios(a, True)[0]),
    ("figure07-suction_side", lambda a: bpm.suction_side_ratios(a, True)[1]),
    ("figure08-bl_thickness-pressure_side", lambda a: bpm.pressure_side_ratios(a)[0]),
    ("figure08-pressure_side", lambda a: bpm.pressure_side_ratios(a)[1]),
    ("figure08-bl_thickness-suction_side", lambda a: bpm.suction_side_ratios(a, False)[0]),
    ("figure08-suction_side", lambda a: bpm.suction_side_ratios(a, False)[1]),
]


@pytest.mark.parametrize("case", BOUNDARY_LAYER, ids=[c[0] for c in BOUNDARY_LAYER])
def test_boundary_layer_thickness_within_10_percent(case):
    name, model = case
    data = _curve(name)
    relative = model(data[:, 0]) / data[:, 1] - 1.0
    assert np.max(np.abs(relative)) < 0.10, np.round(relative, 3)
