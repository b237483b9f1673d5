//! The record of a run at its output times, and its CSV form.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

use super::integrator::Stats;

/// A simulated run sampled at its output times: the time series behind the thesis's figures
/// 6.2–6.21, one entry per output time in every vector.
#[derive(Clone, Debug, PartialEq)]
pub struct Record<const N: usize> {
    /// Output times (s).
    pub t: Vec<f64>,
    /// Joint positions q.
    pub q: Vec<[f64; N]>,
    /// Joint velocities q̇.
    pub qd: Vec<[f64; N]>,
    /// The input u(t, q, q̇) applied at that state, after saturation.
    pub u: Vec<[f64; N]>,
    /// Kinetic energy ½ q̇ᵀ M(q) q̇ of the simulated model (J).
    pub kinetic: Vec<f64>,
    /// Potential energy V(q) of the simulated model (J); zero for a gravity-free model.
    pub potential: Vec<f64>,
    /// Total energy, kinetic + potential (J): constant for a released arm without friction
    /// (figures 6.8 and 6.17).
    pub total: Vec<f64>,
    /// The Lyapunov function V = ½ q̇ᵀ M q̇ + ½ q̃ᵀ Kp q̃ of (6.57), when the input has a
    /// proportional term ([`Controller::spring_energy`](super::Controller::spring_energy)).
    pub lyapunov: Option<Vec<f64>>,
    /// The integrator's work.
    pub stats: Stats,
}

impl<const N: usize> Record<N> {
    /// An empty record with room for `capacity` samples.
    pub(crate) fn with_capacity(capacity: usize, lyapunov: bool) -> Self {
        Self {
            t: Vec::with_capacity(capacity),
            q: Vec::with_capacity(capacity),
            qd: Vec::with_capacity(capacity),
            u: Vec::with_capacity(capacity),
            kinetic: Vec::with_capacity(capacity),
            potential: Vec::with_capacity(capacity),
            total: Vec::with_capacity(capacity),
            lyapunov: lyapunov.then(|| Vec::with_capacity(capacity)),
            stats: Stats::default(),
        }
    }

    /// The number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether there are no samples.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// The CSV header: `t,q1,…,qN,qd1,…,qdN,u1,…,uN,kinetic,potential,total[,lyapunov]`.
    pub fn csv_header(&self) -> String {
        let mut cols = vec!["t".to_string()];
        for prefix in ["q", "qd", "u"] {
            cols.extend((1..=N).map(|i| format!("{prefix}{i}")));
        }
        cols.extend(["kinetic", "potential", "total"].map(String::from));
        if self.lyapunov.is_some() {
            cols.push("lyapunov".into());
        }
        cols.join(",")
    }

    /// Writes the record as CSV: the header of [`Record::csv_header`], then one line per
    /// sample. Numbers use Rust's shortest round-trip formatting, so reading them back gives
    /// the same `f64` values.
    pub fn write_csv<W: Write>(&self, mut w: W) -> io::Result<()> {
        writeln!(w, "{}", self.csv_header())?;
        for k in 0..self.len() {
            write!(w, "{}", self.t[k])?;
            for v in self.q[k].iter().chain(&self.qd[k]).chain(&self.u[k]) {
                write!(w, ",{v}")?;
            }
            write!(
                w,
                ",{},{},{}",
                self.kinetic[k], self.potential[k], self.total[k]
            )?;
            if let Some(v) = &self.lyapunov {
                write!(w, ",{}", v[k])?;
            }
            writeln!(w)?;
        }
        w.flush()
    }

    /// Writes the record as CSV to the file at `path`, creating or truncating it.
    pub fn save_csv(&self, path: impl AsRef<Path>) -> io::Result<()> {
        self.write_csv(BufWriter::new(File::create(path)?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Record<2> {
        let mut r = Record::with_capacity(2, true);
        for (k, t) in [0.0, 0.5].into_iter().enumerate() {
            let k = k as f64;
            r.t.push(t);
            r.q.push([1.0 + k, 2.0]);
            r.qd.push([0.1, -0.2]);
            r.u.push([39.4, -1e-300]);
            r.kinetic.push(1.0 / 3.0);
            r.potential.push(-2.5);
            r.total.push(1.0 / 3.0 - 2.5);
            r.lyapunov.as_mut().unwrap().push(7.0);
        }
        r
    }

    /// The CSV has the documented header, one line per sample, and round-trips every number.
    #[test]
    fn csv_header_and_round_trip() {
        let r = sample();
        let mut buf = Vec::new();
        r.write_csv(&mut buf).unwrap();
        let text = String::from_utf8(buf).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(
            lines[0],
            "t,q1,q2,qd1,qd2,u1,u2,kinetic,potential,total,lyapunov"
        );
        assert_eq!(lines.len(), 3);
        let values: Vec<f64> = lines[2].split(',').map(|v| v.parse().unwrap()).collect();
        assert_eq!(values.len(), 11);
        assert_eq!(values[0], 0.5);
        assert_eq!(values[1], 2.0);
        assert_eq!(values[6], -1e-300);
        assert_eq!(values[7], 1.0 / 3.0);
        assert_eq!(values[9], 1.0 / 3.0 - 2.5);

        let mut plain = r.clone();
        plain.lyapunov = None;
        assert!(plain.csv_header().ends_with(",total"));
        let dir = std::env::temp_dir().join(format!("rne-sim-csv-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("run.csv");
        plain.save_csv(&path).unwrap();
        let saved = std::fs::read_to_string(&path).unwrap();
        assert_eq!(saved.lines().count(), 3);
        assert_eq!(saved.lines().nth(1).unwrap().split(',').count(), 10);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
