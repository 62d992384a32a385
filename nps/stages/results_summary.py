"""Stage ``results_summary``: the page the report opens on, every aircraft × segment of the campaign in one table.

Per aircraft × segment: the segment's id and mission name, the hemisphere maxima of OASPL, OASPL(A) and
BVISPL with where they are (named in the map convention: az 0° behind, 90° on the main rotor's advancing
side, 180° ahead; the straight-down point once, whatever the azimuth), the rotor power at trim (the
blade-element loads' ``power_W``, as the design studies' trade tables), the
loudest distinct directions, the validity warnings and the figures drawn of it. The levels are the
aircraft's summary table's (``results/{aircraft}/summary.parquet``); the page adds nothing computed
anew but the power sum and the distinct loudest directions. Where the campaign certifies, the EPNL
table of each aircraft follows as a table (not a picture).

Stage contract: :mod:`nps.stages`.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from nps.app.io import read_table, rotor_path

LEVELS = (("oaspl", "OASPL (dB)"), ("dba", "OASPL(A) (dBA)"), ("bvispl", "BVISPL (dB)"))
FIGURE_SUFFIXES = (".png", ".csv")


def segment_row(summary: pd.Series, segment_name: str, powers_W: dict, metrics: pd.DataFrame, loudest: int,
                warnings: str) -> dict:
    """One row of the results summary from the aircraft's summary row of a segment, its rotors' power (rotor →
    W: the blade-element loads at trim, as the design studies' trade tables) and its hemisphere metrics (the
    summary's ``levels_variant``)."""
    from nps.plots.maps import direction_name, distinct_directions

    row = {"aircraft": summary["aircraft"], "segment": summary["segment"], "segment_name": segment_name,
           "levels_variant": summary["levels_variant"]}
    for label, _ in LEVELS:
        az, el = float(summary[f"max_{label}_azimuth_deg"]), float(summary[f"max_{label}_elevation_deg"])
        row.update({f"max_{label}_db": float(summary[f"max_{label}_db"]), f"max_{label}_azimuth_deg": az,
                    f"max_{label}_elevation_deg": el, f"max_{label}_where": direction_name(az, el)})
    row["rotor_power_kW"] = float(sum(powers_W.values())) / 1e3
    row["rotor_powers"] = "; ".join(f"{r} {p / 1e3:.1f} kW" for r, p in powers_W.items())
    top = distinct_directions(metrics, "oaspl_db").head(loudest)
    row["loudest_directions"] = "; ".join(f"{direction_name(a, e)}: {v:.1f} dB"
                                          for a, e, v in zip(top["azimuth_deg"], top["elevation_deg"], top["oaspl_db"]))
    row["validity_warnings"] = warnings
    return row


def loads_power_W(loads_dir: str, rotor: str) -> float:
    """A rotor's power (W) in its loads summary (``loads/{rotor}_summary.parquet``: quantity, value, unit)."""
    table = read_table(rotor_path(loads_dir, rotor, "_summary"))
    return float(table.loc[table["quantity"] == "power_W", "value"].iloc[0])


def figures_of(results: Path, aircraft: str, segment: str | None) -> list[str]:
    """The figures and tables drawn of one aircraft × segment (``segment`` None: of the aircraft as a whole),
    as paths relative to the results directory."""
    root = results / aircraft / segment if segment else results / aircraft
    if not root.is_dir():
        return []
    segments = set() if segment else {p.name for p in root.iterdir() if p.is_dir()} - {"figures", "footprint", "certification"}
    found = [p for p in root.rglob("*") if p.suffix in FIGURE_SUFFIXES and p.is_file()
             and p.relative_to(root).parts[0] not in segments]
    return sorted(str(p.relative_to(results)) for p in found)


def summary_table(inputs: dict, params: dict) -> pd.DataFrame:
    """Every aircraft × segment row (:func:`segment_row`), in campaign order, with its figures."""
    results = Path(params["results"])
    rows = []
    for aircraft in params["campaign_aircraft"]:
        summary = read_table(inputs[f"summary_{aircraft}"])
        warnings = pd.read_csv(inputs[f"summary_csv_{aircraft}"], keep_default_na=False)
        for segment in params["segments"]:
            line = summary[summary["segment"] == segment].iloc[0]
            noted = warnings.loc[warnings["segment"] == segment, "validity_warnings"]
            trim = read_table(inputs[f"trim_{aircraft}_{segment}"])
            powers = {rotor: loads_power_W(inputs[f"loads_{aircraft}_{segment}"], rotor) for rotor in trim["rotor"]}
            row = segment_row(line, params["segment_names"][segment], powers,
                              read_table(inputs[f"metrics_{aircraft}_{segment}"]), int(params["loudest"]),
                              str(noted.iloc[0]) if len(noted) else "")
            row["figures"] = "; ".join(figures_of(results, aircraft, segment))
            rows.append(row)
    return pd.DataFrame(rows)


def run(inputs: dict, outputs: dict, params: dict) -> str:
    """The results summary of the campaign.

    inputs: ``summary_<aircraft>`` (summary.parquet), ``summary_csv_<aircraft>`` (summary.csv: the validity
    warnings), ``trim_<aircraft>_<segment>``, ``metrics_<aircraft>_<segment>`` (hemisphere metrics of the
    summary's levels variant), optional ``certification_<aircraft>`` (certification.parquet); any further
    inputs (the campaign's other targets) only order the job after every figure.
    outputs: ``html`` (the page), ``csv`` (one row per aircraft × segment).
    params: ``campaign_aircraft``, ``segments``, ``segment_names`` (id → mission name), ``radius_R``,
    ``radius_m`` (aircraft → the hemisphere's radius in metres), ``loudest`` (how many distinct loudest
    directions to list), ``results`` (the results directory).
    """
    from nps.plots.pages import write_page

    table = summary_table(inputs, params)
    Path(outputs["csv"]).parent.mkdir(parents=True, exist_ok=True)
    table.to_csv(outputs["csv"], index=False, float_format="%.6g")
    write_page("NPS results summary", page_sections(table, inputs, params), outputs["html"], intro=page_intro(params))
    return table[["aircraft", "segment", "max_oaspl_db", "max_dba_db", "max_bvispl_db", "rotor_power_kW"]].to_string()


def page_intro(params: dict) -> str:
    from nps.plots.maps import AZIMUTH_NOTE

    radii = ", ".join(f"{a} {float(r):.1f} m" for a, r in params["radius_m"].items())
    return (f"Maxima over the hemisphere of radius {float(params['radius_R']):g} R ({radii}) that moves with the "
            f"aircraft, from the loads with BVI where the wake was computed. Directions: {AZIMUTH_NOTE}; elevation "
            "negative below the hub plane; the straight-down point is one direction. Figures: the report's "
            "category of the aircraft, subcategory of the segment; paths relative to the results directory.")


def page_sections(table: pd.DataFrame, inputs: dict, params: dict) -> list[tuple[str, str]]:
    """(heading, HTML) of the page: one table per aircraft, then its certification table where computed."""
    from nps.plots.pages import html_table

    columns = {"aircraft": "aircraft", "segment": "segment", "segment_name": "name"}
    for label, header in LEVELS:
        columns.update({f"max_{label}_db": f"max {header}", f"max_{label}_where": "where"})
    columns["rotor_power_kW"] = "rotor power (kW)"
    sections = [("Maxima per aircraft and segment", html_table(table, columns))]
    details = {"segment": "segment", "segment_name": "name", "levels_variant": "loads", "rotor_powers": "rotor power",
               "loudest_directions": "loudest directions (OASPL)", "validity_warnings": "validity warnings",
               "figures": "figures and tables"}
    results = Path(params["results"])
    for aircraft in params["campaign_aircraft"]:
        rows = table[table["aircraft"] == aircraft].assign(figures=lambda t: t["figures"].str.replace("; ", "\n"))
        sections.append((f"{aircraft}: per segment", html_table(rows, details)))
        overall = figures_of(results, aircraft, None)
        if overall:
            sections.append((f"{aircraft}: figures and tables over all segments",
                             html_table(pd.DataFrame({"figure": overall}), {"figure": "file"})))
        if f"certification_{aircraft}" in inputs:
            sections.append(certification_section(aircraft, read_table(inputs[f"certification_{aircraft}"])))
    return sections


def certification_section(aircraft: str, certification: pd.DataFrame) -> tuple[str, str]:
    """The EPNL table of one aircraft: per procedure its segment, the microphones' EPNL, their mean, the
    Chapter 8 limit and the margin (green: compliant, red: exceeded)."""
    from nps.plots.pages import html_table

    columns = {"procedure": "procedure", "segment": "segment", "epnl_centre_db": "centre (EPNdB)",
               "epnl_port_db": "port", "epnl_starboard_db": "starboard", "epnl_db": "EPNL (mean)",
               "limit_db": "limit", "margin_db": "margin"}
    columns = {c: h for c, h in columns.items() if c in certification.columns}
    margins = ["good" if m >= 0.0 else "bad" for m in certification["margin_db"]]
    return f"{aircraft}: certification (ICAO Annex 16 Vol. I Chapter 8)", html_table(certification, columns,
                                                                                    {"margin_db": margins})
