"""Cluster requests of the workflow jobs (nps.app.resources.job_*): cover the measured peaks, grow with
resolution and attempt, threads only where the numba kernels are parallel."""

import pytest

from nps.noise import acoustics
from nps.app import resources as res

BUNDLED = {"n_psi": 360, "n_r": 50, "wake_revolutions": 4, "samples_per_rev": 1024}
# max_rss (MB) of the helicopter seg3/seg5 jobs at the bundled resolution (Snakemake benchmarks,
# 360 hemisphere observers, two rotors, warm numba cache; per-rotor loads jobs then)
MEASURED_MB = {"trim": 126, "loads": 152, "observers": 137, "wake": 344, "acoustics": 385, "hsi": 393,
               "metrics": 316, "hsi_figure": 244, "rotor_figures": 260, "bvi_hotspot": 319, "rotor_maps": 241,
               "study_maps": 178, "summary": 133}


@pytest.mark.parametrize("stage", sorted(MEASURED_MB))
def test_request_covers_the_measured_peak(stage):
    assert res.job_mem_mb(stage, BUNDLED, 360, 2, stage in ("metrics", "hsi_figure")) >= 1.2 * MEASURED_MB[stage]


@pytest.mark.parametrize("stage", sorted(res.RUNTIME_MIN))
def test_requests_grow_linearly_with_attempt(stage):
    assert res.job_mem_mb(stage, BUNDLED, 360, 2, attempt=3) == 3 * res.job_mem_mb(stage, BUNDLED, 360, 2)
    assert res.job_runtime_min(stage, BUNDLED, 360, 2, attempt=2) == 2 * res.job_runtime_min(stage, BUNDLED, 360, 2)


def test_signal_stages_scale_with_observers_and_rotors():
    # hexacopter with the 5-degree hemisphere (19 x 72 observers): 8.4 M samples against 0.74 M
    for stage in ("hsi", "metrics", "bvi_hotspot"):  # every rotor's signals at once
        assert res.job_mem_mb(stage, BUNDLED, 1368, 6) > 2 * res.job_mem_mb(stage, BUNDLED, 360, 2)
    assert res.job_mem_mb("acoustics", BUNDLED, 1368, 6) > 1.5 * res.job_mem_mb("acoustics", BUNDLED, 360, 2)  # rotors in turn
    for stage in ("acoustics", "hsi", "metrics", "bvi_hotspot"):
        assert res.job_runtime_min(stage, BUNDLED, 1368, 6) > 10 * res.job_runtime_min(stage, BUNDLED, 360, 2)
    finer = dict(BUNDLED, n_psi=720)
    assert res.job_runtime_min("wake", finer, 1, 2) == 4 * res.job_runtime_min("wake", BUNDLED, 1, 2)  # n_psi²
    assert res.job_runtime_min("trim", finer, 1, 2) == res.job_runtime_min("trim", BUNDLED, 1, 2)


def test_threads_only_where_kernels_are_parallel():
    assert res.job_threads("wake", 1) == res.MAX_THREADS == 4
    assert res.job_threads("acoustics", 5) == 1 and res.job_threads("acoustics", 40) == 3  # blocks of 16
    assert res.job_threads("acoustics", 360) == 4
    assert res.job_threads("hsi", 2) == 2 and res.job_threads("hsi", 5) == 4
    assert all(res.job_threads(s, 360) == 1 for s in ("trim", "loads", "observers", "metrics", "summary"))
    assert res.OBSERVER_BLOCK == acoustics.OBSERVER_BLOCK


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: res.job_mem_mb("radiation", BUNDLED), "stage"),
        (lambda: res.job_runtime_min("figures", BUNDLED), "stage"),
        (lambda: res.job_threads("plots"), "stage"),
        (lambda: res.job_runtime_min("wake", BUNDLED, attempt=0), "attempt"),
        (lambda: res.job_mem_mb("acoustics", dict(BUNDLED, n_psi=0), 360, 2), "n_psi"),
    ],
)
def test_bad_input_names_the_field(call, message):
    with pytest.raises(ValueError, match=message):
        call()
