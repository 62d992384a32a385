# Tip-vortex wake and BVI loads of every rotor of an aircraft x segment in one job (nps.stages.wake):
# the Beddoes prescribed wake of each rotor with its legacy-VTK series for ParaView, and the BVI loads
# (the wake's induced velocity added to the trimmed loads, read by the acoustics stage as variant "bvi").
# Scheduled in the BVI segments only (models.bvi, models.bvi_segments).


rule wake:
    input:
        trim=f"{BASE}/trim.parquet",
        loads=f"{BASE}/loads",
    output:
        # {rotor}.parquet (wake geometry) and {rotor}_vtk/ per rotor
        wake=directory(f"{BASE}/wake"),
        # {rotor}.parquet (BVI disk table) per rotor
        bvi=directory(f"{BASE}/bvi"),
    params:
        job=plan("wake"),
        code=code("wake"),
    log:
        log_path("wake"),
    benchmark:
        bench_path("wake")
    threads: job_threads("wake")
    resources:
        mem_mb=job_mem_mb("wake"),
        runtime=job_runtime("wake"),
    script:
        STAGE_SCRIPT


ALL_TARGETS.extend(f"{RESULTS}/{a}/{s}/{d}" for a in CAMPAIGN.aircraft for s in CAMPAIGN.bvi_segments() for d in ("wake", "bvi"))
