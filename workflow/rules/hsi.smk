# High-speed-impulsive noise (issue 7): each rotor's signals amplified, sheared and shock-fitted per
# observer with the rotor's own M_r and radiation distance (nps.hsi), all rotors of the aircraft in
# one job per observer set x variant; metrics sum the rotors.
# Only scheduled when config models.hsi is true (metrics then read hsi/ instead of acoustics/).


rule hsi:
    input:
        signals=signals_dir("acoustics"),
        observers=f"{RESULTS}/{{aircraft}}/{{segment}}/observers/{{obsset}}.parquet",
        trim=f"{RESULTS}/{{aircraft}}/{{segment}}/trim.parquet",
    output:
        # {rotor}.parquet (HSI signals) and {rotor}_diagnostics.parquet per rotor
        directory(signals_dir("hsi")),
    params:
        rotors=lambda wildcards: rotor_names(wildcards.aircraft),
        code=nps_hash("hsi"),
    log:
        log_path("hsi", "{aircraft}/{segment}/{obsset}_{variant}"),
    benchmark:
        bench_path("hsi", "{aircraft}/{segment}/{obsset}_{variant}")
    threads: job_threads("hsi")
    group: "radiate"
    resources:
        mem_mb=job_mem_mb("hsi"),
        runtime=job_runtime("hsi"),
    script:
        "../scripts/hsi.py"


rule hsi_figure:
    input:
        signals=signals_dir("acoustics"),
        hsi=signals_dir("hsi"),
        observers=f"{RESULTS}/{{aircraft}}/{{segment}}/observers/{{obsset}}.parquet",
    output:
        report(
            f"{RESULTS}/{{aircraft}}/{{segment}}/figures/hsi_{{obsset}}_{{variant}}.png",
            caption="../report/hsi_observers.rst",
            category="{aircraft}",
            subcategory="{segment}",
            labels={"aircraft": "{aircraft}", "segment": "{segment}", "figure": "HSI histories, {obsset} observers ({variant})"},
        ),
    params:
        rotors=lambda wildcards: rotor_names(wildcards.aircraft),
        code=nps_hash("hsi", "plots/hsi"),
    log:
        log_path("hsi_figure", "{aircraft}/{segment}/{obsset}_{variant}"),
    benchmark:
        bench_path("hsi_figure", "{aircraft}/{segment}/{obsset}_{variant}")
    threads: 1
    group: "radiate"
    resources:
        mem_mb=job_mem_mb("hsi_figure"),
        runtime=job_runtime("hsi_figure"),
    script:
        "../scripts/hsi_figure.py"


ALL_TARGETS.extend(
    f"{RESULTS}/{a}/{s}/hsi/{o}_{v}" for a in CAMPAIGN.aircraft for s in hsi_segments() for o in observer_sets(s) for v in variants(s)
)
ALL_TARGETS.extend(
    f"{RESULTS}/{a}/{s}/figures/hsi_{o}_{v}.png"
    for a in CAMPAIGN.aircraft
    for s in hsi_segments()
    for o in observer_sets(s)
    if config["observer_sets"][o]["kind"] == "points_ahead"
    for v in variants(s)
)
