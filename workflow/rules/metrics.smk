# Noise metrics: OASPL, OASPL_A, BVISPL, PNL(T), per-source levels and 1/3-octave bands per aircraft x
# segment x observer set x variant, from the summed rotor signals (+ HSI, Pegg or BPM broadband, ISO 9613-1
# absorption when the models are on): nps.stages.metrics.
rule metrics:
    input:
        unpack(metrics_signal_inputs),
        trim=f"{BASE}/trim.parquet",
        observers=f"{BASE}/observers/{{obsset}}.parquet",
    output:
        metrics=f"{BASE}/metrics/{{obsset}}_{{variant}}.parquet",
        bands=f"{BASE}/metrics/{{obsset}}_{{variant}}_bands.parquet",
        figure=report(
            f"{BASE}/metrics/{{obsset}}_{{variant}}_spectrum.png",
            caption="../report/metrics_spectrum.rst",
            category="{aircraft}",
            subcategory="{segment}",
            labels={"aircraft": "{aircraft}", "segment": "{segment}", "figure": "spectrum, loudest {obsset} observer ({variant})"},
        ),
    params:
        job=plan("metrics"),
        code=code("metrics"),
    log:
        log_path("metrics", "{aircraft}/{segment}/{obsset}_{variant}"),
    benchmark:
        bench_path("metrics", "{aircraft}/{segment}/{obsset}_{variant}")
    threads: 1
    resources:
        mem_mb=job_mem_mb("metrics"),
        runtime=job_runtime("metrics"),
    script:
        STAGE_SCRIPT


ALL_TARGETS.extend(
    f"{RESULTS}/{a}/{s}/metrics/{o}_{v}.parquet"
    for a, s in campaign_pairs()
    for o in CAMPAIGN.observer_sets(s)
    for v in CAMPAIGN.variants(s)
)
