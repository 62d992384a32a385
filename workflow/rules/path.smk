# Flight paths (config/paths/*.yaml; docs/reference/paths.md): the path's time history and its quasi-static trim
# states (nps.stages.path), each state's source hemisphere through the study's per-segment rules (the state key
# is the segment), and the noise along the path at its receivers (nps.stages.path_footprint). Targets:
# `snakemake -j2 path_NAME` for one path, `paths` for every path of the campaign's aircraft (not part of `all`).


rule path:
    output:
        history=f"{PATHS_RESULTS}/{{path}}/path_history.parquet",
        states=f"{PATHS_RESULTS}/{{path}}/path_states.parquet",
    params:
        job=path_job("path"),
        code=code("path"),
    log:
        log_path("path", "paths/{path}"),
    benchmark:
        bench_path("path", "paths/{path}")
    threads: 1
    resources:
        mem_mb=1000,
        runtime=5,
    script:
        STAGE_SCRIPT


rule path_footprint:
    input:
        unpack(path_footprint_inputs),
    output:
        grid=f"{PATHS_RESULTS}/{{path}}/footprint/grid.parquet",
        microphones=f"{PATHS_RESULTS}/{{path}}/footprint/microphones.parquet",
        histories=f"{PATHS_RESULTS}/{{path}}/footprint/histories.parquet",
        areas=f"{PATHS_RESULTS}/{{path}}/footprint/areas.parquet",
        plan_figure=report(
            f"{PATHS_RESULTS}/{{path}}/footprint/plan.png",
            caption="../report/path_plan.rst",
            category="Flight paths",
            subcategory="{path}",
            labels={"path": "{path}", "figure": "SEL footprint and source level along the path"},
        ),
        history_figure=report(
            f"{PATHS_RESULTS}/{{path}}/footprint/histories.png",
            caption="../report/path_histories.rst",
            category="Flight paths",
            subcategory="{path}",
            labels={"path": "{path}", "figure": "L_A(t) at the microphones"},
        ),
    params:
        job=path_job("path_footprint"),
        code=code("path_footprint"),
    log:
        log_path("path_footprint", "paths/{path}"),
    benchmark:
        bench_path("path_footprint", "paths/{path}")
    threads: 2
    resources:
        mem_mb=3000,
        runtime=15,
    script:
        STAGE_SCRIPT


for _path in CAMPAIGN.paths:

    rule:
        name:
            f"path_{_path}"
        input:
            f"{PATHS_RESULTS}/{_path}/footprint/grid.parquet",


rule paths:
    input:
        [f"{PATHS_RESULTS}/{p}/footprint/grid.parquet" for p in CAMPAIGN.paths],
