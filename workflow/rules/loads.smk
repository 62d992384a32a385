# Rotor blade loads (issue 3): BET, linear inflow, flapping and the three-step trim per
# aircraft x segment x rotor (nps.bet). Disk plots: rule rotor_figures (figures.smk).


rule loads:
    input:
        trim=f"{RESULTS}/{{aircraft}}/{{segment}}/trim.parquet",
    output:
        disk=f"{RESULTS}/{{aircraft}}/{{segment}}/loads/{{rotor}}.parquet",
        summary=f"{RESULTS}/{{aircraft}}/{{segment}}/loads/{{rotor}}_summary.parquet",
        history=f"{RESULTS}/{{aircraft}}/{{segment}}/loads/{{rotor}}_history.parquet",
    params:
        rotor=rotor_config,
        n_psi=config["resolution"]["n_psi"],
        n_r=config["resolution"]["n_r"],
        code=nps_hash("bet", "cli/loads"),
    log:
        log_path("loads", "{aircraft}/{segment}/{rotor}"),
    benchmark:
        bench_path("loads", "{aircraft}/{segment}/{rotor}")
    threads: 1
    group: "prepare"
    resources:
        mem_mb=job_mem_mb("loads"),
        runtime=job_runtime("loads"),
    script:
        "../scripts/loads.py"


ALL_TARGETS.extend(f"{RESULTS}/{a}/{s}/loads/{r}.parquet" for a, s in campaign_pairs() for r in rotor_names(a))
