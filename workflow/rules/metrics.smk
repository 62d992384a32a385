# Noise metrics (issue 6): OASPL, OASPL_A, BVISPL, PNL(T), per-source levels and 1/3-octave bands
# per aircraft x segment x observer set x variant, from the summed rotor signals (+ HSI, Pegg
# broadband, ISO 9613-1 absorption when the models are on).


rule metrics:
    input:
        unpack(metrics_signal_inputs),
        trim=f"{RESULTS}/{{aircraft}}/{{segment}}/trim.parquet",
        observers=f"{RESULTS}/{{aircraft}}/{{segment}}/observers/{{obsset}}.parquet",
    output:
        metrics=f"{RESULTS}/{{aircraft}}/{{segment}}/metrics/{{obsset}}_{{variant}}.parquet",
        bands=f"{RESULTS}/{{aircraft}}/{{segment}}/metrics/{{obsset}}_{{variant}}_bands.parquet",
        figure=report(
            f"{RESULTS}/{{aircraft}}/{{segment}}/metrics/{{obsset}}_{{variant}}_spectrum.png",
            caption="../report/metrics_spectrum.rst",
            category="{aircraft}",
            subcategory="{segment}",
            labels={"aircraft": "{aircraft}", "segment": "{segment}", "figure": "spectrum, loudest {obsset} observer ({variant})"},
        ),
    params:
        rotors=lambda wildcards: rotor_names(wildcards.aircraft),
        solidity=metrics_solidity,
        atmosphere=config["atmosphere"],
        broadband=config["models"]["broadband"],
        absorption=config["models"]["absorption"],
        hsi=lambda wildcards: wildcards.segment in hsi_segments(),
        harmonics=config["acoustics"]["bvispl_harmonics"],
        code=nps_hash("metrics", "spectra", "broadband", "atmosphere", "plots/spectra"),
    log:
        log_path("metrics", "{aircraft}/{segment}/{obsset}_{variant}"),
    benchmark:
        bench_path("metrics", "{aircraft}/{segment}/{obsset}_{variant}")
    threads: 1
    group: "radiate"
    resources:
        mem_mb=job_mem_mb("metrics"),
        runtime=job_runtime("metrics"),
    script:
        "../scripts/metrics.py"


ALL_TARGETS.extend(
    f"{RESULTS}/{a}/{s}/metrics/{o}_{v}.parquet"
    for a, s in campaign_pairs()
    for o in observer_sets(s)
    for v in variants(s)
)
