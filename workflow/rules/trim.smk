# Aircraft trim (NDARC's role): per aircraft x segment, thrust targets and rotor states (nps.stages.trim).


rule trim:
    output:
        trim=f"{BASE}/trim.parquet",
    params:
        aircraft_config=aircraft_config,
        speeds=lambda wildcards: CAMPAIGN.segment(wildcards.segment)["aircraft"][wildcards.aircraft],
        atmosphere=config["atmosphere"],
        allow_outside_validity=ALLOW_OUTSIDE_VALIDITY,
        # disk resolution of the loads that solve the speeds of rpm-controlled rotors (nps.rotor.control.trim_rotor_speeds)
        n_psi=config["resolution"]["n_psi"],
        n_r=config["resolution"]["n_r"],
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
