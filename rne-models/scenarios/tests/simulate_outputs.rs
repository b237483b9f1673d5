//! What `rne simulate` writes: CSV tables, SVG and PNG figures that are valid, non-empty
//! images, findings; the scenario list; user scenario files on the generated kernels and on
//! the expression graph; errors that name what is wrong.

use std::path::{Path, PathBuf};

use rne_scenarios::{find, FileEngine, Format, RunOptions, UserScenario, SCENARIOS};

/// A fresh directory under the system's temporary directory.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rne-simulate-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The width and height of a PNG file, after checking its signature and IHDR chunk.
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    assert_eq!(&bytes[12..16], b"IHDR", "first chunk");
    let word = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
    assert!(bytes.ends_with(b"IEND\xae\x42\x60\x82"), "IEND chunk");
    (word(16), word(20))
}

/// The PD scenario of figure 6.12 writes its CSV (one row per 10 ms over 10 s), an SVG that is
/// a complete document with its title and one polyline per curve, a PNG of the expected size
/// with real content, and its findings.
#[test]
fn pd_scenario_writes_csv_and_valid_images() {
    let dir = temp_dir("pd");
    let outcome = find("elbow-pd-1")
        .unwrap()
        .run(&RunOptions::default())
        .unwrap();
    let written = outcome.write(&dir, &Format::ALL).unwrap();
    assert_eq!(written.len(), 4, "{written:?}");

    let csv = std::fs::read_to_string(dir.join("elbow-pd-1.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t,q1,q2,qd1,qd2,u1,u2,kinetic,potential,total,lyapunov"
    );
    assert_eq!(lines.count(), 1001);

    let svg = std::fs::read_to_string(dir.join("fig6.12-elbow-pd-1.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert!(svg.contains("Figure 6.12"), "title");
    assert_eq!(svg.matches("<svg").count(), 1);
    // Two joint angles and two torques as polylines (references are dashed segments).
    assert!(svg.matches("<polyline").count() >= 4);
    assert!(svg.contains("t (s)") && svg.contains("q (rad)"));

    let png = std::fs::read(dir.join("fig6.12-elbow-pd-1.png")).unwrap();
    assert_eq!(png_size(&png), (1000, 44 + 2 * 300));
    // A blank 1000 x 644 image compresses to about 2 kB; curves, grid and text make it larger.
    assert!(png.len() > 20_000, "{} bytes", png.len());

    let findings = std::fs::read_to_string(dir.join("elbow-pd-1-findings.md")).unwrap();
    assert!(findings.contains("settling time") && findings.contains("3–4 s"));
    assert!(findings
        .lines()
        .all(|l| l.matches('|').count() - l.matches("\\|").count() == 4));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every thesis experiment is listed once, with the figures it reproduces, and can be found by
/// name.
#[test]
fn scenario_list_covers_chapter_6() {
    let mut names: Vec<&str> = SCENARIOS.iter().map(|s| s.name).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), SCENARIOS.len());
    let figures: String = SCENARIOS
        .iter()
        .map(|s| format!("{} ", s.figures))
        .collect();
    for figure in [
        "6.2", "6.3", "6.4", "6.8", "6.10", "6.12", "6.15", "6.16", "6.19", "6.21", "6.4 ",
    ] {
        assert!(figures.contains(figure), "{figure} missing from {figures}");
    }
    assert!(find("lyapunov").is_some() && find("nothing").is_none());
}

/// Writes a scenario file into `dir` and loads it.
fn scenario_file(dir: &Path, name: &str, text: &str) -> UserScenario {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    UserScenario::load(&path).unwrap()
}

/// A user scenario runs PD control with gravity compensation through the same machinery: on
/// the built-in robot's generated kernels and on the expression graph of the same spec file,
/// the runs agree to 1e-8 rad, and adding g(q) to the unsaturated input ("compensate") moves
/// the arm like removing g from the model ("remove", the thesis's way).
#[test]
fn user_scenarios_run_on_generated_kernels_and_on_the_expression_graph() {
    let dir = temp_dir("user");
    let spec = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/planar-elbow.toml"
    );
    let body = |model: &str, gravity: &str| {
        format!(
            "model = \"{model}\"\nduration = 2.0\nsample = 0.05\nq0 = [0.0, 0.0]\n\n\
             [controller]\nkp = [22, 45]\nkd = [15, 8]\nq_ref = [0.3, -0.2]\ngravity = \"{gravity}\"\n\n\
             [integrator]\nmethod = \"dopri5\"\nrtol = 1e-10\natol = 1e-12\n"
        )
    };
    let options = RunOptions::default();
    let builtin = scenario_file(&dir, "builtin.toml", &body("planar-elbow", "remove"));
    let graph = scenario_file(&dir, "graph.toml", &body(spec, "remove"));
    let added = scenario_file(&dir, "added.toml", &body("planar-elbow", "compensate"));
    let last_q = |s: &UserScenario| {
        let outcome = s.run(&options).unwrap();
        outcome.write(&dir, &[Format::Csv, Format::Svg]).unwrap();
        let csv = std::fs::read_to_string(dir.join(format!("{}.csv", s.name()))).unwrap();
        let last: Vec<f64> = csv
            .lines()
            .last()
            .unwrap()
            .split(',')
            .map(|v| v.parse().unwrap())
            .collect();
        assert_eq!(last[0], 2.0);
        [last[1], last[2]]
    };
    let (a, b, c) = (last_q(&builtin), last_q(&graph), last_q(&added));
    eprintln!("generated {a:?}, graph {b:?}, compensated {c:?}");
    for i in 0..2 {
        assert!((a[i] - b[i]).abs() < 1e-8, "{a:?} {b:?}");
        assert!((a[i] - c[i]).abs() < 1e-8, "{a:?} {c:?}");
    }
    assert!((a[0] - 0.3).abs() < 1e-2, "{a:?}");
    assert!(dir.join("builtin.svg").exists() && !dir.join("builtin.png").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A scenario file's robot read from a file runs on its kernels compiled in memory by default
/// and on its programs interpreted on request: the same operations in the same order (fma
/// off), so the two runs' tables are the same text, digit for digit.
#[test]
fn a_file_robot_runs_on_the_jit_exactly_as_on_the_interpreter() {
    let dir = temp_dir("engines");
    let spec = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/planar-elbow.toml"
    );
    let text = format!(
        "model = \"{spec}\"\nduration = 1.0\nsample = 0.05\nq0 = [0.4, -0.1]\n\n\
         [controller]\nkp = [22, 45]\nkd = [15, 8]\nq_ref = [0.3, -0.2]\ngravity = \"compensate\"\n\n\
         [integrator]\nmethod = \"dopri5\"\nrtol = 1e-10\natol = 1e-12\n"
    );
    let scenario = scenario_file(&dir, "file-robot.toml", &text);
    let tables = |engine: FileEngine| {
        let options = RunOptions {
            engine,
            ..RunOptions::default()
        };
        let outcome = scenario.run(&options).unwrap();
        outcome
            .tables
            .iter()
            .map(|t| t.csv.clone())
            .collect::<Vec<_>>()
    };
    let (jit, interpreted) = (tables(FileEngine::Jit), tables(FileEngine::Interpreted));
    assert!(!jit.is_empty() && jit[0].lines().count() > 10);
    assert_eq!(jit, interpreted);
    std::fs::remove_dir_all(&dir).unwrap();
}
