"""Memory estimates (nps.app.resources): bounds of the measured peaks, refusal with the estimate in the
message (issue 14's n_psi 36000 × n_r 5000 and samples_per_rev 5e7), mem_mb for Snakemake."""

import tracemalloc

import pytest
import yaml

from nps.app import resources as res
from nps.core.atmosphere import isa
from nps.rotor.bet import DiskGrid, trim_rotor
from nps.app.config import load_aircraft
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.rotor.trim import FlightCondition, trim_aircraft

# peak RSS above the imported interpreter (MB), helicopter seg3 main rotor (docs/reference/validity.md)
MEASURED_LOADS = [((90, 20), 11.2), ((360, 50), 21.2), ((720, 100), 40.3), ((1440, 100), 103.5), ((1440, 200), 135.5),
                  ((2880, 200), 262.2)]
MEASURED_WAKE = [((360, 50, 4.0), 101.5), ((360, 50, 8.0), 150.8), ((720, 50, 4.0), 154.6), ((720, 100, 4.0), 133.3)]
MEASURED_ACOUSTICS = [((72, 256), 178.3), ((360, 1024), 167.6), ((360, 4096), 448.9), ((720, 4096), 797.8)]
# two rotors (main + tail), synthetic signals: HSI; metrics without / with HSI signals
MEASURED_HSI = [((72, 256), 107.3), ((360, 1024), 220.3), ((360, 4096), 535.3), ((720, 4096), 982.1)]
MEASURED_METRICS = [((72, 256), 40.3, 44.7), ((360, 1024), 159.6, 203.2), ((360, 4096), 460.0, 678.3),
                    ((720, 4096), 862.9, 1315.7)]


def test_estimates_bound_the_measured_peaks_within_a_factor_two():
    for (n_psi, n_r), mb in MEASURED_LOADS:
        assert mb <= res.loads_bytes(n_psi, n_r) / 1e6 <= 2.0 * mb
    for (n_psi, n_r, rev), mb in MEASURED_WAKE:
        assert mb <= res.wake_bvi_bytes(n_psi, n_r, rev) / 1e6 <= 2.0 * mb
    for (n_obs, samples), mb in MEASURED_ACOUSTICS:
        assert mb <= res.acoustics_bytes(n_obs, samples, 360, 50) / 1e6 <= 2.0 * mb
    for (n_obs, samples), mb in MEASURED_HSI:
        assert mb <= res.hsi_bytes(n_obs, samples, 2) / 1e6 <= 2.0 * mb
    for (n_obs, samples), plain, with_hsi in MEASURED_METRICS:
        assert plain <= res.metrics_bytes(n_obs, samples, 2) / 1e6 <= 2.0 * plain
        assert with_hsi <= res.metrics_bytes(n_obs, samples, 2, hsi=True) / 1e6 <= 2.0 * with_hsi


def test_loads_estimate_bounds_the_traced_arrays_of_a_live_trim(repo_root):
    # numpy allocations traced during one rotor trim at 1080 x 100: 42 MB against the 82 MB estimate
    aircraft = load_aircraft(repo_root / "config" / "aircraft" / "helicopter.yaml")
    trim = trim_aircraft(aircraft, FlightCondition(25.7, -2.69, isa(0.0)))
    geometry, op = RotorGeometry.from_config(aircraft["rotors"][0]), OperatingPoint.from_trim_row(trim.iloc[0])
    tracemalloc.start()
    try:
        trim_rotor(geometry, op, DiskGrid(1080, 100))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert res.loads_bytes(1080, 100) / 4.0 < peak <= res.loads_bytes(1080, 100)


def test_issue_14_resolutions_are_refused_with_the_estimate():
    with pytest.raises(res.ResourceError) as info:
        res.check_memory(res.loads_bytes(36000, 5000), "loads (n_psi 36000 x n_r 5000)", available=24e9)
    assert "loads (n_psi 36000 x n_r 5000): needs an estimated 117,262 MB" in str(info.value)
    assert "24,000 MB available" in str(info.value)
    with pytest.raises(res.ResourceError, match="acoustics: needs an estimated"):
        res.check_memory(res.acoustics_bytes(360, int(5e7), 360, 50, 2), "acoustics", available=24e9)
    res.check_memory(res.acoustics_bytes(360, 1024, 360, 50, 2), "acoustics", available=24e9)  # the bundled study fits


def test_mem_mb_scales_with_the_resolution(repo_root):
    config = yaml.safe_load((repo_root / "config" / "config.yaml").read_text())
    resolution = config["resolution"]
    n_obs = res.observer_count(config["observer_sets"]["hemisphere"])
    bundled = res.mem_mb(res.estimate_bytes("acoustics", resolution, n_obs, 2))
    assert n_obs == 360 and bundled == 798  # (250 + 180 + 16.2 + 2 x 95.8) MB x 1.25
    assert res.mem_mb(res.loads_bytes(720, 100)) > res.mem_mb(res.estimate_bytes("loads", resolution)) == 343
    assert res.estimate_bytes("wake", resolution) == res.wake_bvi_bytes(360, 50, 4.0)
    # a second rotor adds the held table of the first: 16 columns x 8 B per station (+ 14 x 8 B per wake row)
    one = res.loads_bytes(360, 50)
    assert res.loads_bytes(360, 50, 2) - one == 128.0 * 360 * 50 == res.loads_bytes(360, 50, 6) - one
    assert res.wake_bvi_bytes(360, 50, 4.0, 2) - res.wake_bvi_bytes(360, 50, 4.0) == 128.0 * 18000 + 112.0 * 72 * 1441
    assert res.estimate_bytes("metrics", resolution, n_obs, 2, hsi=True) == res.metrics_bytes(360, 1024, 2, True)
    assert res.estimate_bytes("hsi", resolution, n_obs, 2) == res.hsi_bytes(360, 1024, 2)
    with pytest.raises(ValueError, match="stage 'figures' has no estimate"):
        res.estimate_bytes("figures", resolution)
    assert [res.observer_count(config["observer_sets"][k]) for k in ("hsi", "ground")] == [5, 169]


def test_bad_resolution_names_the_field():
    with pytest.raises(ValueError, match="n_r: expected an integer >= 1, got 0"):
        res.loads_bytes(360, 0)
    with pytest.raises(ValueError, match="wake_revolutions: expected a number > 0"):
        res.wake_bvi_bytes(360, 50, -1.0)
    assert res.available_bytes() > 0


def test_table_column_counts_match_the_artifacts():
    """nps.app.resources writes the disk and wake column counts out (no numba import in Snakemake); they must match."""
    from nps.app import resources
    from nps.rotor.bet import DISK_COLUMNS
    from nps.wake.prescribed import WAKE_COLUMNS

    assert resources.DISK_TABLE_COLUMNS == len(DISK_COLUMNS)
    assert resources.WAKE_TABLE_COLUMNS == len(WAKE_COLUMNS)
