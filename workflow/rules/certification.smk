# Noise certification (nps.stages.certification, per aircraft): the take-off, overflight and approach
# reference procedures of 14 CFR 36 Appendix H / ICAO Annex 16 Vol. I Chapter 8 flown with the source
# hemispheres of the configured segments (rule source_hemisphere); EPNL at the three microphones, the
# Chapter 8 limits for the maximum mass and the margins. Scheduled when config has `certification`.


rule certification:
    input:
        **{f"hemisphere_{p}": (lambda wildcards, p=p: f"{RESULTS}/{wildcards.aircraft}/{config['certification']['segments'][p]}/source_hemisphere.parquet")
           for p in ("takeoff", "overflight", "approach")},
    output:
        summary=f"{RESULTS}/{{aircraft}}/certification/certification.parquet",
        summary_csv=report(
            f"{RESULTS}/{{aircraft}}/certification/certification.csv",
            caption="../report/certification_table.rst",
            category="{aircraft}",
            subcategory="Footprint and certification",
            labels={"aircraft": "{aircraft}", "figure": "certification EPNL, limits, margins (CSV)"},
        ),
        microphones=f"{RESULTS}/{{aircraft}}/certification/microphones.parquet",
        histories=f"{RESULTS}/{{aircraft}}/certification/histories.parquet",
        pnlt_figure=report(
            f"{RESULTS}/{{aircraft}}/certification/pnlt.png",
            caption="../report/certification_pnlt.rst",
            category="{aircraft}",
            subcategory="Footprint and certification",
            labels={"aircraft": "{aircraft}", "figure": "PNLT at the certification microphones"},
        ),
        table_figure=report(
            f"{RESULTS}/{{aircraft}}/certification/certification.png",
            caption="../report/certification_table.rst",
            category="{aircraft}",
            subcategory="Footprint and certification",
            labels={"aircraft": "{aircraft}", "figure": "certification EPNL, limits, margins (picture)"},
        ),
    params:
        job=plan("certification"),
        code=code("certification"),
    log:
        log_path("certification", "{aircraft}"),
    benchmark:
        bench_path("certification", "{aircraft}")
    threads: 1
    resources:
        mem_mb=1500,
        runtime=10,
    script:
        STAGE_SCRIPT


if "certification" in config:
    ALL_TARGETS.extend(f"{RESULTS}/{a}/certification/certification.parquet" for a in CAMPAIGN.aircraft)
