# Aircraft trim (NDARC's role): per aircraft x segment, thrust targets and rotor states (nps.stages.trim).


rule trim:
    output:
        trim=f"{BASE}/trim.parquet",
    params:
        job=plan("trim"),
        code=code("trim"),
    log:
        log_path("trim"),
    benchmark:
        bench_path("trim")
    threads: 1
    resources:
        mem_mb=job_mem_mb("trim"),
        runtime=job_runtime("trim"),
    script:
        STAGE_SCRIPT


ALL_TARGETS.extend(f"{RESULTS}/{a}/{s}/trim.parquet" for a, s in campaign_pairs())
