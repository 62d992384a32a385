"""PSU-WOPWOP namelists and the case model: grammar and round trips, the VSP2WOPWOP-style Model 360 case read into
its known tree, WOPWOP's carry-over and default rules, and every refusal with its one-line message."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from nps.wopwop.case import (CB, Box, Case, Container, Environment, ObserverSpec, Sphere, format_case,
                             iter_containers, observer_chain, read_case, read_case_list, write_case)
from nps.wopwop.errors import WopwopError
from nps.wopwop.namelist import Group, format_namelist, parse_namelist

DATA = Path(__file__).resolve().parents[1] / "data" / "wopwop"
MODEL360 = DATA / "vsp2wopwop_model360.nam"


# ------------------------------------------------------------------------------------------------ namelist


def test_namelist_grammar():
    """Separators, comments, quotes, logicals, Fortran exponents, repeat counts and indexed assignments."""
    text = """! a comment line
&ContainerIn   ! trailing comment
  Title = 'Blade ''A''',  nbBase = 2 dTau=1.0d-3
  flag1 = .TRUE. flag2 = F, flag3 = .f., flag4 = true
  AxisValue = 0 0 1
  VH = 3*0.0
  big = 1.0E+3, small = -2.5e-3, dot = .5, trail = 2.
  patchGeometryFile(2) = "b.dat"  patchGeometryFile(1) = 'a.dat'
  patchLoadingFile(3) = 'c.dat'
/
$CB Title = "x!y" $end
"""
    groups = parse_namelist(text, "g.nam")
    assert [g.name for g in groups] == ["containerin", "cb"] and [g.line for g in groups] == [2, 11]
    assert groups[0].fields == {
        "title": "Blade 'A'", "nbbase": 2, "dtau": 1.0e-3, "flag1": True, "flag2": False, "flag3": False,
        "flag4": True, "axisvalue": (0, 0, 1), "vh": (0.0, 0.0, 0.0), "big": 1000.0, "small": -2.5e-3, "dot": 0.5,
        "trail": 2.0, "patchgeometryfile": ("a.dat", "b.dat"), "patchloadingfile": (None, None, "c.dat")}
    assert list(groups[0].fields)[:3] == ["title", "nbbase", "dtau"]  # file order
    assert groups[1].fields == {"title": "x!y"}  # '!' inside quotes is text


def test_namelist_round_trip_is_exact():
    """format → parse gives equal values: floats to the last bit, quotes, bools, ints, lists with holes, numpy
    scalars (as the Python scalars they equal)."""
    groups = (Group("EnvironmentIn", {"a": 0.1 + 0.2, "b": 1e-300, "c": -7, "d": True, "e": "it's \"q\"",
                                      "f": (1.5, -2, False, "s"), "g": 6.02214076e23, "h": -0.0,
                                      "i": np.float64(0.1) * 3, "j": np.int64(-4), "k": np.bool_(True),
                                      "l": (np.float32(0.25), np.int32(3))}),
              Group("CB", {"files": (None, "b.dat", None, "d.dat"), "one": ("only",), "x": 123456789.123456789}))
    back = parse_namelist(format_namelist(groups), "rt.nam")
    assert [g.name for g in back] == ["environmentin", "cb"]
    for original, parsed in zip(groups, back):
        expected = {k.lower(): (v[0] if isinstance(v, tuple) and len(v) == 1 else v)
                    for k, v in original.fields.items()}
        assert parsed.fields == expected
    assert math.copysign(1.0, back[0].fields["h"]) == -1.0
    assert back[0].fields["a"] == 0.30000000000000004


@pytest.mark.parametrize("text, message", [
    ("&a\n x = foo /", "line 2: &a: x: unquoted text 'foo', expected a quoted string, a number or a logical "
                       "(.true./.false.)"),
    ("&a x = 1,,2 /", "line 1: &a: x: null value (',,'), expected a value between the commas"),
    ("&a x = 1\n x = 2 /", "line 2: &a: x: assigned twice in this group, expected one assignment per field"),
    ("&a x(1:2) = 1 /", "line 1: &a: x: array section or bad index, expected a single index (i) with i >= 1"),
    ("&a x = 'abc\n/", "line 1: &a: x: unterminated string 'abc, expected a closing ' on the same line"),
    ("&a x = 1", "line 1: &a: the file ends inside &a (opened at line 1), expected '/' to close it"),
    ("&a x = 1\n&b y = 2 /", "line 2: &a: a new group '&b' starts before this one is closed, expected '/' first"),
    ("&a x = 3* /", "line 1: &a: x: null repeated value '3*', expected a value after '*'"),
    ("junk\n&a x = 1 /", "line 1: text outside a namelist group 'junk', expected '&name' or a '!' comment"),
])
def test_namelist_refusals(text, message):
    with pytest.raises(WopwopError) as err:
        parse_namelist(text, "bad.nam")
    assert str(err.value) == "bad.nam: " + message


# ------------------------------------------------------------------------------------------ the Model 360 case


def test_model360_tree():
    """The 4-bladed hover case: environment, one 1x1x3 observer line, Aircraft > Rotor > Blade 1..4 with
    periodicKeyOffset 0, π/2, π, 3π/2, the rotor rotation at Omega = 138.544 rad/s (1323 rpm)."""
    case = read_case(MODEL360)
    env = case.environment
    assert (env.nb_source_containers, env.nb_observer_containers, env.ascii_output, env.spectrum, env.spl_db) == (
        1, 1, True, True, True)
    assert (env.thickness_noise, env.loading_noise, env.total_noise, env.oaspl_db, env.spl_dba) == (
        True, True, True, False, False)
    assert (env.rho_kg_m3, env.c_m_s, env.gamma, env.p_ref_pa) == (1.225, 340.2939, 1.4, 2e-5)  # c given, rest WOPWOP's
    assert env.extra == {"loadingSigmaFlag": True, "MdotrSigmaFlag": True} and not env.sigma  # kept, not modelled
    (obs,) = case.observers
    assert (obs.title, obs.kind, obs.nt, obs.t_min_s, obs.t_max_s) == ("Observers", "box", 1024, 0.0,
                                                                         0.045351473922902494)
    assert obs.box == Box(1, 1, 3, 0.0, 0.0, 14.16544792, 14.16544792, -1.48884857, 1.48884857)
    assert (obs.high_pass_hz, obs.low_pass_hz, obs.octave_approx, obs.attached_to) == (10.0, 20000.0, False, "")
    assert [cb.title for cb in obs.cbs] == ["Observer motion"] and obs.cbs[0].translation_type == "KnownFunction"
    (aircraft,) = case.containers
    assert aircraft.title == "Aircraft" and aircraft.d_tau_s == 0.0003779289493575208
    assert [cb.title for cb in aircraft.cbs] == ["Aircraft motion", "Rotor disk AoA tilt"]
    assert aircraft.cbs[1].angle_type == "TimeIndependent"  # written 'Timeindependent': canonical spelling
    (rotor,) = aircraft.children
    rotation, align = rotor.cbs
    assert (rotation.title, rotation.rotation, rotation.angle_type, rotation.axis_value, rotation.omega_rad_s) == (
        "Rotation", True, "KnownFunction", (0.0, 0.0, 1.0), 138.54423602330988)
    assert math.isclose(rotation.omega_rad_s, 1323 * 2 * math.pi / 60, rel_tol=1e-6)
    assert align.angle_value == -math.pi / 2
    assert [b.title for b in rotor.children] == ["Blade 1", "Blade 2", "Blade 3", "Blade 4"]
    for k, blade in enumerate(rotor.children):
        assert blade.periodic_key_offset == k * math.pi / 2
        assert blade.cbs[0].angle_value == k * math.pi / 2 and blade.cbs[0].axis_value == (0.0, 0.0, 1.0)
        assert (blade.geometry_files, blade.loading_files, blade.d_tau_s) == (("Geom.dat",), ("Load.dat",),
                                                                             aircraft.d_tau_s)  # dTau carried over
    chains = {c.title: [cb.title for cb in chain] for c, chain in iter_containers(case.containers)}
    assert chains["Blade 3"] == ["Aircraft motion", "Rotor disk AoA tilt", "Rotation",
                                 "Rotate to align blades with zero azimuth", "Constant Rotation", "Pitch"]
    assert case.file("Geom.dat") == MODEL360.parent / "Geom.dat"  # a case file read directly: its own folder


def test_model360_round_trip(tmp_path):
    case = read_case(MODEL360)
    cases = write_case(case, tmp_path / "out")
    assert cases == tmp_path / "out" / "cases.nam"
    again = read_case(cases)
    assert again == case and again.path == tmp_path / "out" / MODEL360.name
    assert format_case(again) == format_case(case)


# ------------------------------------------------------------------------------------------ cases.nam


def test_case_list_and_file_resolution(tmp_path):
    """globalFolderName is concatenated with every name (Main.f90, container.f90): './sub/' + 'g.dat'."""
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "case.nam").write_text(MODEL360.read_text())
    (tmp_path / "cases.nam").write_text("&caseName globalFolderName = './sub/', caseNameFile = 'case.nam' /\n")
    refs = read_case_list(tmp_path / "cases.nam")
    assert [(r.global_folder_name, r.case_name_file, r.root) for r in refs] == [("./sub/", "case.nam", tmp_path)]
    case = read_case(tmp_path / "cases.nam")
    assert case.path == tmp_path / "sub" / "case.nam" and case.folder == tmp_path / "sub"
    assert case.file("Geom.dat") == tmp_path / "sub" / "Geom.dat" and case == read_case(MODEL360)
    (tmp_path / "cases.nam").write_text("&caseName globalFolderName = 'sub', caseNameFile = '/case.nam' /\n")
    assert read_case(tmp_path / "cases.nam").file("x.dat") == tmp_path / "subx.dat"  # plain concatenation


def test_several_cases_need_an_index(tmp_path):
    (tmp_path / "a.nam").write_text(MODEL360.read_text())
    (tmp_path / "b.nam").write_text(MODEL360.read_text().replace("c = 340.2939", "c = 343.0"))
    (tmp_path / "cases.nam").write_text("&caseName globalFolderName='./', caseNameFile='a.nam' /\n"
                                        "&caseName globalFolderName='./', caseNameFile='b.nam' /\n")
    with pytest.raises(WopwopError) as err:
        read_case(tmp_path / "cases.nam")
    assert str(err.value) == (f"{tmp_path / 'cases.nam'}: 2 cases (&caseName at lines 1, 2), expected one: pass "
                              "case_index (0-based) to choose")
    assert read_case(tmp_path / "cases.nam", case_index=1).environment.c_m_s == 343.0
    with pytest.raises(WopwopError, match=r"case_index 2, expected 0 to 1 \(2 cases\)"):
        read_case(tmp_path / "cases.nam", case_index=2)
    (tmp_path / "cases.nam").write_text("&caseName globalFolderName='./' /\n")
    with pytest.raises(WopwopError) as err:
        read_case_list(tmp_path / "cases.nam")
    assert str(err.value).endswith("line 1: &caseName: caseNameFile: missing or empty, expected a quoted name "
                                   "(WOPWOP stops without it)")


# ------------------------------------------------------------------------------------- WOPWOP's rules


RICH = """&EnvironmentIn nbContainer = 2, nbObs = 2, acousticPressureFlag = .true., SPLFlag = .true.,
  phaseFlag = .true., audioFolderName = 'audio/', PNLFlag = .true. /
&EnvironmentConstants rho = 1.0, mu = 1.8e-5 /
&ObserverIn Title = 'Hemisphere', nt = 128, tMin = 0.1, tMax = 0.3, radius = 50.0, nbTheta = 13, nbPsi = 4,
  thetaMax = 6.283185307179586, psiMin = -1.5707963267948966, indexSwap = .true., nbFreqRanges = 2,
  windowFunction = 'hanning window', octaveFlag = .true., windowSize = 0.05, sigmaRadius = 0.2 /
&RangeIn Title = 'BPF', minFrequency = 10.0, maxFrequency = 40.0 /
&RangeIn minFrequency = 40.0, maxFrequency = 200.0 /
&ObserverIn Title = 'Cabin', nt = 64, tMin = 0.0, tMax = 0.2, xLoc = 1.0, zLoc = -0.5, attachedTo = 'Hub',
  nbBase = 1, nbBaseObsContFrame = 1, nbBaseLocalFrame = 1 /
&CB Title = 'dropped', TranslationType = 'KnownFunction', VH = -10.0, 0.0, 0.0 /
&CB Title = 'obs frame', TranslationType = 'TimeIndependent', TranslationValue = 0.0, 0.0, 1.0 /
&CB Title = 'local', AngleType = 'TimeIndependent', AxisValue = 1, 0, 0, AngleValue = 0.1 /
&ContainerIn Title = 'Hub', nbBase = 2, nbContainer = 1, nTau = 100, tauMin = 0.0, tauMax = 0.5,
  PeggNoiseFlag = .true. /
&CB Title = 'flight', TranslationType = 'KnownFunction', Y0 = 0, 0, 100, VH = -20, 0, 0, AH = 0.5, 0, 0 /
&CB Title = 'spin', Rotation = .true., AngleType = 'KNOWNFUNCTION', AxisValue = 0, 0, 1, Omega = 40.0,
  Psi0 = 0.25 /
&PeggIn PeggNoiseFile = 'pegg.dat', totalBladeAreaFlag = 'Compute', hubAxis = 0, 0, 1, spreadBands = .true. /
&ContainerIn Title = 'Blade', nbBase = 1, patchGeometryFile(1) = 'g1.dat', patchGeometryFile(2) = 'g2.dat',
  patchLoadingFile(2) = 'l2.dat', periodicKeyOffset = 0.5, isPermeable = .false. /
&CB Title = 'flap', AngleType = 'Periodic', AxisValue = 1, 0, 0, Omega = 40.0, A0 = 0.02, A1 = -0.01, B1 = 0.005,
  A2 = 0.001 /
&ContainerIn Title = 'Fuselage', patchGeometryFile = 'f.dat', dTau = 0.002 /
"""


def _write(tmp_path: Path, text: str, name: str = "case.nam") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def test_wopwop_rules_on_a_rich_case(tmp_path):
    case = read_case(_write(tmp_path, RICH))
    env = case.environment
    # legacy names folded, derived switches on (Main.f90 CreateEnvironment)
    assert (env.nb_source_containers, env.nb_observer_containers) == (2, 2)
    assert (env.total_noise, env.spl_db, env.spectrum, env.audio_folder) == (True, True, True, "audio/")
    assert env.extra == {"PNLFlag": True} and env.narrowband and env.iblank and env.debug_level == 1
    # nu not given: SetEnvironmentalConstants sets mu/rho only when it differs from nu by more than epsilon
    # (1e-5, absolute): here |1.8e-5 - 1.51e-5/1.225| < 1e-5 and WOPWOP keeps the default nu
    assert env.nu_m2_s == 1.51e-5 / 1.225
    hemi, cabin = case.observers
    assert hemi.kind == "sphere" and hemi.sphere == Sphere(50.0, 13, 4, 0.0, 2 * math.pi, -math.pi / 2, 0.0, True)
    assert (hemi.window, hemi.segment_size_s, hemi.octave_flag, hemi.extra) == ("Hanning Window", 0.05, True,
                                                                                {"sigmaRadius": 0.2})
    assert hemi.ranges == (("BPF", 10.0, 40.0), ("BPF", 40.0, 200.0))  # the Title carries over
    assert cabin.octave_flag  # a global in WOPWOP: carried from the previous observer
    assert cabin.kind == "point" and cabin.point == (1.0, 0.0, -0.5)
    assert [cb.title for cb in observer_chain(case, cabin)] == ["obs frame", "flight", "spin", "local"]
    hub, fuselage = case.containers
    assert (hub.d_tau_s, hub.n_tau, hub.tau_max_s) == (0.005, 100, 0.5)  # (tauMax - tauMin) / nTau
    assert hub.pegg and hub.pegg_in == {"PeggNoiseFile": "pegg.dat", "totalBladeAreaFlag": "Compute",
                                        "hubAxis": (0.0, 0.0, 1.0), "spreadBands": True}
    assert hub.cbs[1].angle_type == "KnownFunction" and hub.cbs[1].psi0_rad == 0.25
    (blade,) = hub.children
    assert (blade.d_tau_s, blade.n_tau) == (0.005, 100)  # carried over (passed by reference)
    assert blade.geometry_files == ("g1.dat", "g2.dat") and blade.loading_files == (None, "l2.dat")
    assert (blade.cbs[0].a0, blade.cbs[0].a, blade.cbs[0].b) == (0.02, (-0.01, 0.001), (0.005,))
    assert blade.extra == {"isPermeable": False}
    assert (fuselage.d_tau_s, fuselage.n_tau, fuselage.tau_max_s) == (0.002, 100, 0.5)  # dTau given wins
    again = read_case(write_case(case, tmp_path / "out"))
    assert again == case


@pytest.mark.parametrize("constants, nu", [
    ("rho = 0.5, mu = 1.8e-5", 1.8e-5 / 0.5),            # mu/rho differs from the default nu by > epsilon
    ("rho = 0.5, mu = 1.8e-5, nu = 5e-5", 5e-5),          # nu given, differs from the default by > epsilon: kept
    ("rho = 0.5, mu = 1.8e-5, nu = 2e-5", 1.8e-5 / 0.5),  # within epsilon of the default: "unchanged", mu/rho
    ("", 1.51e-5 / 1.225),                                # WOPWOP's defaults
])
def test_kinematic_viscosity_rule(tmp_path, constants, nu):
    text = BASE.replace("&EnvironmentConstants /", f"&EnvironmentConstants {constants} /")
    assert read_case(_write(tmp_path, text)).environment.nu_m2_s == nu


def test_constructed_case_round_trips(tmp_path):
    """A case built in code (file observer, A(n) arrays longer than two) is written and read back equal."""
    cb = CB(title="flap", angle_type="Periodic", axis_value=(0.0, 1.0, 0.0), omega_rad_s=30.0, a0=0.01,
            a=(0.1, 0.2, 0.3), b=(0.0, -0.1, 0.0, 0.05), translation_type="TimeIndependent",
            translation_value=(1.0, 2.0, 3.0))
    case = Case(Environment(nb_source_containers=1, nb_observer_containers=1, oaspl_dba=True, c_m_s=343.0),
                (ObserverSpec("grid", 100, 0.0, 1.0, "file", file_name="obs.txt", low_pass_hz=5000.0,
                              ranges=(("low", 0.0, 100.0),)),),
                (Container("rotor", cbs=(cb,), geometry_files=("a.dat",), loading_files=(None,), d_tau_s=1e-3,
                           n_tau=0),))
    assert read_case(write_case(case, tmp_path)) == case


FLOWUNSTEADY_STYLE = """&EnvironmentIn
  nbContainer=1
  ASCIIOutputFlag=.true.
  audioFlag=.false.
  acousticPressureFlag=.true.
/
&EnvironmentConstants
  rho   = 1.225
  c     = 343.0
/
 &ObserverIn
   nbBase = 1
   nt   = 360
   fileName = "observergrid.xyz"
   tMin = 0.0
   tMax = 0.05
   highPassFrequency = 20.0
 /
 &CB
   Title='ObserverTranslation'
   iB=1
   TranslationType='KnownFunction'
   Y0=0,0,0
   VH=-10.0,0.0,0.0
 /
&ContainerIn
  dTau        = 0.0001388888888888889
  nbBase      = 0
  nbContainer = 1
/
&ContainerIn
  patchGeometryFile="run_Sys1_Rotor1_Blade1_compact.wop"
  patchLoadingFile="run_Sys1_Rotor1_Blade1_loading_periodic.wop"
  nbBase=0
/
"""


def test_flowunsteady_style_case(tmp_path):
    """The layout byuflowlab/FLOWUnsteady writes: legacy nbContainer, untitled blocks, double quotes, iB."""
    case = read_case(_write(tmp_path, FLOWUNSTEADY_STYLE))
    assert case.environment.nb_source_containers == 1 and case.environment.total_noise  # pressure, no noise flag
    (obs,) = case.observers
    assert (obs.title, obs.kind, obs.file_name) == ("ObserverContainer", "file", "observergrid.xyz")
    assert obs.cbs[0].ib == 1 and obs.cbs[0].vh == (-10.0, 0.0, 0.0)
    (top,) = case.containers
    assert top.title == "Generic Container" and top.children[0].loading_files == (
        "run_Sys1_Rotor1_Blade1_loading_periodic.wop",)
    assert top.children[0].d_tau_s == 0.0001388888888888889


# -------------------------------------------------------------------------------------------- refusals


BASE = """&EnvironmentIn nbSourceContainers = 1 /
&EnvironmentConstants /
&ObserverIn Title = 'Mic', nt = 64, tMin = 0.0, tMax = 0.1, xLoc = 10.0 /
&ContainerIn Title = 'Rotor', nbBase = 1, nbContainer = 1 /
&CB Title = 'Rotation', Rotation = .true., AngleType = 'KnownFunction', AxisValue = 0, 0, 1, Omega = 100.0 /
&ContainerIn Title = 'Blade', patchGeometryFile = 'g.dat' /
"""


def _refusal(tmp_path: Path, text: str) -> str:
    path = _write(tmp_path, text)
    with pytest.raises(WopwopError) as err:
        read_case(path)
    message = str(err.value)
    assert "\n" not in message and message.startswith(f"{path}: ")
    return message[len(f"{path}: "):]


def test_wopwop_defaults(tmp_path):
    """Defaults of constants.f90 SetEnvironmentalConstants, Main.f90 CreateEnvironment, the observer and container
    routines, on a case that gives none of them."""
    case = read_case(_write(tmp_path, BASE))
    env = case.environment
    assert (env.rho_kg_m3, env.c_m_s, env.gamma, env.mu_pa_s, env.p_ref_pa) == (1.225, 342.0, 1.4, 1.51e-5, 2e-5)
    assert (env.rel_humidity_pct, env.gas_constant_j_kg_k, env.integration_type, env.epsilon) == (70.0, 287.04, 0,
                                                                                                    1e-5)
    assert env.nu_m2_s == 1.51e-5 / 1.225 and env.nb_observer_containers == 1  # no count given: 1
    assert (env.narrowband, env.iblank, env.ascii_output, env.acoustic_pressure, env.total_noise) == (
        True, True, False, False, False)
    assert (env.pressure_file, env.spl_file, env.oaspl_file, env.pressure_folder, env.debug_level) == (
        "pressure", "spl", "OASPL", "", 1)
    (mic,) = case.observers
    assert (mic.kind, mic.point, mic.high_pass_hz, mic.low_pass_hz, mic.window) == ("point", (10.0, 0.0, 0.0), 0.0,
                                                                                     math.inf, "")
    assert (mic.octave_flag, mic.octave_approx, mic.octave_number, mic.segment_size_s, mic.nb_harmonics) == (
        False, True, 3.0, 0.0, 0)
    rotor, = case.containers
    assert (rotor.d_tau_s, rotor.n_tau, rotor.periodic_key_offset, rotor.pegg, rotor.bpm) == (0.0, 0, 0.0, False,
                                                                                             False)
    assert [c.title for c, _ in iter_containers(case.containers)] == ["Rotor", "Blade"]
    untitled = read_case(_write(tmp_path, BASE.replace("Title = 'Mic', ", "").replace("Title = 'Blade', ", "")))
    assert untitled.observers[0].title == "ObserverContainer"
    assert untitled.containers[0].children[0].title == "Generic Container"


@pytest.mark.parametrize("old, new, message", [
    ("Omega = 100.0", "Omega = 100.0, Omgea = 1.0",
     "line 5: &CB 'Rotation': omgea: unknown field (did you mean Omega?), expected a field PSU-WOPWOP reads in &CB"),
    ("nbContainer = 1 /", "nbContainer = 1, colour = 'red' /",
     "line 4: &ContainerIn 'Rotor': colour: unknown field, expected a field PSU-WOPWOP reads in &ContainerIn"),
    ("nt = 64, ", "", "line 3: &ObserverIn 'Mic': nt: missing, expected the number of observer times (>= 1)"),
    ("AxisValue = 0, 0, 1, ", "",
     "line 5: &CB 'Rotation': AxisValue: missing, expected the rotation axis (3 numbers) for AngleType "
     "'KnownFunction'"),
    ("nt = 64", "nt = 64.5", "line 3: &ObserverIn 'Mic': nt: got 64.5, expected an integer"),
    ("AxisValue = 0, 0, 1", "AxisValue = 0, 1", "line 5: &CB 'Rotation': AxisValue: got (0, 1), expected 3 numbers"),
    ("Rotation = .true.", "Rotation = 'yes'",
     "line 5: &CB 'Rotation': Rotation: got 'yes', expected .true. or .false."),
    ("'KnownFunction'", "'Spinning'",
     "line 5: &CB 'Rotation': AngleType: got 'Spinning', expected one of 'TimeIndependent', 'KnownFunction', "
     "'Periodic', 'NonPeriodic'"),
    ("Rotation = .true.,", "Rotation = .true., AxisType = 'Wobbly',",
     "line 5: &CB 'Rotation': AxisType: got 'Wobbly', expected one of 'TimeIndependent', 'NonPeriodic'"),
    ("Omega = 100.0 /", "Omega = 100.0, TranslationType = 'Sliding' /",
     "line 5: &CB 'Rotation': TranslationType: got 'Sliding', expected one of 'TimeIndependent', 'KnownFunction', "
     "'Periodic', 'NonPeriodic'"),
    ("nbBase = 1,", "nbBase = 3,",
     "line 4: &ContainerIn 'Rotor': nbBase: nbBase = 3 expects 3 &CB blocks, block 2 is &ContainerIn 'Blade' "
     "(line 6)"),
    ("nbContainer = 1 /", "nbContainer = 2 /",
     "line 4: &ContainerIn 'Rotor': nbContainer: nbContainer = 2 expects 2 &ContainerIn blocks, the file ends "
     "after 1"),
    ("nbContainer = 1 /", "nbContainer = -1 /",
     "line 4: &ContainerIn 'Rotor': nbContainer: got -1, expected a count >= 0"),
    ("xLoc = 10.0", "fileName = ''",
     "line 3: &ObserverIn 'Mic': xLoc/nbx/radius/fileName: observer geometry: none, expected exactly one of a point, "
     "a box, a sphere or a file"),
    ("xLoc = 10.0", "xLoc = 10.0, nbx = 2",
     "line 3: &ObserverIn 'Mic': xLoc/nbx/radius/fileName: observer geometry: point and box, expected exactly one "
     "of a point, a box, a sphere or a file"),
    ("nt = 64", "nt = 0", "line 3: &ObserverIn 'Mic': nt: got 0, expected a count >= 1"),
    ("tMax = 0.1", "tMax = 0.0",
     "line 3: &ObserverIn 'Mic': tMax: tMax = 0.0 <= tMin = 0.0, expected tMax > tMin (an unset range, derived by "
     "WOPWOP from the sources, is not supported by NPS)"),
    ("AxisValue = 0, 0, 1", "AxisValue = 0, 0, 0",
     "line 5: &CB 'Rotation': AxisValue: zero rotation axis (0, 0, 0), expected a nonzero vector"),
    ("'g.dat' /", "'g.dat' /\n&CB Title = 'stray' /",
     "line 7: &CB 'stray': after the last container: nbSourceContainers, nbContainer and nbBase account for every "
     "group before it, expected the end of the file"),
    ("'KnownFunction'", "'NonPeriodic'",
     "line 5: &CB 'Rotation': AngleType: 'NonPeriodic' reads angles from a file (Filename) whose format NPS has not "
     "confirmed in PSU-WOPWOP's source (COB.f90), not supported"),
    ("Rotation = .true.,", "Windframe = .true.,",
     "line 5: &CB 'Rotation': Windframe: .true.: wind-frame CBs (built from the previous CB) are not supported by "
     "NPS"),
    ("AngleType = 'KnownFunction', ", "",
     "line 5: &CB 'Rotation': AxisValue: given without AngleType, expected an AngleType (TimeIndependent, "
     "KnownFunction, Periodic)"),
    ("Omega = 100.0 /", "Omega = 100.0, VH = 1, 0, 0 /",
     "line 5: &CB 'Rotation': VH: given without TranslationType, expected TranslationType = 'TimeIndependent' or "
     "'KnownFunction'"),
    ("patchGeometryFile = 'g.dat'", "patchGeometryFile(1) = 'g.dat', patchGeometryFile(3) = 'h.dat'",
     "line 6: &ContainerIn 'Blade': patchGeometryFile(3): given after an empty patchGeometryFile(2), expected no "
     "gap (WOPWOP stops at the first empty name)"),
    ("xLoc = 10.0", "xLoc = 10.0, attachedTo = 'Nowhere'",
     "line 3: &ObserverIn 'Mic': attachedTo: 0 containers have Title 'Nowhere', expected exactly one"),
    ("tMax = 0.1", "tMax = 0.1, highPassFrequency = 500.0, lowPassFrequency = 100.0",
     "line 3: &ObserverIn 'Mic': highPassFrequency: 500.0 >= lowPassFrequency 100.0, expected highPass < lowPass"),
    ("nbSourceContainers = 1", "nbSourceContainers = 1, nbWall = 1",
     "line 1: &EnvironmentIn: nbWall: 1: walls, not supported by NPS"),
    ("&EnvironmentConstants /", "&EnvironmentConstants c = 0.0 /",
     "line 2: &EnvironmentConstants: c: got 0.0, expected > 0"),
])
def test_refusals_name_file_line_block_and_field(tmp_path, old, new, message):
    assert old in BASE
    assert _refusal(tmp_path, BASE.replace(old, new)) == message


def test_broadband_blocks(tmp_path):
    """A flagged container reads its &BPMIn after its CBs; WOPWOP ignores the flag (and reads no block) where no CB
    of the chain has Rotation = .true., and runs one broadband method per case."""
    flagged = BASE.replace("nbContainer = 1 /", "nbContainer = 1, BPMNoiseFlag = .true. /").replace(
        "Omega = 100.0 /", "Omega = 100.0 /\n&BPMIn BPMNoiseFile = 'bpm.dat', nSect = 2, sectChord = 0.1, 0.12 /")
    rotor = read_case(_write(tmp_path, flagged)).containers[0]
    assert rotor.bpm and rotor.bpm_in == {"BPMNoiseFile": "bpm.dat", "nSect": 2, "sectChord": (0.1, 0.12)}
    assert _refusal(tmp_path, flagged.replace("Rotation = .true., ", "")) == (
        "line 4: &ContainerIn 'Rotor': BPMNoiseFlag: .true. in a container whose CB chain has no Rotation = .true. "
        "CB: WOPWOP ignores the flag and reads no block, expected the flag in a rotating container")
    both = flagged.replace("patchGeometryFile = 'g.dat' /", "patchGeometryFile = 'g.dat', PeggNoiseFlag = .true. /")
    assert _refusal(tmp_path, both) == (
        "line 7: &ContainerIn 'Blade': PeggNoiseFlag: .true. after BPMNoiseFlag in another container: WOPWOP runs one "
        "broadband method per case, expected one of them")
    assert _refusal(tmp_path, flagged.replace("&BPMIn BPMNoiseFile", "&BPMIn nSections = 3, BPMNoiseFile")) == (
        "line 6: &BPMIn: nsections: unknown field (did you mean nSect?), expected a field PSU-WOPWOP reads in &BPMIn")


def test_missing_environment_groups(tmp_path):
    assert _refusal(tmp_path, BASE.split("\n", 1)[1]) == (
        "line 1: &EnvironmentConstants: found where &EnvironmentIn is expected (as the first group)")
    assert _refusal(tmp_path, "! nothing\n") == "&EnvironmentIn missing as the first group, the file ends"


def test_unreadable_file(tmp_path):
    with pytest.raises(WopwopError, match=r"missing\.nam: cannot read the file"):
        read_case(tmp_path / "missing.nam")
