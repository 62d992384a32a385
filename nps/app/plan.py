"""The parameters of every stage job, in one place: what the workflow's rules, the design studies and the
Python API (:mod:`nps.api`) give ``nps.stages.<stage>.run`` for one aircraft (or rig) in one segment.

A job's ``params`` are :func:`stage_params` of its stage, with its wildcards (aircraft, segment, observer
set, variant) added. They are plain, JSON-serialisable values: validated configuration slices with the
schema defaults filled (:mod:`nps.app.config`). Because they are exactly what a stage reads besides its
input artifacts, their canonical JSON is also what a content digest of a stage job covers
(:func:`job_digest`): two jobs with equal digests write bit-identical artifacts.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass
from typing import Any, Mapping

from nps.app.broadband import broadband_model
from nps.app.config import Campaign
from nps.noise.metrics import rotor_solidities
from nps.noise.signals import TONE_SUMS


@dataclass(frozen=True)
class CaseConfig:
    """What the stage parameters of one aircraft in one segment are made of.

    ``aircraft``: the validated aircraft configuration (a rig's: ``{"rotors": [rotor]}``); ``settings``: the
    configuration sections the stages read (the campaign config, or a rig's settings,
    :func:`nps.app.config.rig_settings`); ``speeds``: the mission segment's entry for this aircraft
    (forward_speed_mps, climb_speed_mps, optional rotor_omega_scale), None for a rig or an aircraft-level job;
    ``mission``: the validated mission (certification), None for a rig; ``variants``: the load variants
    radiated in the segment (:meth:`nps.app.config.Campaign.variants`); ``ground_as_written``: the
    ``footprint.ground`` section as the config file writes it (recorded in the certification's metadata).
    """

    aircraft: Mapping[str, Any]
    settings: Mapping[str, Any]
    speeds: Mapping[str, Any] | None = None
    mission: Mapping[str, Any] | None = None
    variants: tuple[str, ...] = ("base",)
    ground_as_written: Mapping[str, Any] | None = None

    @classmethod
    def from_campaign(cls, campaign: Campaign, aircraft: str, segment: str | None = None) -> "CaseConfig":
        """The case of ``aircraft`` in ``segment`` of a validated campaign (``segment`` None: an aircraft-level
        job, e.g. the certification)."""
        speeds = campaign.segment(segment)["aircraft"][aircraft] if segment is not None else None
        variants = tuple(campaign.variants(segment)) if segment is not None else ("base",)
        ground = campaign.as_written("footprint.ground") if "footprint" in campaign.config else None
        return cls(campaign.aircraft[aircraft], campaign.config, speeds, campaign.mission, variants, ground)

    @property
    def rotors(self) -> dict[str, dict]:
        """Rotor name → validated rotor configuration, in aircraft order."""
        return {rotor["name"]: rotor for rotor in self.aircraft["rotors"]}


def _allow(case: CaseConfig) -> bool:
    return bool(case.settings["campaign"]["allow_outside_validity"])


def _trim(case, obsset):
    resolution = case.settings["resolution"]
    return {"aircraft_config": case.aircraft, "speeds": case.speeds, "atmosphere": case.settings["atmosphere"],
            "allow_outside_validity": _allow(case), "n_psi": resolution["n_psi"], "n_r": resolution["n_r"]}


def _path(case, obsset):
    resolution = case.settings["resolution"]
    return {"aircraft_config": case.aircraft, "paths": case.settings["paths"], "atmosphere": case.settings["atmosphere"],
            "allow_outside_validity": _allow(case), "n_psi": resolution["n_psi"], "n_r": resolution["n_r"]}


def _loads(case, obsset):
    resolution = case.settings["resolution"]
    return {"rotors": case.rotors, "n_psi": resolution["n_psi"], "n_r": resolution["n_r"],
            "allow_outside_validity": _allow(case)}


def _wake(case, obsset):
    resolution = case.settings["resolution"]
    return {"rotors": case.rotors, "wake": case.settings["wake"], "revolutions": resolution["wake_revolutions"],
            "steps_per_rev": resolution["n_psi"], "allow_outside_validity": _allow(case)}


def _observers(case, obsset):
    return {"spec": case.settings["observer_sets"][obsset],
            "rotor_roles": {name: rotor["role"] for name, rotor in case.rotors.items()},
            "reference_radius_m": case.aircraft["rotors"][0]["radius_m"], "rotors": case.rotors,
            "allow_outside_validity": _allow(case)}


def _acoustics(case, obsset):
    settings = case.settings
    params = {"rotors": list(case.rotors), "thickness": settings["models"]["thickness"],
              "chord_fractions": settings["acoustics"]["dual_compact_chord_fractions"],
              "samples_per_rev": settings["resolution"]["samples_per_rev"],
              "hinge_offsets_m": {name: rotor["hinge_offset_m"] for name, rotor in case.rotors.items()}}
    phases = {name: rotor["phase_deg"] for name, rotor in case.rotors.items() if "phase_deg" in rotor}
    if any(phases.values()):  # blade phasing (zero phases: the params, and so the artifacts, of before)
        params["phases_deg"] = phases
    return params


def _tone_sum(case) -> dict:
    """``tone_sum`` of an aircraft whose rotors add incoherently; nothing for the coherent default (a rig's one
    rotor included), so coherent jobs keep the params of before."""
    incoherent = "tone_sum" in case.aircraft and case.aircraft["tone_sum"] != TONE_SUMS[0]
    return {"tone_sum": case.aircraft["tone_sum"]} if incoherent else {}


def _hsi(case, obsset):
    return {"rotors": list(case.rotors)}


def _metrics(case, obsset):
    settings = case.settings
    return {"rotors": list(case.rotors), "solidity": rotor_solidities(case.aircraft), "atmosphere": settings["atmosphere"],
            "broadband": settings["models"]["broadband"], "absorption": settings["models"]["absorption"],
            "harmonics": settings["acoustics"]["bvispl_harmonics"], "rotor_configs": case.rotors,
            "allow_outside_validity": _allow(case), **_tone_sum(case)}


def _tones(case, obsset):
    outputs = case.settings["outputs"]
    return {"rotors": list(case.rotors), "harmonics": outputs["tone_harmonics"], "loudest": outputs["spectra_loudest"],
            "observers": outputs["spectra_observers"], **_tone_sum(case)}


def _source_hemisphere(case, obsset):
    settings = case.settings
    return {"rotors": list(case.rotors), "solidity": rotor_solidities(case.aircraft),
            "broadband": settings["models"]["broadband"],
            "reference_radius_m": settings["footprint"]["reference_radius_R"] * case.aircraft["rotors"][0]["radius_m"],
            "obsset": settings["footprint"]["source_set"], "variant": case.variants[-1], **_tone_sum(case),
            **({"rotor_configs": case.rotors, "atmosphere": settings["atmosphere"]} if metrics_reads_disks(settings) else {})}


def _certification(case, obsset):
    certification, ground = case.settings["certification"], case.settings["footprint"]["ground"]
    return {"mission": case.mission, "max_mass_kg": case.aircraft["gross_weight_kg"],
            "segments": certification["segments"], "vne_mps": certification["vne_mps"],
            "approach_min_speed_mps": certification["approach_min_speed_mps"], "ground": ground,
            "ground_as_written": case.ground_as_written, "absorption": case.settings["models"]["absorption"]}


def _footprint(case, obsset):
    footprint = case.settings["footprint"]
    return {"mission": case.mission, "grid": footprint["grid"], "microphones": footprint["microphones"],
            "ground": footprint["ground"], "ground_as_written": case.ground_as_written,
            "atmosphere": case.settings["atmosphere"], "absorption": case.settings["models"]["absorption"]}


PARAMS = {"trim": _trim, "path": _path, "loads": _loads, "wake": _wake, "observers": _observers, "acoustics": _acoustics,
          "wopwop_export": _acoustics, "hsi": _hsi, "metrics": _metrics, "tones": _tones, "source_hemisphere": _source_hemisphere, "certification": _certification, "footprint": _footprint}


def metrics_reads_disks(settings: Mapping[str, Any]) -> bool:
    """Whether the metrics stage reads the rotors' disk tables (input ``disks``): with BPM broadband, or
    ``auto`` (BPM for the rotors outside Pegg's range)."""
    return broadband_model(settings["models"]["broadband"]) in ("bpm", "auto")


def stage_params(stage: str, case: CaseConfig, obsset: str | None = None) -> dict:
    """The ``params`` of a ``stage`` job of ``case`` (``obsset``: the observer set of the observers stage),
    without the wildcards the job adds (aircraft, segment, obsset, variant)."""
    if stage not in PARAMS:
        raise KeyError(f"no parameter plan for stage '{stage}'; planned: {', '.join(PARAMS)}")
    return PARAMS[stage](case, obsset)


def canonical_json(value: Any) -> str:
    """JSON of plain values with sorted keys and exact floats (``repr``): equal text ⇔ equal values."""
    return json.dumps(value, sort_keys=True, separators=(",", ":"), allow_nan=False)


def job_digest(stage: str, code_digest: str, params: Mapping[str, Any], input_digests: Mapping[str, str]) -> str:
    """SHA-256 (first 20 hex digits) of what a stage job's artifacts depend on: the stage, the digest of the
    code it runs (:func:`nps.stages.code.stage_digest`), its params and its inputs' digests."""
    text = canonical_json({"stage": stage, "code": code_digest, "params": params, "inputs": dict(input_digests)})
    return hashlib.sha256(text.encode()).hexdigest()[:20]
