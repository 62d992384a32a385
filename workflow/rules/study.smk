# The study (thesis chapter 7): hemisphere maps, BVI hotspots and summary tables per aircraft.
# Levels come from the hemisphere metrics of the variant with BVI wherever it was computed.
# Figure titles name each segment by its mission name and the hemisphere by its radius in R and metres.


rule study_maps:
    # every map family of one aircraft in one job (one matplotlib start-up)
    input:
        unpack(lambda wc: {s: hemisphere_metrics(wc.aircraft, s) for s in map_segments_all()}),
    output:
        **{
            kind: report(
                f"{RESULTS}/{{aircraft}}/figures/{kind}_maps.png",
                caption="../report/study_maps.rst",
                category="{aircraft}",
                subcategory="Hemisphere maps",
                labels={"aircraft": "{aircraft}", "figure": f"{kind} maps"},
            )
            for kind in map_kinds()
        },
    params:
        segments={kind: MAP_SEGMENTS[kind]() for kind in map_kinds()},
        segment_names=segment_names(),
        radius_R=config["observer_sets"]["hemisphere"]["radius_R"],
        radius_m=lambda wc: hemisphere_radius_m(wc.aircraft),
        code=code("study_maps"),
    log:
        log_path("study_maps", "{aircraft}"),
    benchmark:
        bench_path("study_maps", "{aircraft}")
    threads: 1
    resources:
        mem_mb=job_mem_mb("study_maps"),
        runtime=job_runtime("study_maps"),
    script:
        STAGE_SCRIPT


rule rotor_maps:
    input:
        unpack(lambda wc: {f"signals_{s}": f"{RESULTS}/{wc.aircraft}/{s}/acoustics/hemisphere_base"
                           for s in CAMPAIGN.figure_segments("map")[:2]}),
        observers=lambda wc: f"{RESULTS}/{wc.aircraft}/{CAMPAIGN.figure_segments('map')[0]}/observers/hemisphere.parquet",
    output:
        figure=report(
            f"{RESULTS}/{{aircraft}}/figures/oaspl_maps_{{rotor}}.png",
            caption="../report/rotor_maps.rst",
            category="{aircraft}",
            subcategory="Hemisphere maps",
            labels={"aircraft": "{aircraft}", "figure": "OASPL maps, rotor {rotor} alone"},
        ),
    params:
        segments=lambda wc: CAMPAIGN.figure_segments("map")[:2],
        segment_names=segment_names(),
        radius_R=config["observer_sets"]["hemisphere"]["radius_R"],
        radius_m=lambda wc: hemisphere_radius_m(wc.aircraft),
        code=code("rotor_maps"),
    log:
        log_path("rotor_maps", "{aircraft}/{rotor}"),
    benchmark:
        bench_path("rotor_maps", "{aircraft}/{rotor}")
    threads: 1
    resources:
        mem_mb=job_mem_mb("rotor_maps"),
        runtime=job_runtime("rotor_maps"),
    script:
        STAGE_SCRIPT


rule bvi_hotspot:
    input:
        metrics=f"{BASE}/metrics/hemisphere_bvi.parquet",
        trim=f"{BASE}/trim.parquet",
        base=f"{BASE}/acoustics/hemisphere_base",
        bvi=f"{BASE}/acoustics/hemisphere_bvi",
        observers=f"{BASE}/observers/hemisphere.parquet",
    output:
        hotspot=report(
            f"{BASE}/figures/hotspot_bvi.png",
            caption="../report/bvi_hotspot.rst",
            category="{aircraft}",
            subcategory="{segment}",
            labels={"aircraft": "{aircraft}", "segment": "{segment}", "figure": "BVI hotspot"},
        ),
        # pressure time histories at several directions (BVI loads), same job: one matplotlib start-up
        histories=report(
            f"{BASE}/figures/pressure_hemisphere_bvi.png",
            caption="../report/acoustics_histories.rst",
            category="{aircraft}",
            subcategory="{segment}",
            labels={"aircraft": "{aircraft}", "segment": "{segment}", "figure": "pressure, hemisphere (bvi)"},
        ),
    params:
        rotors=lambda wc: rotor_names(wc.aircraft),
        harmonics=config["acoustics"]["bvispl_harmonics"],
        segment_name=lambda wc: CAMPAIGN.segment(wc.segment)["name"],
        radius_R=config["observer_sets"]["hemisphere"]["radius_R"],
        radius_m=lambda wc: hemisphere_radius_m(wc.aircraft),
        code=code("bvi_hotspot"),
    log:
        log_path("bvi_hotspot"),
    benchmark:
        bench_path("bvi_hotspot")
    threads: 1
    resources:
        mem_mb=job_mem_mb("bvi_hotspot"),
        runtime=job_runtime("bvi_hotspot"),
    script:
        STAGE_SCRIPT


rule summary:
    input:
        unpack(summary_inputs),
    output:
        table=f"{RESULTS}/{{aircraft}}/summary.parquet",
        csv=report(
            f"{RESULTS}/{{aircraft}}/summary.csv",
            caption="../report/summary.rst",
            category="{aircraft}",
            subcategory="Summary",
            labels={"aircraft": "{aircraft}", "figure": "summary table"},
        ),
    params:
        segments=CAMPAIGN.segments,
        rotors=lambda wc: rotor_names(wc.aircraft),
        variants={s: CAMPAIGN.variants(s) for s in CAMPAIGN.segments},
        benchmarks=f"{RESULTS}/benchmarks",
        code=code("summary"),
    log:
        log_path("summary", "{aircraft}"),
    benchmark:
        bench_path("summary", "{aircraft}")
    threads: 1
    resources:
        mem_mb=job_mem_mb("summary"),
        runtime=job_runtime("summary"),
    script:
        STAGE_SCRIPT


ALL_TARGETS.extend(f"{RESULTS}/{a}/summary.parquet" for a in CAMPAIGN.aircraft)
ALL_TARGETS.extend(f"{RESULTS}/{a}/figures/{k}_maps.png" for a in CAMPAIGN.aircraft for k in map_kinds())
ALL_TARGETS.extend(
    f"{RESULTS}/{a}/figures/oaspl_maps_{r}.png"
    for a in CAMPAIGN.aircraft
    for r in antitorque_rotors(a)
    if CAMPAIGN.figure_segments("map")
)
ALL_TARGETS.extend(
    f"{RESULTS}/{a}/{s}/figures/hotspot_bvi.png"
    for a in CAMPAIGN.aircraft
    for s in CAMPAIGN.figure_segments("bvi_map")
    if "bvi" in CAMPAIGN.variants(s)
)


# The campaign's results summary (nps.stages.results_summary): every aircraft x segment in one HTML page and
# CSV, the page the report opens on (workflow/report/workflow.rst inserts it; category "1. Results summary"
# sorts first in the report's menu). It reads the summary tables and lists the figures, so every other target
# of the campaign's aircraft is an input: the job runs last.
rule results_summary:
    input:
        unpack(results_summary_inputs),
    output:
        html=report(
            f"{RESULTS}/results_summary.html",
            caption="../report/results_summary.rst",
            category=SUMMARY_CATEGORY,
            labels={"table": "results summary (page)"},
        ),
        csv=report(
            f"{RESULTS}/results_summary.csv",
            caption="../report/results_summary.rst",
            category=SUMMARY_CATEGORY,
            labels={"table": "results summary (CSV)"},
        ),
    params:
        campaign_aircraft=list(CAMPAIGN.aircraft),
        segments=CAMPAIGN.segments,
        segment_names=segment_names(),
        radius_R=config["observer_sets"]["hemisphere"]["radius_R"],
        radius_m={a: hemisphere_radius_m(a) for a in CAMPAIGN.aircraft},
        loudest=config["outputs"]["spectra_loudest"],
        results=lambda wildcards: RESULTS,  # the results directory the figure paths are relative to
        code=code("results_summary"),
    log:
        log_path("results_summary", "campaign"),
    benchmark:
        bench_path("results_summary", "campaign")
    threads: 1
    resources:
        mem_mb=1000,
        runtime=5,
    script:
        STAGE_SCRIPT


ALL_TARGETS.append(f"{RESULTS}/results_summary.html")
