//! `rne show` on robots whose equations run to megabytes: the size limit, one entry, the
//! compact program, and the round-off that cancels (the UR5's g1, identically 0).

mod common;
use common::rne;

use std::time::{Duration, Instant};

/// The line `label = ...` of an output.
fn line<'a>(out: &'a str, label: &str) -> &'a str {
    out.lines()
        .find(|l| l.starts_with(&format!("{label} = ")))
        .unwrap_or_else(|| panic!("no {label} in\n{out}"))
}

#[test]
fn the_ur5_gravity_torque_about_its_vertical_axis_is_exactly_zero() {
    let out = rne(&["show", "ur5", "--what", "g"]).unwrap();
    assert_eq!(line(&out, "g1"), "g1 = 0");
    assert!(!out.contains("e-1"), "a round-off term is left:\n{out}");
}

#[test]
fn literal_angles_keep_the_round_off_of_cos_half_pi_in_the_kernels() {
    let stats = |extra: &[&str]| {
        let mut args = vec!["stats", "ur5", "--json"];
        args.extend(extra);
        let json: serde_json::Value = serde_json::from_str(&rne(&args).unwrap()).unwrap();
        json["kernels"]
            .as_array()
            .unwrap()
            .iter()
            .find(|k| k["kernel"] == "mass_matrix")
            .unwrap()["cost"]
            .as_u64()
            .unwrap()
    };
    let (exact, literal) = (stats(&[]), stats(&["--literal-angles"]));
    assert!(
        exact < literal,
        "exact right angles {exact}, literal {literal}"
    );
}

#[test]
fn a_limit_prints_the_entries_that_fit_and_lists_the_rest_by_size() {
    let out = rne(&["show", "panda", "--what", "M", "--max-size", "20K"]).unwrap();
    let note = out
        .find("entries printed")
        .unwrap_or_else(|| panic!("no note of what was left out:\n{out}"));
    assert!(
        out[..note].len() <= 20_000 + 200,
        "{} bytes before the note",
        note
    );
    assert!(out.contains("--entry \"M["), "{out}");
    assert!(out.contains("--compact"), "{out}");
}

#[test]
fn one_entry_is_printed_alone_and_a_missing_one_is_named() {
    let out = rne(&["show", "ur5", "--what", "M", "--entry", "M[2,3]"]).unwrap();
    let entries: Vec<&str> = out.lines().filter(|l| l.contains(" = ")).collect();
    assert_eq!(entries.len(), 1, "{out}");
    assert!(entries[0].starts_with("M[2,3] = "), "{out}");
    let missing = rne(&["show", "ur5", "--what", "M", "--entry", "M[9,9]"]).unwrap_err();
    assert!(
        missing.contains("M[9,9]") && missing.contains("M[1,1]"),
        "{missing}"
    );
}

#[test]
fn the_compact_program_computes_each_entry_once_from_named_quantities() {
    let out = rne(&["show", "planar-elbow", "--what", "M", "--compact"]).unwrap();
    for name in ["c2 = cos(q2)", "M[1,1] = ", "M[1,2] = ", "M[2,2] = "] {
        assert!(out.contains(name), "{name} missing:\n{out}");
    }
    let latex = rne(&[
        "show",
        "planar-elbow",
        "--what",
        "M",
        "--compact",
        "--format",
        "latex",
    ]);
    assert!(latex.unwrap().contains("c_{2} &= \\cos(q_{2}) \\\\"));
}

#[test]
fn a_large_robot_stops_at_the_limit_within_seconds() {
    let start = Instant::now();
    let out = rne(&["show", "panda", "--max-size", "100K"]).unwrap();
    let elapsed = start.elapsed();
    assert!(out.len() < 100_000 + 4_000, "{} bytes", out.len());
    assert!(out.contains("entries printed"), "{out}");
    assert!(elapsed < Duration::from_secs(60), "{elapsed:?}");
}

/// A floating-base robot of 23 degrees of freedom (the Baxter fixture), whose every torque
/// depends on the base's orientation: `rne show` stays within the limit, lists every entry it
/// did not print (by size when it printed it, else by name and count), and ends with the
/// commands that print one entry or the compact form.
#[test]
fn a_floating_base_robot_stays_within_the_limit_and_ends_with_the_pointer() {
    let urdf = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../corpus/tests/fixtures/baxter.urdf"
    );
    let out = rne(&["show", urdf, "--floating-base", "--max-size", "100K"]).unwrap();
    let note = out
        .find("entries printed")
        .unwrap_or_else(|| panic!("no note of what was left out:\n{out}"));
    // The header: the robot's line and the floating base's notation, before the first blank
    // line.
    let header = out.find("\n\n").expect("a blank line after the header");
    assert!(out[..header].contains("\n# floating base: "), "{out}");
    assert!(
        note <= header + 100_000 + 100,
        "{note} bytes before the note"
    );
    let last = out.lines().last().unwrap();
    assert!(last.starts_with("# one entry: rne show "), "{last}");
    assert!(last.contains(" --floating-base --entry \""), "{last}");
    assert!(last.ends_with(" --floating-base --compact"), "{last}");
    let entry = |l: &&str| !l.starts_with('#') && l.contains(" = ");
    let printed = out.lines().filter(entry).count();
    assert!(printed > 0, "the cheapest entries are printed:\n{out}");
    let note = out[..note].rfind('\n').map_or(0, |i| i + 1);
    let summary = out[note..].lines().next().unwrap();
    let total: usize = summary
        .split(" of ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("no total in {summary}"));
    assert_eq!(total, 23 + 276 + 529 + 23 + 2, "tau, M, C, g, T and V");
    assert_eq!(listed(&out[note..]) + printed, total, "{}", &out[note..]);
}

/// The entries a note lists: one a line by size (`  M[1,2]   12.0 KB`), `… and N more`, and
/// by name and count (`  C: 529 entries, C[1,1] … C[23,23]`, or one name alone).
fn listed(note: &str) -> usize {
    note.lines()
        .filter_map(|l| l.strip_prefix("#   "))
        .map(|l| {
            let count = |text: &str, marker: &str| {
                text.split(marker).next()?.rsplit(' ').next()?.parse().ok()
            };
            count(l, " entries,")
                .or_else(|| l.strip_prefix("… and ").and_then(|t| count(t, " more")))
                .unwrap_or(1)
        })
        .sum()
}
