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
        job=plan("observers"),
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
        job=plan("acoustics"),
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
