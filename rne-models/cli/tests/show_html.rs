//! `rne show --format html`: the planar elbow's page is written where `--out` says, holds each
//! entry as MathML in a collapsible block, and renders as mathematics in a headless browser
//! (Debian's chromium; CI installs it, and a missing browser fails the test there).

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A fresh directory for one test's page.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rne-show-html-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// `rne show planar-elbow --format html --out DIR` (plus `extra`), its page's text.
fn page(dir: &Path, extra: &[&str]) -> String {
    let output = Command::new(env!("CARGO_BIN_EXE_rne"))
        .args(["show", "planar-elbow", "--format", "html", "--out"])
        .arg(dir)
        .args(extra)
        .output()
        .expect("run rne");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(stdout.contains("index.html"), "{stdout}");
    std::fs::read_to_string(dir.join("index.html")).expect("index.html written")
}

/// The MathML of `M` with subscript `i,j`.
fn m_label(i: usize, j: usize) -> String {
    format!("<msub><mi>M</mi><mrow><mn>{i}</mn><mo>,</mo><mn>{j}</mn></mrow></msub>")
}

#[test]
fn the_page_holds_every_entry_as_mathml_in_a_collapsible_block() {
    let dir = scratch("entries");
    let html = page(&dir, &[]);
    assert!(
        html.contains("<title>Equations of planar-elbow</title>"),
        "{html}"
    );
    for joint in ["<code>q1</code>", "<code>q2</code>"] {
        assert!(html.contains(joint), "{joint} missing");
    }
    for (i, j) in [(1, 1), (1, 2), (2, 2)] {
        let block = format!(
            "<details open><summary>M[{i},{j}]</summary><math display=\"block\">{}<mo>=</mo>",
            m_label(i, j)
        );
        assert!(html.contains(&block), "no block for M[{i},{j}]:\n{html}");
    }
    for entry in ["tau[1]", "tau[2]", "C[2,1]", "g[1]", "g[2]", "T", "V"] {
        assert!(
            html.contains(&format!("<summary>{entry}</summary>")),
            "{entry}"
        );
    }
    // M[1,1] = a + b c2: the cosine of the elbow angle as the thesis abbreviates it.
    assert!(html.contains("<msub><mi>c</mi><mn>2</mn></msub>"), "{html}");
    assert!(html.contains("<section id=\"program\">"), "{html}");
    assert!(html.contains("<msub><mi>c</mi><mn>2</mn></msub><mo>=</mo><mi>cos</mi>"));
    assert!(
        !html.contains("http"),
        "the page must not reach the network"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_size_limit_summarises_the_rest_and_says_how_to_get_an_entry() {
    let dir = scratch("limit");
    let html = page(&dir, &["--max-size", "2K"]);
    assert!(html.contains("entries printed"), "{html}");
    assert!(html.contains("--entry &quot;"), "{html}");
    assert!(html.contains("--format html --out"), "{html}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_page_needs_a_directory_that_can_be_written_before_any_work() {
    let run = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_rne"))
            .args(args)
            .output()
            .expect("run rne")
    };
    let no_dir = run(&["show", "planar-elbow", "--format", "html"]);
    assert_eq!(no_dir.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&no_dir.stderr).contains("--out DIR"));
    let bad = run(&[
        "show",
        "planar-elbow",
        "--format",
        "html",
        "--out",
        "/dev/null/x",
    ]);
    assert_eq!(bad.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--out /dev/null/x"));
    let text = run(&["show", "planar-elbow", "--out", "/tmp"]);
    assert_eq!(text.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&text.stderr).contains("--format html"));
}

/// Debian's chromium, if installed; under CI=true its absence fails the test.
fn chromium() -> Option<PathBuf> {
    let found = std::env::var_os("PATH")
        .into_iter()
        .flat_map(|p| std::env::split_paths(&p).collect::<Vec<_>>())
        .map(|d| d.join("chromium"))
        .find(|p| p.is_file());
    if found.is_none() {
        let ci = std::env::var("CI").is_ok_and(|v| v == "true");
        assert!(
            !ci,
            "chromium is not installed, and CI=true needs it (.ci/run installs it)"
        );
        println!("skipped: chromium is not installed (CI installs it)");
    }
    found
}

/// The DOM chromium builds for `page` after its scripts ran.
fn dump_dom(chromium: &Path, page: &Path, profile: &Path) -> String {
    let mut child = Command::new(chromium)
        .args(["--headless", "--disable-gpu", "--no-sandbox", "--dump-dom"])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("file://{}", page.display()))
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("start chromium");
    let start = Instant::now();
    while child.try_wait().expect("wait for chromium").is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            panic!("chromium did not finish in 60 s");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let output = child.wait_with_output().expect("chromium's output");
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// Measures, in the page, what only a MathML renderer gives: the first formula laid out as a
/// block of math (`display: block math`) with a height, and a subscript set below its base.
const PROBE: &str = "<script>
const math = document.querySelector('math');
const sub = document.querySelector('msub');
const base = sub.firstElementChild.getBoundingClientRect();
const script = sub.lastElementChild.getBoundingClientRect();
document.body.dataset.display = getComputedStyle(math).display;
document.body.dataset.height = math.getBoundingClientRect().height;
document.body.dataset.lowered = script.bottom - base.bottom;
</script>";

#[test]
fn chromium_renders_the_equations_as_mathematics() {
    let Some(chromium) = chromium() else { return };
    let dir = scratch("chromium");
    let html = page(&dir, &[]);
    let probe = dir.join("probe.html");
    std::fs::write(&probe, html.replace("</body>", &format!("{PROBE}</body>"))).unwrap();
    let dom = dump_dom(&chromium, &probe, &dir.join("profile"));
    assert!(dom.contains(&m_label(1, 1)), "no M[1,1] in the DOM:\n{dom}");
    let attribute = |name: &str| -> String {
        let start = dom
            .find(&format!("data-{name}=\""))
            .unwrap_or_else(|| panic!("the probe wrote no {name}:\n{dom}"))
            + name.len()
            + 7;
        dom[start..].split('"').next().unwrap().to_owned()
    };
    assert_eq!(attribute("display"), "block math");
    let height: f64 = attribute("height").parse().unwrap();
    assert!(height > 0.0, "the first formula has height {height}");
    let lowered: f64 = attribute("lowered").parse().unwrap();
    assert!(
        lowered > 0.0,
        "a subscript is not set below its base ({lowered})"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
