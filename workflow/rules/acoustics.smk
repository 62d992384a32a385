# Acoustics (issue 5): observer sets per aircraft x segment, compact-F1A pressure signals of every
# rotor per observer set x load variant (nps.acoustics via nps.cli.observers / nps.cli.rotor_acoustics).
# Pressure time-history figures: rule bvi_hotspot (study.smk). Signals share one grid per aircraft:
# one revolution of the first rotor.
# Hemisphere and points-ahead centre: mean hub of the lift rotors (main-rotor hub of the helicopter,
# midpoint of tandem / coaxial hubs, hub-circle centre of the multirotor); radii in first-rotor radii.


rule observers:
    input:
        trim=f"{RESULTS}/{{aircraft}}/{{segment}}/trim.parquet",
    output:
        f"{RESULTS}/{{aircraft}}/{{segment}}/observers/{{obsset}}.parquet",
    params:
        spec=lambda wildcards: config["observer_sets"][wildcards.obsset],
        rotor_roles=lambda wildcards: {r["name"]: r.get("role", "lift") for r in aircraft_config(wildcards)["rotors"]},
        reference_radius_m=lambda wildcards: aircraft_config(wildcards)["rotors"][0]["radius_m"],
        code=nps_hash("observers", "acoustics", "cli/observers"),
    log:
        log_path("observers", "{aircraft}/{segment}/{obsset}"),
    benchmark:
        bench_path("observers", "{aircraft}/{segment}/{obsset}")
    threads: 1
    group: "prepare"
    resources:
        mem_mb=job_mem_mb("observers"),
        runtime=job_runtime("observers"),
    script:
        "../scripts/observers.py"


rule acoustics:
    input:
        # every rotor's trimmed loads (variant base) or loads with the wake's induced velocity (variant bvi)
        unpack(acoustics_disk_inputs),
        trim=f"{RESULTS}/{{aircraft}}/{{segment}}/trim.parquet",
        observers=f"{RESULTS}/{{aircraft}}/{{segment}}/observers/{{obsset}}.parquet",
    output:
        # one signal table per rotor: {rotor}.parquet (one job per aircraft: ~3 s of start-up saved per rotor)
        directory(signals_dir("acoustics")),
    params:
        rotors=lambda wildcards: rotor_names(wildcards.aircraft),
        thickness=config["models"]["thickness"],
        chord_fractions=config["acoustics"]["dual_compact_chord_fractions"],
        samples_per_rev=config["resolution"]["samples_per_rev"],
        hinge_offsets_m=lambda wildcards: {r["name"]: r.get("hinge_offset_m", 0.0) for r in aircraft_config(wildcards)["rotors"]},
        code=nps_hash("acoustics", "sources", "cli/rotor_acoustics"),
    log:
        log_path("acoustics", "{aircraft}/{segment}/{obsset}_{variant}"),
    benchmark:
        bench_path("acoustics", "{aircraft}/{segment}/{obsset}_{variant}")
    threads: job_threads("acoustics")
    group: "radiate"
    resources:
        mem_mb=job_mem_mb("acoustics"),
        runtime=job_runtime("acoustics"),
    script:
        "../scripts/acoustics.py"
