# Acoustics (issue 5): observer sets per aircraft x segment, compact-F1A pressure signals per rotor x
# observer set x load variant (nps.acoustics via nps.cli.observers / nps.cli.rotor_acoustics), and
# pressure time-history figures. Signals share one grid per aircraft: one revolution of the first rotor.
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
    resources:
        mem_mb=500,
        runtime=5,
    script:
        "../scripts/observers.py"


rule acoustics:
    input:
        # trimmed loads (variant base) or loads with the wake's induced velocity (variant bvi)
        disk=lambda wc: f"{RESULTS}/{wc.aircraft}/{wc.segment}/{'loads' if wc.variant == 'base' else 'bvi'}/{wc.rotor}.parquet",
        trim=f"{RESULTS}/{{aircraft}}/{{segment}}/trim.parquet",
        observers=f"{RESULTS}/{{aircraft}}/{{segment}}/observers/{{obsset}}.parquet",
    output:
        f"{RESULTS}/{{aircraft}}/{{segment}}/acoustics/{{obsset}}/{{rotor}}_{{variant}}.parquet",
    params:
        thickness=config["models"]["thickness"],
        chord_fractions=config["acoustics"]["dual_compact_chord_fractions"],
        samples_per_rev=config["resolution"]["samples_per_rev"],
        reference_rotor=lambda wildcards: rotor_names(wildcards.aircraft)[0],
        hinge_offset_m=lambda wildcards: rotor_config(wildcards).get("hinge_offset_m", 0.0),
        code=nps_hash("acoustics", "sources", "cli/rotor_acoustics"),
    log:
        log_path("acoustics", "{aircraft}/{segment}/{obsset}/{rotor}_{variant}"),
    benchmark:
        bench_path("acoustics", "{aircraft}/{segment}/{obsset}/{rotor}_{variant}")
    threads: 1
    resources:
        mem_mb=2000,
        runtime=10,
    script:
        "../scripts/acoustics.py"


rule acoustics_figure:
    input:
        # signals of every rotor of the aircraft
        unpack(
            lambda wc: {
                f"signal_{r}": f"{RESULTS}/{wc.aircraft}/{wc.segment}/acoustics/{wc.obsset}/{r}_{wc.variant}.parquet"
                for r in rotor_names(wc.aircraft)
            }
        ),
        observers=f"{RESULTS}/{{aircraft}}/{{segment}}/observers/{{obsset}}.parquet",
    output:
        report(
            f"{RESULTS}/{{aircraft}}/{{segment}}/figures/pressure_{{obsset}}_{{variant}}.png",
            caption="../report/acoustics_histories.rst",
            category="{aircraft}",
            subcategory="{segment}",
            labels={"aircraft": "{aircraft}", "segment": "{segment}", "figure": "pressure, {obsset} ({variant})"},
        ),
    params:
        rotors=lambda wildcards: rotor_names(wildcards.aircraft),
        code=nps_hash("plots/acoustics"),
    log:
        log_path("acoustics_figure", "{aircraft}/{segment}/{obsset}_{variant}"),
    benchmark:
        bench_path("acoustics_figure", "{aircraft}/{segment}/{obsset}_{variant}")
    threads: 1
    resources:
        mem_mb=1500,
        runtime=5,
    script:
        "../scripts/acoustics_figure.py"


ALL_TARGETS.extend(
    f"{RESULTS}/{a}/{s}/figures/pressure_{o}_{variants(s)[-1]}.png"
    for a in CAMPAIGN.aircraft
    for s in figure_segments("map")
    for o in observer_sets(s)
    if config["observer_sets"][o]["kind"] in ("hemisphere", "sphere")
)
