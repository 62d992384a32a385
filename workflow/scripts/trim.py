"""Snakemake script: aircraft trim for one aircraft x segment -> trim.parquet."""

from contextlib import redirect_stderr

from nps.atmosphere import isa
from nps.io import write_table
from nps.trim import FlightCondition, trim_aircraft

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    p = snakemake.params
    atmosphere = isa(p.atmosphere["altitude_m"], p.atmosphere["isa_delta_K"], p.atmosphere["relative_humidity_pct"])
    flight = FlightCondition(p.speeds["forward_speed_mps"], p.speeds["climb_speed_mps"], atmosphere)
    table = trim_aircraft(p.aircraft, flight, p.speeds.get("rotor_omega_scale"))
    write_table(
        table,
        snakemake.output[0],
        stage="trim",
        metadata={"aircraft": p.aircraft["name"], "segment": snakemake.wildcards.segment, "speeds": dict(p.speeds)},
    )
    print(table.to_string(), file=log)
