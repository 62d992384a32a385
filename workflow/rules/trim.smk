# Aircraft trim (NDARC's role): per aircraft x segment, thrust targets and rotor states.


rule trim:
    output:
        f"{RESULTS}/{{aircraft}}/{{segment}}/trim.parquet",
    params:
        aircraft=aircraft_config,
        speeds=segment_speeds,
        atmosphere=config["atmosphere"],
        code=nps_hash("trim", "atmosphere"),
    log:
        log_path("trim"),
    benchmark:
        bench_path("trim")
    threads: 1
    group: "prepare"
    resources:
        mem_mb=job_mem_mb("trim"),
        runtime=job_runtime("trim"),
    script:
        "../scripts/trim.py"


ALL_TARGETS.extend(f"{RESULTS}/{a}/{s}/trim.parquet" for a, s in campaign_pairs())
