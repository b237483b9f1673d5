//! The short seeded run CI makes (docs/fuzzing.md): each target for a fixed number of inputs
//! from a fixed seed, with no failure: no panic, no hang, no reader error that does not name
//! the file, no malformed model or module. The long runs use the `rne-fuzz` command.

use rne_fuzz::{repository_root, run, Config, Report, Target};

/// The seed of CI's run.
const SEED: u64 = 20_261_127;

fn seeded_run(target: Target, iterations: u64) -> Report {
    // Chains of at most 100 copied links: a debug build reads a 3000-link chain in seconds.
    let config = Config {
        longest_chain: 100,
        ..Config::iterations(repository_root(), SEED, iterations)
    };
    let report = run(target, &config, &mut |_| {}).expect("the seed files are readable");
    println!("{report}");
    assert_eq!(report.inputs, iterations);
    assert_eq!(report.failure_count, 0, "{report}");
    report
}

#[test]
fn the_urdf_reader_survives_a_seeded_run() {
    let report = seeded_run(Target::Urdf, 600);
    // Mutants both load and fail: the mutations neither leave the files alone nor only break
    // them.
    assert!(report.loaded > 30 && report.rejected > 300, "{report}");
}

#[test]
fn the_toml_reader_survives_a_seeded_run() {
    let report = seeded_run(Target::Toml, 400);
    assert!(report.loaded > 30 && report.rejected > 300, "{report}");
}

#[test]
fn the_generator_survives_a_seeded_run() {
    let report = seeded_run(Target::Generate, 30);
    assert!(report.generated > 10, "{report}");
}
