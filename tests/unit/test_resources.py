"""Cluster requests (nps.resources): cover the measured peaks, grow with resolution and attempt."""

from pathlib import Path

import numpy as np
import pytest
import yaml

from nps import acoustics
from nps.observers import observer_set
from nps.resources import BUNDLED, OBSERVER_BLOCK, JobSize, memory_mb, observer_count, runtime_min, threads

REPO = Path(__file__).resolve().parents[2]

# max_rss (MB) of the helicopter seg3/seg5 jobs at the bundled resolution (Snakemake benchmarks, warm cache)
MEASURED_MB = {"trim": 126, "loads": 152, "observers": 137, "wake": 344, "acoustics": 385, "hsi": 393,
               "metrics": 316, "hsi_figure": 244, "rotor_figures": 260, "bvi_hotspot": 319, "rotor_maps": 241,
               "study_maps": 178, "summary": 133}


@pytest.mark.parametrize("stage", sorted(MEASURED_MB))
def test_request_covers_measured_peak_with_headroom(stage):
    size = JobSize(360, 50, 4, 1024, n_rotors=1 if stage == "loads" else 2, n_observers=360)
    assert memory_mb(stage, size) >= 1.3 * MEASURED_MB[stage]


@pytest.mark.parametrize("stage", sorted(MEASURED_MB))
def test_requests_grow_linearly_with_attempt(stage):
    assert memory_mb(stage, BUNDLED, 3) == 3 * memory_mb(stage, BUNDLED, 1)
    assert runtime_min(stage, BUNDLED, 2) == 2 * runtime_min(stage, BUNDLED, 1)


def test_signal_stages_scale_with_observers_and_rotors():
    fine = JobSize(360, 50, 4, 1024, n_rotors=6, n_observers=19 * 72)  # hexacopter, 5-degree hemisphere
    for stage in ("acoustics", "hsi", "metrics"):
        assert memory_mb(stage, fine) > 2 * memory_mb(stage, BUNDLED)
        assert runtime_min(stage, fine) > 5 * runtime_min(stage, BUNDLED)
    # the signal memory model: ~8.4 M samples x 110 B over the 280 MB baseline, x 1.5 headroom
    assert memory_mb("acoustics", fine) == pytest.approx(1.5 * (280 + 110 * 6 * 1368 * 1024 / 1e6 + 0.7 * 6 * 18), abs=100)


def test_threads_only_where_kernels_are_parallel():
    few, many = JobSize(360, 50, 4, 1024, 2, 5), JobSize(360, 50, 4, 1024, 2, 360)
    assert threads("wake", few) == 4
    assert threads("acoustics", few) == 1 and threads("acoustics", many) == 4  # one observer block of 16
    assert threads("hsi", few) == 4 and threads("hsi", JobSize(360, 50, 4, 1024, 2, 2)) == 2
    assert all(threads(s, many) == 1 for s in ("trim", "loads", "observers", "metrics", "summary"))
    assert OBSERVER_BLOCK == acoustics.OBSERVER_BLOCK


def test_observer_count_matches_the_built_sets():
    config = yaml.safe_load((REPO / "config" / "config.yaml").read_text())
    for spec in config["observer_sets"].values():
        built = observer_set(spec, np.zeros(3), 5.0, (30.0, 0.0, 0.0))
        assert observer_count(spec) == len(built)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: memory_mb("radiation", BUNDLED), "stage"),
        (lambda: runtime_min("wake", BUNDLED, 0), "attempt"),
        (lambda: JobSize(0, 50, 4, 1024), "n_psi"),
        (lambda: JobSize(360, 50, 4, 1024, n_observers=-1), "n_observers"),
        (lambda: observer_count({"kind": "line"}), "kind"),
    ],
)
def test_bad_input_names_the_field(call, message):
    with pytest.raises(ValueError, match=message):
        call()
