# Acoustics: observer sets per aircraft x segment (nps.stages.observers), and the compact-F1A pressure
# signals of every rotor per observer set x load variant (nps.stages.acoustics). Signals share one grid
# per aircraft: one revolution of the first rotor. Hemisphere and points-ahead centre: mean hub of the
# lift rotors; radii in first-rotor radii.


rule observers:
    input:
        trim=f"{BASE}/trim.parquet",
    output:
        observers=f"{BASE}/observers/{{obsset}}.parquet",
    params:
        spec=lambda wildcards: config["observer_sets"][wildcards.obsset],
        rotor_roles=lambda wildcards: {r["name"]: r["role"] for r in aircraft_config(wildcards)["rotors"]},
        reference_radius_m=lambda wildcards: aircraft_config(wildcards)["rotors"][0]["radius_m"],
        rotors=rotor_configs,
        allow_outside_validity=ALLOW_OUTSIDE_VALIDITY,
        code=code("observers"),
    log:
        log_path("observers", "{aircraft}/{segment}/{obsset}"),
    benchmark:
        bench_path("observers", "{aircraft}/{segment}/{obsset}")
    threads: 1
    resources:
        mem_mb=job_mem_mb("observers"),
        runtime=job_runtime("observers"),
    script:
        STAGE_SCRIPT


rule acoustics:
    input:
        # every rotor's trimmed loads (variant base) or loads with the wake's induced velocity (variant bvi)
        disks=variant_disks,
        trim=f"{BASE}/trim.parquet",
        observers=f"{BASE}/observers/{{obsset}}.parquet",
    output:
        # one signal table per rotor: {rotor}.parquet
        signals=directory(signals_dir("acoustics")),
    params:
        rotors=job_rotors,
        thickness=setting("models", "thickness"),
        chord_fractions=setting("acoustics", "dual_compact_chord_fractions"),
        samples_per_rev=setting("resolution", "samples_per_rev"),
        hinge_offsets_m=lambda wildcards: {r["name"]: r["hinge_offset_m"] for r in aircraft_config(wildcards)["rotors"]},
        code=code("acoustics"),
    log:
        log_path("acoustics", "{aircraft}/{segment}/{obsset}_{variant}"),
    benchmark:
        bench_path("acoustics", "{aircraft}/{segment}/{obsset}_{variant}")
    threads: job_threads("acoustics")
    resources:
        mem_mb=job_mem_mb("acoustics"),
        runtime=job_runtime("acoustics"),
    script:
        STAGE_SCRIPT


ALL_TARGETS.extend(
    f"{RESULTS}/{a}/{s}/acoustics/{o}_{v}"
    for a, s in campaign_pairs()
    for o in CAMPAIGN.observer_sets(s)
    for v in CAMPAIGN.variants(s)
)
