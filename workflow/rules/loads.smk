# Rotor blade loads: BET, linear inflow, flapping and the three-step trim of every rotor of an aircraft
# x segment in one job (nps.stages.loads; one file set per rotor). Disk plots: rule rotor_figures.


rule loads:
    input:
        trim=f"{BASE}/trim.parquet",
    output:
        # {rotor}.parquet (disk table), {rotor}_summary.parquet, {rotor}_history.parquet per rotor
        loads=directory(f"{BASE}/loads"),
    params:
        job=plan("loads"),
        code=code("loads"),
    log:
        log_path("loads"),
    benchmark:
        bench_path("loads")
    threads: 1
    resources:
        mem_mb=job_mem_mb("loads"),
        runtime=job_runtime("loads"),
    script:
        STAGE_SCRIPT


ALL_TARGETS.extend(f"{RESULTS}/{a}/{s}/loads" for a, s in campaign_pairs())
