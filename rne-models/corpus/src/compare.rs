//! One URDF against Pinocchio: rne reads it, sets the base, constrains mimic followers (URDF
//! semantics, Pinocchio's `mimic=True`), maps Pinocchio's states onto its own joint order by
//! joint name, and compares inverse dynamics, M, g, the bias and forward dynamics from the
//! interpreted symbolic kernels (exactly the programs `derive_dynamics!` emits) and from the
//! numeric reference.
//!
//! Errors are relative to the robot's scale over the states: torque-like outputs (τ, g, bias)
//! to the torque scale S = the largest |entry| of Pinocchio's τ, g, bias and the forward
//! dynamics' input forces; M to its largest |entry|; forward dynamics by the forces its error
//! stands for, |M_pin (q̈_rne − q̈_pin)| / S, which does not grow with the conditioning of M.

use std::path::Path;
use std::time::{Duration, Instant};

use rne_codegen::Kernel;
use rne_reference::Reference;
use rne_symbolic::model::Base;
use rne_symbolic::spec::{LoadOptions, SpecWarningKind};
use rne_symbolic::RobotModel;
use rne_symbolic::{read_robot, Description};

use super::kernels::{check_every_kernel, KernelCheck};
use super::values::{BaseValues, RobotValues, State};
use rne_interpreted::{Interpreted, StateRef};

/// Seeded random states per robot and base at which every kernel is compared with the
/// reference ([`check_every_kernel`]), and their seed.
pub const KERNEL_STATES: usize = 4;
const KERNEL_SEED: u64 = 2026;

/// [`BaseValues::mimic`] of values computed with every mimic follower a joint of its own.
pub(crate) const FREE: &str = "free";

/// The kernels compared with Pinocchio.
pub const CORPUS_KERNELS: [Kernel; 5] = [
    Kernel::InverseDynamics,
    Kernel::MassMatrix,
    Kernel::GravityTorques,
    Kernel::BiasTorques,
    Kernel::ForwardDynamics,
];

/// What rne made of one URDF, on both bases.
#[derive(Clone, Debug)]
pub struct RobotReport {
    /// The file, relative to the robots directory.
    pub file: String,
    /// rne's reading as the file describes it: the joint variables with mimic followers
    /// constrained and the warnings, or the error.
    pub load: Result<Loaded, String>,
    /// Bolted to the world.
    pub fixed: CaseReport,
    /// On a free-flyer.
    pub floating: CaseReport,
}

/// A file rne read.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// Joint variables with mimic followers constrained (fixed base).
    pub dof: usize,
    /// What each warning is about, in a few words.
    pub warnings: Vec<&'static str>,
}

/// One file on one base.
#[derive(Clone, Debug)]
pub enum CaseReport {
    /// Both loaded it and were compared.
    Compared(Comparison),
    /// Pinocchio could not load it (its message).
    PinocchioRefuses(String),
    /// rne could not load or use it while Pinocchio could (rne's message).
    RneRefuses(String),
    /// A fixed base and no moving joint: Pinocchio has an empty model, rne says nothing moves.
    NothingMoves,
}

/// rne against Pinocchio on one base.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// Size of the velocity.
    pub nv: usize,
    /// How Pinocchio applied the mimic joints (`none`, `pinocchio`, `projected`, `free`).
    pub mimic: String,
    /// Time to build the interpreted programs of the compared kernels.
    pub generation: Duration,
    /// The interpreted symbolic kernels' errors.
    pub symbolic: Errors,
    /// The numeric reference's errors.
    pub numeric: Errors,
    /// Why forward dynamics was not compared, when it was not.
    pub forward_skipped: Option<String>,
    /// Every kernel the generator can emit against the numeric reference
    /// ([`check_every_kernel`]).
    pub kernels: Vec<KernelCheck>,
}

/// Largest relative errors over the states (see the module docs for the scales).
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct Errors {
    /// Inverse dynamics.
    pub tau: f64,
    /// Mass matrix.
    pub mass_matrix: f64,
    /// Gravity torques.
    pub gravity: f64,
    /// Bias forces.
    pub bias: f64,
    /// Forward dynamics, when compared.
    pub forward: Option<f64>,
}

impl Errors {
    /// The largest error and the quantity it belongs to.
    pub fn max(&self) -> (f64, &'static str) {
        let mut all = vec![
            (self.tau, "ID"),
            (self.mass_matrix, "M"),
            (self.gravity, "g"),
            (self.bias, "bias"),
        ];
        all.extend(self.forward.map(|e| (e, "FD")));
        all.into_iter().fold((0.0, "ID"), |best, e| {
            if e.0 > best.0 || e.0.is_nan() {
                e
            } else {
                best
            }
        })
    }
}

/// Reads `dir/values.file` and compares it with Pinocchio on both bases: with mimic followers
/// constrained, or, where Pinocchio's values treat every follower as a joint of its own
/// (`mimic` = `free`), as rne reads the file with [`LoadOptions::free_mimic`].
pub fn check_robot(dir: &Path, values: &RobotValues) -> RobotReport {
    let path = dir.join(&values.file);
    let read = read_robot(Description::file(&path), &LoadOptions::default());
    let free = LoadOptions {
        free_mimic: true,
        ..LoadOptions::default()
    };
    let read_free = [&values.fixed, &values.floating]
        .iter()
        .any(|v| v.mimic.as_deref() == Some(FREE))
        .then(|| read_robot(Description::file(&path), &free));
    // Messages name the file relative to the robots directory, as the table does.
    let prefix = format!("{}/", dir.display());
    let relative = |e: &dyn std::fmt::Display| e.to_string().replace(&prefix, "");
    let load = read.as_ref().map_err(|e| relative(e)).and_then(|model| {
        let mut constrained = model.clone();
        constrained
            .constrain_mimic_joints()
            .map_err(|e| e.to_string())?;
        Ok(Loaded {
            dof: constrained.dof(),
            warnings: model
                .warnings
                .iter()
                .map(|w| warning_kind(w.kind()))
                .collect(),
        })
    });
    let case = |base: Base, pinocchio: &BaseValues| {
        let free = pinocchio.mimic.as_deref() == Some(FREE);
        let read = match &read_free {
            Some(read_free) if free => read_free,
            _ => &read,
        };
        match (read, &pinocchio.error) {
            (_, Some(error)) => CaseReport::PinocchioRefuses(relative(error)),
            (Err(error), None) => CaseReport::RneRefuses(relative(error)),
            (Ok(model), None) => case_report(model, base, pinocchio, free),
        }
    };
    RobotReport {
        file: values.file.clone(),
        fixed: case(Base::Fixed, &values.fixed),
        floating: case(Base::Floating, &values.floating),
        load,
    }
}

fn warning_kind(kind: SpecWarningKind) -> &'static str {
    match kind {
        SpecWarningKind::TriangleInequality => "triangle inequality",
        SpecWarningKind::NegligibleNegativeInertia => "negligible negative inertia",
        SpecWarningKind::MasslessSubtree => "massless subtree",
        SpecWarningKind::MimicLeaderMissing => "mimic leader missing",
        _ => "other",
    }
}

/// The larger of two errors, a NaN error being the largest of all.
fn worst(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::INFINITY
    } else {
        a.max(b)
    }
}

/// One base of a file rne read; mimic followers constrained unless `free_mimic`.
fn case_report(
    model: &RobotModel,
    base: Base,
    pinocchio: &BaseValues,
    free_mimic: bool,
) -> CaseReport {
    let mut model = model.clone();
    model.set_base(base);
    if !free_mimic {
        if let Err(e) = model.constrain_mimic_joints() {
            return CaseReport::RneRefuses(e.to_string());
        }
    }
    if let Err(e) = model.check_moves() {
        return if pinocchio.nv == 0 {
            CaseReport::NothingMoves
        } else {
            CaseReport::RneRefuses(e.to_string())
        };
    }
    match compare(&model, pinocchio) {
        Ok(comparison) => CaseReport::Compared(Comparison {
            kernels: check_every_kernel(&model, KERNEL_STATES, KERNEL_SEED),
            ..comparison
        }),
        Err(e) => CaseReport::RneRefuses(e),
    }
}

/// Where each entry of rne's velocity sits in Pinocchio's.
struct JointMap {
    /// Entries before the joints (6 on a floating base).
    offset: usize,
    /// For rne's joint k, Pinocchio's joint index.
    joints: Vec<usize>,
}

impl JointMap {
    fn new(model: &RobotModel, pinocchio: &BaseValues) -> Result<JointMap, String> {
        let layout = model.state_layout();
        if layout.nv() != pinocchio.nv {
            return Err(format!(
                "rne has NV = {} ({} joints), Pinocchio {} ({})",
                layout.nv(),
                model.joint_names().join(", "),
                pinocchio.nv,
                pinocchio.joints.join(", ")
            ));
        }
        let joints = model
            .joint_names()
            .iter()
            .map(|name| {
                pinocchio
                    .joints
                    .iter()
                    .position(|p| p == name)
                    .ok_or_else(|| format!("Pinocchio has no joint variable `{name}`"))
            })
            .collect::<Result<_, _>>()?;
        Ok(JointMap {
            offset: layout.v_offset(),
            joints,
        })
    }

    /// Pinocchio's index of rne's velocity entry `k`.
    fn index(&self, k: usize) -> usize {
        if k < self.offset {
            k
        } else {
            self.offset + self.joints[k - self.offset]
        }
    }

    /// A velocity-sized vector of Pinocchio's in rne's order.
    fn vector(&self, pinocchio: &[f64]) -> Vec<f64> {
        (0..pinocchio.len())
            .map(|k| pinocchio[self.index(k)])
            .collect()
    }

    /// rne's configuration: the base's seven entries, then the joints' values.
    fn configuration(&self, state: &State) -> Vec<f64> {
        let base = state.base.map_or_else(Vec::new, |b| b.to_vec());
        base.into_iter()
            .chain(self.joints.iter().map(|&p| state.q[p]))
            .collect()
    }
}

/// Largest |a − b| over the entries, `b` in Pinocchio's order and `a` in rne's.
fn vector_error(map: &JointMap, rne: &[f64], pinocchio: &[f64]) -> f64 {
    rne.iter()
        .enumerate()
        .map(|(k, x)| (x - pinocchio[map.index(k)]).abs())
        .fold(0.0, worst)
}

fn matrix_error(map: &JointMap, rne: &[Vec<f64>], pinocchio: &[Vec<f64>]) -> f64 {
    let mut max = 0.0f64;
    for (i, row) in rne.iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            max = worst(max, (x - pinocchio[map.index(i)][map.index(j)]).abs());
        }
    }
    max
}

/// |M_pin (q̈ − q̈_pin)|∞ with M_pin and q̈_pin in Pinocchio's order and q̈ in rne's.
fn forward_error(map: &JointMap, qdd: &[f64], state: &State, pin_qdd: &[f64]) -> f64 {
    let mut delta = vec![0.0; qdd.len()];
    for (k, x) in qdd.iter().enumerate() {
        delta[map.index(k)] = x - pin_qdd[map.index(k)];
    }
    state
        .mass_matrix
        .iter()
        .map(|row| {
            row.iter()
                .zip(&delta)
                .map(|(m, d)| m * d)
                .sum::<f64>()
                .abs()
        })
        .fold(0.0, worst)
}

fn max_abs(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// One engine's outputs at one state, rne's order.
struct Outputs {
    tau: Vec<f64>,
    mass_matrix: Vec<Vec<f64>>,
    gravity: Vec<f64>,
    bias: Vec<f64>,
    forward: Option<Vec<f64>>,
}

/// rne's inverse dynamics, M, g, bias and forward dynamics, from the interpreted kernels and
/// from the reference, against Pinocchio's `pinocchio` at each of its states.
fn compare(model: &RobotModel, pinocchio: &BaseValues) -> Result<Comparison, String> {
    let map = JointMap::new(model, pinocchio)?;
    let invertible = model.check_mass_matrix_invertible();
    let kernels = if invertible.is_ok() {
        &CORPUS_KERNELS[..]
    } else {
        &CORPUS_KERNELS[..4]
    };
    let start = Instant::now();
    let interpreted = Interpreted::with_kernels(model, kernels);
    let generation = start.elapsed();
    let mut reference = Reference::try_new(&model.to_numeric()).map_err(|e| e.to_string())?;
    let forward_skipped = match (
        &invertible,
        pinocchio.states.iter().all(|s| s.qdd.is_some()),
    ) {
        (Err(e), _) => Some(format!("rne: {e}")),
        (Ok(()), false) => Some("M is singular (Pinocchio)".to_owned()),
        (Ok(()), true) => None,
    };
    let forward = forward_skipped.is_none();
    let scales = scales(pinocchio);
    let mut symbolic = Errors::default();
    let mut numeric = Errors::default();
    for state in &pinocchio.states {
        let q = map.configuration(state);
        let (v, a, tau) = (
            map.vector(&state.v),
            map.vector(&state.a),
            map.vector(&state.tau_fd),
        );
        let state_ref = StateRef {
            q: &q,
            qd: &v,
            qdd: &a,
            tau: &tau,
        };
        let from_symbolic = symbolic_outputs(&interpreted, state_ref, forward)?;
        let from_reference =
            reference_outputs(&mut reference, state_ref, forward).map_err(|e| e.to_string())?;
        symbolic.add(&map, &from_symbolic, state, scales);
        numeric.add(&map, &from_reference, state, scales);
    }
    Ok(Comparison {
        nv: pinocchio.nv,
        mimic: pinocchio.mimic.clone().unwrap_or_else(|| "none".to_owned()),
        generation,
        symbolic,
        numeric,
        forward_skipped,
        kernels: Vec::new(),
    })
}

/// The robot's scales over Pinocchio's states: (the largest |entry| of τ, g, the bias and the
/// forward dynamics' input forces, the largest |entry| of M).
fn scales(pinocchio: &BaseValues) -> (f64, f64) {
    let (mut torque_scale, mut mass_scale) = (f64::MIN_POSITIVE, f64::MIN_POSITIVE);
    for state in &pinocchio.states {
        for v in [&state.tau, &state.g, &state.bias, &state.tau_fd] {
            torque_scale = torque_scale.max(max_abs(v));
        }
        for row in &state.mass_matrix {
            mass_scale = mass_scale.max(max_abs(row));
        }
    }
    (torque_scale, mass_scale)
}

/// The interpreted symbolic kernels' [`Outputs`] at `state` (forward dynamics when
/// `forward`).
fn symbolic_outputs(
    interpreted: &Interpreted,
    state: StateRef<'_>,
    forward: bool,
) -> Result<Outputs, String> {
    let eval = |kernel| {
        interpreted
            .evaluate(kernel, state)
            .map_err(|e| e.to_string())
    };
    let rows = |flat: Vec<f64>| -> Vec<Vec<f64>> {
        flat.chunks(interpreted.nv().max(1))
            .map(<[f64]>::to_vec)
            .collect()
    };
    Ok(Outputs {
        tau: eval(Kernel::InverseDynamics)?,
        mass_matrix: rows(eval(Kernel::MassMatrix)?),
        gravity: eval(Kernel::GravityTorques)?,
        bias: eval(Kernel::BiasTorques)?,
        forward: if forward {
            Some(eval(Kernel::ForwardDynamics)?)
        } else {
            None
        },
    })
}

/// The numeric reference's [`Outputs`] at `state` (forward dynamics when `forward`).
fn reference_outputs(
    reference: &mut Reference,
    state: StateRef<'_>,
    forward: bool,
) -> Result<Outputs, rne_reference::ReferenceError> {
    let StateRef { q, qd, qdd, tau } = state;
    Ok(Outputs {
        tau: reference.inverse_dynamics(q, qd, qdd)?.as_slice().to_vec(),
        mass_matrix: {
            let m = reference.mass_matrix(q)?;
            m.row_iter().map(|r| r.iter().copied().collect()).collect()
        },
        gravity: reference.gravity_torques(q)?.as_slice().to_vec(),
        bias: reference.bias_torques(q, qd)?.as_slice().to_vec(),
        forward: if forward {
            Some(reference.forward_dynamics(q, qd, tau)?.as_slice().to_vec())
        } else {
            None
        },
    })
}

impl Errors {
    /// Takes in the errors of `outputs` against Pinocchio's `state`, relative to `scales`
    /// (torque, M).
    fn add(&mut self, map: &JointMap, outputs: &Outputs, state: &State, scales: (f64, f64)) {
        let (torque_scale, mass_scale) = scales;
        let torque = |rne: &[f64], pin: &[f64]| vector_error(map, rne, pin) / torque_scale;
        self.tau = worst(self.tau, torque(&outputs.tau, &state.tau));
        self.mass_matrix = worst(
            self.mass_matrix,
            matrix_error(map, &outputs.mass_matrix, &state.mass_matrix) / mass_scale,
        );
        self.gravity = worst(self.gravity, torque(&outputs.gravity, &state.g));
        self.bias = worst(self.bias, torque(&outputs.bias, &state.bias));
        if let (Some(qdd), Some(pin_qdd)) = (&outputs.forward, &state.qdd) {
            let e = forward_error(map, qdd, state, pin_qdd) / torque_scale;
            self.forward = Some(self.forward.map_or(e, |f| worst(f, e)));
        }
    }
}
