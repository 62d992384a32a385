# The study (thesis chapter 7): hemisphere maps, BVI hotspots and summary tables per aircraft.
# Levels come from the hemisphere metrics of the variant with BVI wherever it was computed.

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
        code=nps_hash("study", "plots/maps", "plots/study"),
    log:
        log_path("study_maps", "{aircraft}"),
    benchmark:
        bench_path("study_maps", "{aircraft}")
    threads: 1
    group: "figures"
    resources:
        mem_mb=job_mem_mb("study_maps"),
        runtime=job_runtime("study_maps"),
    script:
        "../scripts/study_maps.py"


rule rotor_maps:
    input:
        signals=lambda wc: [f"{RESULTS}/{wc.aircraft}/{s}/acoustics/hemisphere_base" for s in figure_segments("map")[:2]],
        observers=lambda wc: f"{RESULTS}/{wc.aircraft}/{figure_segments('map')[0]}/observers/hemisphere.parquet",
    output:
        report(
            f"{RESULTS}/{{aircraft}}/figures/oaspl_maps_{{rotor}}.png",
            caption="../report/rotor_maps.rst",
            category="{aircraft}",
            subcategory="Hemisphere maps",
            labels={"aircraft": "{aircraft}", "figure": "OASPL maps, rotor {rotor} alone"},
        ),
    params:
        segments=lambda wc: figure_segments("map")[:2],
        code=nps_hash("plots/maps", "plots/study"),
    log:
        log_path("rotor_maps", "{aircraft}/{rotor}"),
    benchmark:
        bench_path("rotor_maps", "{aircraft}/{rotor}")
    threads: 1
    group: "figures"
    resources:
        mem_mb=job_mem_mb("rotor_maps"),
        runtime=job_runtime("rotor_maps"),
    script:
        "../scripts/rotor_maps.py"


rule bvi_hotspot:
    input:
        metrics=f"{RESULTS}/{{aircraft}}/{{segment}}/metrics/hemisphere_bvi.parquet",
        trim=f"{RESULTS}/{{aircraft}}/{{segment}}/trim.parquet",
        base=f"{RESULTS}/{{aircraft}}/{{segment}}/acoustics/hemisphere_base",
        bvi=f"{RESULTS}/{{aircraft}}/{{segment}}/acoustics/hemisphere_bvi",
        observers=f"{RESULTS}/{{aircraft}}/{{segment}}/observers/hemisphere.parquet",
    output:
        hotspot=report(
            f"{RESULTS}/{{aircraft}}/{{segment}}/figures/hotspot_bvi.png",
            caption="../report/bvi_hotspot.rst",
            category="{aircraft}",
            subcategory="{segment}",
            labels={"aircraft": "{aircraft}", "segment": "{segment}", "figure": "BVI hotspot"},
        ),
        # pressure time histories at several directions (BVI loads), same job: one matplotlib start-up
        histories=report(
            f"{RESULTS}/{{aircraft}}/{{segment}}/figures/pressure_hemisphere_bvi.png",
            caption="../report/acoustics_histories.rst",
            category="{aircraft}",
            subcategory="{segment}",
            labels={"aircraft": "{aircraft}", "segment": "{segment}", "figure": "pressure, hemisphere (bvi)"},
        ),
    params:
        rotors=lambda wc: rotor_names(wc.aircraft),
        harmonics=config["acoustics"]["bvispl_harmonics"],
        code=nps_hash("study", "plots/study", "plots/acoustics", "spectra"),
    log:
        log_path("bvi_hotspot"),
    benchmark:
        bench_path("bvi_hotspot")
    threads: 1
    group: "figures"
    resources:
        mem_mb=job_mem_mb("bvi_hotspot"),
        runtime=job_runtime("bvi_hotspot"),
    script:
        "../scripts/bvi_hotspot.py"


rule summary:
    input:
        trims=lambda wc: [f"{RESULTS}/{wc.aircraft}/{s}/trim.parquet" for s in CAMPAIGN.segments],
        loads=lambda wc: [f"{RESULTS}/{wc.aircraft}/{s}/loads/{r}_summary.parquet" for s in CAMPAIGN.segments for r in rotor_names(wc.aircraft)],
        metrics=lambda wc: [f"{RESULTS}/{wc.aircraft}/{s}/metrics/hemisphere_{v}.parquet" for s in CAMPAIGN.segments for v in variants(s)],
        # not read: makes the wake jobs finish first so their wall times are in the table
        wakes=lambda wc: [f"{RESULTS}/{wc.aircraft}/{s}/wake" for s in bvi_segments()],
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
        variants={s: variants(s) for s in CAMPAIGN.segments},
        benchmarks=f"{RESULTS}/benchmarks",
        code=nps_hash("study"),
    log:
        log_path("summary", "{aircraft}"),
    benchmark:
        bench_path("summary", "{aircraft}")
    threads: 1
    group: "figures"
    resources:
        mem_mb=job_mem_mb("summary"),
        runtime=job_runtime("summary"),
    script:
        "../scripts/summary.py"


ALL_TARGETS.extend(f"{RESULTS}/{a}/summary.parquet" for a in CAMPAIGN.aircraft)
ALL_TARGETS.extend(f"{RESULTS}/{a}/figures/{k}_maps.png" for a in CAMPAIGN.aircraft for k in map_kinds())
ALL_TARGETS.extend(
    f"{RESULTS}/{a}/figures/oaspl_maps_{r}.png" for a in CAMPAIGN.aircraft for r in antitorque_rotors(a) if figure_segments("map")
)
ALL_TARGETS.extend(
    f"{RESULTS}/{a}/{s}/figures/hotspot_bvi.png" for a in CAMPAIGN.aircraft for s in figure_segments("bvi_map") if "bvi" in variants(s)
)
