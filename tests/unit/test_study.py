"""Study summaries: hotspot location, segment summary rows and stage wall times from benchmark files."""

import numpy as np
import pandas as pd
import pytest

from nps.stages.summary import stage_wall_times
from nps.app.study import hotspot, segment_summary


def test_hotspot_finds_maximum_and_breaks_ties_by_observer():
    metrics = pd.DataFrame({
        "observer": [3, 1, 2],
        "azimuth_deg": [10.0, 20.0, 30.0],
        "elevation_deg": [-5.0, -10.0, -15.0],
        "bvispl_db": [80.0, 90.0, 90.0],
    })
    spot = hotspot(metrics, "bvispl_db")
    assert spot == {"value": 90.0, "observer": 1, "azimuth_deg": 20.0, "elevation_deg": -10.0}


def test_stage_wall_times_sums_job_files(tmp_path):
    def bench(path, seconds):
        path.parent.mkdir(parents=True, exist_ok=True)
        pd.DataFrame({"s": [seconds], "h:m:s": ["0:00:01"]}).to_csv(path, sep="\t", index=False)

    bench(tmp_path / "trim/heli/seg3.tsv", 0.5)
    bench(tmp_path / "loads/heli/seg3/main.tsv", 1.25)
    bench(tmp_path / "loads/heli/seg3/tail.tsv", 0.75)
    bench(tmp_path / "acoustics/heli/seg3/hemisphere/main_base.tsv", 2.0)
    bench(tmp_path / "loads/heli/seg30/main.tsv", 100.0)  # another segment: must not count
    times = stage_wall_times(tmp_path, "heli", "seg3")
    assert times == {"trim": 0.5, "loads": 2.0, "acoustics": 2.0}
    assert np.isclose(sum(times.values()), 4.5)


def _metrics(bvispl_db):
    n = len(bvispl_db)
    return pd.DataFrame({"observer": np.arange(n), "azimuth_deg": 10.0 * np.arange(n), "elevation_deg": -5.0 * np.arange(n),
                         "oaspl_db": np.full(n, 90.0), "oaspl_dba": np.full(n, 80.0), "bvispl_db": np.asarray(bvispl_db, float)})


def test_segment_summary_reports_bvi_levels_and_the_comparison_without_bvi():
    """Levels from the BVI variant; the without-BVI maximum from the base variant, or flagged when not radiated."""
    trim = pd.DataFrame({"rotor": ["main"], "thrust_N": [1000.0], "mu_x": [0.1], "pitch_rad": [np.radians(2.0)],
                         "roll_rad": [0.0], "flight_path_rad": [np.radians(-6.0)]})
    loads = {"main": pd.DataFrame({"quantity": ["trim_iterations", "thrust_N"], "value": [3.0, 1001.0], "unit": ["-", "N"]})}
    both = segment_summary("heli", "seg3", trim, loads, {"base": _metrics([60.0, 62.0]), "bvi": _metrics([70.0, 95.0])}, {})
    assert both["levels_variant"] == "bvi" and both["without_bvi_computed"]
    assert both["max_bvispl_db"] == 95.0 and both["max_bvispl_azimuth_deg"] == 10.0
    assert both["max_bvispl_without_bvi_db"] == 62.0
    assert both["main_thrust_error_rel"] == pytest.approx(1e-3)
    assert both["pitch_deg"] == pytest.approx(2.0)
    only_bvi = segment_summary("heli", "seg6", trim, loads, {"bvi": _metrics([70.0, 95.0])}, {"trim": 1.5})
    assert not only_bvi["without_bvi_computed"] and only_bvi["max_bvispl_without_bvi_db"] == 95.0
    assert only_bvi["wall_trim_s"] == 1.5 and only_bvi["wall_acoustics_s"] == 0.0
