# Rotor blade loads (issue 3): BET, linear inflow, flapping and the three-step trim per
# aircraft x segment x rotor (nps.bet), and the disk plots of each rotor's loads.


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
    resources:
        mem_mb=800,
        runtime=5,
    script:
        "../scripts/loads.py"


rule loads_disk_figure:
    input:
        disk=f"{RESULTS}/{{aircraft}}/{{segment}}/loads/{{rotor}}.parquet",
    output:
        report(
            f"{RESULTS}/{{aircraft}}/{{segment}}/figures/disk_{{rotor}}.png",
            caption="../report/loads_disk.rst",
            category="Rotor loads",
            subcategory="{aircraft} {segment}",
            labels={"aircraft": "{aircraft}", "segment": "{segment}", "rotor": "{rotor}"},
        ),
    params:
        rotation_sign=lambda wildcards: 1 if rotor_config(wildcards)["rotation"] == "ccw" else -1,
        code=nps_hash("plots/disk"),
    log:
        log_path("loads_disk_figure", "{aircraft}/{segment}/{rotor}"),
    benchmark:
        bench_path("loads_disk_figure", "{aircraft}/{segment}/{rotor}")
    threads: 1
    resources:
        mem_mb=800,
        runtime=5,
    script:
        "../scripts/loads_figure.py"


ALL_TARGETS.extend(f"{RESULTS}/{a}/{s}/loads/{r}.parquet" for a, s in campaign_pairs() for r in rotor_names(a))
ALL_TARGETS.extend(
    f"{RESULTS}/{a}/{s}/figures/disk_{r}.png" for a in CAMPAIGN.aircraft for s in figure_segments("disk") for r in figure_rotors(a)
)
