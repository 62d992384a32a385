# Design studies (config/studies/NAME.yaml, nps.app.designs, docs/reference/studies.md): `snakemake -j2 study_NAME`
# (or `snakemake -j2 all --config study=NAME`). Each design x aircraft is one job (nps.stages.case) that runs the
# chain of every segment in one process through the stage cache results/studies/cache/, where a stage job is stored under the
# digest of its code, params and inputs: jobs of designs that differ in a field a stage does not read reuse its
# artifacts. A design's id is the digest of its variable values, so adding a value adds jobs and changes none.
wildcard_constraints:
    study="|".join(STUDY_NAMES) or "no_study",
    design="d[0-9a-f]{10}",


rule case:
    output:
        rows=f"{RESULTS}/studies/{{study}}/{{design}}/{{aircraft}}.parquet",
    params:
        job=case_params,
        code=code("case"),
    log:
        log_path("case", "{study}/{design}/{aircraft}"),
    benchmark:
        bench_path("case", "{study}/{design}/{aircraft}")
    threads: 1
    resources:
        mem_mb=case_mem_mb,
        runtime=case_runtime,
    script:
        STAGE_SCRIPT


rule trade:
    input:
        unpack(study_rows),
    output:
        table=f"{RESULTS}/studies/{{study}}/trade.parquet",
        csv=report(f"{RESULTS}/studies/{{study}}/trade.csv", caption="../report/trade_table.rst", category="Design studies",
                   subcategory="{study}", labels={"study": "{study}", "figure": "trade table (CSV)"}),
        html=report(f"{RESULTS}/studies/{{study}}/trade.html", caption="../report/trade_table.rst", category="Design studies",
                    subcategory="{study}", labels={"study": "{study}", "figure": "trade table"}),
        sensitivity=f"{RESULTS}/studies/{{study}}/sensitivity.parquet",
        sensitivity_csv=f"{RESULTS}/studies/{{study}}/sensitivity.csv",
        refused_csv=report(f"{RESULTS}/studies/{{study}}/refused.csv", caption="../report/trade_table.rst", category="Design studies",
                           subcategory="{study}", labels={"study": "{study}", "figure": "refused designs (CSV)"}),
        ranking_csv=report(f"{RESULTS}/studies/{{study}}/ranking.csv", caption="../report/trade_sensitivity.rst",
                           category="Design studies", subcategory="{study}", labels={"study": "{study}", "figure": "sensitivity ranking (CSV)"}),
        trends=report(f"{RESULTS}/studies/{{study}}/trends.png", caption="../report/trade_trends.rst", category="Design studies",
                      subcategory="{study}", labels={"study": "{study}", "figure": "metrics against the variables"}),
        pareto_figure=report(f"{RESULTS}/studies/{{study}}/pareto.png", caption="../report/trade_pareto.rst",
                             category="Design studies", subcategory="{study}", labels={"study": "{study}", "figure": "noise against power"}),
        sensitivity_figure=report(f"{RESULTS}/studies/{{study}}/sensitivity.png", caption="../report/trade_sensitivity.rst",
                                  category="Design studies", subcategory="{study}", labels={"study": "{study}", "figure": "sensitivity ranking"}),
    params:
        variables=lambda wildcards: {v.label: v.base_value for v in design_study(wildcards.study).variables},
        designs=lambda wildcards: [d.id for d in design_study(wildcards.study).designs],
        dropped=lambda wildcards: [list(item) for item in design_study(wildcards.study).dropped],
        pareto=lambda wildcards: design_study(wildcards.study).spec.get("pareto", {}),
        code=code("trade"),
    log:
        log_path("trade", "{study}"),
    benchmark:
        bench_path("trade", "{study}")
    threads: 1
    resources:
        mem_mb=1000,
        runtime=10,
    script:
        STAGE_SCRIPT


for _study in STUDY_NAMES:

    rule:
        name:
            f"study_{_study}"
        input:
            study_targets(_study),


if REQUESTED_STUDY is not None:
    if REQUESTED_STUDY not in STUDY_NAMES:
        sys.stderr.write(f"NPS configuration error: --config study={REQUESTED_STUDY}: expected one of {STUDY_NAMES} "
                         f"(files {STUDIES_DIR}/NAME.yaml)\n")
        raise SystemExit(1)
    ALL_TARGETS.extend(study_targets(REQUESTED_STUDY))
