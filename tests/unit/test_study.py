"""Study summaries: hotspot location and stage wall times from benchmark files."""

import numpy as np
import pandas as pd

from nps.study import hotspot, stage_wall_times


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
