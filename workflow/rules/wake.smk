# Tip-vortex wake (issue 4): Beddoes prescribed wake of each rotor from its trimmed loads
# (nps.wake), its legacy-VTK series for ParaView and the top/side-view figure.
# Scheduled only when config models.bvi is true (the wake exists for the BVI loads).


rule wake:
    input:
        disk=f"{RESULTS}/{{aircraft}}/{{segment}}/loads/{{rotor}}.parquet",
        summary=f"{RESULTS}/{{aircraft}}/{{segment}}/loads/{{rotor}}_summary.parquet",
        trim=f"{RESULTS}/{{aircraft}}/{{segment}}/trim.parquet",
    output:
        wake=f"{RESULTS}/{{aircraft}}/{{segment}}/wake/{{rotor}}.parquet",
        vtk=directory(f"{RESULTS}/{{aircraft}}/{{segment}}/wake/{{rotor}}_vtk"),
    params:
        wake=config["wake"],
        revolutions=config["resolution"]["wake_revolutions"],
        steps_per_rev=config["resolution"]["n_psi"],
        code=nps_hash("wake", "bvi", "vtk", "cli/wake"),
    log:
        log_path("wake", "{aircraft}/{segment}/{rotor}"),
    benchmark:
        bench_path("wake", "{aircraft}/{segment}/{rotor}")
    threads: 1
    resources:
        mem_mb=1000,
        runtime=5,
    script:
        "../scripts/wake.py"


rule wake_figure:
    input:
        wake=f"{RESULTS}/{{aircraft}}/{{segment}}/wake/{{rotor}}.parquet",
        disk=f"{RESULTS}/{{aircraft}}/{{segment}}/loads/{{rotor}}.parquet",
    output:
        report(
            f"{RESULTS}/{{aircraft}}/{{segment}}/figures/wake_{{rotor}}.png",
            caption="../report/wake_views.rst",
            category="Wake and BVI",
            subcategory="{aircraft} {segment}",
            labels={"aircraft": "{aircraft}", "segment": "{segment}", "rotor": "{rotor}", "figure": "wake"},
        ),
    params:
        radius_m=lambda wildcards: rotor_config(wildcards)["radius_m"],
        code=nps_hash("plots/wake", "plots/disk"),
    log:
        log_path("wake_figure", "{aircraft}/{segment}/{rotor}"),
    benchmark:
        bench_path("wake_figure", "{aircraft}/{segment}/{rotor}")
    threads: 1
    resources:
        mem_mb=800,
        runtime=5,
    script:
        "../scripts/wake_figure.py"


if config["models"]["bvi"]:
    ALL_TARGETS.extend(
        f"{RESULTS}/{a}/{s}/{kind}"
        for a in CAMPAIGN.aircraft
        for s in bvi_segments()
        for r in rotor_names(a)
        for kind in (f"wake/{r}.parquet",) + ((f"figures/wake_{r}.png",) if s in figure_segments("disk") and r in figure_rotors(a) else ())
    )
