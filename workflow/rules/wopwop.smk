# PSU-WOPWOP export (nps.stages.wopwop_export): every aircraft x segment x observer set x load variant of the
# campaign as a complete PSU-WOPWOP case directory (cases.nam, case.nam, observer files, per rotor a compact geometry
# file and a periodic loading file), the same computation as the acoustics rule's. Not part of `all`: run
# `snakemake -j2 wopwop` to export the whole campaign, or name one case directory.


rule wopwop_export:
    input:
        disks=variant_disks,
        trim=f"{BASE}/trim.parquet",
        observers=f"{BASE}/observers/{{obsset}}.parquet",
    output:
        case=directory(f"{BASE}/wopwop/{{obsset}}_{{variant}}"),
    params:
        job=plan("wopwop_export"),
        code=code("wopwop_export"),
    log:
        log_path("wopwop_export", "{aircraft}/{segment}/{obsset}_{variant}"),
    benchmark:
        bench_path("wopwop_export", "{aircraft}/{segment}/{obsset}_{variant}")
    threads: 1
    resources:
        mem_mb=job_mem_mb("acoustics"),
        runtime=5,
    script:
        STAGE_SCRIPT


rule wopwop:
    input:
        [
            f"{RESULTS}/{a}/{s}/wopwop/{o}_{v}"
            for a, s in campaign_pairs()
            for o in CAMPAIGN.observer_sets(s)
            for v in CAMPAIGN.variants(s)
        ],
