"""A PSU-WOPWOP case: ``cases.nam``, the case file and its tree of namelist groups, as frozen dataclasses.

Read order and field lists are PSU-WOPWOP 3.4.3's own (Fortran sources in the public index):

- ``cases.nam``: repeated ``&caseName globalFolderName, caseNameFile /`` (Main.f90 main loop). The case file is
  ``trim(globalFolderName)//trim(caseNameFile)`` and every file a case names (patch and loading files,
  container.f90 CreateContainer; the observer ``fileName``, ObserverContainerObject
  CreateExternalDefinitionSurface) is ``trim(globalFolderName)//name``: a plain concatenation, relative to the
  directory WOPWOP runs in, the one holding ``cases.nam`` (:meth:`Case.file`). A folder name needs its
  trailing '/'.
- The case file: ``&EnvironmentIn`` (Main.f90 CreateEnvironment: field list and defaults), then
  ``&EnvironmentConstants`` (constants.f90 SetEnvironmentalConstants: rho 1.225 kg/m³, c 342 m/s, gamma 1.4,
  mu 1.51e-5 Pa s, nu = mu/rho unless given, P_ref 2e-5 Pa, RelHumidity 70 %, gasConstant 287.04 J/(kg K),
  integrationType 0, epsilon 1e-5), then ``nbObserverContainers`` observers, then ``nbSourceContainers`` trees
  of containers.
- An observer (ObserverContainerObject InitializeObserverContainer): ``&ObserverIn``, its ``nbBase`` ``&CB``
  blocks (read by the routine that builds its geometry), then, when ``attachedTo`` is set,
  ``nbBaseObsContFrame`` and ``nbBaseLocalFrame`` ``&CB`` blocks (AttachObsContToObject, which drops the
  ``nbBase`` ones), then ``nbFreqRanges`` ``&RangeIn`` blocks. Geometry, in WOPWOP's precedence: ``fileName``,
  a sphere (``radius``, ``nbTheta``, ``nbPsi``, ``theta/psiMin/Max``, ``indexSwap``), a box (``nbx``, ``nby``,
  ``nbz``, ``x/y/zMin/Max``), a point (``xLoc``, ``yLoc``, ``zLoc``). Legacy names are folded into their
  successors as WOPWOP does: ``windowSize`` → ``segmentSize``, ``increment`` → ``segmentStepSize``,
  ``spectrumIncrement`` → ``segmentIncrement``, ``octaveBand`` → ``octaveNumber``.
- A container (container.f90 CreateContainer, recursive): ``&ContainerIn``, its ``nbBase`` ``&CB`` blocks, a
  ``&PeggIn`` / ``&BPMIn`` block when ``PeggNoiseFlag`` / ``BPMNoiseFlag`` is set (broadband module
  ReadPeggNamelist / ReadBPMNamelist: field lists), then its ``nbContainer`` children, each a container. The
  variables dTau, tauMin, tauMax, nTau are the caller's, passed by reference: a value read in one
  ``&ContainerIn`` carries over to every container read after it; a container's step is dTau, or
  (tauMax − tauMin)/nTau when dTau is 0 and nTau > 0. A child's CB list is its parent's list followed by its own
  CBs (:func:`iter_containers`). ``periodicKeyOffset`` is the container's own (default 0).
- ``&CB`` fields: PsuAeroacoustics/wopwopd ``namelist.d`` (COB.f90 itself was not readable in the index):
  Title, Rotation, Windframe, iB, AxisType, TranslationType, AngleType, AH, VH, Y0, Omega, Psi0, A0, A1, A2, B1,
  B2, A(n), B(n), Filename, AxisValue, TranslationValue, AngleValue, flightPath, flightPathAccel, nbWayPoints.
  Angles in radians, Omega in rad/s (VSP2WOPWOP writes Omega = 2π rpm/60 and angles in radians). Their
  kinematics: :mod:`nps.wopwop.motion`.

Every value keeps its effective meaning: WOPWOP's defaults filled in, legacy names folded, derived switches
applied (``acousticPressureFlag`` without a noise flag turns ``totalNoiseFlag`` on; ``phaseFlag`` turns
``spectrumFlag`` on; ``SPLFlag`` / ``OASPLFlag`` / ``pressureGradientFlag`` → ``SPLdBFlag`` / ``OASPLdBFlag`` /
``pressureGradient1AFlag``; ``nbObs`` / ``nbContainer`` → ``nbObserverContainers`` / ``nbSourceContainers``;
no observer count → 1). Fields PSU-WOPWOP reads but NPS does not model (sigma-surface flags, audio, FSC, PNL
metrics, ...) are kept, as given, in the ``extra`` mapping of their block, so :func:`write_case` round-trips
them; ``read_case(write_case(case))`` equals ``case`` (paths aside).

Refused, in one line naming the file, the line and block (``&CB 'Rotation'``) and the field
(:class:`~nps.wopwop.errors.WopwopError`): unknown fields, wrong types, missing required fields (observer nt;
AxisValue with an AngleType; AngleValue, Omega, TranslationValue for their types; a CB's rotation or
translation values without their type; a ``&RangeIn`` frequency, which WOPWOP would silently take from the
previous block), values outside their lists (AngleType, AxisType, TranslationType, windowFunction), counts that
disagree with the blocks that follow (a count running past the end of the file or onto a block of another kind,
blocks left over after the last container), negative counts, a legacy name given with its successor, nt < 1,
tMax <= tMin (WOPWOP would derive an unset range from the source data; NPS does not), highPassFrequency >=
lowPassFrequency or a band narrower than 1/(tMax − tMin) and a range starting above the Nyquist frequency (as
WOPWOP does), an observer with no or two kinds of geometry (WOPWOP would silently pick one), box or sphere counts
< 1, a sphere radius <= 0, rho, c, mu or nu <= 0, a negative source-time step, a patch file after an empty one or
a loading file without its geometry file (WOPWOP stops counting at the first empty name), more than 100 patch
files, a zero rotation axis, ``attachedTo`` naming no container or several, and features NPS does not reproduce:
NonPeriodic angles, axes and translations (their file format is in COB.f90, unread), Periodic translations,
wind-frame CBs, flight paths, the legacy ``nbAircraft`` tree, walls, FAA certification runs, FSC observers,
``readInPressureFlag``, Isom's thickness noise, BWI blocks, a broadband flag in a container whose CB chain has
no ``Rotation = .true.`` CB (WOPWOP ignores the flag and reads no block) and both broadband methods in one
case (WOPWOP keeps one).
"""

from __future__ import annotations

import difflib
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterator

from nps.wopwop.errors import WopwopError
from nps.wopwop.namelist import Group, format_namelist, parse_namelist

ANGLE_TYPES = ("TimeIndependent", "KnownFunction", "Periodic", "NonPeriodic")
AXIS_TYPES = ("TimeIndependent", "NonPeriodic")
TRANSLATION_TYPES = ("TimeIndependent", "KnownFunction", "Periodic", "NonPeriodic")
WINDOWS = ("", "Hanning Window", "Blackman Window", "Flat Top Window", "Hamming Window")  # wopwopd namelist.d
MAX_PATCH_FILES = 100  # container.f90 MAX_NB_PATCH_FILES
ZERO3 = (0.0, 0.0, 0.0)
_CODE = "*"  # a field the readers and writers handle in code (counts, legacy names, geometry)


# ---------------------------------------------------------------------------------------------- the model


@dataclass(frozen=True)
class CB:
    """One change of base (``&CB``): x_parent = R(t) x_local + T(t) (:func:`nps.wopwop.motion.cb_motion`).
    Types in their canonical spelling (None: no rotation / no translation); angles in rad, Omega in rad/s,
    translations in m (VH m/s, AH m/s²); ``a``, ``b``: the Periodic harmonics A1, A2, ... and B1, B2, ...;
    ``rotation``: WOPWOP's "true rotation" mark (the rotor shaft), no kinematic effect."""

    title: str = ""
    rotation: bool = False
    axis_type: str = "TimeIndependent"
    angle_type: str | None = None
    translation_type: str | None = None
    axis_value: tuple | None = None
    angle_value: float | None = None
    translation_value: tuple | None = None
    omega_rad_s: float | None = None
    psi0_rad: float = 0.0
    a0: float = 0.0
    a: tuple = ()
    b: tuple = ()
    vh: tuple = ZERO3
    ah: tuple = ZERO3
    y0: tuple = ZERO3
    filename: str | None = None
    ib: int | None = None
    windframe: bool = False
    extra: dict = field(default_factory=dict)
    line: int = field(default=0, compare=False)


@dataclass(frozen=True)
class Box:
    """Observer box: nbx × nby × nbz points from min to max (m) per axis, x fastest (ObserverContainerObject
    CreateObsContPlane). WOPWOP quirk: an axis with a count of 1 and min ≠ max sits at (min + max)/2 only when
    debugLevel > 1 (the shift is inside the warning's test); otherwise at min."""

    nbx: int
    nby: int
    nbz: int
    x_min_m: float = 0.0
    x_max_m: float = 0.0
    y_min_m: float = 0.0
    y_max_m: float = 0.0
    z_min_m: float = 0.0
    z_max_m: float = 0.0


@dataclass(frozen=True)
class Sphere:
    """Observer sphere section: x = R cosθ cosψ, y = R sinθ cosψ, z = R sinψ (θ azimuth from +x, ψ elevation,
    rad), steps (max − min)/(n − 1); θ fastest unless ``index_swap`` (CreateSphericalSectionObsCont; a count of 1
    puts the points at the min angle)."""

    radius_m: float
    nb_theta: int
    nb_psi: int
    theta_min_rad: float = 0.0
    theta_max_rad: float = 0.0
    psi_min_rad: float = 0.0
    psi_max_rad: float = 0.0
    index_swap: bool = False


@dataclass(frozen=True)
class ObserverSpec:
    """One observer container (``&ObserverIn`` and its blocks). ``kind``: "point" (``point``, m), "box", "sphere"
    or "file" (``file_name``, resolved with :meth:`Case.file`); observer times t_min + i (t_max − t_min)/(nt − 1);
    ``cbs``: its ``nbBase`` CBs; with ``attached_to``, its chain is ``obs_frame_cbs`` + the named container's chain
    + ``local_frame_cbs`` (:func:`observer_chain`); ``ranges``: (title, min Hz, max Hz) per ``&RangeIn``;
    ``low_pass_hz`` inf: no low-pass; ``window`` "": none."""

    title: str
    nt: int
    t_min_s: float
    t_max_s: float
    kind: str
    point: tuple | None = None
    box: Box | None = None
    sphere: Sphere | None = None
    file_name: str | None = None
    attached_to: str = ""
    cbs: tuple = ()
    obs_frame_cbs: tuple = ()
    local_frame_cbs: tuple = ()
    high_pass_hz: float = 0.0
    low_pass_hz: float = math.inf
    window: str = ""
    segment_size_s: float = 0.0
    segment_step_s: float = 0.0
    segment_increment: int = 0
    nb_harmonics: int = 0
    octave_flag: bool = False
    octave_number: float = 3.0
    octave_approx: bool = True
    atm_atten: bool = False
    ranges: tuple = ()
    extra: dict = field(default_factory=dict)
    line: int = field(default=0, compare=False)


@dataclass(frozen=True)
class Container:
    """One ``&ContainerIn`` and its subtree. ``cbs``: its own CBs (its chain: :func:`iter_containers`);
    ``loading_files[i]`` goes with ``geometry_files[i]`` (None: none); the source-time values are the effective
    ones (carried over from earlier containers, dTau derived from nTau); ``pegg_in`` / ``bpm_in``: the fields
    given in its ``&PeggIn`` / ``&BPMIn`` block."""

    title: str = "Generic Container"
    cbs: tuple = ()
    children: tuple = ()
    geometry_files: tuple = ()
    loading_files: tuple = ()
    d_tau_s: float = 0.0
    n_tau: int = 0
    tau_min_s: float = 0.0
    tau_max_s: float = 0.0
    periodic_key_offset: float = 0.0
    pegg: bool = False
    bpm: bool = False
    pegg_in: dict | None = None
    bpm_in: dict | None = None
    extra: dict = field(default_factory=dict)
    line: int = field(default=0, compare=False)


@dataclass(frozen=True)
class Environment:
    """``&EnvironmentIn`` switches and ``&EnvironmentConstants``, effective values (SI: kg/m³, m/s, Pa s, m²/s,
    Pa, %, J/(kg K)); ``extra``: the other EnvironmentIn fields given (sigma flags, PNL metrics, ...)."""

    nb_source_containers: int = 1
    nb_observer_containers: int = 1
    ascii_output: bool = False
    acoustic_pressure: bool = False
    thickness_noise: bool = False
    loading_noise: bool = False
    total_noise: bool = False
    spectrum: bool = False
    oaspl_db: bool = False
    oaspl_dba: bool = False
    spl_db: bool = False
    spl_dba: bool = False
    broadband: bool = False
    narrowband: bool = True
    phase: bool = False
    complex_pressure: bool = False
    audio: bool = False
    sigma: bool = False
    pressure_gradient_1a: bool = False
    iblank: bool = True
    debug_level: int = 1
    pressure_folder: str = ""
    spl_folder: str = ""
    sigma_folder: str = ""
    audio_folder: str = ""
    pressure_file: str = "pressure"
    spl_file: str = "spl"
    oaspl_file: str = "OASPL"
    phase_file: str = "phase"
    complex_pressure_file: str = "complexPressure"
    sigma_file: str = "sigma"
    audio_file: str = "audio"
    rho_kg_m3: float = 1.225
    c_m_s: float = 342.0
    gamma: float = 1.4
    mu_pa_s: float = 1.51e-5
    nu_m2_s: float = 1.51e-5 / 1.225
    p_ref_pa: float = 2e-5
    rel_humidity_pct: float = 70.0
    gas_constant_j_kg_k: float = 287.04
    integration_type: int = 0
    epsilon: float = 1e-5
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Case:
    """A case: its environment, observers and container trees. ``path``: the case file; files it names resolve
    as ``root / (global_folder_name + name)`` (:meth:`file`); paths do not take part in equality."""

    environment: Environment
    observers: tuple
    containers: tuple
    path: Path = field(default=Path("case.nam"), compare=False)
    root: Path = field(default=Path("."), compare=False)
    global_folder_name: str = field(default="", compare=False)

    @property
    def folder(self) -> Path:
        """globalFolderName resolved against the directory WOPWOP runs in."""
        return self.root / self.global_folder_name

    def file(self, name: str) -> Path:
        """A file the case names, as WOPWOP opens it: trim(globalFolderName)//name, from ``root``."""
        return self.root / (self.global_folder_name + name.rstrip())


@dataclass(frozen=True)
class CaseRef:
    """One ``&caseName`` of a ``cases.nam``; ``root``: the directory holding it (WOPWOP's working directory)."""

    global_folder_name: str
    case_name_file: str
    root: Path
    line: int = field(default=0, compare=False)

    @property
    def case_path(self) -> Path:
        return self.root / (self.global_folder_name + self.case_name_file)


# ------------------------------------------------------------------------------------------- the schemas


@dataclass(frozen=True)
class _Field:
    name: str                 # canonical spelling
    kind: str                 # str bool int float vec3 floats strs
    attr: str | None = None   # dataclass attribute; None: kept in ``extra``; _CODE: handled in code
    default: object = None


def _schema(*rows) -> tuple[_Field, ...]:
    return tuple(_Field(*row) for row in rows)


def _flags(names: str, attr=None, default=False) -> list[tuple]:
    return [(name, "bool", attr, default) for name in names.split()]


_ENV_IN = _schema(
    ("nbSourceContainers", "int", _CODE, 0), ("nbObserverContainers", "int", _CODE, 0),
    ("nbContainer", "int", _CODE, 0), ("nbObs", "int", _CODE, 0), ("nbAircraft", "int", _CODE, 0),
    ("nbWall", "int", _CODE, 0), ("wallIteration", "int"),
    ("ASCIIOutputFlag", "bool", "ascii_output", False), ("acousticPressureFlag", "bool", "acoustic_pressure", False),
    ("thicknessNoiseFlag", "bool", "thickness_noise", False), ("loadingNoiseFlag", "bool", "loading_noise", False),
    ("totalNoiseFlag", "bool", "total_noise", False), ("spectrumFlag", "bool", "spectrum", False),
    ("OASPLdBFlag", "bool", "oaspl_db", False), ("OASPLdBAFlag", "bool", "oaspl_dba", False),
    ("SPLdBFlag", "bool", "spl_db", False), ("SPLdBAFlag", "bool", "spl_dba", False),
    ("broadbandFlag", "bool", "broadband", False), ("narrowbandFlag", "bool", "narrowband", True),
    ("phaseFlag", "bool", "phase", False), ("complexPressureFlag", "bool", "complex_pressure", False),
    ("audioFlag", "bool", "audio", False), ("sigmaFlag", "bool", "sigma", False),
    ("PressureGradient1AFlag", "bool", "pressure_gradient_1a", False), ("iBlankFlag", "bool", "iblank", True),
    ("debugLevel", "int", "debug_level", 1),
    ("pressureFolderName", "str", "pressure_folder", ""), ("SPLFolderName", "str", "spl_folder", ""),
    ("sigmaFolderName", "str", "sigma_folder", ""), ("audioFolderName", "str", "audio_folder", ""),
    ("pressureFileName", "str", "pressure_file", "pressure"), ("SPLFileName", "str", "spl_file", "spl"),
    ("OASPLFileName", "str", "oaspl_file", "OASPL"), ("phaseFileName", "str", "phase_file", "phase"),
    ("complexPressureFileName", "str", "complex_pressure_file", "complexPressure"),
    ("sigmaFileName", "str", "sigma_file", "sigma"), ("audioFileName", "str", "audio_file", "audio"),
    *_flags("OASPLFlag SPLFlag PressureGradientFlag readInPressureFlag isomsThicknessNoiseFlag FAACertFlag", _CODE),
    ("FAACertFile", "str"), ("sigmaStructuredFormat", "str"), ("sigmaUnstructuredFormat", "str"),
    *_flags("PNLFlag PNLTFlag PartH36Flag EPNLFlag forceEPNL SELFlag forceSEL BWINoiseFlag loadingNoiseSigmaFlag "
            "thicknessNoiseSigmaFlag totalNoiseSigmaFlag normalSigmaFlag machSigmaFlag observerSigmaFlag "
            "observerContainerSigmaFlag velocitySigmaFlag accelerationSigmaFlag densitySigmaFlag momentumSigmaFlag "
            "pressureSigmaFlag loadingSigmaFlag areaSigmaFlag MdotrSigmaFlag iblankSigmaFlag"),
)
_CONSTANTS = _schema(
    ("rho", "float", "rho_kg_m3", 1.225), ("c", "float", "c_m_s", 342.0), ("gamma", "float", "gamma", 1.4),
    ("mu", "float", "mu_pa_s", 1.51e-5), ("nu", "float", _CODE), ("integrationType", "int", "integration_type", 0),
    ("epsilon", "float", "epsilon", 1e-5), ("P_ref", "float", "p_ref_pa", 2e-5),
    ("RelHumidity", "float", "rel_humidity_pct", 70.0), ("gasConstant", "float", "gas_constant_j_kg_k", 287.04),
)
_POINT = ("xLoc", "yLoc", "zLoc")
_BOX = ("nbx", "nby", "nbz", "xMin", "xMax", "yMin", "yMax", "zMin", "zMax")
_SPHERE = ("radius", "nbTheta", "nbPsi", "thetaMin", "thetaMax", "psiMin", "psiMax", "indexSwap")
_COUNTS = ("nbx", "nby", "nbz", "nbTheta", "nbPsi")
_OBSERVER = _schema(
    ("Title", "str", "title", "ObserverContainer"), ("nt", "int", "nt"), ("tMin", "float", "t_min_s", 0.0),
    ("tMax", "float", "t_max_s", 0.0), ("attachedTo", "str", "attached_to", ""),
    ("highPassFrequency", "float", "high_pass_hz", 0.0), ("lowPassFrequency", "float", "low_pass_hz", math.inf),
    ("windowFunction", "str", "window", ""), ("segmentSize", "float", "segment_size_s", 0.0),
    ("segmentStepSize", "float", "segment_step_s", 0.0), ("segmentIncrement", "int", "segment_increment", 0),
    ("nbHarmonics", "int", "nb_harmonics", 0), ("octaveFlag", "bool", "octave_flag", False),
    ("octaveNumber", "float", "octave_number", 3.0), ("octaveApproxFlag", "bool", "octave_approx", True),
    ("AtmAtten", "bool", "atm_atten", False),
    *[(n, "int" if n in _COUNTS else "bool" if n == "indexSwap" else "float", _CODE) for n in _POINT + _BOX + _SPHERE],
    ("fileName", "str", _CODE), ("FSCInputFileName", "str", _CODE),
    *[(n, "int", _CODE) for n in "nbBase nbBaseObsContFrame nbBaseObsFrame nbBaseLocalFrame nbFreqRanges".split()],
    ("windowSize", "float", _CODE), ("increment", "float", _CODE), ("spectrumIncrement", "int", _CODE),
    ("octaveBand", "float", _CODE),
    ("nbNewSegments", "int"), ("nbObsTimeExpansions", "int"), ("maxObsTimeExpansions", "int"),
    ("sigmaRadius", "float"), ("FSCOutputFileName", "str"), *_flags("FSCOutputFlag FSCThicknessFlag FSCLoadingFlag"),
    ("percentOverlap", "float"), ("numAverages", "int"), ("averageSide", "str"), ("CorrFlag", "bool"),
)
_RANGE = _schema(("Title", "str"), ("minFrequency", "float"), ("maxFrequency", "float"))
_CB = _schema(
    ("Title", "str", "title", ""), ("Rotation", "bool", "rotation", False), ("Windframe", "bool", "windframe", False),
    ("iB", "int", "ib"), ("AxisType", "str", _CODE), ("AngleType", "str", _CODE), ("TranslationType", "str", _CODE),
    ("AxisValue", "vec3", "axis_value"), ("AngleValue", "float", "angle_value"), ("Omega", "float", "omega_rad_s"),
    ("Psi0", "float", "psi0_rad", 0.0), ("A0", "float", "a0", 0.0),
    *[(n, "float", _CODE) for n in ("A1", "A2", "B1", "B2")], ("A", "floats", _CODE), ("B", "floats", _CODE),
    ("TranslationValue", "vec3", "translation_value"), ("Y0", "vec3", "y0", ZERO3), ("VH", "vec3", "vh", ZERO3),
    ("AH", "vec3", "ah", ZERO3), ("Filename", "str", "filename"),
    ("flightPath", "bool", _CODE), ("flightPathAccel", "str"), ("nbWayPoints", "int"),
)
_CONTAINER = _schema(
    ("Title", "str", "title", "Generic Container"), ("nbContainer", "int", _CODE), ("nbBase", "int", _CODE),
    ("dTau", "float", _CODE), ("nTau", "int", _CODE), ("tauMin", "float", _CODE), ("tauMax", "float", _CODE),
    ("patchGeometryFile", "strs", _CODE), ("patchLoadingFile", "strs", _CODE),
    ("periodicKeyOffset", "float", "periodic_key_offset", 0.0), ("PeggNoiseFlag", "bool", "pegg", False),
    ("BPMNoiseFlag", "bool", "bpm", False), ("BWINoiseFlag", "bool", _CODE), ("isPermeable", "bool"),
)
_PEGG = _schema(
    *[(n, "str") for n in "PeggNoiseFile totalBladeAreaFlag bladeRadiusFlag rotSpeedFlag CLBarFlag hubAxisFlag "
      "totalThrustFlag".split()],
    *[(n, "float") for n in "totalBladeArea bladeRadius rotSpeed CLBar totalThrust deltadB".split()],
    ("hubAxis", "vec3"), *_flags("spreadBands keepEnergyConst EPNLPrime"),
)
_BPM = _schema(
    *[(n, "str") for n in "BPMNoiseFile sectChordFlag SectLengthFlag TEthicknessFlag TEflowAngleFlag TipLCSFlag "
      "SectAOAFlag UFlag".split()],
    *[(n, "int") for n in "nSect uniformBlade BLTrip".split()], ("TipLCS", "float"),
    *[(n, "floats") for n in "sectChord SectLength TEthickness TEflowAngle SectAOA U".split()],
    *_flags("LBLVSnoise TBLTEnoise bluntNoise bladeTipNoise roundBladeTip"),
)
_CASENAME = _schema(("globalFolderName", "str"), ("caseNameFile", "str"))
_DISPLAY = {"environmentin": "EnvironmentIn", "environmentconstants": "EnvironmentConstants",
            "observerin": "ObserverIn", "cb": "CB", "rangein": "RangeIn", "containerin": "ContainerIn",
            "peggin": "PeggIn", "bpmin": "BPMIn", "casename": "caseName"}


# ------------------------------------------------------------------------------- values and their errors


def _label(group: Group) -> str:
    """``&CB 'Rotation'``: the group's name and, when it has one, its Title."""
    name = "&" + _DISPLAY.get(group.name, group.name)
    title = group.fields.get("title")
    return f"{name} '{title.rstrip()}'" if isinstance(title, str) else name


def _fail(path: str, group: Group, field_name: str, what: str) -> WopwopError:
    return WopwopError(f"{path}: line {group.line}: {_label(group)}: {field_name}: {what}")


def _show(value) -> str:
    if isinstance(value, tuple):
        return "(" + ", ".join("<unset>" if v is None else _show(v) for v in value) + ")"
    if isinstance(value, bool):
        return ".true." if value else ".false."
    return f"'{value}'" if isinstance(value, str) else repr(value)


def _number(value):
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else None


def _numbers(value):
    values = value if isinstance(value, tuple) else (value,)
    converted = [_number(v) for v in values]
    return None if None in converted else tuple(converted)


_KINDS = {
    "str": ("a quoted string", lambda v: v if isinstance(v, str) else None),
    "bool": (".true. or .false.", lambda v: v if isinstance(v, bool) else None),
    "int": ("an integer", lambda v: v if isinstance(v, int) and not isinstance(v, bool) else None),
    "float": ("a number", _number),
    "vec3": ("3 numbers", lambda v: _numbers(v) if isinstance(v, tuple) and len(v) == 3 else None),
    "floats": ("numbers", _numbers),
    "strs": ("quoted strings", lambda v: (v,) if isinstance(v, str) else
             v if isinstance(v, tuple) and all(s is None or isinstance(s, str) for s in v) else None),
}


def _given(path: str, group: Group, schema: tuple[_Field, ...]) -> dict:
    """The fields a group gives, by canonical name, converted to their kind; unknown names and wrong types refused."""
    by_lower = {f.name.lower(): f for f in schema}
    out = {}
    for key, raw in group.fields.items():
        spec = by_lower.get(key)
        if spec is None:
            close = difflib.get_close_matches(key, list(by_lower), n=1)
            hint = f" (did you mean {by_lower[close[0]].name}?)" if close else ""
            raise _fail(path, group, key, f"unknown field{hint}, expected a field PSU-WOPWOP reads in "
                                          f"&{_DISPLAY.get(group.name, group.name)}")
        expected, convert = _KINDS[spec.kind]
        value = convert(raw)
        if value is None:
            raise _fail(path, group, spec.name, f"got {_show(raw)}, expected {expected}")
        out[spec.name] = value
    return out


def _attrs(schema: tuple[_Field, ...], given: dict) -> dict:
    """Dataclass keyword arguments: given values or defaults, for the fields with an attribute."""
    return {f.attr: given.get(f.name, f.default) for f in schema if f.attr not in (None, _CODE)}


def _extra(schema: tuple[_Field, ...], given: dict) -> dict:
    return {f.name: given[f.name] for f in schema if f.attr is None and f.name in given}


def _choice(path: str, group: Group, name: str, value: str, choices: tuple[str, ...]) -> str:
    """A case-insensitive choice, in its canonical spelling."""
    for choice in choices:
        if value.strip().lower() == choice.lower():
            return choice
    raise _fail(path, group, name, f"got '{value}', expected one of {', '.join(repr(c) for c in choices)}")


def _count(path: str, group: Group, given: dict, name: str, minimum: int = 0) -> int:
    value = given.get(name, 0)
    if value < minimum:
        raise _fail(path, group, name, f"got {value}, expected a count >= {minimum}")
    return value


def _refuse_if(path: str, group: Group, given: dict, name: str, what: str) -> None:
    """Refuse a switch NPS does not reproduce when it is given as true (or nonzero)."""
    if given.get(name):
        raise _fail(path, group, name, f"{_show(given[name])}: {what}, not supported by NPS")


# ----------------------------------------------------------------------------------- the group sequence


class _Blocks:
    """The case file's groups, consumed in WOPWOP's read order."""

    def __init__(self, groups: tuple[Group, ...], path: str):
        self.groups, self.path, self.next = groups, path, 0

    def take(self, owner: Group, count_field: str, name: str, k: int, n: int) -> Group:
        """Block ``k`` of the ``n`` ``&name`` blocks ``owner``'s ``count_field`` announces."""
        what = f"{count_field} = {n} expects {n} &{_DISPLAY[name]} block{'s' if n > 1 else ''}"
        if self.next >= len(self.groups):
            raise _fail(self.path, owner, count_field, f"{what}, the file ends after {k - 1}")
        group = self.groups[self.next]
        if group.name != name:
            raise _fail(self.path, owner, count_field, f"{what}, block {k} is {_label(group)} (line {group.line})")
        self.next += 1
        return group

    def first(self, name: str, after: str) -> Group:
        """The next group, which must be ``&name``."""
        if self.next >= len(self.groups):
            raise WopwopError(f"{self.path}: &{_DISPLAY[name]} missing {after}, the file ends")
        group = self.groups[self.next]
        if group.name != name:
            raise WopwopError(f"{self.path}: line {group.line}: {_label(group)}: found where &{_DISPLAY[name]} "
                              f"is expected ({after})")
        self.next += 1
        return group


# -------------------------------------------------------------------------------------------- environment


def _environment(path: str, env_in: Group, constants: Group) -> Environment:
    """Both environment groups, with WOPWOP's defaults and derived switches (Main.f90 CreateEnvironment)."""
    given = _given(path, env_in, _ENV_IN)
    for name, what in (("nbAircraft", "the legacy AircraftIn/RotorIn/BladeIn tree"), ("nbWall", "walls"),
                       ("FAACertFlag", "FAA certification runs (their own observer defaults and file)"),
                       ("readInPressureFlag", "reading WOPWOP pressure files instead of the sources"),
                       ("isomsThicknessNoiseFlag", "Isom's thickness noise")):
        _refuse_if(path, env_in, given, name, what)
    kw = _attrs(_ENV_IN, given)
    kw["nb_observer_containers"] = _legacy_count(path, env_in, given, "nbObserverContainers", "nbObs") or 1
    kw["nb_source_containers"] = _legacy_count(path, env_in, given, "nbSourceContainers", "nbContainer")
    if kw["nb_source_containers"] == 0:
        raise _fail(path, env_in, "nbSourceContainers", "missing or 0, expected a count >= 1")
    kw["spl_db"] = kw["spl_db"] or given.get("SPLFlag", False)
    kw["oaspl_db"] = kw["oaspl_db"] or given.get("OASPLFlag", False)
    kw["pressure_gradient_1a"] = kw["pressure_gradient_1a"] or given.get("PressureGradientFlag", False)
    kw["spectrum"] = kw["spectrum"] or kw["phase"]
    if kw["acoustic_pressure"] and not (kw["thickness_noise"] or kw["loading_noise"] or kw["total_noise"]):
        kw["total_noise"] = True
    return Environment(**kw, **_constants(path, constants), extra=_extra(_ENV_IN, given))


def _legacy_count(path: str, group: Group, given: dict, name: str, legacy: str) -> int:
    """A container count and its legacy name (only one may be given)."""
    value, old = _count(path, group, given, name), _count(path, group, given, legacy)
    if value and old:
        raise _fail(path, group, legacy, f"given with {name}, expected only {name} (its successor)")
    return value or old


def _constants(path: str, group: Group) -> dict:
    """EnvironmentConstants with nu as SetEnvironmentalConstants settles it: a given nu differing from the
    default mu/rho by more than epsilon is kept; otherwise nu = mu/rho when that differs from it by more."""
    given = _given(path, group, _CONSTANTS)
    kw = _attrs(_CONSTANTS, given)
    for name, attr in (("rho", "rho_kg_m3"), ("c", "c_m_s"), ("mu", "mu_pa_s")):
        if kw[attr] <= 0.0:
            raise _fail(path, group, name, f"got {kw[attr]!r}, expected > 0")
    nu_default = 1.51e-5 / 1.225
    nu = given.get("nu", nu_default)
    if nu <= 0.0:
        raise _fail(path, group, "nu", f"got {nu!r}, expected > 0")
    if abs(nu_default - nu) <= kw["epsilon"] and abs(kw["mu_pa_s"] / kw["rho_kg_m3"] - nu) > kw["epsilon"]:
        nu = kw["mu_pa_s"] / kw["rho_kg_m3"]
    kw["nu_m2_s"] = nu
    return kw


# --------------------------------------------------------------------------------------------------- CB


def _cb(path: str, group: Group) -> CB:
    """One ``&CB``, checked for what its types need."""
    given = _given(path, group, _CB)
    kw = _attrs(_CB, given)
    for name, attr, choices in (("AxisType", "axis_type", AXIS_TYPES), ("AngleType", "angle_type", ANGLE_TYPES),
                                ("TranslationType", "translation_type", TRANSLATION_TYPES)):
        kw[attr] = _choice(path, group, name, given[name], choices) if name in given else None
    kw["axis_type"] = kw["axis_type"] or "TimeIndependent"
    kw["a"], kw["b"] = (_harmonics(path, group, given, letter) for letter in "AB")
    extra = _extra(_CB, given)
    if "flightPath" in given:
        _refuse_if(path, group, given, "flightPath", "flight-path CBs (way points)")
        extra["flightPath"] = given["flightPath"]
    cb = CB(**kw, extra=extra, line=group.line)
    _check_rotation(path, group, cb, given)
    _check_translation(path, group, cb, given)
    return cb


def _harmonics(path: str, group: Group, given: dict, letter: str) -> tuple:
    """The Periodic harmonics A1, A2, ... (or B): the array ``A`` or the scalars ``A1``, ``A2``, not both."""
    scalars = [name for name in (letter + "1", letter + "2") if name in given]
    if letter in given and scalars:
        raise _fail(path, group, scalars[0], f"given with the array {letter}, expected either {letter}(n) or "
                                             f"{letter}1/{letter}2")
    if letter in given:
        return given[letter]
    values = [given.get(letter + "1", 0.0), given.get(letter + "2", 0.0)]
    return tuple(values[:2 if letter + "2" in given else 1 if scalars else 0])


_ROTATION_FIELDS = ("AxisValue", "AngleValue", "Omega", "A0", "A1", "A2", "B1", "B2", "A", "B", "Rotation")


def _check_rotation(path: str, group: Group, cb: CB, given: dict) -> None:
    if cb.windframe:
        raise _fail(path, group, "Windframe", ".true.: wind-frame CBs (built from the previous CB) are not "
                                              "supported by NPS")
    if cb.axis_type == "NonPeriodic":
        raise _fail(path, group, "AxisType", "'NonPeriodic' reads the axis from a file whose format NPS has not "
                                             "confirmed in PSU-WOPWOP's source (COB.f90), not supported")
    if cb.angle_type is None:
        stray = [name for name in _ROTATION_FIELDS if given.get(name)]
        if stray:
            raise _fail(path, group, stray[0], f"given without AngleType, expected an AngleType "
                                               f"({', '.join(ANGLE_TYPES[:3])})")
        return
    if cb.angle_type == "NonPeriodic":
        raise _fail(path, group, "AngleType", "'NonPeriodic' reads angles from a file (Filename) whose format NPS "
                                              "has not confirmed in PSU-WOPWOP's source (COB.f90), not supported")
    if cb.axis_value is None:
        raise _fail(path, group, "AxisValue", f"missing, expected the rotation axis (3 numbers) for AngleType "
                                              f"'{cb.angle_type}'")
    if math.hypot(*cb.axis_value) == 0.0:
        raise _fail(path, group, "AxisValue", "zero rotation axis (0, 0, 0), expected a nonzero vector")
    needed = {"TimeIndependent": ("AngleValue", cb.angle_value), "KnownFunction": ("Omega", cb.omega_rad_s),
              "Periodic": ("Omega", cb.omega_rad_s)}[cb.angle_type]
    if needed[1] is None:
        raise _fail(path, group, needed[0], f"missing, expected a number for AngleType '{cb.angle_type}'")


def _check_translation(path: str, group: Group, cb: CB, given: dict) -> None:
    if cb.translation_type is None:
        stray = [name for name in ("TranslationValue", "Y0", "VH", "AH") if name in given]
        if stray:
            raise _fail(path, group, stray[0], "given without TranslationType, expected TranslationType = "
                                               "'TimeIndependent' or 'KnownFunction'")
        return
    if cb.translation_type in ("Periodic", "NonPeriodic"):
        raise _fail(path, group, "TranslationType", f"'{cb.translation_type}': its data format is not confirmed in "
                                                    "PSU-WOPWOP's source (COB.f90), not supported by NPS")
    if cb.translation_type == "TimeIndependent" and cb.translation_value is None:
        raise _fail(path, group, "TranslationValue", "missing, expected 3 numbers for TranslationType "
                                                     "'TimeIndependent'")


def _cbs(path: str, blocks: _Blocks, owner: Group, count_field: str, n: int) -> tuple[CB, ...]:
    return tuple(_cb(path, blocks.take(owner, count_field, "cb", k, n)) for k in range(1, n + 1))


# --------------------------------------------------------------------------------------------- observers


def _observer(path: str, blocks: _Blocks, group: Group, state: dict) -> ObserverSpec:
    """One observer container and its CB and range blocks."""
    given = _given(path, group, _OBSERVER)
    for name, what in (("FSCInputFileName", "FSC collocation-point observers"),):
        _refuse_if(path, group, given, name, what)
    if given.get("nbBaseObsFrame", -1) >= 0:
        raise _fail(path, group, "nbBaseObsFrame", "the legacy name of nbBaseObsContFrame (WOPWOP stops on it), "
                                                   "expected nbBaseObsContFrame")
    kw = _attrs(_OBSERVER, given)
    kw["octave_flag"] = given.get("octaveFlag", state["octave_flag"])  # a global of WOPWOP's: it carries over
    state["octave_flag"] = kw["octave_flag"]
    _fold_legacy(path, group, given, kw)
    _check_times(path, group, kw)
    counts = {name: _count(path, group, given, name) for name in
              ("nbBase", "nbBaseObsContFrame", "nbBaseLocalFrame", "nbFreqRanges")}
    if not kw["attached_to"].strip():
        for name in ("nbBaseObsContFrame", "nbBaseLocalFrame"):
            if counts[name]:
                raise _fail(path, group, name, f"{counts[name]} without attachedTo, expected 0 (WOPWOP reads these "
                                               "CB blocks only for an attached observer)")
    geometry = _geometry(path, group, given)
    cbs = _cbs(path, blocks, group, "nbBase", counts["nbBase"])
    frame = _cbs(path, blocks, group, "nbBaseObsContFrame", counts["nbBaseObsContFrame"])
    local = _cbs(path, blocks, group, "nbBaseLocalFrame", counts["nbBaseLocalFrame"])
    ranges = _ranges(path, blocks, group, counts["nbFreqRanges"], kw)
    return ObserverSpec(**kw, **geometry, cbs=cbs, obs_frame_cbs=frame, local_frame_cbs=local, ranges=ranges,
                        extra=_extra(_OBSERVER, given), line=group.line)


def _fold_legacy(path: str, group: Group, given: dict, kw: dict) -> None:
    """WOPWOP's legacy observer names, folded into their successors; the window name canonical."""
    if given.get("windowSize", 0.0) > 0.0:
        kw["segment_size_s"] = given["windowSize"]
    if given.get("increment", 0.0) > 0.0:
        kw["segment_step_s"] = given["increment"]
    if given.get("spectrumIncrement", 0) > 0:
        if kw["segment_increment"] > 0:
            raise _fail(path, group, "spectrumIncrement", "given with segmentIncrement, expected only "
                                                          "segmentIncrement (the same variable)")
        kw["segment_increment"] = given["spectrumIncrement"]
    if given.get("octaveBand", 0.0) != 0.0:
        kw["octave_number"] = given["octaveBand"]
    kw["window"] = _choice(path, group, "windowFunction", kw["window"], WINDOWS)


def _check_times(path: str, group: Group, kw: dict) -> None:
    if kw["nt"] is None:
        raise _fail(path, group, "nt", "missing, expected the number of observer times (>= 1)")
    if kw["nt"] < 1:
        raise _fail(path, group, "nt", f"got {kw['nt']}, expected a count >= 1")
    if kw["t_max_s"] <= kw["t_min_s"]:
        raise _fail(path, group, "tMax", f"tMax = {kw['t_max_s']!r} <= tMin = {kw['t_min_s']!r}, expected "
                                         "tMax > tMin (an unset range, derived by WOPWOP from the sources, is not "
                                         "supported by NPS)")
    if kw["high_pass_hz"] >= kw["low_pass_hz"]:
        raise _fail(path, group, "highPassFrequency", f"{kw['high_pass_hz']!r} >= lowPassFrequency "
                                                      f"{kw['low_pass_hz']!r}, expected highPass < lowPass")
    if kw["low_pass_hz"] - kw["high_pass_hz"] <= 1.0 / (kw["t_max_s"] - kw["t_min_s"]):
        raise _fail(path, group, "lowPassFrequency", "lowPassFrequency - highPassFrequency <= 1/(tMax - tMin), "
                                                     "expected a band wider than one frequency bin")


def _geometry(path: str, group: Group, given: dict) -> dict:
    """Exactly one kind of observer geometry, checked as WOPWOP needs it to take that branch."""
    kinds = [kind for kind, names in (("point", _POINT), ("box", _BOX), ("sphere", _SPHERE)) if
             any(name in given for name in names)] + (["file"] if given.get("fileName", "").strip() else [])
    if len(kinds) != 1:
        found = "none" if not kinds else " and ".join(kinds)
        raise _fail(path, group, "xLoc/nbx/radius/fileName", f"observer geometry: {found}, expected exactly one "
                                                             "of a point, a box, a sphere or a file")
    kind = kinds[0]
    value = {n: given.get(n, 0 if n in _COUNTS else False if n == "indexSwap" else 0.0) for n in _BOX + _SPHERE}
    if kind == "point":
        return {"kind": kind, "point": tuple(float(given.get(n, 0.0)) for n in _POINT)}
    if kind == "file":
        return {"kind": kind, "file_name": given["fileName"].rstrip()}
    names = ("nbx", "nby", "nbz") if kind == "box" else ("nbTheta", "nbPsi")
    for name in names:
        _count(path, group, value, name, minimum=1)
    if kind == "box":
        return {"kind": kind, "box": Box(*(value[n] for n in _BOX))}
    if value["radius"] <= 0.0:
        raise _fail(path, group, "radius", f"got {value['radius']!r}, expected a sphere radius > 0")
    return {"kind": kind, "sphere": Sphere(*(value[n] for n in _SPHERE))}


def _ranges(path: str, blocks: _Blocks, owner: Group, n: int, kw: dict) -> tuple:
    """The ``&RangeIn`` blocks: (title, min Hz, max Hz). A missing Title carries over as in WOPWOP (the
    variable is shared with ``&ObserverIn``); the frequencies must be given in every block."""
    out, title = [], kw["title"]
    nyquist_hz = kw["nt"] / 2 / (kw["t_max_s"] - kw["t_min_s"])
    for k in range(1, n + 1):
        group = blocks.take(owner, "nbFreqRanges", "rangein", k, n)
        given = _given(path, group, _RANGE)
        title = given.get("Title", title)
        for name in ("minFrequency", "maxFrequency"):
            if name not in given:
                raise _fail(path, group, name, "missing, expected a frequency in Hz (WOPWOP would reuse the "
                                               "previous block's value)")
        if given["minFrequency"] >= nyquist_hz:
            raise _fail(path, group, "minFrequency", f"{given['minFrequency']!r} Hz >= the Nyquist frequency "
                                                     f"{nyquist_hz!r} Hz, expected below it")
        out.append((title, given["minFrequency"], given["maxFrequency"]))
    return tuple(out)


# -------------------------------------------------------------------------------------------- containers


def _container(path: str, blocks: _Blocks, group: Group, state: dict, parent_chain: tuple) -> Container:
    """One ``&ContainerIn`` and, depth-first, everything it announces."""
    given = _given(path, group, _CONTAINER)
    _refuse_if(path, group, given, "BWINoiseFlag", "blade-wake-interaction broadband blocks (&BWIIn)")
    kw = _attrs(_CONTAINER, given)
    kw.update(_source_time(path, group, given, state["tau"]))
    kw.update(_patch_files(path, group, given))
    n_children = _count(path, group, given, "nbContainer")
    cbs = _cbs(path, blocks, group, "nbBase", _count(path, group, given, "nbBase"))
    chain = parent_chain + cbs
    kw.update(_broadband(path, blocks, group, kw, chain, state))
    children = []
    for k in range(1, n_children + 1):
        child = blocks.take(group, "nbContainer", "containerin", k, n_children)
        children.append(_container(path, blocks, child, state, chain))
    return Container(**kw, cbs=cbs, children=tuple(children), extra=_extra(_CONTAINER, given), line=group.line)


def _source_time(path: str, group: Group, given: dict, tau: dict) -> dict:
    """dTau, nTau, tauMin, tauMax: given values update the carried ones; dTau from nTau when dTau is 0."""
    tau.update({name: given[name] for name in tau if name in given})
    if tau["nTau"] < 0:
        raise _fail(path, group, "nTau", f"got {tau['nTau']}, expected a count >= 0")
    d_tau = tau["dTau"]
    if d_tau == 0.0 and tau["nTau"] > 0:
        d_tau = (tau["tauMax"] - tau["tauMin"]) / tau["nTau"]
    if d_tau < 0.0:
        raise _fail(path, group, "dTau", f"source-time step {d_tau!r} s, expected >= 0")
    return {"d_tau_s": d_tau, "n_tau": tau["nTau"], "tau_min_s": tau["tauMin"], "tau_max_s": tau["tauMax"]}


def _patch_files(path: str, group: Group, given: dict) -> dict:
    """Geometry file names up to the first empty one (WOPWOP counts no further) and their loading files."""
    geometry = [(name or "").rstrip() for name in given.get("patchGeometryFile", ())]
    loading = [(name or "").rstrip() for name in given.get("patchLoadingFile", ())]
    for name, names in (("patchGeometryFile", geometry), ("patchLoadingFile", loading)):
        if len(names) > MAX_PATCH_FILES:
            raise _fail(path, group, name, f"{len(names)} files, expected at most {MAX_PATCH_FILES}")
    n = geometry.index("") if "" in geometry else len(geometry)
    late = [k for k in range(n, len(geometry)) if geometry[k]]
    if late:
        raise _fail(path, group, f"patchGeometryFile({late[0] + 1})", f"given after an empty "
                    f"patchGeometryFile({n + 1}), expected no gap (WOPWOP stops at the first empty name)")
    orphans = [k for k in range(n, len(loading)) if loading[k]]
    if orphans:
        k = orphans[0] + 1
        raise _fail(path, group, f"patchLoadingFile({k})", f"has no patchGeometryFile({k}), expected a geometry "
                                                          "file for every loading file")
    loading += [""] * (n - len(loading))
    return {"geometry_files": tuple(geometry[:n]), "loading_files": tuple(name or None for name in loading[:n])}


def _broadband(path: str, blocks: _Blocks, group: Group, kw: dict, chain: tuple, state: dict) -> dict:
    """The ``&PeggIn`` / ``&BPMIn`` block of a flagged container (after its CBs, before its children)."""
    out = {}
    for flag, attr, name, schema in (("PeggNoiseFlag", "pegg", "peggin", _PEGG),
                                     ("BPMNoiseFlag", "bpm", "bpmin", _BPM)):
        if not kw[attr]:
            continue
        if not any(cb.rotation for cb in chain):
            raise _fail(path, group, flag, ".true. in a container whose CB chain has no Rotation = .true. CB: WOPWOP "
                                           "ignores the flag and reads no block, expected the flag in a rotating "
                                           "container")
        if state["broadband"] not in (None, flag):
            raise _fail(path, group, flag, f".true. after {state['broadband']} in another container: WOPWOP runs one "
                                           "broadband method per case, expected one of them")
        state["broadband"] = flag
        out[attr + "_in"] = _given(path, blocks.take(group, flag, name, 1, 1), schema)
    return out


# ------------------------------------------------------------------------------------------------ reading


def _read_text(path: Path, shown: str) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except OSError as error:
        raise WopwopError(f"{shown}: cannot read the file ({error.strerror or error}), expected a namelist text file")
    except UnicodeDecodeError as error:
        raise WopwopError(f"{shown}: byte {error.start}: not UTF-8 text, expected a namelist text file")


def _case_refs(groups: tuple[Group, ...], shown: str, root: Path) -> tuple[CaseRef, ...]:
    refs = []
    for group in groups:
        if group.name != "casename":
            raise WopwopError(f"{shown}: line {group.line}: {_label(group)}: not a &caseName group, expected only "
                              "&caseName groups in a case list")
        given = _given(shown, group, _CASENAME)
        for name in ("globalFolderName", "caseNameFile"):
            if not given.get(name, "").strip():
                raise _fail(shown, group, name, "missing or empty, expected a quoted name (WOPWOP stops without it)")
        refs.append(CaseRef(given["globalFolderName"].rstrip(), given["caseNameFile"].rstrip(), root, group.line))
    if not refs:
        raise WopwopError(f"{shown}: no &caseName group, expected at least one")
    return tuple(refs)


def read_case_list(path) -> tuple[CaseRef, ...]:
    """The cases of a ``cases.nam`` (Main.f90: one ``&caseName globalFolderName, caseNameFile /`` per case)."""
    shown = str(path)
    return _case_refs(parse_namelist(_read_text(Path(path), shown), shown), shown, Path(path).parent)


def read_case(path, case_index: int | None = None) -> Case:
    """A case, from a ``cases.nam`` (one case, or the 0-based ``case_index``-th) or from a case file directly
    (then files it names resolve from its own directory)."""
    shown = str(path)
    groups = parse_namelist(_read_text(Path(path), shown), shown)
    if not (groups and groups[0].name == "casename"):
        if case_index not in (None, 0):
            raise WopwopError(f"{shown}: a case file (one case), case_index {case_index} expected None or 0")
        return _case(groups, Path(path), shown, Path(path).parent, "")
    refs = _case_refs(groups, shown, Path(path).parent)
    if case_index is None and len(refs) != 1:
        lines = ", ".join(str(ref.line) for ref in refs)
        raise WopwopError(f"{shown}: {len(refs)} cases (&caseName at lines {lines}), expected one: pass case_index "
                          "(0-based) to choose")
    index = 0 if case_index is None else case_index
    if not 0 <= index < len(refs):
        raise WopwopError(f"{shown}: case_index {index}, expected 0 to {len(refs) - 1} ({len(refs)} cases)")
    ref = refs[index]
    case_path = ref.case_path
    return _case(parse_namelist(_read_text(case_path, str(case_path)), str(case_path)), case_path, str(case_path),
                 ref.root, ref.global_folder_name)


def _case(groups: tuple[Group, ...], case_path: Path, shown: str, root: Path, global_folder: str) -> Case:
    """The case file's groups in WOPWOP's read order (Main.f90 CreateEnvironment)."""
    blocks = _Blocks(groups, shown)
    env_in = blocks.first("environmentin", "as the first group")
    environment = _environment(shown, env_in, blocks.first("environmentconstants", "after &EnvironmentIn"))
    state = {"tau": {"dTau": 0.0, "nTau": 0, "tauMin": 0.0, "tauMax": 0.0}, "broadband": None, "octave_flag": False}
    n_obs, n_src = environment.nb_observer_containers, environment.nb_source_containers
    observers = tuple(_observer(shown, blocks, blocks.take(env_in, "nbObserverContainers", "observerin", k, n_obs),
                                state) for k in range(1, n_obs + 1))
    containers = tuple(_container(shown, blocks, blocks.take(env_in, "nbSourceContainers", "containerin", k, n_src),
                                  state, ()) for k in range(1, n_src + 1))
    if blocks.next < len(groups):
        extra = groups[blocks.next]
        raise WopwopError(f"{shown}: line {extra.line}: {_label(extra)}: after the last container: nbSourceContainers, "
                          "nbContainer and nbBase account for every group before it, expected the end of the file")
    case = Case(environment, observers, containers, case_path, root, global_folder)
    for observer, group in zip(observers, [g for g in groups if g.name == "observerin"]):
        if observer.attached_to.strip():
            _attached_container(case, observer, shown, group)
    return case


# ----------------------------------------------------------------------------------------- chains


def iter_containers(containers, parent_chain: tuple = ()) -> Iterator[tuple[Container, tuple]]:
    """Every container depth-first in file order, with its full CB chain: its ancestors' CBs, then its own (the
    order WOPWOP appends them in; the first CB listed is applied last, :func:`nps.wopwop.motion.chain_motion`)."""
    for container in containers:
        chain = parent_chain + tuple(container.cbs)
        yield container, chain
        yield from iter_containers(container.children, chain)


def _attached_container(case: Case, observer: ObserverSpec, shown: str, group: Group | None = None) -> tuple:
    name = observer.attached_to.strip()
    chains = [chain for container, chain in iter_containers(case.containers) if container.title.strip() == name]
    if len(chains) != 1:
        where = f"line {group.line if group else observer.line}: &ObserverIn '{observer.title}': attachedTo"
        raise WopwopError(f"{shown}: {where}: {len(chains)} containers have Title '{name}', expected exactly one")
    return chains[0]


def observer_chain(case: Case, observer: ObserverSpec) -> tuple:
    """An observer's CB chain (first CB applied last): its ``nbBase`` CBs, or, when attached to a container,
    ``obs_frame_cbs`` + that container's full chain + ``local_frame_cbs`` (ObserverContainerObject
    AttachObsContToObject; the ``nbBase`` CBs are dropped, as in WOPWOP)."""
    if not observer.attached_to.strip():
        return tuple(observer.cbs)
    return tuple(observer.obs_frame_cbs) + _attached_container(case, observer, str(case.path)) + tuple(
        observer.local_frame_cbs)


# ------------------------------------------------------------------------------------------------ writing


def _fields(obj, schema: tuple[_Field, ...], always: tuple[str, ...] = ()) -> dict:
    """Namelist fields of a dataclass: attribute values that differ from WOPWOP's default (and ``always``)."""
    out = {}
    for spec in schema:
        if spec.attr in (None, _CODE):
            continue
        value = getattr(obj, spec.attr)
        if value is not None and (value != spec.default or spec.name in always):
            out[spec.name] = value
    return out


def _environment_groups(case: Case) -> list[Group]:
    env = case.environment
    fields = {"nbSourceContainers": len(case.containers), "nbObserverContainers": len(case.observers)}
    fields.update(_fields(env, _ENV_IN))
    fields.update(env.extra)
    constants = _fields(env, _CONSTANTS, always=("rho", "c"))
    constants["nu"] = env.nu_m2_s
    return [Group("EnvironmentIn", fields), Group("EnvironmentConstants", constants)]


def _cb_group(cb: CB) -> Group:
    fields = {"Title": cb.title}
    if cb.angle_type:
        fields["AxisType"], fields["AngleType"] = cb.axis_type, cb.angle_type
    if cb.translation_type:
        fields["TranslationType"] = cb.translation_type
    fields.update(_fields(cb, _CB))
    for letter, values in (("A", cb.a), ("B", cb.b)):
        if len(cb.a) <= 2 and len(cb.b) <= 2:
            fields.update({f"{letter}{n}": v for n, v in enumerate(values, 1)})
        elif values:
            fields[letter] = tuple(values)
    fields.update(cb.extra)
    return Group("CB", fields)


def _observer_groups(obs: ObserverSpec) -> list[Group]:
    fields = _fields(obs, _OBSERVER, always=("Title", "nt", "tMin", "tMax", "octaveFlag"))
    if obs.kind == "point":
        fields.update(zip(_POINT, obs.point))
    elif obs.kind == "box":
        fields.update(zip(_BOX, (getattr(obs.box, f) for f in Box.__dataclass_fields__)))
    elif obs.kind == "sphere":
        fields.update(zip(_SPHERE, (getattr(obs.sphere, f) for f in Sphere.__dataclass_fields__)))
    else:
        fields["fileName"] = obs.file_name
    counts = (("nbBase", obs.cbs), ("nbBaseObsContFrame", obs.obs_frame_cbs), ("nbBaseLocalFrame", obs.local_frame_cbs),
              ("nbFreqRanges", obs.ranges))
    fields.update({name: len(items) for name, items in counts if items})
    fields.update(obs.extra)
    groups = [Group("ObserverIn", fields)]
    groups += [_cb_group(cb) for cb in obs.cbs + obs.obs_frame_cbs + obs.local_frame_cbs]
    groups += [Group("RangeIn", {"Title": t, "minFrequency": lo, "maxFrequency": hi}) for t, lo, hi in obs.ranges]
    return groups


def _container_groups(c: Container) -> list[Group]:
    fields = {"Title": c.title, "nbContainer": len(c.children), "nbBase": len(c.cbs), "dTau": c.d_tau_s,
              "nTau": c.n_tau, "tauMin": c.tau_min_s, "tauMax": c.tau_max_s}
    if c.geometry_files:
        fields["patchGeometryFile"] = tuple(c.geometry_files)
    if any(c.loading_files):
        fields["patchLoadingFile"] = tuple(c.loading_files)
    fields.update(_fields(c, _CONTAINER))
    fields.update(c.extra)
    groups = [Group("ContainerIn", fields)] + [_cb_group(cb) for cb in c.cbs]
    groups += [Group(name, dict(block)) for name, block in (("PeggIn", c.pegg_in), ("BPMIn", c.bpm_in)) if block]
    for child in c.children:
        groups += _container_groups(child)
    return groups


def format_case(case: Case) -> str:
    """The case file's text: environment, observers, container trees, in WOPWOP's read order; counts from the
    lists, every container's source-time values written out (they would otherwise carry over)."""
    groups = _environment_groups(case)
    for observer in case.observers:
        groups += _observer_groups(observer)
    for container in case.containers:
        groups += _container_groups(container)
    return "! PSU-WOPWOP case file written by NPS (nps.wopwop.case)\n" + format_namelist(groups)


def write_case(case: Case, directory) -> Path:
    """Write ``cases.nam`` (globalFolderName './') and the case file (the case's file name, ``case.nam`` when it
    was itself called cases.nam) into ``directory``; binary patch files are not written. Returns the
    ``cases.nam`` path; :func:`read_case` of it gives a Case equal to ``case``."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    name = case.path.name if case.path.name.lower() != "cases.nam" else "case.nam"
    (directory / name).write_text(format_case(case), encoding="utf-8")
    cases = directory / "cases.nam"
    cases.write_text(format_namelist([Group("caseName", {"globalFolderName": "./", "caseNameFile": name})]),
                     encoding="utf-8")
    return cases
