"""``models.broadband: pegg | bpm | none | auto`` in the metrics stage (nps.stages.metrics, nps.app.config.broadband_model,
nps.noise.broadband.rotor.trimmed_rotor_broadband_msp)."""

import copy
import warnings

import numpy as np
import pandas as pd
import pytest

from nps.core.atmosphere import isa
from nps.noise.broadband.rotor import hub_frame_observers, medium_from_atmosphere, rotor_broadband_msp
from nps.app.broadband import broadband_model
from nps.app.config import ConfigError, load_aircraft, read_yaml, validate
from nps.app.io import read_metadata, read_table, write_table
from nps.noise.metrics import STUDY_BANDS, rotor_solidities
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.noise.spectra import level_db
from nps.stages.metrics import run
from tests.trim_tables import complete_trim

HUB = np.array([1.0, 2.0, 3.0])
R_GH = np.diag([-1.0, -1.0, 1.0])  # main rotor without shaft tilt: x_H aft, y_H starboard
OBSERVERS_G = np.array([[31.0, 2.0, -40.0], [1.0, 32.0, 3.5], [-45.0, -10.0, -20.0]])


def test_broadband_model_spellings():
    assert [broadband_model(v) for v in (True, False, "pegg", "bpm", "none", "auto")] == ["pegg", "none", "pegg", "bpm", "none",
                                                                                         "auto"]
    with pytest.raises(ValueError, match="models.broadband"):
        broadband_model("maybe")
    config = read_yaml("config/config.yaml")
    for value in ("pegg", "bpm", "none", "auto", True, False):
        validate(dict(config, models=dict(config["models"], broadband=value)), "config", "c.yaml")
    with pytest.raises(ConfigError, match="models.broadband"):
        validate(dict(config, models=dict(config["models"], broadband="bmp")), "config", "c.yaml")


def test_hub_frame_observers_inverts_the_trim_frame():
    row = {"hub_x_m": HUB[0], "hub_y_m": HUB[1], "hub_z_m": HUB[2],
           **{f"r_gh_{i}{j}": R_GH[i, j] for i in range(3) for j in range(3)}}
    np.testing.assert_allclose(hub_frame_observers(row, OBSERVERS_G) @ R_GH.T + HUB, OBSERVERS_G, rtol=1e-14)
    np.testing.assert_allclose(hub_frame_observers(row, OBSERVERS_G)[0], [-30.0, 0.0, -43.0])


def _aircraft():
    aircraft = copy.deepcopy(load_aircraft("config/aircraft/helicopter.yaml"))
    aircraft["rotors"] = aircraft["rotors"][:1]
    return aircraft


def _disk(rotor):
    """Hovering main rotor disk table (36 azimuths × 8 stations), uniform inflow, 5° angle of attack."""
    n_psi, n_r, radius, omega = 36, 8, rotor["radius_m"], rotor["omega_rad_s"]
    edges = np.linspace(rotor["root_cutout_m"], radius, n_r + 1)
    r = 0.5 * (edges[1:] + edges[:-1])
    return pd.DataFrame({
        "psi_rad": np.repeat(2 * np.pi * np.arange(n_psi) / n_psi, n_r), "r_m": np.tile(r, n_psi),
        "dr_m": np.tile(np.diff(edges), n_psi), "chord_m": rotor["chord_m"], "beta_rad": 0.03,
        "ut_mps": np.tile(omega * r, n_psi), "up_mps": 10.0, "alpha_eff_rad": np.radians(5.0),
    })


def _write_inputs(tmp_path, aircraft):
    rotor = aircraft["rotors"][0]
    trim = complete_trim(pd.DataFrame([{
        "rotor": "main", "n_blades": np.int32(rotor["n_blades"]), "radius_m": rotor["radius_m"], "omega_rad_s": rotor["omega_rad_s"],
        "thrust_N": 5.0e4, "ct": 0.005, "hub_x_m": HUB[0], "hub_y_m": HUB[1], "hub_z_m": HUB[2],
        **{f"r_gh_{i}{j}": R_GH[i, j] for i in range(3) for j in range(3)}}]))
    write_table(trim, tmp_path / "trim.parquet", stage="trim")
    observers = pd.DataFrame({"observer": np.int32([2, 0, 1]), "x_m": OBSERVERS_G[:, 0], "y_m": OBSERVERS_G[:, 1],
                              "z_m": OBSERVERS_G[:, 2], "vx_mps": 0.0, "vy_mps": 0.0, "vz_mps": 0.0,
                              "elevation_deg": 0.0, "azimuth_deg": 0.0})
    write_table(observers, tmp_path / "obs.parquet", stage="observers")
    n = 256
    time = np.arange(n) * (2 * np.pi / rotor["omega_rad_s"]) / n
    p = np.cos(2 * np.pi * 4 * np.arange(n) / n)
    signal = pd.DataFrame({"observer": np.repeat(np.int32([0, 1, 2]), 2 * n), "group": np.tile(np.repeat(["loading", "thickness"], n), 3),
                           "time_s": np.tile(time, 6), "p_Pa": np.tile(p, 6)})
    write_table(signal, tmp_path / "sig" / "main.parquet", stage="acoustics")
    write_table(_disk(rotor), tmp_path / "loads" / "main.parquet", stage="loads")
    return trim, observers


def _run(tmp_path, aircraft, broadband, absorption=False, **extra):
    inputs = {"signals": tmp_path / "sig", "trim": tmp_path / "trim.parquet", "observers": tmp_path / "obs.parquet",
              "disks": tmp_path / "loads"}
    outputs = {"metrics": tmp_path / f"m_{broadband}.parquet", "bands": tmp_path / f"b_{broadband}.parquet"}
    params = {"rotors": ["main"], "solidity": rotor_solidities(aircraft),
              "atmosphere": {"altitude_m": 0.0, "isa_delta_K": 0.0, "relative_humidity_pct": 70.0},
              "broadband": broadband, "absorption": absorption, "harmonics": [7, 40], "aircraft": "helicopter",
              "segment": "seg1", "obsset": "obs", "variant": "base",
              "rotor_configs": {"main": aircraft["rotors"][0]}, **extra}
    run(inputs, outputs, params)
    return read_table(outputs["metrics"]), read_table(outputs["bands"])


def test_bpm_broadband_is_the_rotor_average_at_the_hub_frame_observers(tmp_path):
    """With ``bpm`` the band table's broadband levels are rotor_broadband_msp's total at the observers in H
    (ascending ids), to 1e-9 dB; absorption lowers them; the metadata keeps the configured value."""
    aircraft = _aircraft()
    trim, observers = _write_inputs(tmp_path, aircraft)
    configs = {"main": aircraft["rotors"][0]}
    metrics, bands = _run(tmp_path, aircraft, "bpm", rotor_configs=configs)
    row = trim.iloc[0]
    order = np.argsort(observers["observer"].to_numpy())
    direct = rotor_broadband_msp(_disk(aircraft["rotors"][0]), RotorGeometry.from_config(aircraft["rotors"][0]),
                                 OperatingPoint.from_trim_row(row), hub_frame_observers(row, OBSERVERS_G[order]),
                                 medium_from_atmosphere(isa(0.0)), STUDY_BANDS)["total"]
    broadband = bands[bands.source == "broadband"].sort_values(["observer", "band"]).level_db.to_numpy()
    np.testing.assert_allclose(broadband, level_db(direct).reshape(-1), atol=1e-9)
    assert read_metadata(tmp_path / "m_bpm.parquet")["broadband"] == "bpm"
    absorbed, _ = _run(tmp_path, aircraft, "bpm", absorption=True, rotor_configs=configs)
    assert np.all(absorbed.oaspl_broadband_db < metrics.oaspl_broadband_db)
    (tmp_path / "loads" / "main.parquet").rename(tmp_path / "main_disk.parquet")
    with pytest.raises(ValueError, match="loads"):
        _run(tmp_path, aircraft, "bpm")


def test_pegg_spellings_agree_and_warn_outside_the_data_range(tmp_path):
    """``true`` and ``pegg`` give the same tables; a 5 kN rotor warns (Pegg outside its range); ``none``
    has no broadband source and no warning."""
    aircraft = _aircraft()
    _write_inputs(tmp_path, aircraft)
    legacy, legacy_bands = _run(tmp_path, aircraft, True)
    named, named_bands = _run(tmp_path, aircraft, "pegg")
    pd.testing.assert_frame_equal(legacy, named)
    pd.testing.assert_frame_equal(legacy_bands, named_bands)
    assert read_metadata(tmp_path / "m_True.parquet")["broadband"] is True
    trim = read_table(tmp_path / "trim.parquet").assign(thrust_N=5.0e3)
    write_table(trim, tmp_path / "trim.parquet", stage="trim")
    with pytest.warns(UserWarning, match="thrust_N=5000 outside Pegg"):
        _run(tmp_path, aircraft, "pegg")

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        silent, silent_bands = _run(tmp_path, aircraft, "none")
    assert "oaspl_broadband_db" not in silent.columns and "broadband" not in set(silent_bands.source)


def test_metrics_command_chooses_the_model(tmp_path, capsys, repo_root):
    """``python -m nps metrics --broadband bpm --disks DIR`` runs BPM; without --disks it stops with one line."""
    from nps.__main__ import main as nps_main

    aircraft = _aircraft()
    _write_inputs(tmp_path, aircraft)
    args = ["metrics", "--aircraft", str(repo_root / "config/aircraft/helicopter.yaml"), "--rotor", "main",
            "--trim", str(tmp_path / "trim.parquet"), "--observers", str(tmp_path / "obs.parquet"),
            "--signals", str(tmp_path / "sig"), "--out", str(tmp_path / "m.parquet"), "--bands-out", str(tmp_path / "b.parquet"),
            "--no-absorption", "--broadband", "bpm"]
    assert nps_main(args) == 2 and "--disks" in capsys.readouterr().err
    assert nps_main(args + ["--disks", str(tmp_path / "loads")]) == 0
    assert read_metadata(tmp_path / "m.parquet")["broadband"] == "bpm"
    assert "oaspl_broadband_db" in read_table(tmp_path / "m.parquet").columns


def test_source_hemisphere_takes_the_metrics_broadband(tmp_path):
    """The source-hemisphere product with ``bpm`` holds the metrics stage's BPM band levels (no absorption, observers
    on a hemisphere at its reference radius), not Pegg's: footprints and certification agree with the metrics."""
    from nps.mission.source_hemisphere import PRODUCT_BANDS, observer_direction
    from nps.stages.source_hemisphere import run as source_hemisphere

    aircraft = _aircraft()
    _write_inputs(tmp_path, aircraft)
    azimuth, elevation = np.array([0.0, 90.0, 200.0]), np.array([-10.0, -40.0, -70.0])
    positions = HUB + 50.0 * observer_direction(np.radians(azimuth), np.radians(elevation))
    write_table(pd.DataFrame({"observer": np.int32([0, 1, 2]), "x_m": positions[:, 0], "y_m": positions[:, 1],
                              "z_m": positions[:, 2], "vx_mps": 0.0, "vy_mps": 0.0, "vz_mps": 0.0,
                              "elevation_deg": elevation, "azimuth_deg": azimuth}), tmp_path / "obs.parquet", stage="observers")
    _, bands = _run(tmp_path, aircraft, "bpm")
    inputs = {"signals": tmp_path / "sig", "trim": tmp_path / "trim.parquet", "observers": tmp_path / "obs.parquet",
              "disks": tmp_path / "loads"}
    params = {"rotors": ["main"], "solidity": rotor_solidities(aircraft), "broadband": "bpm", "reference_radius_m": 50.0,
              "rotor_configs": {"main": aircraft["rotors"][0]}, "aircraft": "helicopter", "segment": "seg1",
              "obsset": "obs", "variant": "base",
              "atmosphere": {"altitude_m": 0.0, "isa_delta_K": 0.0, "relative_humidity_pct": 70.0}}
    source_hemisphere(inputs, {"hemisphere": tmp_path / "h.parquet"}, params)
    product = read_table(tmp_path / "h.parquet")
    expected = bands[(bands.source == "broadband") & bands.band.between(PRODUCT_BANDS[0], PRODUCT_BANDS[-1])]
    got = product[product.source == "broadband"].sort_values(["observer", "band"])
    np.testing.assert_allclose(got.level_db.to_numpy(), expected.sort_values(["observer", "band"]).level_db.to_numpy(), atol=1e-9)
    assert read_metadata(tmp_path / "h.parquet")["broadband"] == "bpm"


# --- auto: BPM for the rotors outside Pegg's data range, Pegg for the others ---------------------------------------

TAIL_HUB = HUB + np.array([-9.0, 0.5, 0.3])


def _two_rotor_inputs(root, names):
    """Inputs of the stage for the helicopter's rotors ``names`` (main inside Pegg's range at 50 kN, tail at
    R = 1.55 m outside it): trim rows, the same synthetic signals on one time grid, hovering disks."""
    aircraft = copy.deepcopy(load_aircraft("config/aircraft/helicopter.yaml"))
    configs = {r["name"]: r for r in aircraft["rotors"]}
    rows = []
    for name in names:
        rotor, hub = configs[name], HUB if name == "main" else TAIL_HUB
        rows.append({"rotor": name, "n_blades": np.int32(rotor["n_blades"]), "radius_m": rotor["radius_m"],
                     "omega_rad_s": rotor["omega_rad_s"], "thrust_N": 5.0e4 if name == "main" else 4.0e3,
                     "ct": 0.005 if name == "main" else 0.004, "hub_x_m": hub[0], "hub_y_m": hub[1], "hub_z_m": hub[2],
                     **{f"r_gh_{i}{j}": R_GH[i, j] for i in range(3) for j in range(3)}})
    write_table(complete_trim(pd.DataFrame(rows)), root / "trim.parquet", stage="trim")
    observers = pd.DataFrame({"observer": np.int32([2, 0, 1]), "x_m": OBSERVERS_G[:, 0], "y_m": OBSERVERS_G[:, 1],
                              "z_m": OBSERVERS_G[:, 2], "vx_mps": 0.0, "vy_mps": 0.0, "vz_mps": 0.0,
                              "elevation_deg": 0.0, "azimuth_deg": 0.0})
    write_table(observers, root / "obs.parquet", stage="observers")
    n = 256
    time = np.arange(n) * (2 * np.pi / configs["main"]["omega_rad_s"]) / n
    p = np.cos(2 * np.pi * 4 * np.arange(n) / n)
    for name in names:
        signal = pd.DataFrame({"observer": np.repeat(np.int32([0, 1, 2]), 2 * n),
                               "group": np.tile(np.repeat(["loading", "thickness"], n), 3),
                               "time_s": np.tile(time, 6), "p_Pa": np.tile(p, 6)})
        write_table(signal, root / "sig" / f"{name}.parquet", stage="acoustics")
        write_table(_disk(configs[name]), root / "loads" / f"{name}.parquet", stage="loads")
    return aircraft


def _run_rotors(root, names, broadband):
    aircraft = _two_rotor_inputs(root, names)
    inputs = {"signals": root / "sig", "trim": root / "trim.parquet", "observers": root / "obs.parquet",
              "disks": root / "loads"}
    outputs = {"metrics": root / "m.parquet", "bands": root / "b.parquet"}
    params = {"rotors": list(names), "solidity": rotor_solidities(aircraft),
              "atmosphere": {"altitude_m": 0.0, "isa_delta_K": 0.0, "relative_humidity_pct": 70.0},
              "broadband": broadband, "absorption": True, "harmonics": [7, 40], "aircraft": "helicopter",
              "segment": "seg1", "obsset": "obs", "variant": "base",
              "rotor_configs": {r["name"]: r for r in aircraft["rotors"]}}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run(inputs, outputs, params)
    bands = read_table(outputs["bands"])
    msp = 10.0 ** (bands[bands.source == "broadband"].sort_values(["observer", "band"]).level_db.to_numpy() / 10.0)
    return msp, read_metadata(outputs["metrics"]), read_metadata(outputs["bands"])


def test_auto_gives_bpm_to_the_rotor_outside_pegg_and_pegg_to_the_other(tmp_path):
    """``auto`` on main + tail: the broadband bands are the energy sum of Pegg on the main rotor alone and BPM on
    the tail rotor alone (1e-9 dB); the metadata keep ``auto`` and record the choice per rotor."""
    auto, meta, band_meta = _run_rotors(tmp_path / "both", ["main", "tail"], "auto")
    main_pegg, main_meta, _ = _run_rotors(tmp_path / "main", ["main"], "pegg")
    tail_bpm, _, _ = _run_rotors(tmp_path / "tail", ["tail"], "bpm")
    tail_pegg, tail_meta, _ = _run_rotors(tmp_path / "tail_pegg", ["tail"], "pegg")
    np.testing.assert_allclose(10 * np.log10(auto), 10 * np.log10(main_pegg + tail_bpm), atol=1e-9)
    assert not np.allclose(10 * np.log10(auto), 10 * np.log10(main_pegg + tail_pegg), atol=0.1)
    assert meta["broadband"] == "auto" and meta["broadband_rotors"] == {"main": "pegg", "tail": "bpm"}
    assert band_meta["broadband_rotors"] == meta["broadband_rotors"]
    # model-range warnings in the metadata: Pegg on the tail rotor is outside his range; none for the main rotor
    assert any("Pegg: rotor 'tail'" in w and "radius_m=1.55" in w for w in tail_meta["model_warnings"]), tail_meta
    assert "model_warnings" not in main_meta and "broadband_rotors" not in main_meta
    assert not any(w.startswith("Pegg") for w in meta.get("model_warnings", []))


def test_auto_without_disks_names_the_input(tmp_path):
    aircraft = _two_rotor_inputs(tmp_path, ["main", "tail"])
    params = {"rotors": ["main", "tail"], "solidity": rotor_solidities(aircraft),
              "atmosphere": {"altitude_m": 0.0, "isa_delta_K": 0.0, "relative_humidity_pct": 70.0},
              "broadband": "auto", "absorption": False, "harmonics": [7, 40], "aircraft": "helicopter",
              "segment": "seg1", "obsset": "obs", "variant": "base",
              "rotor_configs": {r["name"]: r for r in aircraft["rotors"]}}
    inputs = {"signals": tmp_path / "sig", "trim": tmp_path / "trim.parquet", "observers": tmp_path / "obs.parquet"}
    with pytest.raises(ValueError, match="broadband 'auto' needs the input 'disks'"):
        run(inputs, {"metrics": tmp_path / "m.parquet", "bands": tmp_path / "b.parquet"}, params)
    assert not (tmp_path / "m.parquet").exists()


def test_source_hemisphere_auto_without_disks_names_the_input(tmp_path):
    """``auto`` with a rotor outside Pegg's range needs the disk tables in the source-hemisphere stage too."""
    from nps.stages.source_hemisphere import run as source_hemisphere

    aircraft = _two_rotor_inputs(tmp_path, ["main", "tail"])
    params = {"rotors": ["main", "tail"], "solidity": rotor_solidities(aircraft), "broadband": "auto",
              "reference_radius_m": 50.0, "rotor_configs": {r["name"]: r for r in aircraft["rotors"]},
              "atmosphere": {"altitude_m": 0.0, "isa_delta_K": 0.0, "relative_humidity_pct": 70.0}}
    inputs = {"signals": tmp_path / "sig", "trim": tmp_path / "trim.parquet", "observers": tmp_path / "obs.parquet"}
    with pytest.raises(ValueError, match="broadband 'auto' needs the input 'disks'"):
        source_hemisphere(inputs, {"hemisphere": tmp_path / "h.parquet"}, params)
    assert not (tmp_path / "h.parquet").exists()
