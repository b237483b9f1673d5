//! Measured joint trajectories: q, q̇, q̈ and τ per sample, read from and written to CSV.
//!
//! The first line names the columns: `q1 … qN`, `qd1 … qdN`, `qdd1 … qddN`, `tau1 … tauN`
//! for the N joints in the model's joint order (`rne check MODEL` lists it), in any order, and
//! on a floating base `q1 … q(NV+1)` and `qd1 … qdNV` (docs/design.md §4.5's layout: the base's
//! position and quaternion, its velocity, acceleration and wrench first), and
//! optionally `t` (time, s), which identification ignores. Every other line is one sample of
//! numbers separated by commas. Blank lines and lines starting with `#` are skipped. Errors
//! name the file, the line and the column.

use std::fmt::Write as _;
use std::path::Path;

use crate::IdentifyError;

/// One sample.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// Time, s, when the data have it.
    pub t: Option<f64>,
    /// Joint positions.
    pub q: Vec<f64>,
    /// Joint rates.
    pub qd: Vec<f64>,
    /// Joint accelerations.
    pub qdd: Vec<f64>,
    /// Joint torques (forces for prismatic joints).
    pub tau: Vec<f64>,
}

/// A joint trajectory of `joints` joints.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurements {
    /// Number of positions per sample (NQ: `joints`, or `joints + 1` on a floating base).
    pub positions: usize,
    /// Number of joints: rates, accelerations and forces per sample (NV).
    pub joints: usize,
    /// The samples in order.
    pub samples: Vec<Sample>,
}

/// The four signals of a sample, in column-name order.
const SIGNALS: [&str; 4] = ["q", "qd", "qdd", "tau"];

/// Where column `name` goes: `Some(None)` for time, `Some(Some((signal, joint)))` for a
/// signal of a joint, `None` if it is not a column of data of these `sizes` (per signal).
fn column_of(name: &str, sizes: [usize; 4]) -> Option<Option<(usize, usize)>> {
    if name == "t" {
        return Some(None);
    }
    // Longest prefix first: `qdd3` is not `qd` of joint `d3`.
    [2, 3, 1, 0].into_iter().find_map(|s| {
        let joint: usize = name.strip_prefix(SIGNALS[s])?.parse().ok()?;
        (1..=sizes[s])
            .contains(&joint)
            .then_some(Some((s, joint - 1)))
    })
}

/// The error of `file` at `line` (and `column`, its position and name).
fn data_error(
    file: &Path,
    line: usize,
    column: Option<(usize, String)>,
    message: String,
) -> IdentifyError {
    IdentifyError::Data {
        file: file.to_path_buf(),
        line,
        column,
        message,
    }
}

/// Where each of the header's columns `names` (on line `header_line` of `file`) goes, as
/// [`column_of`] says, for data of `sizes` entries per signal: every column known, none twice,
/// none of the signals' columns missing.
fn slots(
    file: &Path,
    header_line: usize,
    names: &[&str],
    sizes: [usize; 4],
) -> Result<Vec<Option<(usize, usize)>>, IdentifyError> {
    let error = |column, message| data_error(file, header_line, column, message);
    let expected = expected_header(sizes);
    let joints = sizes[1];
    let mut slots = Vec::with_capacity(names.len());
    let mut seen: Vec<Vec<bool>> = sizes.iter().map(|&n| vec![false; n]).collect();
    for (k, name) in names.iter().enumerate() {
        let column = Some((k + 1, (*name).to_owned()));
        let slot = column_of(name, sizes).ok_or_else(|| {
            error(
                column.clone(),
                format!("unknown column for a {joints}-joint model; expected {expected}"),
            )
        })?;
        if let Some((s, j)) = slot {
            if std::mem::replace(&mut seen[s][j], true) {
                return Err(error(column, "duplicate column".into()));
            }
        } else if slots.contains(&None) {
            return Err(error(column, "duplicate column".into()));
        }
        slots.push(slot);
    }
    let missing: Vec<String> = (0..sizes[0].max(joints))
        .flat_map(|j| (0..4).map(move |s| (j, s)))
        .filter(|&(j, s)| j < sizes[s] && !seen[s][j])
        .map(|(j, s)| format!("{}{}", SIGNALS[s], j + 1))
        .collect();
    if !missing.is_empty() {
        return Err(error(
            None,
            format!("missing columns {}", missing.join(", ")),
        ));
    }
    Ok(slots)
}

/// The sample on line `line` of `file`, `text`, its fields going to `slots` (the header's
/// columns `names`) of data of `sizes` entries per signal: as many fields as columns, each a
/// finite number.
fn parse_sample(
    file: &Path,
    (line, text): (usize, &str),
    names: &[&str],
    slots: &[Option<(usize, usize)>],
    sizes: [usize; 4],
) -> Result<Sample, IdentifyError> {
    let error = |column, message| data_error(file, line, column, message);
    let fields: Vec<&str> = text.split(',').map(str::trim).collect();
    if fields.len() != names.len() {
        return Err(error(
            None,
            format!("{} fields, the header has {}", fields.len(), names.len()),
        ));
    }
    let mut sample = Sample {
        t: None,
        q: vec![0.0; sizes[0]],
        qd: vec![0.0; sizes[1]],
        qdd: vec![0.0; sizes[2]],
        tau: vec![0.0; sizes[3]],
    };
    for (k, (field, slot)) in fields.iter().zip(slots).enumerate() {
        let column = || Some((k + 1, names[k].to_owned()));
        let value: f64 = field
            .parse()
            .map_err(|_| error(column(), format!("`{field}` is not a number")))?;
        if !value.is_finite() {
            return Err(error(column(), format!("`{field}` is not finite")));
        }
        match *slot {
            None => sample.t = Some(value),
            Some((s, j)) => sample.signal_mut(s)[j] = value,
        }
    }
    Ok(sample)
}

impl Measurements {
    /// Reads the CSV file `path` of data for `joints` joints (a fixed base).
    pub fn read(path: &Path, joints: usize) -> Result<Measurements, IdentifyError> {
        Measurements::read_sized(path, joints, joints)
    }

    /// Reads the CSV file `path` of data with `positions` entries of q and `joints` of the
    /// other signals (NQ and NV).
    pub fn read_sized(
        path: &Path,
        positions: usize,
        joints: usize,
    ) -> Result<Measurements, IdentifyError> {
        let text = std::fs::read_to_string(path).map_err(|cause| IdentifyError::Io {
            file: path.to_path_buf(),
            cause,
        })?;
        Measurements::parse_sized(&text, path, positions, joints)
    }

    /// Parses CSV `text` (from `file`, for messages) of data for `joints` joints.
    pub fn parse(text: &str, file: &Path, joints: usize) -> Result<Measurements, IdentifyError> {
        Measurements::parse_sized(text, file, joints, joints)
    }

    /// Parses CSV `text` (from `file`, for messages) of data with `positions` entries of q and
    /// `joints` of the other signals.
    pub fn parse_sized(
        text: &str,
        file: &Path,
        positions: usize,
        joints: usize,
    ) -> Result<Measurements, IdentifyError> {
        let sizes = [positions, joints, joints, joints];
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(k, l)| (k + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let (header_line, header) = lines.next().ok_or_else(|| {
            let expected = expected_header(sizes);
            data_error(
                file,
                1,
                None,
                format!("no header; expected the columns {expected}"),
            )
        })?;
        let names: Vec<&str> = header.split(',').map(str::trim).collect();
        let slots = slots(file, header_line, &names, sizes)?;
        let mut samples = Vec::new();
        for (line, text) in lines {
            samples.push(parse_sample(file, (line, text), &names, &slots, sizes)?);
        }
        if samples.is_empty() {
            return Err(data_error(
                file,
                header_line,
                None,
                "no samples after the header".into(),
            ));
        }
        Ok(Measurements {
            positions,
            joints,
            samples,
        })
    }

    /// The CSV text: a header `t, q1…, qd1…, qdd1…, tau1…` (no `t` if the first sample has no
    /// time), then one line per sample with every number in Rust's shortest round-trip form.
    pub fn to_csv(&self) -> String {
        let timed = self.samples.first().is_some_and(|s| s.t.is_some());
        let mut header: Vec<String> = Vec::new();
        if timed {
            header.push("t".into());
        }
        for (s, signal) in SIGNALS.iter().enumerate() {
            let size = if s == 0 { self.positions } else { self.joints };
            header.extend((1..=size).map(|j| format!("{signal}{j}")));
        }
        let mut out = header.join(",");
        out.push('\n');
        for sample in &self.samples {
            let mut fields: Vec<f64> = Vec::new();
            if timed {
                fields.push(sample.t.unwrap_or(f64::NAN));
            }
            for s in 0..4 {
                fields.extend(sample.signal(s));
            }
            let line: Vec<String> = fields.iter().map(f64::to_string).collect();
            let _ = writeln!(out, "{}", line.join(","));
        }
        out
    }

    /// Writes [`Measurements::to_csv`] to `path`, creating its directory.
    pub fn write(&self, path: &Path) -> Result<(), IdentifyError> {
        let io = |cause| IdentifyError::Io {
            file: path.to_path_buf(),
            cause,
        };
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(io)?;
        }
        std::fs::write(path, self.to_csv()).map_err(io)
    }
}

impl Sample {
    fn signal(&self, s: usize) -> &[f64] {
        [&self.q, &self.qd, &self.qdd, &self.tau][s]
    }

    fn signal_mut(&mut self, s: usize) -> &mut [f64] {
        match s {
            0 => &mut self.q,
            1 => &mut self.qd,
            2 => &mut self.qdd,
            _ => &mut self.tau,
        }
    }
}

/// `q1..qN, qd1..qdN, qdd1..qddN, tau1..tauN (and optionally t)`.
fn expected_header(sizes: [usize; 4]) -> String {
    let list: Vec<String> = SIGNALS
        .iter()
        .zip(sizes)
        .map(|(s, n)| format!("{s}1..{s}{n}"))
        .collect();
    format!("{} (and optionally t)", list.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Measurements, IdentifyError> {
        Measurements::parse(text, Path::new("data.csv"), 2)
    }

    /// Columns in any order, comments and blank lines, and a CSV round trip.
    #[test]
    fn reads_columns_by_name_and_round_trips() {
        let text =
            "# measured\ntau2,q1,q2,qd1,qd2,qdd1,qdd2,tau1,t\n\n4,1,2,0.5,0.25,-1,-2,3,0.01\n";
        let m = parse(text).expect("valid");
        let s = &m.samples[0];
        assert_eq!(
            (s.q.clone(), s.tau.clone(), s.t),
            (vec![1.0, 2.0], vec![3.0, 4.0], Some(0.01))
        );
        assert_eq!(parse(&m.to_csv()).expect("round trip"), m);
    }

    /// Each kind of bad data is an error that names the file, the line and the column.
    #[test]
    fn bad_data_names_file_line_and_column() {
        let header = "q1,q2,qd1,qd2,qdd1,qdd2,tau1,tau2";
        let cases = [
            (
                format!("{header}\n1,2,3,4,5,6,7,x\n"),
                "data.csv:2: column 8 (`tau2`): `x` is not a number",
            ),
            (
                format!("{header}\n1,2,3,4,5,6,7,inf\n"),
                "data.csv:2: column 8 (`tau2`): `inf` is not finite",
            ),
            (
                format!("{header}\n1,2,3\n"),
                "data.csv:2: 3 fields, the header has 8",
            ),
            (
                format!("{header},tau3\n"),
                "data.csv:1: column 9 (`tau3`): unknown column",
            ),
            (
                format!("{header},q1\n"),
                "data.csv:1: column 9 (`q1`): duplicate column",
            ),
            (
                "q1,q2\n1,2\n".to_owned(),
                "data.csv:1: missing columns qd1, qdd1, tau1, qd2",
            ),
            (
                format!("{header}\n"),
                "data.csv:1: no samples after the header",
            ),
            (String::new(), "data.csv:1: no header"),
        ];
        for (text, message) in cases {
            let error = parse(&text).expect_err(message).to_string();
            assert!(error.starts_with(message), "{error}\nexpected: {message}");
        }
    }
}
