# Source hemispheres as a product (nps.stages.source_hemisphere, per aircraft x segment: the far-field
# `footprint.source_set` hemisphere's unabsorbed band levels referred to 10 R) and the mission's ground
# footprint (nps.stages.footprint, per aircraft: the mission profile flown with those hemispheres over the
# ground grid and the named microphones). Scheduled when config has `footprint` and the mission a profile.


rule source_hemisphere:
    input:
        unpack(source_hemisphere_inputs),
    output:
        hemisphere=f"{BASE}/source_hemisphere.parquet",
    params:
        job=plan("source_hemisphere"),
        code=code("source_hemisphere"),
    log:
        log_path("source_hemisphere"),
    benchmark:
        bench_path("source_hemisphere")
    threads: 1
    resources:
        mem_mb=1500,
        runtime=10,
    script:
        STAGE_SCRIPT


rule footprint:
    input:
        unpack(footprint_inputs),
    output:
        grid=f"{RESULTS}/{{aircraft}}/footprint/grid.parquet",
        microphones=f"{RESULTS}/{{aircraft}}/footprint/microphones.parquet",
        histories=f"{RESULTS}/{{aircraft}}/footprint/histories.parquet",
        areas=f"{RESULTS}/{{aircraft}}/footprint/areas.parquet",
        areas_csv=report(
            f"{RESULTS}/{{aircraft}}/footprint/areas.csv",
            caption="../report/footprint_areas.rst",
            category="{aircraft}",
            subcategory="Footprint and certification",
            labels={"aircraft": "{aircraft}", "figure": "contour areas (table)"},
        ),
        sel_figure=report(
            f"{RESULTS}/{{aircraft}}/footprint/sel.png",
            caption="../report/footprint_contours.rst",
            category="{aircraft}",
            subcategory="Footprint and certification",
            labels={"aircraft": "{aircraft}", "figure": "SEL footprint"},
        ),
        lamax_figure=report(
            f"{RESULTS}/{{aircraft}}/footprint/lamax.png",
            caption="../report/footprint_contours.rst",
            category="{aircraft}",
            subcategory="Footprint and certification",
            labels={"aircraft": "{aircraft}", "figure": "L_Amax footprint"},
        ),
    params:
        job=plan("footprint"),
        code=code("footprint"),
    log:
        log_path("footprint", "{aircraft}"),
    benchmark:
        bench_path("footprint", "{aircraft}")
    threads: 2
    resources:
        mem_mb=3000,
        runtime=15,
    script:
        STAGE_SCRIPT


if "footprint" in config and profile_segments():
    ALL_TARGETS.extend(f"{RESULTS}/{a}/footprint/grid.parquet" for a in CAMPAIGN.aircraft)
