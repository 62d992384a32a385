"""The report for designers: the straight-down point named once, the results summary equal to the summary
tables, the front page naming the summary, figure conventions (orientation note, labelled contours, wake
layout, spectrum contrast)."""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from nps.app.study import hotspot
from nps.noise.observers import hemisphere
from nps.plots.acoustics import pick_observers
from nps.plots.maps import AZIMUTH_NOTE, direction_name, distinct_directions, hemisphere_map

REPO = Path(__file__).resolve().parents[2]


def pole_loudest_levels(observers: pd.DataFrame) -> pd.DataFrame:
    """OASPL falling with elevation above the pole: every straight-down observer is equally the loudest."""
    table = observers[["observer", "azimuth_deg", "elevation_deg"]].copy()
    table["oaspl_db"] = 100.0 + 0.1 * np.abs(table["elevation_deg"]) - 0.001 * table["azimuth_deg"] * (table["elevation_deg"] > -90)
    return table


def test_direction_names_follow_the_map_convention():
    assert direction_name(135.0, -30.0) == "az 135° (ahead, advancing side), el −30°"
    assert direction_name(270.0, 0.0) == "az 270° (retreating side), el 0°"
    assert direction_name(0.0, -45.0) == "az 0° (behind), el −45°"
    assert direction_name(180.0, -90.0) == direction_name(45.0, -90.0) == "straight below"


def test_the_loudest_observer_list_holds_the_pole_once():
    observers = hemisphere([0.0, 0.0, 0.0], 10.0, 4, 8)
    levels = pole_loudest_levels(observers)
    assert (levels.nlargest(3, "oaspl_db")["elevation_deg"] == -90.0).all()  # the raw list: the pole 3 times
    top = distinct_directions(levels, "oaspl_db").head(3)
    assert list(top["elevation_deg"]).count(-90.0) == 1
    assert top["observer"].iloc[0] == 24  # the first pole observer (lowest id of the ties)
    assert len(distinct_directions(levels)) == len(levels) - 7


def test_pressure_history_observers_are_distinct_directions():
    """The loudest observer at the pole: the "straight below" panel is not drawn a second time."""
    observers = hemisphere([0.0, 0.0, 0.0], 10.0, 4, 8)
    total = np.zeros((len(observers), 8))
    total[30, ::2] = 1.0  # observer 30: az 270°, el −90°
    picks = pick_observers(observers, observers["observer"].to_numpy(), total)
    assert list(picks.values())[0] == 30 and "straight below" in list(picks)[0]
    poles = [o for o in picks.values() if observers.loc[observers["observer"] == o, "elevation_deg"].iloc[0] == -90.0]
    assert poles == [30], picks


def write_campaign(root: Path) -> tuple[dict, dict, pd.DataFrame]:
    """Summary, trim and metrics tables of one aircraft in two segments, as the summary stage writes them."""
    observers = hemisphere([0.0, 0.0, 0.0], 10.0, 4, 8)
    inputs, rows = {}, []
    for k, segment in enumerate(("seg2", "seg3")):
        metrics = pole_loudest_levels(observers).assign(oaspl_dba=lambda t: t["oaspl_db"] - 5.0,
                                                        bvispl_db=lambda t: t["oaspl_db"] - 10.0 - t["azimuth_deg"] / 100)
        metrics["oaspl_db"] += k
        path = root / "heli" / segment
        path.mkdir(parents=True)
        metrics.to_parquet(path / "metrics.parquet")
        pd.DataFrame({"rotor": ["main", "tail"], "power_W": [3.9e5, 1.9e4]}).to_parquet(path / "trim.parquet")
        (path / "loads").mkdir()
        for rotor, power in (("main", 4.0e5 + k), ("tail", 2.0e4)):  # the blade-element power at trim is the one shown
            pd.DataFrame({"quantity": ["thrust_N", "power_W"], "value": [1.0, power], "unit": ["N", "W"]}).to_parquet(
                path / "loads" / f"{rotor}_summary.parquet")
        (path / "figures").mkdir()
        (path / "figures" / "hotspot_bvi.png").write_bytes(b"png")
        row = {"aircraft": "heli", "segment": segment, "levels_variant": "bvi"}
        for column, label in (("oaspl_db", "oaspl"), ("oaspl_dba", "dba"), ("bvispl_db", "bvispl")):
            spot = hotspot(metrics, column)
            row.update({f"max_{label}_db": spot["value"], f"max_{label}_azimuth_deg": spot["azimuth_deg"],
                        f"max_{label}_elevation_deg": spot["elevation_deg"]})
        rows.append(row)
        inputs.update({f"trim_heli_{segment}": path / "trim.parquet", f"metrics_heli_{segment}": path / "metrics.parquet",
                       f"loads_heli_{segment}": path / "loads"})
    summary = pd.DataFrame(rows)
    summary.to_parquet(root / "heli" / "summary.parquet")
    pd.DataFrame({"segment": ["seg2", "seg3"], "validity_warnings": ["", "wake too short"]}).to_csv(root / "heli" / "summary.csv")
    inputs.update({"summary_heli": root / "heli" / "summary.parquet", "summary_csv_heli": root / "heli" / "summary.csv"})
    certification = pd.DataFrame({"procedure": ["takeoff", "approach"], "segment": ["seg2", "seg3"], "epnl_db": [90.0, 95.0],
                                  "limit_db": [92.0, 94.0], "margin_db": [2.0, -1.0]})
    certification.to_parquet(root / "heli" / "certification.parquet")
    inputs["certification_heli"] = root / "heli" / "certification.parquet"
    params = {"campaign_aircraft": ["heli"], "segments": ["seg2", "seg3"],
              "segment_names": {"seg2": "level flight", "seg3": "6 deg descent (BVI)"}, "radius_R": 10.0,
              "radius_m": {"heli": 76.2}, "loudest": 3, "results": str(root)}
    return inputs, params, summary


def test_results_summary_equals_the_summary_tables(tmp_path):
    from nps.stages.results_summary import run

    inputs, params, summary = write_campaign(tmp_path / "results")
    outputs = {"html": tmp_path / "out" / "results_summary.html", "csv": tmp_path / "out" / "results_summary.csv"}
    run(inputs, outputs, params)
    table = pd.read_csv(outputs["csv"], keep_default_na=False)
    assert list(table["segment_name"]) == ["level flight", "6 deg descent (BVI)"]
    for column in [c for c in summary.columns if c.startswith("max_")]:
        assert np.allclose(table[column], summary[column], rtol=1e-6, atol=0.0), column
    assert list(table["max_oaspl_where"]) == ["straight below", "straight below"]
    assert np.allclose(table["rotor_power_kW"], [420.0, 420.001])
    assert all(t.count("straight below") == 1 and t.count("; ") == 2 for t in table["loudest_directions"])
    assert list(table["validity_warnings"]) == ["", "wake too short"]
    assert table["figures"].iloc[1] == "heli/seg3/figures/hotspot_bvi.png"
    page = outputs["html"].read_text()
    assert "6 deg descent (BVI)" in page and "76.2 m" in page and AZIMUTH_NOTE in page
    assert page.startswith('<div class="nps-page">') and "<html" not in page  # a fragment the front page inserts
    assert 'class="bad">-1.0' in page and 'class="good">2.0' in page  # the certification table, as a table


def test_the_report_front_page_names_the_summary():
    front = (REPO / "workflow/report/workflow.rst").read_text()
    rules = (REPO / "workflow/rules/study.smk").read_text() + (REPO / "workflow/rules/common.smk").read_text()
    assert "results_summary.html" in front and ":file:" in front  # inserted into the front page
    assert '"1. Results summary"' in front and 'SUMMARY_CATEGORY = "1. Results summary"' in rules
    assert "showResultInfo" in front  # the figure index links every result
    assert (REPO / "workflow/report/results_summary.rst").is_file()
    assert sorted(["1. Results summary", "Design studies", "coaxial", "helicopter"],
                  key=str.casefold)[0] == "1. Results summary"


def test_every_map_says_its_orientation_and_labels_its_contours():
    observers = hemisphere([0.0, 0.0, 0.0], 10.0, 7, 24)
    levels = 90.0 + 10.0 * np.cos(np.radians(observers["azimuth_deg"])) * np.cos(np.radians(observers["elevation_deg"]))
    fig, ax = plt.subplots()
    hemisphere_map(ax, observers["azimuth_deg"], observers["elevation_deg"], levels, marker=(45.0, -90.0))
    assert AZIMUTH_NOTE in ax.get_xlabel()
    assert {"behind", "advancing", "ahead", "retreating"} <= {w for t in ax.get_xticklabels() for w in t.get_text().split()}
    assert ax.texts, "contour lines without labels"
    assert "straight below" in ax.get_legend().get_texts()[0].get_text()
    plt.close(fig)


def test_wake_views_share_one_scale_without_a_sliver():
    from nps.plots.wake import wake_views

    age = np.linspace(0.0, 4.0 * np.pi, 200)
    nodes = np.stack([np.stack([np.cos(age + k * np.pi) + 0.2 * age, np.sin(age + k * np.pi), -0.02 * age], axis=1)
                      for k in range(2)]) * 7.0
    blades = np.stack([[[0.0, 0.0, 0.0], nodes[k, 0]] for k in range(2)])
    fig = wake_views(nodes, blades, 7.0, ages_rev=np.tile(age / (2 * np.pi), (2, 1)))
    top, side = fig.axes[:2]
    assert top.get_xlim() == side.get_xlim()
    assert side.get_position().height > 0.1 * top.get_position().height
    assert "revolutions" in fig.axes[-1].get_xlabel()
    plt.close(fig)


def test_spectrum_sources_are_told_apart():
    from matplotlib.colors import to_rgb

    from nps.plots.spectra import SOURCE_STYLES

    colours = [np.array(to_rgb(c)) for c, _, _ in SOURCE_STYLES.values()]
    gaps = [np.abs(a - b).sum() for i, a in enumerate(colours) for b in colours[i + 1:]]
    assert min(gaps) > 0.4  # Okabe–Ito: the closest pair (blue, bluish green) differs in line style too
    assert all(c.sum() < 2.4 for c in colours)  # none washes out on white
    assert len({s for _, s, _ in SOURCE_STYLES.values() if s != "-"}) >= 2


def test_titles_name_the_segment_and_the_radius():
    from nps.plots import hemisphere_title, segment_title

    assert segment_title("seg3", "6 deg descent (BVI)") == "seg3, 6 deg descent (BVI)"
    assert segment_title("seg3") == "seg3"
    assert hemisphere_title(10.0, 76.2) == "hemisphere of radius 10 R = 76.2 m"


def test_the_spectrum_names_its_loudest_observer_once_by_direction(tmp_path):
    from types import SimpleNamespace

    from nps.plots.spectra import loudest_observer_figure

    observers = hemisphere([0.0, 0.0, 0.0], 10.0, 4, 8)
    metrics = pole_loudest_levels(observers)
    frequency = np.arange(65) * 10.0
    levels = SimpleNamespace(frequency_hz=frequency, tonal_msp=np.full((len(metrics), frequency.size), 1e-2))
    centres = 10.0 ** (np.arange(10, 44) / 10.0)
    bands = pd.DataFrame([{"observer": o, "source": s, "band": b, "center_hz": c, "level_db": 60.0 - b / 10}
                          for o in metrics["observer"] for s in ("thickness", "loading", "total")
                          for b, c in enumerate(centres)])
    trim = pd.DataFrame({"n_blades": [4], "omega_rad_s": [2 * np.pi * 5.0]})
    fig = loudest_observer_figure(metrics, bands, levels, trim, (7, 40), "heli seg3", tmp_path / "s.png")
    title = fig.axes[0].get_title()
    assert title == "heli seg3: observer 24 (loudest, straight below)", title
    assert (tmp_path / "s.png").stat().st_size > 10_000
    plt.close(fig)


def test_the_front_page_of_a_large_campaign_parses_without_a_system_message(tmp_path):
    """The front page as Snakemake renders it (Jinja with trim_blocks and lstrip_blocks, then docutils'
    publish_parts): a campaign of 4 aircraft × 6 segments × 20 figures gives no line over docutils' line-length
    limit (10,000 characters: one longer line replaces the page by "System Message: ERROR/3") and every figure
    is linked from the index."""
    from dataclasses import dataclass
    from types import SimpleNamespace

    from docutils.core import publish_parts
    from jinja2 import Environment

    @dataclass(frozen=True, order=True)
    class Category:
        name: str

    categories = {}
    for aircraft in ("coaxial", "helicopter", "hexacopter", "tandem"):
        categories[Category(aircraft)] = {
            Category(f"seg{k}, 6 deg descent (BVI)"): [
                SimpleNamespace(path=Path(f"results/{aircraft}/seg{k}/figures/figure_{n:02d}.png"), name=f"figure_{n:02d}.png",
                                labels={"figure": f"{aircraft} seg{k} figure {n}"}) for n in range(20)]
            for k in range(1, 7)}
    summary = SimpleNamespace(path=tmp_path / "results_summary.html")  # inserted as a file: its lines are not limited
    summary.path.write_text('<div class="nps-page">' + "<tr><td>helicopter</td><td>seg3</td></tr>" * 2000 + "</div>\n")
    config = SimpleNamespace(config={"observer_sets": {"hemisphere": {"radius_R": 3.0}}})
    text = Environment(trim_blocks=True, lstrip_blocks=True).from_string(
        (REPO / "workflow/report/workflow.rst").read_text()).render(snakemake=config, categories=categories, files=[summary])
    assert max(len(line) for line in text.splitlines()) < 1000
    html = publish_parts(text, writer="html", settings_overrides={"report_level": 1})["html_body"]
    assert "System Message" not in html and "ERROR" not in html
    assert html.count("app.showResultInfo(") == 4 * 6 * 20 and html.count("<td>seg3</td>") == 2000
    assert "tandem seg6 figure 19</a>\n" in html and "coaxial seg1 figure 0</a> ·" in html
    # a page taller than the screen starts at its top (Snakemake centres it in a flex box: checked in Chromium,
    # docs/reference/report.md "Checked in a browser")
    assert "> .grow.flex.gap-3.p-3.items-start { margin-top: auto; margin-bottom: auto; }" in html


def test_a_report_of_design_studies_alone_does_not_point_to_a_results_summary():
    """``snakemake --report … study_NAME`` has no results summary: its front page says where the studies are
    instead of "Start with the results summary below"."""
    from types import SimpleNamespace

    from jinja2 import Environment

    config = SimpleNamespace(config={"observer_sets": {"hemisphere": {"radius_R": 3.0}}})
    text = Environment(trim_blocks=True, lstrip_blocks=True).from_string(
        (REPO / "workflow/report/workflow.rst").read_text()).render(snakemake=config, categories={}, files=[])
    assert "Start with the results summary below" not in text
    assert 'category "Design studies", one subcategory' in text
