# Tip-vortex wake and BVI loads (issue 4), one job per aircraft x segment for all its rotors:
# the Beddoes prescribed wake of each rotor from its trimmed loads (nps.wake) with its legacy-VTK
# series for ParaView, and the BVI loads, i.e. the wake's induced velocity added to the trimmed
# loads without re-trim (nps.bvi; same schema as loads/{rotor}.parquet, read by the acoustics stage
# as variant "bvi"). One job instead of two per rotor: each numba process pays ~3 s of start-up.
# Scheduled only in models.bvi_segments when config models.bvi is true.


rule wake:
    input:
        unpack(wake_inputs),
    output:
        # {rotor}.parquet (wake geometry) and {rotor}_vtk/ per rotor
        wake=directory(f"{RESULTS}/{{aircraft}}/{{segment}}/wake"),
        # {rotor}.parquet (BVI disk table) per rotor
        bvi=directory(f"{RESULTS}/{{aircraft}}/{{segment}}/bvi"),
    params:
        rotors=lambda wildcards: {r: rotor_config_named(wildcards.aircraft, r) for r in rotor_names(wildcards.aircraft)},
        wake=config["wake"],
        revolutions=config["resolution"]["wake_revolutions"],
        steps_per_rev=config["resolution"]["n_psi"],
        code=nps_hash("wake", "bvi", "bet", "vtk", "cli/bvi", "cli/wake"),
    log:
        log_path("wake"),
    benchmark:
        bench_path("wake")
    threads: job_threads("wake")
    resources:
        mem_mb=job_mem_mb("wake"),
        runtime=job_runtime("wake"),
    script:
        "../scripts/wake.py"


if config["models"]["bvi"]:
    ALL_TARGETS.extend(f"{RESULTS}/{a}/{s}/{d}" for a in CAMPAIGN.aircraft for s in bvi_segments() for d in ("wake", "bvi"))
