# Rotor test cases (config/tests/*.yaml, nps.rig.case): an isolated rotor in hover or in a wind tunnel with
# hub-fixed microphones. The set-up (stage rotor_test) writes the trim row and the microphone table; the study's
# own stages then run: loads, wake (+ BVI loads) where models.bvi, acoustics, metrics, and the BVISPL carpet of
# plane microphone groups where metrics.carpet. Targets: `snakemake -j2 rotor_tests` (every test), or one test
# by its name (`snakemake -j2 hart_ii_bl`, `snakemake -j2 itr_hover`).
rule rotor_test:
    input:
        config=str(TESTS_DIR / "{test}.yaml"),
    output:
        trim=f"{TEST_RESULTS}/trim.parquet",
        observers=f"{TEST_RESULTS}/microphones.parquet",
    params:
        code=code("rotor_test"),
    log:
        f"{RESULTS}/logs/rotor_test/{{test}}.log",
    threads: 1
    resources:
        mem_mb=500,
        runtime=5,
    script:
        STAGE_SCRIPT


rule rotor_test_loads:
    input:
        trim=f"{TEST_RESULTS}/trim.parquet",
    output:
        loads=directory(f"{TEST_RESULTS}/loads"),
    params:
        rotors=rotor_test_rotors,
        n_psi=lambda wildcards: ROTOR_TESTS[wildcards.test]["resolution"]["n_psi"],
        n_r=lambda wildcards: ROTOR_TESTS[wildcards.test]["resolution"]["n_r"],
        aircraft=lambda wildcards: wildcards.test,
        segment="test",
        code=code("loads"),
    log:
        f"{RESULTS}/logs/rotor_test_loads/{{test}}.log",
    threads: 1
    resources:
        mem_mb=800,
        runtime=5,
    script:
        TEST_SCRIPT


rule rotor_test_wake:
    input:
        trim=f"{TEST_RESULTS}/trim.parquet",
        loads=f"{TEST_RESULTS}/loads",
    output:
        wake=directory(f"{TEST_RESULTS}/wake"),
        bvi=directory(f"{TEST_RESULTS}/bvi"),
    params:
        rotors=rotor_test_rotors,
        wake=config["wake"],
        revolutions=lambda wildcards: ROTOR_TESTS[wildcards.test]["resolution"]["wake_revolutions"],
        steps_per_rev=lambda wildcards: ROTOR_TESTS[wildcards.test]["resolution"]["n_psi"],
        aircraft=lambda wildcards: wildcards.test,
        segment="test",
        code=code("wake"),
    log:
        f"{RESULTS}/logs/rotor_test_wake/{{test}}.log",
    threads: 1
    resources:
        mem_mb=2000,
        runtime=10,
    script:
        TEST_SCRIPT


rule rotor_test_acoustics:
    input:
        disks=lambda wildcards: f"{RESULTS}/tests/{wildcards.test}/{'bvi' if test_variant(wildcards.test) == 'bvi' else 'loads'}",
        trim=f"{TEST_RESULTS}/trim.parquet",
        observers=f"{TEST_RESULTS}/microphones.parquet",
    output:
        signals=directory(f"{TEST_RESULTS}/acoustics"),
    params:
        rotors=lambda wildcards: list(rotor_test_rotors(wildcards)),
        thickness=lambda wildcards: ROTOR_TESTS[wildcards.test]["models"]["thickness"],
        chord_fractions=config["acoustics"]["dual_compact_chord_fractions"],
        samples_per_rev=lambda wildcards: ROTOR_TESTS[wildcards.test]["resolution"]["samples_per_rev"],
        hinge_offsets_m=lambda wildcards: {n: r.get("hinge_offset_m", 0.0) for n, r in rotor_test_rotors(wildcards).items()},
        aircraft=lambda wildcards: wildcards.test,
        segment="test",
        obsset="microphones",
        variant=lambda wildcards: test_variant(wildcards.test),
        code=code("acoustics"),
    log:
        f"{RESULTS}/logs/rotor_test_acoustics/{{test}}.log",
    threads: 1
    resources:
        mem_mb=2000,
        runtime=15,
    script:
        TEST_SCRIPT


rule rotor_test_metrics:
    input:
        signals=f"{TEST_RESULTS}/acoustics",
        trim=f"{TEST_RESULTS}/trim.parquet",
        observers=f"{TEST_RESULTS}/microphones.parquet",
    output:
        metrics=f"{TEST_RESULTS}/metrics.parquet",
        bands=f"{TEST_RESULTS}/metrics_bands.parquet",
        figure=f"{TEST_RESULTS}/spectrum.png",
    params:
        rotors=lambda wildcards: list(rotor_test_rotors(wildcards)),
        solidity=lambda wildcards: rotor_solidities({"rotors": list(rotor_test_rotors(wildcards).values())}),
        atmosphere=config["atmosphere"],
        broadband=False,
        absorption=False,
        harmonics=lambda wildcards: ROTOR_TESTS[wildcards.test]["metrics"]["bvispl_harmonics"],
        aircraft=lambda wildcards: wildcards.test,
        segment="test",
        obsset="microphones",
        variant=lambda wildcards: test_variant(wildcards.test),
        code=code("metrics"),
    log:
        f"{RESULTS}/logs/rotor_test_metrics/{{test}}.log",
    threads: 1
    resources:
        mem_mb=1500,
        runtime=10,
    script:
        TEST_SCRIPT


rule rotor_test_carpet:
    input:
        metrics=f"{TEST_RESULTS}/metrics.parquet",
        observers=f"{TEST_RESULTS}/microphones.parquet",
    output:
        figure=f"{TEST_RESULTS}/carpet.png",
    params:
        groups=lambda wildcards: [g for g, m in enumerate(ROTOR_TESTS[wildcards.test]["microphones"]) if m["kind"] == "plane"],
        level="bvispl_db",
        label=lambda wildcards: "BVISPL, BPF harmonics {}-{} (dB)".format(*ROTOR_TESTS[wildcards.test]["metrics"]["bvispl_harmonics"]),
        title=lambda wildcards: f"{wildcards.test}: NPS prediction",
        code=code("carpet"),
    log:
        f"{RESULTS}/logs/rotor_test_carpet/{{test}}.log",
    threads: 1
    resources:
        mem_mb=800,
        runtime=5,
    script:
        TEST_SCRIPT


rule rotor_tests:
    input:
        [t for test in ROTOR_TESTS for t in test_targets(test)],


for _test in ROTOR_TESTS:
    rule:
        name: _test
        input: test_targets(_test)
