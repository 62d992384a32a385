# Tone tables (level and phase of each BPF harmonic, per rotor and total) and narrowband spectra per
# aircraft x segment x observer set x variant, from the acoustics signals (free field): nps.stages.tones.
# Observer sets: outputs.tone_observer_sets (default all); spectra and CSV rows for the
# outputs.spectra_loudest loudest observers and the outputs.spectra_observers ids.
rule tones:
    input:
        signals=signals_dir("acoustics"),
        trim=f"{BASE}/trim.parquet",
    output:
        tones=f"{BASE}/tones/{{obsset}}_{{variant}}.parquet",
        tones_csv=f"{BASE}/tones/{{obsset}}_{{variant}}_selected.csv",
        spectra=f"{BASE}/tones/{{obsset}}_{{variant}}_spectra.parquet",
    params:
        job=plan("tones"),
        code=code("tones"),
    log:
        log_path("tones", "{aircraft}/{segment}/{obsset}_{variant}"),
    benchmark:
        bench_path("tones", "{aircraft}/{segment}/{obsset}_{variant}")
    threads: 1
    resources:
        mem_mb=1000,
        runtime=5,
    script:
        STAGE_SCRIPT


ALL_TARGETS.extend(
    f"{RESULTS}/{a}/{s}/tones/{o}_{v}.parquet"
    for a, s in campaign_pairs()
    for o in CAMPAIGN.tone_observer_sets(s)
    for v in CAMPAIGN.variants(s)
)
