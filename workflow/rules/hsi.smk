# High-speed-impulsive noise: each rotor's signals amplified, sheared and shock-fitted per observer with
# the rotor's own M_r and radiation distance (nps.stages.hsi), all rotors of the aircraft in one job per
# observer set x variant; metrics sum the rotors. Scheduled in the HSI segments (models.hsi, hsi_segments).


rule hsi:
    input:
        signals=signals_dir("acoustics"),
        observers=f"{BASE}/observers/{{obsset}}.parquet",
        trim=f"{BASE}/trim.parquet",
    output:
        # {rotor}.parquet (HSI signals) and {rotor}_diagnostics.parquet per rotor
        hsi=directory(signals_dir("hsi")),
    params:
        job=plan("hsi"),
        code=code("hsi"),
    log:
        log_path("hsi", "{aircraft}/{segment}/{obsset}_{variant}"),
    benchmark:
        bench_path("hsi", "{aircraft}/{segment}/{obsset}_{variant}")
    threads: job_threads("hsi")
    resources:
        mem_mb=job_mem_mb("hsi"),
        runtime=job_runtime("hsi"),
    script:
        STAGE_SCRIPT


rule hsi_figure:
    input:
        signals=signals_dir("acoustics"),
        hsi=signals_dir("hsi"),
        observers=f"{BASE}/observers/{{obsset}}.parquet",
    output:
        figure=report(
            f"{BASE}/figures/hsi_{{obsset}}_{{variant}}.png",
            caption="../report/hsi_observers.rst",
            category="{aircraft}",
            subcategory="{segment}",
            labels={"aircraft": "{aircraft}", "segment": "{segment}", "figure": "HSI histories, {obsset} observers ({variant})"},
        ),
    params:
        rotors=lambda wildcards: rotor_names(wildcards.aircraft),
        description=lambda wildcards: f"observers {config['observer_sets'][wildcards.obsset]['radius_R']:g} R ahead",
        segment_name=lambda wildcards: CAMPAIGN.segment(wildcards.segment)["name"],
        code=code("hsi_figure"),
    log:
        log_path("hsi_figure", "{aircraft}/{segment}/{obsset}_{variant}"),
    benchmark:
        bench_path("hsi_figure", "{aircraft}/{segment}/{obsset}_{variant}")
    threads: 1
    resources:
        mem_mb=job_mem_mb("hsi_figure"),
        runtime=job_runtime("hsi_figure"),
    script:
        STAGE_SCRIPT


ALL_TARGETS.extend(
    f"{RESULTS}/{a}/{s}/hsi/{o}_{v}"
    for a in CAMPAIGN.aircraft
    for s in CAMPAIGN.hsi_segments()
    for o in CAMPAIGN.observer_sets(s)
    for v in CAMPAIGN.variants(s)
)
ALL_TARGETS.extend(
    f"{RESULTS}/{a}/{s}/figures/hsi_{o}_{v}.png"
    for a in CAMPAIGN.aircraft
    for s in CAMPAIGN.hsi_segments()
    for o in CAMPAIGN.observer_sets(s)
    if config["observer_sets"][o]["kind"] == "points_ahead"
    for v in CAMPAIGN.variants(s)
)
