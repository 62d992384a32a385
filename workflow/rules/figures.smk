# Per-rotor figures of one aircraft x segment in one job (one matplotlib start-up): disk plots of the
# trimmed loads, and where the wake is computed its top/side views and the BVI loading disk maps
# (nps.stages.rotor_figures). Rotors drawn: figure_rotors() (all of a one- or two-rotor aircraft, else the first).


rule rotor_figures:
    input:
        unpack(rotor_figure_inputs),
    output:
        # disk_{rotor}.png, and wake_{rotor}.png, bvi_{rotor}.png in segments with the wake
        figures=report(
            directory(f"{BASE}/figures/rotors"),
            patterns=["{kind,disk|wake|bvi}_{rotor}.png"],
            caption="../report/rotor_figures.rst",
            category="{aircraft}",
            subcategory="{segment}",
            labels={"aircraft": "{aircraft}", "segment": "{segment}", "figure": "{kind}, rotor {rotor}"},
        ),
    params:
        rotors=lambda wildcards: {
            r: {"rotation_sign": 1 if CAMPAIGN.rotor(wildcards.aircraft, r)["rotation"] == "ccw" else -1,
                "radius_m": CAMPAIGN.rotor(wildcards.aircraft, r)["radius_m"]}
            for r in figure_rotors(wildcards.aircraft)
        },
        segment_name=lambda wildcards: CAMPAIGN.segment(wildcards.segment)["name"],
        code=code("rotor_figures"),
    log:
        log_path("rotor_figures"),
    benchmark:
        bench_path("rotor_figures")
    threads: 1
    resources:
        mem_mb=job_mem_mb("rotor_figures"),
        runtime=job_runtime("rotor_figures"),
    script:
        STAGE_SCRIPT


ALL_TARGETS.extend(f"{RESULTS}/{a}/{s}/figures/rotors" for a in CAMPAIGN.aircraft for s in CAMPAIGN.figure_segments("disk"))
