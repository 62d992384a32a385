# Rigs (config/rigs/*.yaml, nps.rig.case): an isolated rotor on a test stand or in a wind tunnel with
# hub-fixed microphones. The study's rules run a rig as aircraft "rigs", segment NAME (results/rigs/NAME/,
# common.smk): the set-up here (stage rig) writes the trim row and the microphone table (observer set
# "microphones"); the study's loads, wake (+ BVI loads) where models.bvi, acoustics and metrics rules follow,
# with the rig's own settings; the BVISPL carpet of the plane microphone groups where `carpet`, and the loads at
# the radial stations (station_loads) where `stations_r_over_R`. A rig may hold several rotors (rotors:). With
# `loads_only` a rig's targets stop before the acoustics (set-up, loads, wake and BVI loads, station loads).
# Targets: `snakemake -j2 rigs` (every rig), or one rig by its name (`snakemake -j2 hart_ii_bl`).

# a rig's trim and microphones are the set-up's, not the aircraft trim's or an observer set's
ruleorder: rig > trim
ruleorder: rig > observers


rule rig:
    input:
        config=lambda wildcards: str(RIGS_DIR / f"{wildcards.segment}.yaml"),
    output:
        trim=f"{BASE}/trim.parquet",
        observers=f"{BASE}/observers/microphones.parquet",
    wildcard_constraints:
        aircraft=RIG_AIRCRAFT,
    params:
        code=code("rig"),
    log:
        log_path("rig"),
    benchmark:
        bench_path("rig")
    threads: 1
    resources:
        mem_mb=job_mem_mb("rig"),
        runtime=job_runtime("rig"),
    script:
        STAGE_SCRIPT


rule carpet:
    input:
        metrics=lambda wildcards: f"{RESULTS}/{wildcards.aircraft}/{wildcards.segment}/metrics/microphones_{rig_variant(wildcards.segment)}.parquet",
        observers=f"{BASE}/observers/microphones.parquet",
    output:
        figure=f"{BASE}/carpet.png",
    wildcard_constraints:
        aircraft=RIG_AIRCRAFT,
    params:
        groups=lambda wildcards: [g for g, m in enumerate(RIGS[wildcards.segment]["microphones"]) if m["kind"] == "plane"],
        level="bvispl_db",
        label=lambda wildcards: "BVISPL, BPF harmonics {}-{} (dB)".format(*settings(wildcards)["acoustics"]["bvispl_harmonics"]),
        title=lambda wildcards: f"{wildcards.segment}: NPS prediction",
        code=code("carpet"),
    log:
        log_path("carpet"),
    benchmark:
        bench_path("carpet")
    threads: 1
    resources:
        mem_mb=job_mem_mb("carpet"),
        runtime=job_runtime("carpet"),
    script:
        STAGE_SCRIPT


# C_n and M^2 C_n against azimuth at the rig's stations_r_over_R, every rotor (or each rotor's own
# rotors[].stations_r_over_R: nps.rig.case.station_params; nps.stages.station_loads), from the trimmed loads (base)
# or the loads with the wake's induced velocity (bvi)
rule station_loads:
    input:
        disks=variant_disks,
        trim=f"{BASE}/trim.parquet",
    output:
        table=f"{BASE}/station_loads/{{variant}}.parquet",
    wildcard_constraints:
        aircraft=RIG_AIRCRAFT,
    params:
        stations=lambda wildcards: station_params(RIGS[wildcards.segment])["stations"],
        rotors=lambda wildcards: station_params(RIGS[wildcards.segment])["rotors"],
        code=code("station_loads"),
    log:
        log_path("station_loads", "{aircraft}/{segment}_{variant}"),
    benchmark:
        bench_path("station_loads", "{aircraft}/{segment}_{variant}")
    threads: 1
    resources:  # a set-up-sized job (tables of one rotor each): the rig stage's requests
        mem_mb=job_mem_mb("rig"),
        runtime=job_runtime("rig"),
    script:
        STAGE_SCRIPT


rule rigs:
    input:
        [target for rig in RIGS for target in rig_targets(rig)],


for _rig in RIGS:
    rule:
        name: _rig
        input: rig_targets(_rig)
