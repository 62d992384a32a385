# BVI loads (issue 4): the wake's induced velocity added to the trimmed loads without re-trim
# (nps.bvi); same schema as loads/{rotor}.parquet, read by the acoustics stage as variant "bvi".
# Scheduled only when config models.bvi is true.


rule bvi:
    input:
        disk=f"{RESULTS}/{{aircraft}}/{{segment}}/loads/{{rotor}}.parquet",
        summary=f"{RESULTS}/{{aircraft}}/{{segment}}/loads/{{rotor}}_summary.parquet",
        trim=f"{RESULTS}/{{aircraft}}/{{segment}}/trim.parquet",
    output:
        f"{RESULTS}/{{aircraft}}/{{segment}}/bvi/{{rotor}}.parquet",
    params:
        rotor=rotor_config,
        wake=config["wake"],
        revolutions=config["resolution"]["wake_revolutions"],
        steps_per_rev=config["resolution"]["n_psi"],
        code=nps_hash("wake", "bvi", "bet", "cli/bvi", "cli/wake"),
    log:
        log_path("bvi", "{aircraft}/{segment}/{rotor}"),
    benchmark:
        bench_path("bvi", "{aircraft}/{segment}/{rotor}")
    threads: 1
    resources:
        mem_mb=1500,
        runtime=5,
    script:
        "../scripts/bvi.py"


rule bvi_figure:
    input:
        disk=f"{RESULTS}/{{aircraft}}/{{segment}}/loads/{{rotor}}.parquet",
        bvi=f"{RESULTS}/{{aircraft}}/{{segment}}/bvi/{{rotor}}.parquet",
    output:
        report(
            f"{RESULTS}/{{aircraft}}/{{segment}}/figures/bvi_{{rotor}}.png",
            caption="../report/bvi_disk.rst",
            category="Wake and BVI",
            subcategory="{aircraft} {segment}",
            labels={"aircraft": "{aircraft}", "segment": "{segment}", "rotor": "{rotor}", "figure": "BVI loads"},
        ),
    params:
        rotation_sign=lambda wildcards: 1 if rotor_config(wildcards)["rotation"] == "ccw" else -1,
        code=nps_hash("plots/wake", "plots/disk"),
    log:
        log_path("bvi_figure", "{aircraft}/{segment}/{rotor}"),
    benchmark:
        bench_path("bvi_figure", "{aircraft}/{segment}/{rotor}")
    threads: 1
    resources:
        mem_mb=800,
        runtime=5,
    script:
        "../scripts/bvi_figure.py"


if config["models"]["bvi"]:
    ALL_TARGETS.extend(
        f"{RESULTS}/{a}/{s}/{kind}"
        for a in CAMPAIGN.aircraft
        for s in bvi_segments()
        for r in rotor_names(a)
        for kind in (f"bvi/{r}.parquet",) + ((f"figures/bvi_{r}.png",) if s in figure_segments("disk") and r in figure_rotors(a) else ())
    )
