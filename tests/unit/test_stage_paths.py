"""One code path per stage: the command writes the same bytes as calling the stage's run function."""

from nps.cli import loads as loads_cli
from nps.cli import trim as trim_cli
from nps.app.config import load_aircraft, load_mission
from nps.stages import loads, trim


def test_command_and_run_write_identical_artifacts(tmp_path, repo_root):
    aircraft_path = repo_root / "config/aircraft/coaxial.yaml"
    mission_path = repo_root / "config/missions/demo.yaml"
    assert trim_cli.main(["--aircraft", str(aircraft_path), "--mission", str(mission_path), "--segment", "seg2",
                          "--out", str(tmp_path / "cli/trim.parquet")]) == 0
    aircraft = load_aircraft(aircraft_path)
    speeds = next(s for s in load_mission(mission_path)["segments"] if s["id"] == "seg2")["aircraft"]["coaxial"]
    atmosphere = {"altitude_m": 0.0, "isa_delta_K": 0.0, "relative_humidity_pct": 70.0}
    trim.run({}, {"trim": tmp_path / "run/trim.parquet"},
             {"aircraft_config": aircraft, "speeds": speeds, "atmosphere": atmosphere, "segment": "seg2",
              "n_psi": 360, "n_r": 50})
    assert (tmp_path / "cli/trim.parquet").read_bytes() == (tmp_path / "run/trim.parquet").read_bytes()

    trim_path = str(tmp_path / "run/trim.parquet")
    assert loads_cli.main(["--aircraft", str(aircraft_path), "--trim", trim_path, "--n-psi", "36", "--n-r", "10",
                           "--out-dir", str(tmp_path / "cli/loads")]) == 0
    loads.run({"trim": trim_path}, {"loads": tmp_path / "run/loads"},
              {"rotors": {r["name"]: r for r in aircraft["rotors"]}, "n_psi": 36, "n_r": 10, "aircraft": "coaxial",
               "segment": "seg2"})
    written = sorted(p.name for p in (tmp_path / "cli/loads").iterdir())
    assert written == sorted(p.name for p in (tmp_path / "run/loads").iterdir()) and len(written) == 6
    for name in written:
        assert (tmp_path / "cli/loads" / name).read_bytes() == (tmp_path / "run/loads" / name).read_bytes(), name


def test_path_command_and_run_write_identical_artifacts(tmp_path, repo_root):
    """``python -m nps path`` at its defaults and the stage run with the plan's params (the config schema's
    defaults) write the same bytes."""
    from nps.app.config import load_path, schema_defaults
    from nps.app.plan import CaseConfig, stage_params
    from nps.cli import path as path_cli
    from nps.stages import path

    aircraft_path = repo_root / "config/aircraft/hexacopter.yaml"
    path_file = repo_root / "config/paths/hexacopter_transition.yaml"
    assert path_cli.main(["--aircraft", str(aircraft_path), "--path", str(path_file), "--out", str(tmp_path / "cli")]) == 0
    aircraft = load_aircraft(aircraft_path)
    params = stage_params("path", CaseConfig(aircraft, schema_defaults("config")))
    params.update(aircraft="hexacopter", path_config=load_path(path_file, params["paths"]["dt_s"]))
    path.run({}, {"history": tmp_path / "run/path_history.parquet", "states": tmp_path / "run/path_states.parquet"}, params)
    for name in ("path_history.parquet", "path_states.parquet"):
        assert (tmp_path / "cli" / name).read_bytes() == (tmp_path / "run" / name).read_bytes(), name
    import pandas as pd

    states = pd.read_parquet(tmp_path / "run/path_states.parquet")  # hover at the start of the acceleration: one key
    assert (states.groupby("state").size() == 6).all()
    assert set(pd.read_parquet(tmp_path / "run/path_history.parquet").state) <= set(states.state)
