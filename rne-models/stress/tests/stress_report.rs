//! What `rne stress --quick --out DIR` writes: every case runs, the report has a section, a
//! table and an explanation per case, and the figures are written as SVG and PNG; the kernels
//! compiled in memory give the interpreter's report.

use rne_stress::{Effort, Engine, Settings};

#[test]
fn quick_stress_report_is_written() {
    let dir = std::env::temp_dir().join(format!("rne-stress-{}", std::process::id()));
    let quick = |engine| Settings {
        effort: Effort::Quick,
        engine,
    };
    let report = rne_stress::run(quick(Engine::Jit), |_| {}).unwrap();
    // The compiled programs perform the interpreter's operations in its order: the same bits,
    // so the same report, every figure included, but for the wall-clock times of the chaotic
    // runs (section 6, which runs the compiled elbow under either engine).
    let interpreted = rne_stress::run(quick(Engine::Interpreted), |_| {}).unwrap();
    assert_eq!(
        without_section_6(&report.markdown()),
        without_section_6(&interpreted.markdown())
    );
    let written = report.write(&dir).unwrap();
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(written.contains(&dir.join("report.md")));
    for section in 0..=8 {
        assert!(
            report.contains(&format!("\n## {section}. ")),
            "section {section}"
        );
    }
    assert!(!report.contains("NaN |"), "a table has NaN entries");
    let robots = rne_models::BUILTIN_ROBOTS.len();
    assert_eq!(
        report.matches(" | all |").count(),
        robots,
        "compiled kernels = graph"
    );
    assert!(report.contains("| 0 | 0 |"), "non-finite table");
    for figure in [
        "stress-conditioning",
        "stress-chaos-energy",
        "stress-chaos-divergence",
        "stress-joint-count",
    ] {
        for ext in ["svg", "png"] {
            let path = dir.join(format!("{figure}.{ext}"));
            let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
            assert!(size > 1000, "{} is missing or empty", path.display());
        }
        assert!(report.contains(&format!("({figure}.svg)")));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `report` without its section 6 (the chaotic runs, whose table has wall-clock times).
fn without_section_6(report: &str) -> String {
    let start = report.find("\n## 6. ").expect("section 6");
    let end = report.find("\n## 7. ").expect("section 7");
    assert!(end - start > 1000, "section 6 is the chaotic runs' tables");
    format!("{}{}", &report[..start], &report[end..])
}
